// Scenario → initial particles: lattice fill of fluid bodies, dummy layers of solid boundaries and
// their ghost nodes (paper Section 3.3.1), hydrostatic start, Eq. 24a sound speed, case errors;
// soil bodies: porosity, pore pressure, geostatic stress, wetted walls, engine set-up.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/geometry.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/soil_setup.h"

namespace cascade {
namespace {

using v1::ScenarioSpec;

ScenarioSpec base_case(int dimensions, double dp, double h_over_dp = 1.3) {
  ScenarioSpec s;
  s.set_name("test");
  s.set_dimensions(dimensions);
  s.set_dp(dp);
  s.set_h_over_dp(h_over_dp);
  s.set_end_time(1.0);
  for (int c = 0; c < dimensions; ++c) s.add_gravity(c == dimensions - 1 ? -9.81 : 0.0);
  auto* water = s.add_materials();
  water->set_name("water");
  water->mutable_water()->set_density(1000.0);
  return s;
}

void set_domain(ScenarioSpec& s, std::vector<double> lo, std::vector<double> hi) {
  s.mutable_domain()->clear_min();
  s.mutable_domain()->clear_max();
  for (double v : lo) s.mutable_domain()->add_min(v);
  for (double v : hi) s.mutable_domain()->add_max(v);
}

void set_box(v1::Shape* shape, std::vector<double> lo, std::vector<double> hi) {
  for (double v : lo) shape->mutable_box()->add_min(v);
  for (double v : hi) shape->mutable_box()->add_max(v);
}

v1::Body* add_body(ScenarioSpec& s, const std::string& name, v1::BodyKind kind) {
  auto* b = s.add_bodies();
  b->set_name(name);
  b->set_kind(kind);
  if (kind == v1::FLUID) b->set_material("water");
  return b;
}

Vec3 at(const HostParticles& p, const std::vector<double>& field, std::size_t n) {
  return p.dimensions == 2 ? Vec3(field[2 * n], 0.0, field[2 * n + 1])
                           : Vec3(field[3 * n], field[3 * n + 1], field[3 * n + 2]);
}

// Index of the particle of `phase` at x (within dp/100), or -1.
long find(const HostParticles& p, const Vec3& x, Phase phase, double dp) {
  for (std::size_t n = 0; n < p.size(); ++n)
    if (p.phase[n] == phase && (at(p, p.position, n) - x).norm() < 0.01 * dp) return static_cast<long>(n);
  return -1;
}

std::string error_key(const ScenarioSpec& s) {
  try {
    build_particles(s);
  } catch (const CaseError& e) {
    return e.key();
  }
  return "(no error)";
}

// 2D tank: interior [0, 1] × [0, 0.7], walls 3 dp thick, domain = the tank's outer box; water
// fills [0, 1] × [0, 0.5].
constexpr double kTankDp = 0.02;
ScenarioSpec tank_2d(double h_over_dp) {
  const double t = 3 * kTankDp;
  ScenarioSpec s = base_case(2, kTankDp, h_over_dp);
  set_domain(s, {-t, -t}, {1 + t, 0.7});
  auto* tank = add_body(s, "tank", v1::BOUNDARY);
  set_box(tank->mutable_shape(), {-t, -t}, {1 + t, 0.7});
  set_box(tank->add_subtract(), {0, 0}, {1, 0.8});
  set_box(add_body(s, "water", v1::FLUID)->mutable_shape(), {0, 0}, {1, 0.5});
  return s;
}

TEST(ParticleBuilder, TankWaterAndDummyCountsAreExact) {
  // Wall thickness 3 dp. 2h = 2.6 dp → 3 layers: the walls are entirely dummy particles except the
  // corner point (2.5 dp, 2.5 dp) deep, 3.54 dp from the inner corner.
  ParticleSet set = build_particle_set(tank_2d(1.3));
  const HostParticles& p = set.particles;
  EXPECT_EQ(p.count(Phase::water), 50u * 25u);
  EXPECT_EQ(p.count(Phase::boundary), 2u * 3u * 35u + 3u * 50u + 2u * 8u);
  ASSERT_EQ(set.bodies.size(), 2u);
  EXPECT_NEAR(set.bodies[0].thickness, 3 * kTankDp, 1e-12);
  EXPECT_NEAR(set.bodies[0].wetted_surface, 1.0 + 2 * 0.7, 1e-9);  // floor + inner wall faces
  EXPECT_EQ(set.bodies[0].count, p.count(Phase::boundary));
  EXPECT_EQ(set.bodies[1].first, set.bodies[0].count);

  // h = 2 dp: 2h = 4 dp → 4 layers, deeper than the 3 dp walls: the wall stays 3 deep, the corner
  // keeps all 9 points, except none are beyond the walls.
  const HostParticles q = build_particles(tank_2d(2.0));
  EXPECT_EQ(q.count(Phase::boundary), 2u * 3u * 35u + 3u * 50u + 2u * 9u);
}

TEST(ParticleBuilder, TankGhostsMirrorAcrossFacesAndReflectThroughCorners) {
  const HostParticles p = build_particles(tank_2d(1.3));
  const double dp = kTankDp;
  const long floor = find(p, Vec3(0.49, 0, -dp / 2), Phase::boundary, dp);
  ASSERT_GE(floor, 0);
  EXPECT_LT((at(p, p.ghost, floor) - Vec3(0.49, 0, dp / 2)).norm(), 1e-12);
  const long deep = find(p, Vec3(0.49, 0, -2.5 * dp), Phase::boundary, dp);
  ASSERT_GE(deep, 0);
  EXPECT_LT((at(p, p.ghost, deep) - Vec3(0.49, 0, 2.5 * dp)).norm(), 1e-12);
  const long wall = find(p, Vec3(1 + 1.5 * dp, 0, 0.31), Phase::boundary, dp);
  ASSERT_GE(wall, 0);
  EXPECT_LT((at(p, p.ghost, wall) - Vec3(1 - 1.5 * dp, 0, 0.31)).norm(), 1e-12);
  const long corner = find(p, Vec3(-dp / 2, 0, -dp / 2), Phase::boundary, dp);
  ASSERT_GE(corner, 0);
  EXPECT_LT((at(p, p.ghost, corner) - Vec3(dp / 2, 0, dp / 2)).norm(), 1e-12);
  const long corner2 = find(p, Vec3(1 + 2.5 * dp, 0, -0.5 * dp), Phase::boundary, dp);
  ASSERT_GE(corner2, 0);
  EXPECT_LT((at(p, p.ghost, corner2) - Vec3(1 - 2.5 * dp, 0, 0.5 * dp)).norm(), 1e-12);
  EXPECT_LT(find(p, Vec3(-2.5 * dp, 0, -2.5 * dp), Phase::boundary, dp), 0);  // beyond 3 dp of the corner

  // Fluid ghosts are their positions; velocity zero; bodies tagged; (z, x) order within a body.
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] == Phase::water) {
      EXPECT_EQ(at(p, p.ghost, n), at(p, p.position, n));
      EXPECT_EQ(p.body[n], 1u);
    } else {
      EXPECT_EQ(p.body[n], 0u);
      EXPECT_NEAR(p.water_density[n], 1000.0, 0.0);
    }
    if (n > 0 && p.body[n] == p.body[n - 1]) {
      const Vec3 a = at(p, p.position, n - 1), b = at(p, p.position, n);
      EXPECT_TRUE(a.z() < b.z() || (a.z() == b.z() && a.x() < b.x())) << n;
    }
  }
}

