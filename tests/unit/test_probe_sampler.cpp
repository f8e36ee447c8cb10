// ProbeSampler on hand-made frames with known values: point (Shepard), max and mean probes of the
// soil fields and their components, and the errors for fields a frame lacks; the parts that the
// processes of a split run take (ProbeSampler::parts) combine to the whole frame's values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/field_frame.h"
#include "server/io/probe_sampler.h"
#include "tests/unit/process_frames.h"

namespace cascade {
namespace {

constexpr double kH = 0.1;  // smoothing length: the kernel support is 2h = 0.2 m

// A 2D frame (positions (x, 0, z)) of soil, water and boundary particles with every soil field
// of the engine. Each particle sets only the values a probe reads; the rest are fillers that a
// wrong component, phase or domain test would pick up instead.
class SoilFrameBuilder {
 public:
  struct Particle {
    std::uint8_t phase = 1;  // 0 water, 1 soil, 2 boundary
    double x = 0, z = 0;
    double pore_pressure = 0, numerical_density = 2000;
    double stress_zz = 0, seepage_z = 0, effective_stress_xy = 0;
    std::uint8_t free_surface = 0;
  };

  void add(const Particle& p) { particles_.push_back(p); }

  FieldFrame build(bool with_free_surface = true) const {
    FieldFrame frame;
    frame.dimensions = 2;
    FieldFrame::RealField pore_pressure{"pore_pressure", "Pa", 1, {}};
    FieldFrame::RealField saturation{"saturation", "1", 1, {}};
    FieldFrame::RealField numerical_density{"numerical_density", "kg/m^3", 1, {}};
    FieldFrame::RealField seepage{"seepage", "m/s", 3, {}};
    FieldFrame::RealField stress{"stress", "Pa", 6, {}};
    FieldFrame::RealField effective_stress{"effective_stress", "Pa", 6, {}};
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      const Particle& p = particles_[i];
      frame.position.insert(frame.position.end(), {p.x, 0.0, p.z});
      frame.phase.push_back(p.phase);
      frame.id.push_back(static_cast<std::uint32_t>(i));
      frame.free_surface.push_back(p.free_surface);
      pore_pressure.values.push_back(p.pore_pressure);
      saturation.values.push_back(0.5);
      numerical_density.values.push_back(p.numerical_density);
      // x and y of the seepage are large, so that reading the wrong component shows.
      seepage.values.insert(seepage.values.end(), {3.0, 2.0, p.seepage_z});
      // Voigt xx, yy, zz, xy, yz, zx: every other component above any zz of the frame.
      stress.values.insert(stress.values.end(), {1e7, 2e7, p.stress_zz, 4e7, 5e7, 6e7});
      effective_stress.values.insert(effective_stress.values.end(),
                                     {1e7, 2e7, 3e7, p.effective_stress_xy, 5e7, 6e7});
    }
    if (!with_free_surface) frame.free_surface.clear();
    frame.fields = {pore_pressure, saturation, numerical_density, seepage, stress,
                    effective_stress};
    return frame;
  }

