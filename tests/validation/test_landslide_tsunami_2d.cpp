// The landslide-generated wave of Section 4.4 (cases/landslide_tsunami_2d.yaml, after Viroulet et
// al. 2013): a dry granular mass slides down a 45° slope into 0.148 m of still water.
//  - The leading wave passes the four gauges in order (its first crest later at each) and loses
//    height on the way (Fig. 17 of the paper; Viroulet et al.: the leading wave's amplitude
//    decays with distance).
//  - Its crest at gauge 1 against the impulse-product relation of Heller & Hager (2010), "Impulse
//    product parameter in landslide generated impulse waves", J. Waterway Port Coastal Ocean Eng.
//    136(3):145-155: a_M/h = (4/9) P^(4/5), P = F S^(1/2) M^(1/4) cos(6α/7)^(1/2), with
//    F = V_s/sqrt(g h) the slide Froude number at impact, S = s/h the relative slide thickness,
//    M = m_s/(ρ_w b h²) the relative slide mass, α the slope angle. V_s is measured from the run:
//    the speed of the slide's centroid when the centroid crosses the still water surface. a_M is
//    the largest crest of the near field, which ends near x_M = (11/2) P^(1/2) h (0.48 m here);
//    gauge 1 (x/h = 3) is the nearest gauge. The form (with H_M = (5/9) P^(4/5) h and
//    a_M = (4/5) H_M) and the tested ranges (0.86 <= F <= 6.83, 0.17 <= P <= 8.13) are those of
//    Heller, Hager & Minor (2009), VAW-Mitteilung 211, Eqs. 3.12-3.16 and Table 3-2, as two
//    public transcriptions give them; F = 0.60 here is below the tested range (P = 0.35 inside
//    it). The band, ±30%, is the relation's data scatter as we remember it: no stored source
//    states it (docs/cases.md, "Landslide tsunami").
//  - No particle leaves the domain, and the water and soil particle counts, hence their masses
//    (a particle's mass is fixed), are those of the start; and no water or soil particle enters
//    the slope or the floor: none is ever (at the 5 ms samples) deeper inside them than dp/2
//    (solid_depth.h; docs/physics.md, "Impenetrable walls": before the wall contact, 4 water
//    particles of the wedge under the dry slide's front went through the slope's dummy layers and
//    out of the domain).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "server/io/probe_sampler.h"
#include "tests/validation/case_run.h"
#include "tests/validation/slide_counts.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

using testing::count;
using testing::PhaseCounts;
using testing::soil_centroid;

constexpr double kG = 9.81, kDepth = 0.148, kSlopeAngle = 45.0 * M_PI / 180.0;
constexpr double kLeg = 0.11, kSoilDensity = 2500.0, kWaterDensity = 1000.0;
constexpr double kSampleInterval = 0.005;  // s, 200 Hz

struct Crest {
  double time = NAN, amplitude = NAN;
};

// The leading crest of an elevation record η(t) (above the still level): the first local maximum
// after η first exceeds `threshold`, the largest η before it falls below the threshold again.
Crest leading_crest(const std::vector<double>& t, const std::vector<double>& eta, double threshold) {
  Crest c;
  std::size_t k = 0;
  while (k < eta.size() && !(eta[k] > threshold)) ++k;
  for (; k < eta.size() && eta[k] > threshold; ++k)
    if (!(eta[k] <= c.amplitude)) c = {t[k], eta[k]};
  return c;
}