// 3D: a floor slab, an obstacle box standing on it, water beside the obstacle.
ScenarioSpec obstacle_3d() {
  const double dp = 0.05;
  ScenarioSpec s = base_case(3, dp);
  set_domain(s, {0, 0, -0.15}, {1, 0.5, 0.6});
  set_box(add_body(s, "floor", v1::BOUNDARY)->mutable_shape(), {0, 0, -0.15}, {1, 0.5, 0});
  set_box(add_body(s, "obstacle", v1::BOUNDARY)->mutable_shape(), {0.3, 0.05, 0}, {0.7, 0.45, 0.2});
  set_box(add_body(s, "water", v1::FLUID)->mutable_shape(), {0, 0, 0}, {0.3, 0.5, 0.3});
  return s;
}

TEST(ParticleBuilder, ObstacleOnFloorGhostsStayOutOfSolids) {
  const ScenarioSpec s = obstacle_3d();
  const double dp = s.dp();
  const ParticleSet set = build_particle_set(s);
  const HostParticles& p = set.particles;
  EXPECT_EQ(p.count(Phase::water), 6u * 10u * 6u);

  auto inside = [](const Vec3& x, const Vec3& lo, const Vec3& hi) {
    return (x.array() > lo.array() + 1e-9).all() && (x.array() < hi.array() - 1e-9).all();
  };
  const Vec3 floor_lo(0, 0, -0.15), floor_hi(1, 0.5, 0), obst_lo(0.3, 0.05, 0), obst_hi(0.7, 0.45, 0.2);
  std::set<std::tuple<long, long, long>> sites;
  std::size_t obstacle_dummies = 0;
  for (std::size_t n = 0; n < p.size(); ++n) {
    const Vec3 x = at(p, p.position, n);
    EXPECT_TRUE(sites.emplace(std::lround(x.x() / dp * 2), std::lround(x.y() / dp * 2), std::lround(x.z() / dp * 2))
                    .second)
        << "duplicate particle at " << x.transpose();
    if (p.phase[n] != Phase::boundary) continue;
    const Vec3 g = at(p, p.ghost, n);
    EXPECT_FALSE(inside(g, floor_lo, floor_hi) || inside(g, obst_lo, obst_hi))
        << "body " << p.body[n] << " dummy " << x.transpose() << " ghost " << g.transpose();
    if (p.body[n] == 1) {
      ++obstacle_dummies;
      EXPECT_TRUE(inside(x, obst_lo, obst_hi));
    }
  }
  EXPECT_GT(obstacle_dummies, 0u);
  // Obstacle dummy next to its covered bottom face but 0.175 m from its wetted faces: dropped.
  EXPECT_LT(find(p, Vec3(0.475, 0.225, 0.025), Phase::boundary, dp), 0);
  // Floor under the obstacle's middle: more than 3 dp from any wetted surface, dropped.
  EXPECT_LT(find(p, Vec3(0.475, 0.225, -0.025), Phase::boundary, dp), 0);
  // Floor just under the obstacle's edge: kept once, as the floor's, reflected through the edge.
  const long edge = find(p, Vec3(0.325, 0.225, -0.025), Phase::boundary, dp);
  ASSERT_GE(edge, 0);
  EXPECT_EQ(p.body[edge], 0u);
  EXPECT_LT((at(p, p.ghost, edge) - Vec3(0.275, 0.225, 0.025)).norm(), 1e-12);
  // Floor beside the obstacle: a plane mirror through the floor's top.
  const long open = find(p, Vec3(0.825, 0.225, -0.075), Phase::boundary, dp);
  ASSERT_GE(open, 0);
  EXPECT_LT((at(p, p.ghost, open) - Vec3(0.825, 0.225, 0.075)).norm(), 1e-12);
  // Obstacle side: mirrored across the face x = 0.3.
  const long side = find(p, Vec3(0.325, 0.225, 0.125), Phase::boundary, dp);
  ASSERT_GE(side, 0);
  EXPECT_EQ(p.body[side], 1u);
  EXPECT_LT((at(p, p.ghost, side) - Vec3(0.275, 0.225, 0.125)).norm(), 1e-12);
  // Wetted: floor top minus the obstacle's footprint; obstacle: top and 4 sides.
  EXPECT_NEAR(set.bodies[0].wetted_surface, 0.5 - 0.4 * 0.4, 1e-9);
  EXPECT_NEAR(set.bodies[1].wetted_surface, 0.4 * 0.4 + 4 * 0.4 * 0.2, 1e-9);
}