 private:
  std::vector<Particle> particles_;
};

v1::Probe make_probe(const std::string& name, v1::ProbeKind kind, const std::string& field,
                     const std::string& phase, std::vector<double> position = {}) {
  v1::Probe probe;
  probe.set_name(name);
  probe.set_kind(kind);
  probe.set_field(field);
  probe.set_phase(phase);
  for (double c : position) probe.add_position(c);
  return probe;
}

v1::ScenarioSpec unit_square(const std::vector<v1::Probe>& probes, int dimensions = 2) {
  v1::ScenarioSpec spec;
  spec.set_dimensions(dimensions);
  for (int a = 0; a < dimensions; ++a) {
    spec.mutable_domain()->add_min(0.0);
    spec.mutable_domain()->add_max(1.0);
  }
  for (const auto& p : probes) *spec.add_probes() = p;
  return spec;
}

// The soil column of the tests, with its probe values worked out by hand:
// - a 3 x 3 block of soil at x, z in {0.45, 0.5, 0.55} with the hydrostatic pore pressure
//   p_w = 9810 (1 - z) Pa: symmetric about (0.5, 0.5), so Shepard interpolation of this linear
//   field gives exactly p_w(0.5) = 4905 Pa there;
// - two soil particles at (0.15, 0.2) and (0.25, 0.2), equally far from (0.2, 0.2), with
//   p_w = 1000 and 4000 Pa and numerical densities 1000 and 2000 kg/m^3, so volumes V = m/ρ in the
//   ratio 2 : 1: the point value there is (2 x 1000 + 4000) / 3 = 2000 Pa;
// - one soil particle at (0.5, 0.75), 0.25 m (beyond 2h) from (0.5, 0.5), p_w = 1e6 Pa;
// - one soil particle outside the domain at (1.05, 0.5), and water and boundary particles next
//   to the probe points, all with values that would change every result if they were counted.
FieldFrame soil_column(bool with_free_surface = true) {
  SoilFrameBuilder b;
  const double zs[3] = {0.45, 0.5, 0.55};
  int k = 0;
  for (double x : zs)
    for (double z : zs) {
      SoilFrameBuilder::Particle p;
      p.x = x, p.z = z;
      p.pore_pressure = 9810.0 * (1.0 - z);
      p.stress_zz = -20000.0 * (1.0 - z);  // -11000 … -9000 Pa
      p.seepage_z = -1e-5;
      p.effective_stress_xy = 100.0;
      p.free_surface = k++ < 2;  // two of the nine
      b.add(p);
    }
  SoilFrameBuilder::Particle left, right, far, outside, water, boundary;
  left.x = 0.15, left.z = 0.2, left.pore_pressure = 1000, left.numerical_density = 1000;
  left.stress_zz = -16000, left.seepage_z = -4e-5, left.effective_stress_xy = 400;
  right.x = 0.25, right.z = 0.2, right.pore_pressure = 4000, right.numerical_density = 2000;
  right.stress_zz = -16000, right.seepage_z = -7e-5, right.effective_stress_xy = 400;
  far.x = 0.5, far.z = 0.75, far.pore_pressure = 1e6;
  far.stress_zz = -5000, far.seepage_z = -1e-5, far.effective_stress_xy = 100, far.free_surface = 1;
  b.add(left), b.add(right), b.add(far);
  outside.x = 1.05, outside.z = 0.5, outside.pore_pressure = 1e6;
  outside.stress_zz = 1e6, outside.seepage_z = 1.0, outside.effective_stress_xy = 1e6;
  outside.free_surface = 1;
  water.phase = 0, water.x = 0.5, water.z = 0.5, water.numerical_density = 1000;
  water.pore_pressure = -1e6, water.stress_zz = 0, water.seepage_z = 5.0;
  boundary.phase = 2, boundary.x = 0.2, boundary.z = 0.2;
  boundary.pore_pressure = 1e6, boundary.stress_zz = 100, boundary.seepage_z = 5.0;
  b.add(outside), b.add(water), b.add(boundary);
  return b.build(with_free_surface);
}

TEST(ProbeSampler, SoilFieldsAndComponentsOfAHandMadeFrame) {
  const ProbeSampler sampler(
      unit_square({
          make_probe("p_centre", v1::POINT, "pore_pressure", "soil", {0.5, 0.5}),
          make_probe("p_pair", v1::POINT, "pore_pressure", "soil", {0.2, 0.2}),
          make_probe("p_nothing", v1::POINT, "pore_pressure", "soil", {0.9, 0.9}),
          make_probe("szz_max", v1::MAX, "stress_zz", "soil"),
          make_probe("qz_mean", v1::MEAN, "seepage_z", "soil"),
          make_probe("sxy_mean", v1::MEAN, "effective_stress_xy", "soil"),
          make_probe("surface", v1::MEAN, "free_surface", "soil"),
          make_probe("sat_max", v1::MAX, "saturation", "soil"),
      }),
      kH, 1.0);
  EXPECT_EQ(sampler.names(), (std::vector<std::string>{"p_centre", "p_pair", "p_nothing", "szz_max",
                                                       "qz_mean", "sxy_mean", "surface",
                                                       "sat_max"}));
  const std::vector<double> v = sampler.sample(soil_column());
  ASSERT_EQ(v.size(), 8u);
  EXPECT_NEAR(v[0], 4905.0, 1e-9 * 4905.0);  // symmetric block, linear field
  EXPECT_NEAR(v[1], 2000.0, 1e-9 * 2000.0);  // volume-weighted: (2 x 1000 + 4000) / 3
  EXPECT_TRUE(std::isnan(v[2]));             // no soil particle within 2h
  EXPECT_EQ(v[3], -5000.0);                  // the far particle; outside, water, boundary ignored
  // 10 particles at -1e-5 m/s, one at -4e-5, one at -7e-5: -21e-5 / 12.
  EXPECT_NEAR(v[4], -1.75e-5, 1e-15);
  EXPECT_NEAR(v[5], (10 * 100.0 + 2 * 400.0) / 12.0, 1e-12);  // 150 Pa
  EXPECT_DOUBLE_EQ(v[6], 3.0 / 12.0);                          // 2 of the block + the far one
  EXPECT_EQ(v[7], 0.5);
}

TEST(ProbeSampler, ScalarFieldPicksVoigtAndVectorComponents) {
  FieldFrame frame;
  frame.dimensions = 3;
  frame.position = {0, 0, 0, 1, 1, 1};
  frame.phase = {1, 1};
  frame.id = {0, 1};
  frame.free_surface = {0, 1};
  frame.fields.push_back({"effective_stress", "Pa", 6, {1, 2, 3, 4, 5, 6, 11, 12, 13, 14, 15, 16}});
  frame.fields.push_back({"displacement", "m", 3, {0.1, 0.2, 0.3, 1.1, 1.2, 1.3}});
  frame.fields.push_back({"plastic_strain", "1", 1, {0.01, 0.02}});
  const char* const voigt[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c)
    EXPECT_EQ(ProbeSampler::scalar_field(frame, std::string("effective_stress_") + voigt[c]),
              (std::vector<double>{c + 1.0, c + 11.0}))
        << voigt[c];
  EXPECT_EQ(ProbeSampler::scalar_field(frame, "displacement_y"), (std::vector<double>{0.2, 1.2}));
  EXPECT_EQ(ProbeSampler::scalar_field(frame, "plastic_strain"), (std::vector<double>{0.01, 0.02}));
  EXPECT_EQ(ProbeSampler::scalar_field(frame, "free_surface"), (std::vector<double>{0.0, 1.0}));
  for (const char* bad : {"effective_stress", "effective_stress_x", "displacement_xx",
                          "displacement", "displacement_w", "plastic_strain_x", "stress_zz", "_x"})
    EXPECT_THROW(ProbeSampler::scalar_field(frame, bad), std::invalid_argument) << bad;

  const ProbeSampler sampler(
      unit_square({make_probe("uy", v1::MEAN, "displacement_y", "soil")}, 3), kH, 1.0);
  const std::vector<double> mean = sampler.sample(frame);
  ASSERT_EQ(mean.size(), 1u);
  EXPECT_DOUBLE_EQ(mean[0], 0.7);  // (0.2 + 1.2) / 2
}

TEST(ProbeSampler, FieldsTheFrameLacksAreErrors) {
  // A water-only case: the frame has today's fields and no free_surface.
  FieldFrame water;
  water.dimensions = 2;
  water.position = {0.5, 0.0, 0.5};
  water.phase = {0};
  water.id = {0};
  water.fields = {{"velocity", "m/s", 3, {1.0, 0.0, -2.0}},
                  {"pressure", "Pa", 1, {100.0}},
                  {"density", "kg/m^3", 1, {1000.0}},
                  {"numerical_density", "kg/m^3", 1, {1000.0}}};
  EXPECT_EQ(
      ProbeSampler(unit_square({make_probe("u", v1::MAX, "velocity_z", "water")}), kH, 1.0).sample(water),
      (std::vector<double>{-2.0}));
  for (const char* field : {"pore_pressure", "stress_zz", "seepage_z", "free_surface"}) {
    const ProbeSampler sampler(unit_square({make_probe("p", v1::MEAN, field, "water")}), kH, 1.0);
    EXPECT_THROW(sampler.sample(water), std::invalid_argument) << field;
  }
  // A soil frame whose free_surface is empty.
  const ProbeSampler surface(unit_square({make_probe("s", v1::MAX, "free_surface", "soil")}), kH,
                             1.0);
  EXPECT_THROW(surface.sample(soil_column(false)), std::invalid_argument);
  EXPECT_EQ(surface.sample(soil_column(true)), (std::vector<double>{1.0}));
}

// A tank of water at rest, 0.4 m deep in 2D (dp = 0.05 m, ρ = 1000 kg/m³, m = ρ dp² per metre),
// with the soil column's particles beside it.
FieldFrame tank_and_soil() {
  FieldFrame frame = soil_column();
  const double dp = 0.05;
  std::uint32_t id = std::uint32_t(frame.size());
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 8; ++k) {
      const double x = 0.6 + (i + 0.5) * dp, z = (k + 0.5) * dp;
      frame.position.insert(frame.position.end(), {x, 0.0, z});
      frame.phase.push_back(0);
      frame.id.push_back(id++);
      frame.free_surface.push_back(0);
      for (auto& f : frame.fields) {
        const double value = f.name == "pore_pressure" ? 9810.0 * (0.4 - z) : f.name == "numerical_density" ? 1000.0 : 0.0;
        f.values.insert(f.values.end(), std::size_t(f.components), value);
      }
    }
  return frame;
}

