// Cundall's local damping of the geostatic stage (server/physics/local_damping.h) on one particle:
// a_k ← a_k − α |a_k| sign(v_k), the undamped |a| kept, and the equilibrium measure of one particle.
#include <gtest/gtest.h>

#include <cmath>

#include "server/physics/local_damping.h"
#include "server/physics/swcc/gardner.h"

namespace cascade {
namespace {

using V = Vec<double, 2>;

struct OneParticle {
  V velocity, acceleration;
  double unbalanced = -1;

  V damped(double alpha) {
    ParticleView<double, 2> p{};
    p.velocity = &velocity;
    p.acceleration = &acceleration;
    LocalDamping<double, 2>{p, &unbalanced, alpha}(0);
    return acceleration;
  }
};

TEST(GeostaticLocalDamping, OpposesTheVelocityInProportionToTheForce) {
  const double alpha = 0.8;
  // Accelerating along its motion: each component loses α of its magnitude.
  OneParticle along{V(1.0, -2.0), V(3.0, -4.0)};
  const V a = along.damped(alpha);
  EXPECT_DOUBLE_EQ(a[0], 3.0 * (1 - alpha));
  EXPECT_DOUBLE_EQ(a[1], -4.0 * (1 - alpha));
  EXPECT_DOUBLE_EQ(along.unbalanced, 5.0);
  // Decelerating: the damping force, against the velocity, adds α of the magnitude.
  OneParticle against{V(-1.0, 2.0), V(3.0, -4.0)};
  const V b = against.damped(alpha);
  EXPECT_DOUBLE_EQ(b[0], 3.0 * (1 + alpha));
  EXPECT_DOUBLE_EQ(b[1], -4.0 * (1 + alpha));
  // No velocity in a component: no damping there (sign(0) = 0).
  OneParticle still{V(0.0, 2.0), V(3.0, 4.0)};
  const V c = still.damped(alpha);
  EXPECT_EQ(c[0], 3.0);
  EXPECT_DOUBLE_EQ(c[1], 4.0 * (1 - alpha));
}

TEST(GeostaticLocalDamping, ZeroCoefficientLeavesTheAccelerationAsItIs) {
  OneParticle moving{V(0.3, -0.7), V(-2.5, 9.75)};
  const V a = moving.damped(0.0);
  EXPECT_EQ(a[0], -2.5);
  EXPECT_EQ(a[1], 9.75);
  EXPECT_DOUBLE_EQ(moving.unbalanced, std::hypot(2.5, 9.75));
}

TEST(GeostaticLocalDamping, EquilibriumOfOneParticleIsItsAccelerationOverGravity) {
  SoilMaterial soil;
  soil.grain_density = 2650;
  soil.hydraulic = HydraulicModel<double>(Gardner<double>{0.2, 1.0, 2.0, 9810.0});
  const double porosity = 0.3, saturation = 0.5, density = 1010.0, unbalanced = 0.5, mass = 10.0;
  const std::uint8_t material = 0;
  const V velocity(0.03, -0.04);
  const EquilibriumOfParticle<double, 2> of{&soil,      &material,  &porosity, &saturation, &density,
                                            &velocity,  &unbalanced, mass,     9.81,        1000.0};
  const EquilibriumSums<double> sums = of(0);
  const double m = ((1 - porosity) * 2650 + saturation * porosity * 1000.0) * mass / density;  // ρ_s V (Eq. 28a)
  EXPECT_DOUBLE_EQ(sums.max_force, m * unbalanced);
  EXPECT_DOUBLE_EQ(sums.weight, m * 9.81);
  EXPECT_EQ(sums.particles, 1.0);
  EXPECT_DOUBLE_EQ(sums.max_speed, 0.05);
  soil.rigid = true;  // a rigid skeleton takes no part
  EXPECT_EQ(of(0).particles, 0.0);
}

}  // namespace
}  // namespace cascade