TEST(ParticleBuilder, PolygonFillMatchesAreaInEitherOrientation) {
  const double dp = 0.01;
  for (bool reversed : {false, true}) {
    ScenarioSpec s = base_case(2, dp);
    set_domain(s, {-0.1, -0.1}, {1.1, 0.9});
    auto* poly = add_body(s, "wedge", v1::FLUID)->mutable_shape()->mutable_polygon();
    std::vector<std::pair<double, double>> v = {{0, 0}, {1, 0}, {0, 0.8}};
    if (reversed) std::reverse(v.begin(), v.end());
    for (auto [x, z] : v) {
      auto* q = poly->add_vertices();
      q->set_x(x);
      q->set_z(z);
    }
    const HostParticles p = build_particles(s);
    EXPECT_NEAR(double(p.size()), 0.4 / (dp * dp), 0.02 * 0.4 / (dp * dp));
    for (std::size_t n = 0; n < p.size(); ++n) {
      const Vec3 x = at(p, p.position, n);
      EXPECT_TRUE(x.x() > 0 && x.z() > 0 && x.x() / 1.0 + x.z() / 0.8 < 1.0) << x.transpose();
    }
  }
}

TEST(ParticleBuilder, ExtrudedPolygonFillAndGhosts) {
  const double dp = 0.02;
  ScenarioSpec s = base_case(3, dp);
  set_domain(s, {0, 0, 0}, {2, 0.5, 1});
  // A non-convex solid: an L-shaped step, extruded over the whole width.
  auto* step = add_body(s, "step", v1::BOUNDARY)->mutable_shape()->mutable_extruded_polygon();
  for (auto [x, z] : std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, 0.2}, {1, 0.2}, {1, 0.4}, {0, 0.4}}) {
    auto* q = step->add_vertices();
    q->set_x(x);
    q->set_z(z);
  }
  step->set_y_min(0);
  step->set_y_max(0.5);
  // Water: a trapezoid, extruded.
  auto* trap = add_body(s, "water", v1::FLUID)->mutable_shape()->mutable_extruded_polygon();
  for (auto [x, z] : std::vector<std::pair<double, double>>{{1, 0.2}, {2, 0.2}, {2, 0.6}, {1.4, 0.6}}) {
    auto* q = trap->add_vertices();
    q->set_x(x);
    q->set_z(z);
  }
  trap->set_y_min(0);
  trap->set_y_max(0.5);
  const ParticleSet set = build_particle_set(s);
  const HostParticles& p = set.particles;
  const double volume = 0.5 * (1.0 + 0.6) * 0.4 * 0.5;
  EXPECT_NEAR(double(p.count(Phase::water)), volume / std::pow(dp, 3), 0.03 * volume / std::pow(dp, 3));
  // Wetted: the two treads and the riser (caps and outer faces face out of the domain).
  EXPECT_NEAR(set.bodies[0].wetted_surface, (1.0 + 1.0 + 0.2) * 0.5, 1e-9);
  auto in_step = [](const Vec3& x) {
    return x.x() > 1e-9 && x.z() > 1e-9 && x.y() > 1e-9 && x.y() < 0.5 - 1e-9 &&
           ((x.x() < 1 - 1e-9 && x.z() < 0.4 - 1e-9) || (x.x() < 2 - 1e-9 && x.z() < 0.2 - 1e-9));
  };
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] != Phase::boundary) continue;
    const Vec3 x = at(p, p.position, n), g = at(p, p.ghost, n);
    EXPECT_TRUE(in_step(x));
    EXPECT_FALSE(in_step(g)) << x.transpose() << " → " << g.transpose();
  }
  // Below the tread x > 1: plane mirror; diagonally below the foot of the riser (the solid's
  // re-entrant corner), point reflection through the corner.
  const long tread = find(p, Vec3(1.51, 0.25, 0.15), Phase::boundary, dp);
  ASSERT_GE(tread, 0);
  EXPECT_LT((at(p, p.ghost, tread) - Vec3(1.51, 0.25, 0.25)).norm(), 1e-12);
  const long foot = find(p, Vec3(0.99, 0.25, 0.19), Phase::boundary, dp);
  ASSERT_GE(foot, 0);
  EXPECT_LT((at(p, p.ghost, foot) - Vec3(1.01, 0.25, 0.21)).norm(), 1e-12);
  const long riser = find(p, Vec3(0.97, 0.25, 0.29), Phase::boundary, dp);
  ASSERT_GE(riser, 0);
  EXPECT_LT((at(p, p.ghost, riser) - Vec3(1.03, 0.25, 0.29)).norm(), 1e-12);
}

