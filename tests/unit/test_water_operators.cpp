// The water terms against analytic values: renormalised gradient (Eq. 25), δ-SPH diffusion
// (Eqs. 23a, 24b), the ghost-node extrapolation of the solid boundary (Eqs. 30-35), the equation
// of state (Eq. 6) and the artificial sound speed (Eq. 24a).
#include <gtest/gtest.h>

#include <random>

#include "server/physics/renormalised_gradient.h"
#include "server/physics/solid_boundary.h"
#include "server/physics/water_interaction.h"
#include "tests/unit/particle_fixture.h"

namespace cascade {
namespace {

using testing::ParticleFixture;

// A block of water on a jittered lattice, with a free surface on every side.
ParticleFixture<2> jittered_block(double dp, double jitter, std::uint32_t seed) {
  ParticleFixture<2> f(dp, 1.3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * dp, jitter * dp);
  for (int i = 0; i < 30; ++i)
    for (int k = 0; k < 20; ++k) f.add({(i + 0.5) * dp + u(rng), (k + 0.5) * dp + u(rng)}, Phase::water);
  f.finish({-0.1, -0.1, 0}, {0.5, 0.4, 0});
  return f;
}

TEST(RenormalisedGradient, ExactForLinearFieldEverywhereIncludingFreeSurface) {
  auto f = jittered_block(0.01, 0.2, 1);
  const Vec<double, 2> g(3.5, -9.81);  // kg/m⁴
  for (std::size_t i = 0; i < f.position.size(); ++i)
    raw(f.water_density)[i] = 1000.0 + g.dot(raw(f.position)[i]);
  f.run(RenormalisedDensityGradient<double, 2>{f.view(), f.grid, f.neighbours->view(), f.sph, f.water, nullptr});
  for (std::size_t i = 0; i < f.position.size(); ++i) {
    EXPECT_NEAR(raw(f.gradient)[i][0], g[0], 1e-8) << i;
    EXPECT_NEAR(raw(f.gradient)[i][1], g[1], 1e-8) << i;
    EXPECT_NEAR(raw(f.pressure)[i], f.water.pressure(raw(f.water_density)[i]), 1e-9);
  }
}

TEST(DensityDiffusion, VanishesForLinearFieldAndDiffusesABump) {
  auto f = jittered_block(0.01, 0.1, 2);
  const Vec<double, 2> g(0.0, -9.81 * 1000.0 / (20.0 * 20.0));  // hydrostatic ρ_w gradient
  for (std::size_t i = 0; i < f.position.size(); ++i)
    raw(f.water_density)[i] = 1000.0 + g.dot(raw(f.position)[i]);
  f.run(RenormalisedDensityGradient<double, 2>{f.view(), f.grid, f.neighbours->view(), f.sph, f.water, nullptr});
  f.run(WaterInteraction<double, 2>{f.view(), f.grid, f.neighbours->view(), f.sph, f.water, nullptr});
  // At rest the continuity rate is the δ-term alone. For a linear field its two parts cancel pair
  // by pair but for the η² of Eq. 24b: the residue is below η²/(r² + η²) < 3% (jitter 0.1 dp) of
  // the scale δ h c0 Σ_j V_j 2|F_ij| |G·x_ij| of the first part alone.
  const double h = f.sph.h;
  for (std::size_t i = 0; i < f.position.size(); ++i) {
    const Vec<double, 2> x = raw(f.position)[i];
    double scale = 0;
    f.grid.for_each_neighbour(x, raw(f.position), [&](std::uint32_t j, const Vec<double, 2>& x_ij, double r2) {
      if (j == i) return;
      scale += f.sph.mass / raw(f.density)[j] * 2 * std::fabs(f.sph.kernel.gradient_factor(std::sqrt(r2))) *
               std::fabs(g.dot(x_ij));
    });
    scale *= f.water.delta * h * f.water.c0;
    EXPECT_LE(std::fabs(raw(f.water_density_rate)[i]), 0.03 * scale) << i;
  }

  // A bump of +1 kg/m³ on one interior particle: its rate is negative, its neighbours' positive,
  // and the diffusion moves mass without creating any (Σ V_i dρ_w/dt = 0).
  std::size_t centre = 0;
  double best = 1e9;
  for (std::size_t i = 0; i < f.position.size(); ++i) {
    const double d = (raw(f.position)[i] - Vec<double, 2>(0.15, 0.1)).norm();
    if (d < best) best = d, centre = i;
  }
  raw(f.water_density)[centre] += 1.0;
  f.run(RenormalisedDensityGradient<double, 2>{f.view(), f.grid, f.neighbours->view(), f.sph, f.water, nullptr});
  f.run(WaterInteraction<double, 2>{f.view(), f.grid, f.neighbours->view(), f.sph, f.water, nullptr});
  EXPECT_LT(raw(f.water_density_rate)[centre], -1.0);
  double total = 0;
  for (std::size_t i = 0; i < f.position.size(); ++i) total += raw(f.water_density_rate)[i] * f.sph.mass / raw(f.density)[i];
  EXPECT_NEAR(total, 0.0, 1e-9 * std::fabs(raw(f.water_density_rate)[centre]));
}

// Dummy particles below a flat wall at z = 0 with ghost nodes mirrored above it.
ParticleFixture<2> wall_with_water(double dp) {
  ParticleFixture<2> f(dp, 1.3);
  for (int i = 0; i < 40; ++i) {
    const double x = (i + 0.5) * dp;
    for (int k = 0; k < 15; ++k) f.add({x, (k + 0.5) * dp}, Phase::water);
    for (int k = 0; k < 3; ++k) f.add({x, -(k + 0.5) * dp}, Phase::boundary, {x, (k + 0.5) * dp});
  }
  f.finish({-0.1, -0.1, 0}, {0.5, 0.3, 0});
  return f;
}

// The water side of a wall (solid_boundary.h): the ghost node's value is first-order exact for a
// linear ρ_w (Eqs. 30, 31), and the dummy takes it with the hydrostatic gradient of the wall's
// momentum balance, p_b = p_g + ρ_w0 g·(x_b − x_g) (Adami et al. 2012, Eq. 27 with a_w = 0):
// for a linear field the dummy's ρ_w is ρ_w(x_g) + ρ_w0 g·(x_b − x_g)/c², and for the
// hydrostatic field (∇ρ_w = ρ_w0 g/c²) it is exact. Velocities are reversed (Eqs. 34a, 35a).
TEST(SolidBoundary, CarriesGhostValueWithHydrostaticGradientAndReversesVelocity) {
  auto f = wall_with_water(0.01);
  f.sph.gravity = Vec<double, 2>(0.0, -9.81);
  const double c2 = f.water.c0 * f.water.c0;
  const Vec<double, 2> hydrostatic = f.water.rho0 * f.sph.gravity / c2;
  const Vec<double, 2> u(0.3, -0.05);
  for (const Vec<double, 2> gradient : {Vec<double, 2>(0.7, -24.5), hydrostatic}) {
    for (std::size_t i = 0; i < f.position.size(); ++i)
      if (raw(f.phase)[i] == Phase::water) {
        raw(f.water_density)[i] = 1000.0 + gradient.dot(raw(f.position)[i]);
        raw(f.velocity)[i] = u;
      }
    f.run(SolidBoundaryWater<double, 2>{f.view(), f.grid, f.sph, f.water, nullptr});
    int checked = 0;
    for (std::size_t i = 0; i < f.position.size(); ++i) {
      if (raw(f.phase)[i] != Phase::boundary) continue;
      const Vec<double, 2> x = raw(f.position)[i];
      if (x[0] < 0.05 || x[0] > 0.35) continue;  // away from the block's side edges
      const Vec<double, 2> x_g(x[0], -x[1]);     // the ghost node, mirrored across z = 0
      const double expected = 1000.0 + gradient.dot(x_g) + f.water.rho0 * f.sph.gravity.dot(x - x_g) / c2;
      EXPECT_NEAR(raw(f.water_density)[i], expected, 1e-8) << "x = " << x.transpose();
      EXPECT_NEAR(raw(f.pressure)[i], f.water.pressure(expected), 1e-3);
      if (gradient == hydrostatic) EXPECT_NEAR(raw(f.water_density)[i], 1000.0 + gradient.dot(x), 1e-8);
      EXPECT_NEAR(raw(f.velocity)[i][0], -u[0], 1e-12);
      EXPECT_NEAR(raw(f.velocity)[i][1], -u[1], 1e-12);
      ++checked;
    }
    EXPECT_GT(checked, 50);
  }
}

TEST(SolidBoundary, ShepardFallbackWhenFewWaterNeighbours) {
  ParticleFixture<2> f(0.01, 1.3);
  // One water particle: A_g is singular, the Shepard value (Eq. 33b) is that particle's density.
  f.add({0.0, 0.005}, Phase::water);
  f.add({0.0, -0.005}, Phase::boundary, {0.0, 0.005});
  f.add({0.3, -0.005}, Phase::boundary, {0.3, 0.005});  // no water near its ghost: rests at ρ_w0
  f.finish({-0.1, -0.1, 0}, {0.5, 0.3, 0});
  for (std::size_t i = 0; i < f.position.size(); ++i)
    if (raw(f.phase)[i] == Phase::water) raw(f.water_density)[i] = 1003.0;
  f.run(SolidBoundaryWater<double, 2>{f.view(), f.grid, f.sph, f.water, nullptr});
  for (std::size_t i = 0; i < f.position.size(); ++i) {
    if (raw(f.phase)[i] != Phase::boundary) continue;
    const double expected = raw(f.position)[i][0] < 0.1 ? 1003.0 : 1000.0;
    EXPECT_NEAR(raw(f.water_density)[i], expected, 1e-9);
  }
}

TEST(EquationOfState, LinearWithArtificialSoundSpeed) {
  const WaterConstants<double> w{1000.0, 25.0, 0.1, 0.01};
  EXPECT_DOUBLE_EQ(w.pressure(1000.0), 0.0);
  EXPECT_DOUBLE_EQ(w.pressure(1001.0), 625.0);
  EXPECT_DOUBLE_EQ(w.density(w.pressure(997.5)), 997.5);
  // Eq. 24a: 10 max(v_max, sqrt(Δp/ρ)); a 0.3 m column: v = sqrt(2 g H), Δp = ρ g H.
  const double g = 9.81, H = 0.3;
  EXPECT_NEAR(artificial_sound_speed(std::sqrt(2 * g * H), 1000 * g * H, 1000), 10 * std::sqrt(2 * g * H), 1e-12);
  EXPECT_NEAR(artificial_sound_speed(0.1, 1000 * 9.81 * 2.0, 1000), 10 * std::sqrt(9.81 * 2.0), 1e-12);
}

// Free water cavitates at its vapour pressure: no gauge pressure below 2.339 − 101.325 kPa, however
// far it expands; above that the linear law is unchanged.
TEST(EquationOfState, CavitatesAtTheVapourPressure) {
  const WaterConstants<double> w{1000.0, 83.0, 0.1, 0.01};
  EXPECT_DOUBLE_EQ(w.pressure(130.0), -98986.0);                      // −6 MPa by the linear law
  EXPECT_DOUBLE_EQ(w.pressure(990.0), 83.0 * 83.0 * (990.0 - 1000.0));  // −68.9 kPa: above it
  EXPECT_DOUBLE_EQ(w.pressure(985.0), -98986.0);                      // −103 kPa by the linear law
}

}  // namespace
}  // namespace cascade
