// Raw pointers into the soil and pore-water arrays, handed to the soil kernels by value at each
// launch (the soil counterpart of ParticleView). For a soil particle the ParticleView fields
// water_density and pressure hold its pore water's ρ_w and p_w; for a dummy particle they belong
// to the free water, and its soil side, seen by soil neighbours only, is here.
#pragma once

#include <cstdint>

#include "server/core/soil_material.h"
#include "server/core/types.h"
#include "server/physics/pore_water_account.h"
#include "server/physics/soil_momentum.h"

namespace cascade {

// How a free-surface soil particle takes the hydraulic condition of Eq. 39.
enum class SurfaceState : std::uint8_t {
  flux = 0,     // the prescribed rainfall or evaporation flux
  ponded = 1,   // p_w held at the ponding pressure p_max
  drying = 2,   // p_w held at the drying limit p_min
  held = 3,     // p_w held at the prescribed surface pressure (HydraulicForcing::surface_pressure)
};

template <typename Real, int Dim>
struct SoilView {
  const SoilMaterial* materials;       // EngineConfig::soils on the device
  const std::uint8_t* material;        // per particle: index into materials
  Real* porosity;                      // φ (Eq. 26a)
  Real* saturation;                    // S_w(p_c) (Eqs. 14, 42, 43)
  Real* conductivity;                  // K = K_sat K_rel(p_c) (Eqs. 15, 42b, 43b), by the seepage pass
  Vec<Real, Dim>* seepage;             // q_w (Eq. 27b), per soil particle; between the
                                       // gradient and seepage passes, ⟨∇p_w⟩^L (Eq. 25)
  // The dummies' soil side, indexed by b − GridView::moving_end (the dummy block's own index):
  Real* dummy_pore_pressure;           // p_w of the pore water (Eq. 32b)
  Voigt<Real>* dummy_stress;           // total stress σ (Eq. 32a)
  Vec<Real, Dim>* dummy_velocity;      // −v_g (Eqs. 34a, 35a)
  std::uint8_t* free_surface;          // per soil particle: 1 where ∇·x is below the threshold (Eq. 38)
  std::uint8_t* surface_state;         // per soil particle: a SurfaceState
  Voigt<Real>* effective_stress;       // per soil particle: σ' (Eqs. 7, 8); its total stress
                                       // σ' − S_w p_w I is formed where it is read
  Mat<Real, Dim>* velocity_gradient;   // per soil particle: L_ab = ∂v_a/∂x_b (Eqs. 26c, 26d)
  Real* porosity_rate;                 // per soil particle: dφ/dt (Eq. 26a)
  Real* plastic_strain;                // per soil particle: κ (Eq. 12)
  Vec<Real, Dim>* skeleton_acceleration;  // per soil particle: ā_s, the low-passed a_s of Eq. 27b
                                         // (seepage_inertia.h)
  // Drained walls (Eqs. 36, 37): per particle, 0 for an impermeable wall (and every other phase),
  // k > 0 for a dummy of the wall whose prescribed pore pressure is wall_pore_pressure[k − 1].
  const std::uint8_t* wall;
  const Real* wall_pore_pressure;
  PoreWaterInflow<Real>* pore_water_inflow;  // per soil particle: what enters through each boundary
                                             // (pore_water_account.h), by the soil pass
};

// The pore-water state of Eq. 6 with the soil's bulk modulus: p_w = K_w/ρ_w0 (ρ_w − ρ_w0), and
// its inverse (Eq. 36b).
template <typename Real>
CASCADE_HD inline Real pore_pressure(const SoilMaterial& m, Real rho0, Real pore_density) {
  return Real(m.water_bulk_modulus) / rho0 * (pore_density - rho0);
}
template <typename Real>
CASCADE_HD inline Real pore_density_of(const SoilMaterial& m, Real rho0, Real pressure) {
  return rho0 * (Real(1) + pressure / Real(m.water_bulk_modulus));
}

}  // namespace cascade