TEST(ParticleBuilder, HalfSpaceSlopeGhostsMirrorAcrossThePlane) {
  const double dp = 0.01;
  ScenarioSpec s = base_case(2, dp);
  set_domain(s, {0, 0}, {1, 1});
  auto* slope = add_body(s, "slope", v1::BOUNDARY)->mutable_shape()->mutable_half_space();
  slope->add_point(0), slope->add_point(0.2);
  slope->add_normal(-0.5), slope->add_normal(1.0);
  set_box(add_body(s, "water", v1::FLUID)->mutable_shape(), {0, 0}, {1, 0.6});
  const HostParticles p = build_particles(s);
  const Vec3 n = Vec3(-0.5, 0, 1).normalized(), origin(0, 0, 0.2);
  const double thickness = 3 * dp;
  std::size_t mirrored = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 x = at(p, p.position, i);
    const double d = (x - origin).dot(n);
    if (p.phase[i] == Phase::water) {
      EXPECT_GT(d, 0.0);
      continue;
    }
    EXPECT_LE(d, 0.0);
    EXPECT_GT(d, -thickness);
    const Vec3 g = at(p, p.ghost, i);
    EXPECT_GT((g - origin).dot(n), 0.0) << x.transpose();
    const Vec3 foot = x - d * n;  // projection onto the plane
    if (foot.x() > 0.0 && foot.x() < 1.0 && foot.z() < 1.0) {
      EXPECT_NEAR((g - origin).dot(n), -d, 1e-12);
      EXPECT_LT((g - (x - 2 * d * n)).norm(), 1e-12);
      ++mirrored;
    }
  }
  EXPECT_GT(mirrored, 250u);  // ~ 3 layers along the 1.12 m of slope
  // Count: every lattice point of the domain within 3 dp below the plane and with its foot in the
  // domain is a dummy particle.
  EXPECT_GE(p.count(Phase::boundary), mirrored);
}

TEST(ParticleBuilder, HydrostaticDensityProfile) {
  ScenarioSpec s = tank_2d(1.3);
  s.mutable_bodies(1)->mutable_initial()->set_hydrostatic(true);
  const double g = 9.81, rho0 = 1000.0;
  // Eq. 24a from the water height H = 0.5 m: v_max = sqrt(2 g H) beats sqrt(Δp/ρ) = sqrt(g H).
  const double c0 = 10.0 * std::sqrt(2 * g * 0.5);
  const HostParticles p = build_particles(s);
  EXPECT_NEAR(water_sound_speed(s, 0, p), c0, 1e-9);
  std::size_t checked = 0;
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] != Phase::water) continue;
    const double z = at(p, p.position, n).z();
    EXPECT_NEAR(p.water_density[n], rho0 + rho0 * g * (0.5 - z) / (c0 * c0), 1e-9);
    ++checked;
  }
  EXPECT_EQ(checked, 1250u);

  s.mutable_materials(0)->mutable_water()->set_sound_speed(30.0);
  EXPECT_DOUBLE_EQ(water_sound_speed(s, 0, p), 30.0);
  const HostParticles q = build_particles(s);
  const long bottom = find(q, Vec3(0.51, 0, 0.01), Phase::water, kTankDp);
  ASSERT_GE(bottom, 0);
  EXPECT_NEAR(q.water_density[bottom], rho0 + rho0 * g * 0.49 / 900.0, 1e-9);
  s.mutable_materials(0)->mutable_water()->set_sound_speed(0.0);
  s.mutable_materials(0)->mutable_water()->set_max_speed(5.0);
  s.mutable_materials(0)->mutable_water()->set_max_pressure(1e5);
  EXPECT_NEAR(water_sound_speed(s, 0, p), 100.0, 1e-9);  // sqrt(1e5 / 1000) = 10 > 5
}

TEST(ParticleBuilder, FirstFluidBodyWinsAndVelocityIsSet) {
  ScenarioSpec s = base_case(2, 0.1);
  set_domain(s, {0, 0}, {2, 1});
  set_box(add_body(s, "a", v1::FLUID)->mutable_shape(), {0, 0}, {1, 1});
  auto* b = add_body(s, "b", v1::FLUID);
  set_box(b->mutable_shape(), {0.5, 0}, {2, 1});
  b->mutable_initial()->add_velocity(1.5);
  b->mutable_initial()->add_velocity(-0.5);
  const ParticleSet set = build_particle_set(s);
  EXPECT_EQ(set.bodies[0].count, 100u);
  EXPECT_EQ(set.bodies[1].count, 100u);
  for (std::size_t n = set.bodies[1].first; n < set.particles.size(); ++n) {
    EXPECT_GT(set.particles.position[2 * n], 1.0);
    EXPECT_EQ(set.particles.velocity[2 * n], 1.5);
    EXPECT_EQ(set.particles.velocity[2 * n + 1], -0.5);
  }
}

