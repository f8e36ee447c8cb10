// Dry soil keeps its suction while it deforms (issue 13, item 4): the residual water of a
// retention curve is held at the grain contacts and moves with the grains (docs/physics.md,
// "Grain-bound water"; server/physics/swcc/grain_bound_water.h).
//
// The landslide flume of cases/landslide_tsunami_2d.yaml at 100 kPa suction: Gardner's curve
// (S_min = 0.001, α = 20 /m) puts the free water share S_max S_e = exp(−α p_c/γ_w) at 1e−89 and the
// relative conductivity with it, so no water can flow and the skeleton's dilation (porosity 0.4 to
// 0.7 in the slide) squeezes none. The pore water of each particle is then a closed system whose
// mass per unit volume of grains, ρ_w e S_w(p_c, φ) with e = φ/(1 − φ) and ρ_w = ρ_w0 (1 + p_w/K_w)
// (Eq. 6), the model conserves exactly: the tolerance is round-off. With Eq. 27a's S_w ε̇_v in place
// of the free share, the residual water took dp_w = −(K_w/φ) dε_v and the slide's dilation drove
// the suction past megapascals (at 10 kPa: −3 MPa and a failed run at 0.78 s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "server/physics/swcc/grain_bound_water.h"
#include "tests/validation/case_run.h"
#include "tests/validation/slide_counts.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

constexpr double kSuction = 1e5;  // Pa
constexpr double kEnd = 0.6;      // s: the slide has entered the water and spread (porosity ≈ 0.7)

// ρ_w e S_w / ρ_w0 of one soil particle: its pore water per unit volume of grains.
double water_per_grain(const SoilMaterial& m, double pore_pressure, double porosity) {
  const double saturation = saturation_at_porosity(m.hydraulic, m.reference_porosity, -pore_pressure, porosity);
  return (1.0 + pore_pressure / m.water_bulk_modulus) * porosity / (1.0 - porosity) * saturation;
}

struct SoilWater {
  std::map<std::uint32_t, double> per_grain;  // by particle id
  double porosity_max = 0, suction_min = INFINITY, suction_max = -INFINITY;
};

SoilWater soil_water(const FieldFrame& f, const SoilMaterial& m) {
  const FieldFrame::RealField* pressure = f.find("pore_pressure");
  const FieldFrame::RealField* porosity = f.find("porosity");
  SoilWater w;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.phase[i] != std::uint8_t(Phase::soil)) continue;
    const double p = pressure->values[i], phi = porosity->values[i];
    w.per_grain[f.id[i]] = water_per_grain(m, p, phi);
    w.porosity_max = std::max(w.porosity_max, phi);
    w.suction_min = std::min(w.suction_min, -p);
    w.suction_max = std::max(w.suction_max, -p);
  }
  return w;
}

TEST(DrySoil, DilatingSlideKeepsItsResidualWaterAndSuction) {
  testing::CaseRun run("landslide_tsunami_2d.yaml", {"bodies[3].initial.suction=" + std::to_string(kSuction)});
  const SoilMaterial& m = run.config.soils.at(0);
  const SoilWater start = soil_water(run.engine->frame(), m);
  ASSERT_NEAR(start.suction_min, kSuction, 1.0) << "the override did not reach the granular mass";
  double worst_change = 0, porosity_max = 0, suction_min = INFINITY, suction_max = -INFINITY;
  for (double t = 0.05; t <= kEnd + 1e-9; t += 0.05) {
    run.run_until(t);
    const SoilWater now = soil_water(run.engine->frame(), m);
    ASSERT_EQ(now.per_grain.size(), start.per_grain.size());
    for (const auto& [id, value] : now.per_grain)
      worst_change = testing::worst_of(worst_change, std::fabs(value / start.per_grain.at(id) - 1.0));
    porosity_max = std::max(porosity_max, now.porosity_max);
    suction_min = std::min(suction_min, now.suction_min);
    suction_max = std::max(suction_max, now.suction_max);
  }
  std::printf("to t = %.2f s: porosity up to %.3f, suction %.6g to %.6g Pa, water per grain within %.3g\n", kEnd,
              porosity_max, suction_min, suction_max, worst_change);
  EXPECT_GT(porosity_max, 0.6) << "the slide did not dilate: the test would not show the residual water";
  const std::string case_name = "Dry granular slide at 100 kPa suction (cases/landslide_tsunami_2d.yaml)";
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "a closed pore water: no flow at K_rel = 1e-89, no free water to squeeze",
                    .metric = "largest change of a particle's water per grain ρ_w e S_w, 50 ms samples to 0.6 s",
                    .measured = worst_change, .reference_value = 1e-12, .bound = testing::Bound::at_most,
                    .tolerance_source = "round-off of the density and porosity updates over 10^4 steps"});
  CASCADE_VALIDATE({.case_name = case_name, .reference = "the initial suction (grain-bound water)",
                    .metric = "largest suction reached [kPa]", .measured = 1e-3 * suction_max,
                    .reference_value = 1e-3 * kSuction, .tolerance = 1e-6, .relative = true,
                    .tolerance_source = "the water per grain's round-off, through dp_w = K_w dρ_w/ρ_w0"});
}

}  // namespace
}  // namespace cascade
