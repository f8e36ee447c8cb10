// A 2D soil column built particle by particle for the soil validation tests, apart from the case
// loader: periodic in x (z up), soil on three layers of dummy particles below z = 0, whose ghost
// nodes mirror them across the wall. The caller gives the soil, the initial pore pressure and
// effective stress as functions of z.
#pragma once

#include <cmath>
#include <functional>

#include "server/core/engine.h"
#include "server/physics/soil_momentum.h"

namespace cascade::testing {

struct SoilColumn {
  double dp = 0.01;
  double h_over_dp = 1.3;
  double height = 0.6;      // m of soil above the wall at z = 0
  int columns = 12;         // periodic width: columns · dp, at least 6.3 h
  double water_density = 1000.0;
  double gravity = 9.81;
  double porosity = 0.4;
  SoilMaterial soil;
  std::function<double(double)> pore_pressure = [](double) { return 0.0; };            // p_w(z), Pa
  std::function<Voigt<double>(double)> effective_stress = [](double) { return Voigt<double>::Zero(); };
  HydraulicForcing forcing;

  double top_layer() const { return height - 0.5 * dp; }  // z of the top particles

  HostParticles particles() const {
    HostParticles p;
    p.dimensions = 2;
    auto add = [&](double x, double z, Phase phase, double ghost_z) {
      const bool is_soil = phase == Phase::soil;
      p.position.insert(p.position.end(), {x, z});
      p.velocity.insert(p.velocity.end(), {0.0, 0.0});
      p.ghost.insert(p.ghost.end(), {x, ghost_z});
      p.phase.push_back(phase);
      p.body.push_back(is_soil ? 0 : 1);
      p.water_density.push_back(is_soil ? water_density * (1 + pore_pressure(z) / soil.water_bulk_modulus)
                                        : water_density);
      p.porosity.push_back(is_soil ? porosity : 0.0);
      p.soil_material.push_back(0);
      const Voigt<double> s = is_soil ? effective_stress(z) : Voigt<double>::Zero();
      p.effective_stress.insert(p.effective_stress.end(), s.data(), s.data() + 6);
    };
    const int layers = int(std::lround(height / dp));
    for (int k = 0; k < layers; ++k)
      for (int i = 0; i < columns; ++i) add((i + 0.5) * dp, (k + 0.5) * dp, Phase::soil, (k + 0.5) * dp);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < columns; ++i) add((i + 0.5) * dp, -(k + 0.5) * dp, Phase::boundary, (k + 0.5) * dp);
    return p;
  }

  EngineConfig config() const {
    EngineConfig e;
    e.dimensions = 2;
    e.dp = dp;
    e.h = h_over_dp * dp;
    e.gravity = {0.0, -gravity, 0.0};
    e.domain_min = {0.0, -0.05, 0.0};
    e.domain_max = {columns * dp, height + 0.05, 0.0};
    e.periodic = {true, false, false};
    e.water_density = water_density;
    e.soils = {soil};
    e.soils[0].reference_porosity = porosity;  // the retention curve holds at the initial porosity
    e.forcing = forcing;
    return e;
  }
};

// Hydrostatic pore pressure of the weakly compressible pore water, dp/dz = −ρ_w0 (1 + p/K_w) g
// (Eq. 6), zero at z_surface.
inline double compressible_hydrostatic(double rho0, double g, double bulk_modulus, double z_surface, double z) {
  return bulk_modulus * std::expm1(rho0 * g * (z_surface - z) / bulk_modulus);
}

}  // namespace cascade::testing