TEST(ParticleBuilder, PeriodicAxisWrapsSolidsAndClipsBodies) {
  // A channel periodic in x: the floor's end faces touch its own periodic image, so only its top
  // is wetted; a floor longer than the domain is clipped to it rather than refused.
  const double dp = 0.02;
  for (double floor_end : {1.0, 1.3}) {
    ScenarioSpec s = base_case(2, dp);
    set_domain(s, {0, -0.06}, {1, 0.5});
    for (bool p : {true, false}) s.mutable_domain()->add_periodic(p);
    set_box(add_body(s, "floor", v1::BOUNDARY)->mutable_shape(), {-0.3, -0.06}, {floor_end, 0});
    set_box(add_body(s, "water", v1::FLUID)->mutable_shape(), {-0.5, 0}, {1.5, 0.2});
    const ParticleSet set = build_particle_set(s);
    const HostParticles& p = set.particles;
    EXPECT_EQ(p.count(Phase::water), 50u * 10u);
    EXPECT_EQ(p.count(Phase::boundary), 50u * 3u);
    EXPECT_NEAR(set.bodies[0].wetted_surface, 1.0, 1e-9);
    for (std::size_t n = 0; n < p.size(); ++n) {
      const Vec3 x = at(p, p.position, n);
      EXPECT_TRUE(x.x() > 0 && x.x() < 1) << x.transpose();
      if (p.phase[n] == Phase::boundary)
        EXPECT_LT((at(p, p.ghost, n) - Vec3(x.x(), 0, -x.z())).norm(), 1e-12) << x.transpose();
    }
  }
}

TEST(ParticleBuilder, CaseErrorsNameTheKey) {
  {  // water entirely inside the tank wall
    ScenarioSpec s = tank_2d(1.3);
    set_box(add_body(s, "buried", v1::FLUID)->mutable_shape(), {-0.05, 0.1}, {-0.01, 0.2});
    EXPECT_EQ(error_key(s), "bodies[2]");
  }
  {  // water sticking out of the domain
    ScenarioSpec s = tank_2d(1.3);
    s.mutable_bodies(1)->mutable_shape()->mutable_box()->set_max(1, 0.9);
    EXPECT_EQ(error_key(s), "bodies[1]");
  }
  {
    ScenarioSpec s = tank_2d(1.3);
    s.mutable_bodies(1)->set_material("oil");
    EXPECT_EQ(error_key(s), "bodies[1].material");
  }
  {  // 10^10 particles: refused before any is made
    ScenarioSpec s = tank_2d(1.3);
    s.set_dp(1e-5);
    EXPECT_EQ(error_key(s), "dp");
  }
  {
    ScenarioSpec s = base_case(3, 0.1);
    set_domain(s, {0, 0, 0}, {1, 1, 1});
    auto* poly = add_body(s, "p", v1::FLUID)->mutable_shape()->mutable_polygon();
    for (int k = 0; k < 3; ++k) poly->add_vertices()->set_x(k);
    EXPECT_EQ(error_key(s), "bodies[0].shape.polygon");
  }
  {
    ScenarioSpec s = base_case(2, 0.1);
    set_domain(s, {0, 0}, {1, 1});
    add_body(s, "nothing", v1::FLUID);
    EXPECT_EQ(error_key(s), "bodies[0].shape");
  }
  {
    ScenarioSpec s = base_case(2, 0.1);
    set_domain(s, {0, 0}, {1, 1});
    set_box(add_body(s, "flat", v1::FLUID)->mutable_shape(), {0, 0}, {1, 0});
    EXPECT_EQ(error_key(s), "bodies[0].shape.box.max");
  }
  {
    ScenarioSpec s = base_case(2, 0.1);
    set_domain(s, {0, 0}, {1, 1});
    EXPECT_EQ(error_key(s), "domain");
  }
  {  // a floor whose only face lies on the domain's edge: no wetted surface, no dummy particles
    ScenarioSpec s = tank_2d(1.3);
    set_box(add_body(s, "buried_floor", v1::BOUNDARY)->mutable_shape(), {-0.06, -0.06}, {1.06, -0.04});
    EXPECT_EQ(error_key(s), "bodies[2]");
  }
}