TEST(ProbeSampler, PartsOfProcessesCombineToTheWholeFramesValues) {
  v1::Probe rightmost_water = make_probe("front", v1::FRONT, "", "water");
  rightmost_water.set_axis("x");
  rightmost_water.set_origin(0.6);
  v1::Probe lowest_soil = make_probe("toe", v1::FRONT, "", "soil");
  lowest_soil.set_axis("y");  // case axis y: z in 2D
  lowest_soil.set_minimum(true);
  const ProbeSampler sampler(
      unit_square({
          make_probe("p_centre", v1::POINT, "pore_pressure", "soil", {0.5, 0.5}),
          make_probe("p_pair", v1::POINT, "pore_pressure", "soil", {0.2, 0.2}),
          make_probe("p_water", v1::POINT, "pore_pressure", "water", {0.8, 0.2}),
          make_probe("p_nothing", v1::POINT, "pore_pressure", "soil", {0.9, 0.9}),
          make_probe("level", v1::ELEVATION, "", "water", {0.8}),
          make_probe("dry", v1::ELEVATION, "", "water", {0.1}),
          rightmost_water,
          lowest_soil,
          make_probe("szz_max", v1::MAX, "stress_zz", "soil"),
          make_probe("qz_mean", v1::MEAN, "seepage_z", "soil"),
      }),
      kH, 1000.0 * 0.05 * 0.05);
  const FieldFrame whole = tank_and_soil();
  const std::vector<double> expected = sampler.sample(whole);
  EXPECT_NEAR(expected[4], 0.4, 0.5 * 0.05);  // the tank's surface, within dp/2
  EXPECT_TRUE(std::isnan(expected[5]));
  EXPECT_DOUBLE_EQ(expected[6], 0.4 - 0.025);

  for (int processes : {1, 2, 3}) {
    std::vector<int> owner(whole.size());
    for (std::size_t i = 0; i < owner.size(); ++i) owner[i] = int((7 * i) % std::size_t(processes));
    std::vector<std::vector<ProbeSampler::Part>> parts;
    int process = 0;
    for (const FieldFrame& local : frames_of_processes(whole, owner, processes)) {
      const std::vector<char> owned = owned_rows(local, process++);
      parts.push_back(ProbeSampler::unflatten(ProbeSampler::flatten(sampler.parts(local, &owned))));
    }
    const std::vector<double> combined = sampler.combine(parts);
    ASSERT_EQ(combined.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      if (std::isnan(expected[k])) {
        EXPECT_TRUE(std::isnan(combined[k])) << sampler.names()[k];
      } else if (k == 4 || (k >= 6 && k <= 8)) {  // an elevation in id order, the extremes: the same bits
        EXPECT_EQ(combined[k], expected[k]) << sampler.names()[k] << " at " << processes << " processes";
      } else {  // sums in another order: round-off
        EXPECT_NEAR(combined[k], expected[k], 1e-13 * std::fabs(expected[k])) << sampler.names()[k];
      }
    }
  }
}

TEST(ProbeSampler, MalformedPartsAreRefused) {
  const ProbeSampler sampler(unit_square({make_probe("p", v1::MEAN, "pore_pressure", "soil")}), kH, 1.0);
  const std::vector<double> good = ProbeSampler::flatten(sampler.parts(soil_column()));
  EXPECT_NO_THROW(ProbeSampler::unflatten(good));
  for (std::size_t cut = 0; cut < good.size(); ++cut)
    EXPECT_THROW(ProbeSampler::unflatten(std::vector<double>(good.begin(), good.begin() + std::ptrdiff_t(cut))),
                 std::invalid_argument)
        << cut;
  std::vector<double> longer = good;
  longer.push_back(0.0);
  EXPECT_THROW(ProbeSampler::unflatten(longer), std::invalid_argument);
  EXPECT_THROW(sampler.combine({{}}), std::invalid_argument);  // a process's parts of no probe
}

}  // namespace
}  // namespace cascade