TEST(LandslideTsunami2d, WaveReachesGaugesInOrderAndGauge1MatchesHellerHager) {
  testing::CaseRun run("landslide_tsunami_2d.yaml");
  const ProbeSampler sampler(run.spec, run.config.h, run.config.water_density * run.config.dp * run.config.dp);
  const auto names = sampler.names();
  const FieldFrame start = run.engine->frame();
  const PhaseCounts n0 = count(start, run.spec);
  const std::vector<double> still = sampler.sample(start);  // the gauges' still level

  std::vector<double> time;
  std::vector<std::vector<double>> eta(4);
  double centroid_z = 0, centroid_speed = 0, impact_speed = NAN, impact_time = NAN;
  testing::WallWatch walls(run.spec);
  walls.sample(start);
  soil_centroid(start, &centroid_z, &centroid_speed);
  for (double t = kSampleInterval; t <= run.spec.end_time() + 1e-9; t += kSampleInterval) {
    run.run_until(t);
    const FieldFrame f = run.engine->frame();
    const std::vector<double> values = sampler.sample(f);
    time.push_back(f.time);
    for (int g = 0; g < 4; ++g) eta[g].push_back(values[g] - still[g]);
    walls.sample(f);
    const double previous_z = centroid_z, previous_speed = centroid_speed;
    soil_centroid(f, &centroid_z, &centroid_speed);
    if (std::isnan(impact_speed) && centroid_z <= kDepth) {  // linear in between the samples
      const double w = (previous_z - kDepth) / (previous_z - centroid_z);
      impact_speed = previous_speed + w * (centroid_speed - previous_speed);
      impact_time = f.time - (1 - w) * kSampleInterval;
    }
  }
  const PhaseCounts n1 = count(run.engine->frame(), run.spec);

  const double gauge1_max = *std::max_element(eta[0].begin(), eta[0].end());
  std::vector<Crest> crest(4);
  for (int g = 0; g < 4; ++g) {
    crest[g] = leading_crest(time, eta[g], 0.2 * gauge1_max);
    std::printf("%s: leading crest %.2f mm at t = %.3f s\n", names[g].c_str(), 1e3 * crest[g].amplitude,
                crest[g].time);
  }

  // Heller & Hager (2010) with the slide of the case: its thickness normal to the slope (the
  // triangle's height over its hypotenuse) and its mass per unit width.
  const double froude = impact_speed / std::sqrt(kG * kDepth);
  const double thickness = kLeg / std::sqrt(2.0);
  const double relative_thickness = thickness / kDepth;
  const double relative_mass = kSoilDensity * 0.5 * kLeg * kLeg / (kWaterDensity * kDepth * kDepth);
  const double impulse = froude * std::sqrt(relative_thickness) * std::pow(relative_mass, 0.25) *
                         std::sqrt(std::cos(6.0 / 7.0 * kSlopeAngle));
  const double predicted = 4.0 / 9.0 * std::pow(impulse, 0.8) * kDepth;
  std::printf("slide centroid at the still water level at t = %.3f s, speed %.3f m/s: F = %.3f, S = %.3f, "
              "M = %.3f, P = %.3f\n", impact_time, impact_speed, froude, relative_thickness, relative_mass, impulse);

  ASSERT_TRUE(std::isfinite(impact_speed)) << "the slide's centroid never reached the water";
  for (int g = 0; g < 4; ++g) ASSERT_TRUE(std::isfinite(crest[g].time)) << names[g] << " saw no wave";
  for (int g = 1; g < 4; ++g) {
    EXPECT_GT(crest[g].time, crest[g - 1].time) << names[g] << " before " << names[g - 1];
    EXPECT_LT(crest[g].amplitude, crest[g - 1].amplitude) << names[g] << " higher than " << names[g - 1];
  }
  const std::string case_name = "Landslide into a flume 2D (cases/landslide_tsunami_2d.yaml)";
  char heller_hager[192];
  std::snprintf(heller_hager, sizeof heller_hager,
                "Heller & Hager (2010), J. Waterway Port Coastal Ocean Eng. 136(3):145-155, a_M = (4/9) P^(4/5) h; "
                "F = %.2f here, below its tested 0.86-6.83", froude);
  CASCADE_VALIDATE({.case_name = case_name, .reference = heller_hager,
                    .metric = "leading crest at gauge 1 (x/h = 3) [mm]", .measured = 1e3 * crest[0].amplitude,
                    .reference_value = 1e3 * predicted, .tolerance = 0.3, .relative = true,
                    .tolerance_source = "the relation's data scatter as remembered; no stored source states it "
                                        "(docs/cases.md, \"Landslide tsunami\")"});
  testing::validate_nothing_lost(case_name, n0, n1, "at the end");
  walls.validate(case_name, "at the 5 ms samples");
}

}  // namespace
}  // namespace cascade