TEST(Geometry, RegionSurfaceOfATankAndClosestPoints) {
  // Box minus a box poking out of its top: floor and the two inner walls, plus outer faces.
  const Region tank(Shape::box({-1, -1}, {3, 2}, 2, "s"), {Shape::box({0, 0}, {2, 5}, 2, "t")});
  double inner = 0.0, outer = 0.0;
  for (const Face& f : tank.surface(1e-6)) {
    const Vec3 mid = 0.5 * (f.vertices[0] + f.vertices[1]);
    const bool is_inner = mid.x() >= 0 && mid.x() <= 2 && mid.z() >= 0;
    (is_inner ? inner : outer) += f.measure();
    if (is_inner) EXPECT_FALSE(tank.contains(mid + 0.01 * f.normal)) << mid.transpose();
    else EXPECT_FALSE(tank.contains(mid + 0.01 * f.normal));
    EXPECT_TRUE(tank.contains(mid - 0.01 * f.normal)) << mid.transpose();
  }
  EXPECT_NEAR(inner, 2.0 + 2 * 2.0, 1e-12);
  EXPECT_NEAR(outer, 4 + 2 * 3 + 2 * 1, 1e-12);  // bottom, outer sides, two wall tops

  const Face tri = Face::make({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, Vec3(0, 0, 1));
  EXPECT_LT((tri.closest_point(Vec3(0.2, 0.2, 3)) - Vec3(0.2, 0.2, 0)).norm(), 1e-15);
  EXPECT_LT((tri.closest_point(Vec3(1, 1, -1)) - Vec3(0.5, 0.5, 0)).norm(), 1e-15);
  EXPECT_LT((tri.closest_point(Vec3(-1, -2, 0)) - Vec3(0, 0, 0)).norm(), 1e-15);
}

// --- Soil bodies ----------------------------------------------------------------------------------

constexpr double kG = 9.81;
constexpr double kRho = 1000.0;

// Table 2's soil as a material of `s`: van Genuchten (S_min 0.3, λ 0.447, p_ref 19357 Pa); linear
// elastic E = 50 MPa, ν = 0.3 unless `rigid`.
void add_soil_material(ScenarioSpec& s, const std::string& name, bool rigid, double bulk_modulus = 2e6) {
  auto* m = s.add_materials();
  m->set_name(name);
  auto* soil = m->mutable_soil();
  soil->set_grain_density(2650);
  soil->set_porosity(0.3);
  soil->set_saturated_conductivity(1e-3);
  soil->set_water_bulk_modulus(bulk_modulus);
  auto* vg = soil->mutable_hydraulic()->mutable_van_genuchten();
  vg->set_s_min(0.3);
  vg->set_s_max(1.0);
  vg->set_lambda(0.447);
  vg->set_p_ref(19357);
  soil->set_rigid(rigid);
  if (!rigid) {
    soil->mutable_mechanical()->mutable_linear_elastic()->set_youngs_modulus(50e6);
    soil->mutable_mechanical()->mutable_linear_elastic()->set_poisson_ratio(0.3);
  }
}

// Eq. 14 (ERRATA.md) written out here, apart from the model's code.
double table2_saturation(double p_c) {
  if (p_c <= 0) return 1.0;
  return 0.3 + 0.7 * std::pow(1.0 + std::pow(p_c / 19357.0, 1.0 / (1.0 - 0.447)), -0.447);
}

// A soil-only 2D case: no water material, gravity -z.
ScenarioSpec soil_case(double dp, double h_over_dp) {
  ScenarioSpec s;
  s.set_name("soil");
  s.set_dimensions(2);
  s.set_dp(dp);
  s.set_h_over_dp(h_over_dp);
  s.set_end_time(1.0);
  s.add_gravity(0.0);
  s.add_gravity(-kG);
  return s;
}

// Every particle has the soil fields: zeros except for soil particles.
void expect_soil_fields_sized(const HostParticles& p) {
  ASSERT_EQ(p.porosity.size(), p.size());
  ASSERT_EQ(p.soil_material.size(), p.size());
  ASSERT_EQ(p.effective_stress.size(), 6 * p.size());
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] == Phase::soil) continue;
    EXPECT_EQ(p.porosity[n], 0.0);
    for (int c = 0; c < 6; ++c) EXPECT_EQ(p.effective_stress[6 * n + c], 0.0);
  }
}

TEST(SoilBuilder, InfiltrationColumnCountsPorePressureAndGeostaticStress) {
  const ScenarioSpec spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/infiltration_1d.yaml");
  const ParticleSet set = build_particle_set(spec);
  const HostParticles& p = set.particles;
  // 12 columns of 150 soil particles on 4 dummy layers (2h = 3.6 dp); the base's bottom lies on
  // the domain's edge and its sides meet their periodic images: only its top is wetted.
  EXPECT_EQ(p.count(Phase::soil), 12u * 150u);
  EXPECT_EQ(p.count(Phase::boundary), 12u * 4u);
  EXPECT_EQ(p.count(Phase::water), 0u);
  EXPECT_NEAR(set.bodies[0].wetted_surface, 0.24, 1e-12);
  expect_soil_fields_sized(p);

  const double phi = 0.4, rho_s = 2650, kw = 2e6;
  std::size_t checked = 0;
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] == Phase::boundary) {
      EXPECT_EQ(p.water_density[n], kRho);
      continue;
    }
    ASSERT_EQ(p.phase[n], Phase::soil);
    const double z = at(p, p.position, n).z();
    EXPECT_EQ(p.porosity[n], phi);
    EXPECT_EQ(p.soil_material[n], 0);
    // Water table at z = 0: p_w = -ρ_w0 g z (Section 4.1), as the pore-water density of Eq. 36b.
    const double p_w = -kRho * kG * z;
    EXPECT_NEAR(p.water_density[n], kRho * (1 + p_w / kw), 1e-9);
    // Geostatic stress by hand: Gardner's S_w = 0.23 + 0.77 exp(-2 z) integrates in closed form,
    // σ_zz = -g ∫_z^3 [(1 - φ) ρ_s + φ ρ_w0 S_w] dz'; σ' = σ_zz + S_w p_w (Eq. 7); rigid: K0 = 1.
    const double depth = 3.0 - z;
    const double total =
        -kG * ((1 - phi) * rho_s * depth + phi * kRho * (0.23 * depth + 0.385 * (std::exp(-2 * z) - std::exp(-6.0))));
    const double effective = total + (0.23 + 0.77 * std::exp(-2 * z)) * p_w;
    const double* stress = &p.effective_stress[6 * n];
    EXPECT_NEAR(stress[2], effective, 1e-9 * std::abs(effective) + 1e-9) << "z = " << z;
    EXPECT_NEAR(stress[0], effective, 1e-9 * std::abs(effective) + 1e-9);
    EXPECT_NEAR(stress[1], effective, 1e-9 * std::abs(effective) + 1e-9);
    for (int c = 3; c < 6; ++c) EXPECT_EQ(stress[c], 0.0);
    if (std::abs(z - 1.01) < 1e-9) ++checked;
  }
  EXPECT_EQ(checked, 12u);  // one depth in every column
  // At z = 1.01 m, worked out by hand: σ_zz = -33.03 kPa, S_w p_w = 0.3322 × (-9.908 kPa) =
  // -3.29 kPa, so σ'_zz = -36.32 kPa.
  const long n = find(p, Vec3(0.13, 0, 1.01), Phase::soil, 0.02);
  ASSERT_GE(n, 0);
  EXPECT_NEAR(p.effective_stress[6 * n + 2], -36323.4, 0.1);
}

