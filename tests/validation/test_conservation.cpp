// Conservation and determinism of the water scheme.
//  - A closed periodic box of water (no walls, no gravity) with a random velocity field: total
//    momentum Σ m v is conserved to round-off, because every pair force is equal and opposite
//    (Eq. 23b as implemented, docs/physics.md) and both members of a pair see each other.
//  - Mass: particle masses are constant and no particle is created or lost in a closed tank.
//  - Determinism: the same CPU run twice gives identical bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <omp.h>

#include "tests/validation/case_run.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

constexpr const char* kPeriodicBox = R"(
name: periodic_box
dimensions: 2
dp: 0.01
h_over_dp: 1.3
end_time: 1.0
domain: {min: [0, 0], max: [0.3, 0.2], periodic: [true, true]}
gravity: [0, 0]
materials:
  - {name: water, water: {density: 1000, sound_speed: 20}}
bodies:
  - {name: water, kind: fluid, material: water, shape: {box: {min: [0, 0], max: [0.3, 0.2]}}}
)";

std::array<double, 3> momentum(const FieldFrame& frame, double mass, double* magnitude) {
  const auto* v = frame.find("velocity");
  std::array<double, 3> p{};
  *magnitude = 0;
  for (std::size_t i = 0; i < frame.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      p[c] += mass * v->values[3 * i + c];
      *magnitude += mass * std::fabs(v->values[3 * i + c]);
    }
  return p;
}

TEST(Conservation, MomentumOfPeriodicBoxToRoundOff) {
  auto spec = load_case_text(kPeriodicBox);
  auto particles = build_particles(spec);
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, 0.5);
  for (double& v : particles.velocity) v = n(rng);  // violent: |v| ≈ 0.7 m/s against c0 = 20 m/s
  const auto config = engine_config(spec, particles, Precision::double_precision);
  auto engine = make_engine(config, particles);
  const double mass = config.water_density * config.dp * config.dp;

  double scale0 = 0;
  const auto p0 = momentum(engine->frame(), mass, &scale0);
  for (int k = 0; k < 400; ++k) engine->step();
  double scale = 0;
  const auto p1 = momentum(engine->frame(), mass, &scale);
  ASSERT_GT(engine->time(), 0.005);
  ASSERT_EQ(engine->lost_particles(), 0u);
  double drift = 0;  // the largest component's change over Σ m|v|, a NaN kept
  for (int c = 0; c < 3; ++c) {
    const double d = std::fabs(p1[c] - p0[c]) / scale0;
    if (std::isnan(d) || d > drift) drift = d;
  }
  CASCADE_VALIDATE({.case_name = "Periodic box of water, random velocities (tests/validation/test_conservation.cpp)",
                    .reference = "conservation of momentum: pair forces equal and opposite (Eq. 23b)",
                    .metric = "largest |Δ(Σ m v)| component over 400 steps / Σ m|v|", .measured = drift,
                    .reference_value = 1e-12, .bound = testing::Bound::at_most,
                    .tolerance_source = "round-off in double precision (the test's bound, no derivation)"});
  // The flow did something: the velocity field has changed, not only been carried.
  EXPECT_GT(std::fabs(scale - scale0), 1e-3 * scale0);
}

TEST(Conservation, MassAndParticleCountInClosedTank) {
  testing::CaseRun run("dam_break_2d.yaml", {"dp=0.0073"});
  const std::size_t water = run.set.particles.count(Phase::water);
  run.run_until(0.15);
  const FieldFrame frame = run.engine->frame();
  std::size_t count = 0;
  for (auto p : frame.phase) count += (p == 0);
  EXPECT_EQ(count, water);
  EXPECT_EQ(run.engine->lost_particles(), 0u);
  EXPECT_EQ(frame.size(), run.set.particles.size());
  // Every id appears once: no particle duplicated or dropped by the reordering.
  std::vector<int> seen(frame.size(), 0);
  for (auto id : frame.id) ++seen.at(id);
  for (int s : seen) ASSERT_EQ(s, 1);
}

void expect_identical(const FieldFrame& a, const FieldFrame& b) {
  ASSERT_EQ(a.time, b.time);
  ASSERT_EQ(a.position.size(), b.position.size());
  EXPECT_EQ(std::memcmp(a.position.data(), b.position.data(), a.position.size() * sizeof(double)), 0);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t f = 0; f < a.fields.size(); ++f)
    EXPECT_EQ(std::memcmp(a.fields[f].values.data(), b.fields[f].values.data(), a.fields[f].values.size() * sizeof(double)), 0)
        << a.fields[f].name;
}

// Every sum over neighbours belongs to one particle and runs in a fixed order (its list, and
// the SIMD lanes of one build), and the step's reductions (minimum Δt, largest drift) are exact:
// the thread count does not change a bit.
TEST(Determinism, OneAndTwoThreadsGiveIdenticalBits) {
  auto run_with = [](int threads) {
    omp_set_num_threads(threads);
    testing::CaseRun run("dam_break_2d.yaml", {"dp=0.0073"});
    run.run_steps(300);
    return run.engine->frame();
  };
  const FieldFrame one = run_with(1);
  const FieldFrame two = run_with(2);
  omp_set_num_threads(omp_get_num_procs());
  expect_identical(one, two);
}

// The same for the soil and pore-water passes (cases/infiltration_1d.yaml, coarsened).
TEST(Determinism, SoilRunTwiceGivesIdenticalBits) {
  auto run_once = [] {
    testing::CaseRun run("infiltration_1d.yaml",
                         {"dp=0.04", "domain.min=[0.0, -0.16]", "domain.max=[0.48, 3.1]",
                          "bodies[0].shape.box.min=[0.0, -0.16]", "bodies[0].shape.box.max=[0.48, 0.0]",
                          "bodies[1].shape.box.max=[0.48, 3.0]"});
    run.run_steps(200);
    return run.engine->frame();
  };
  expect_identical(run_once(), run_once());
}

TEST(Determinism, SameRunTwiceGivesIdenticalBits) {
  auto run_once = [] {
    testing::CaseRun run("dam_break_2d.yaml", {"dp=0.0073"});
    run.run_steps(300);
    return run.engine->frame();
  };
  expect_identical(run_once(), run_once());
}

}  // namespace
}  // namespace cascade