TEST(SoilBuilder, SubmergedSoilCarriesItsBuoyantWeight) {
  // Soil 0.5 m deep under water standing to z = 0.8: water table at the water surface. The
  // effective stress is the buoyant weight, -(ρ_sat - ρ_w0) g (0.5 - z), K0 = ν/(1 - ν).
  ScenarioSpec s = base_case(2, 0.02, 1.8);
  add_soil_material(s, "sand", false);
  set_domain(s, {0, -0.08}, {0.24, 1.0});
  for (bool periodic : {true, false}) s.mutable_domain()->add_periodic(periodic);
  set_box(add_body(s, "base", v1::BOUNDARY)->mutable_shape(), {0, -0.08}, {0.24, 0});
  auto* soil = add_body(s, "bed", v1::FLUID);
  soil->set_material("sand");
  set_box(soil->mutable_shape(), {0, 0}, {0.24, 0.5});
  soil->mutable_initial()->set_water_table(0.8);
  auto* water = add_body(s, "sea", v1::FLUID);  // after the soil: fills the box above it only
  set_box(water->mutable_shape(), {0, 0}, {0.24, 0.8});
  water->mutable_initial()->set_hydrostatic(true);
  const ParticleSet set = build_particle_set(s);
  const HostParticles& p = set.particles;
  EXPECT_EQ(p.count(Phase::soil), 12u * 25u);
  EXPECT_EQ(p.count(Phase::water), 12u * 15u);
  EXPECT_EQ(p.count(Phase::boundary), 12u * 4u);
  expect_soil_fields_sized(p);
  const double rho_sat = 0.7 * 2650 + 0.3 * kRho, k0 = 0.3 / 0.7;
  for (std::size_t n = 0; n < p.size(); ++n) {
    const double z = at(p, p.position, n).z();
    if (p.phase[n] == Phase::water) EXPECT_GT(z, 0.5);
    if (p.phase[n] != Phase::soil) continue;
    EXPECT_NEAR(p.water_density[n], kRho * (1 + kRho * kG * (0.8 - z) / 2e6), 1e-9);
    const double buoyant = -(rho_sat - kRho) * kG * (0.5 - z);
    EXPECT_NEAR(p.effective_stress[6 * n + 2], buoyant, 1e-8) << "z = " << z;
    EXPECT_NEAR(p.effective_stress[6 * n + 0], k0 * buoyant, 1e-8);
    EXPECT_NEAR(p.effective_stress[6 * n + 1], k0 * buoyant, 1e-8);
  }
  // k0 given: it replaces ν/(1 - ν).
  s.mutable_bodies(1)->mutable_initial()->set_k0(0.8);
  const HostParticles q = build_particles(s);
  const long n = find(q, Vec3(0.05, 0, 0.25), Phase::soil, 0.02);
  ASSERT_GE(n, 0);
  EXPECT_NEAR(q.effective_stress[6 * n + 0], 0.8 * q.effective_stress[6 * n + 2], 1e-9);
}

TEST(SoilBuilder, StressFromEachColumnsOwnTop) {
  // An L-shaped soil body (tall at x < 0.12, low beyond) at a uniform suction of 10 kPa: the
  // vertical stress of a particle is the weight of its own column, σ_zz = -ρ_s g (z_top - z).
  ScenarioSpec s = soil_case(0.02, 1.5);
  add_soil_material(s, "sand", true);
  set_domain(s, {0, 0}, {0.24, 0.6});
  auto* b = add_body(s, "step", v1::FLUID);
  b->set_material("sand");
  auto* poly = b->mutable_shape()->mutable_polygon();
  for (auto [x, z] : std::vector<std::pair<double, double>>{{0, 0}, {0.24, 0}, {0.24, 0.3}, {0.12, 0.3}, {0.12, 0.5},
                                                           {0, 0.5}}) {
    auto* v = poly->add_vertices();
    v->set_x(x);
    v->set_z(z);
  }
  b->mutable_initial()->set_suction(1e4);
  const HostParticles p = build_particles(s);
  EXPECT_EQ(p.count(Phase::soil), 6u * 25u + 6u * 15u);
  const double s_w = table2_saturation(1e4);
  const double rho_mix = 0.7 * 2650 + s_w * 0.3 * kRho;  // Eq. 28a with ρ_w0 = 1000 (no water material)
  for (auto [x, top] : std::vector<std::pair<double, double>>{{0.05, 0.5}, {0.17, 0.3}}) {
    const long n = find(p, Vec3(x, 0, 0.09), Phase::soil, 0.02);
    ASSERT_GE(n, 0);
    const double effective = -rho_mix * kG * (top - 0.09) + s_w * -1e4;
    EXPECT_NEAR(p.effective_stress[6 * n + 2], effective, 1e-8 * std::abs(effective)) << "x = " << x;
    EXPECT_NEAR(p.effective_stress[6 * n + 0], effective, 1e-8 * std::abs(effective));  // rigid: K0 = 1
    EXPECT_NEAR(p.water_density[n], kRho * (1 - 1e4 / 2e6), 1e-12);
  }
}

TEST(SoilBuilder, SoilIsWettedLikeWater) {
  // The tank of TankWaterAndDummyCountsAreExact with soil for water: the same dummy layers.
  ScenarioSpec s = tank_2d(1.3);
  add_soil_material(s, "sand", false);
  s.mutable_bodies(1)->set_material("sand");
  const HostParticles p = build_particles(s);
  EXPECT_EQ(p.count(Phase::soil), 50u * 25u);
  EXPECT_EQ(p.count(Phase::water), 0u);
  EXPECT_EQ(p.count(Phase::boundary), 2u * 3u * 35u + 3u * 50u + 2u * 8u);
  for (std::size_t n = 0; n < p.size(); ++n)
    if (p.phase[n] == Phase::soil) EXPECT_EQ(p.soil_material[n], 0);  // the only soil, though materials[1]
}

TEST(SoilBuilder, SoilMaterialIndexCountsSoilsOnly) {
  ScenarioSpec s = soil_case(0.1, 1.3);
  add_soil_material(s, "clay", true);
  s.add_materials()->set_name("water");
  s.mutable_materials(1)->mutable_water();
  add_soil_material(s, "sand", true);
  set_domain(s, {0, 0}, {1, 1});
  auto* lower = add_body(s, "lower", v1::FLUID);
  lower->set_material("sand");
  set_box(lower->mutable_shape(), {0, 0}, {1, 0.5});
  auto* upper = add_body(s, "upper", v1::FLUID);
  upper->set_material("clay");
  set_box(upper->mutable_shape(), {0, 0.5}, {1, 1});
  const ParticleSet set = build_particle_set(s);
  for (std::size_t n = 0; n < set.particles.size(); ++n)
    EXPECT_EQ(set.particles.soil_material[n], n < set.bodies[1].first ? 1 : 0);  // sand is soils[1]
}

TEST(SoilBuilder, PorePressureBelowMinusKwIsACaseError) {
  ScenarioSpec s = soil_case(0.02, 1.3);
  add_soil_material(s, "sand", true, 2e5);
  set_domain(s, {0, 0}, {0.5, 1});
  auto* b = add_body(s, "dry", v1::FLUID);
  b->set_material("sand");
  set_box(b->mutable_shape(), {0, 0}, {0.5, 0.5});
  b->mutable_initial()->set_water_table(-25);  // p_w = -255 kPa at the top: below -K_w = -200 kPa
  EXPECT_EQ(error_key(s), "bodies[0].initial.water_table");
  b->mutable_initial()->set_water_table(-15);
  EXPECT_EQ(error_key(s), "(no error)");
}

TEST(SoilBuilder, EngineConfigOfSoilCases) {
  // Soil only: ρ_w0 = 1000, no free water (c_w0 = 0), one SoilMaterial, the forcing at t = 0.
  ScenarioSpec s = soil_case(0.02, 1.3);
  add_soil_material(s, "sand", false, 5e5);
  set_domain(s, {0, 0}, {0.5, 1});
  auto* b = add_body(s, "column", v1::FLUID);
  b->set_material("sand");
  set_box(b->mutable_shape(), {0, 0}, {0.5, 0.5});
  auto* rain = s.mutable_hydraulics()->add_rainfall();
  rain->set_time(0);
  rain->set_intensity(3e-6);
  s.mutable_hydraulics()->add_rainfall()->set_time(100);
  s.mutable_hydraulics()->set_drying_pressure(-1e4);
  const HostParticles p = build_particles(s);
  EngineConfig c = engine_config(s, p, Precision::double_precision);
  EXPECT_DOUBLE_EQ(c.water_density, 1000);
  EXPECT_DOUBLE_EQ(c.sound_speed, 0);
  ASSERT_EQ(c.soils.size(), 1u);
  EXPECT_DOUBLE_EQ(c.soils[0].water_bulk_modulus, 5e5);
  EXPECT_DOUBLE_EQ(c.soils[0].grain_density, 2650);
  EXPECT_DOUBLE_EQ(c.soils[0].mechanical.youngs_modulus, 50e6);
  EXPECT_DOUBLE_EQ(c.forcing.rainfall_intensity, 3e-6);
  EXPECT_DOUBLE_EQ(c.forcing.ponding_pressure, 0);
  EXPECT_DOUBLE_EQ(c.forcing.drying_pressure, -1e4);
  EXPECT_FALSE(c.forcing.has_region);
  EXPECT_DOUBLE_EQ(hydraulic_forcing(s, 100).rainfall_intensity, 0);

  // With water: ρ_w0 and c_w0 are the water's.
  ScenarioSpec w = s;
  auto* water = w.add_materials();
  water->set_name("water");
  water->mutable_water()->set_density(1025);
  water->mutable_water()->set_sound_speed(20);
  auto* pool = add_body(w, "pool", v1::FLUID);
  set_box(pool->mutable_shape(), {0, 0.5}, {0.5, 0.7});
  c = engine_config(w, build_particles(w), Precision::double_precision);
  EXPECT_DOUBLE_EQ(c.water_density, 1025);
  EXPECT_DOUBLE_EQ(c.sound_speed, 20);
  EXPECT_EQ(c.soils.size(), 1u);

  // Neither water nor soil.
  ScenarioSpec none = s;
  none.mutable_materials(0)->clear_soil();
  EXPECT_THROW(engine_config(none, p, Precision::double_precision), CaseError);
}

}  // namespace
}  // namespace cascade
