// Pore-water continuity of a soil particle (Eq. 27a with ERRATA.md), its numerical density
// (Eq. 22) and its seepage time-step limit (Eqs. 40c, 41):
//   dρ_w,i/dt = −(1/C_r,i) [ ρ_w,i ( Σ_j V_j (q_w,j − q_w,i)·∇_i W_ij + S_w,i ε̇_v,i )
//                            − δ h c_pw0 Σ_{j soil} V_j ψ_ij·∇_i W_ij ],
//   C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eq. 28b), ψ_ij of Eq. 24b on the pore-water densities.
// The δ-term carries the opposite sign to the printed Eq. 27a, whose form inside −1/C_r [...]
// would be anti-diffusive (ERRATA.md): with it, a local pore-pressure bump decays. Neighbours of
// the divergence are the soil and the dummy particles (whose q_w = −q_g closes the wall,
// Eq. 35b); free water does not exchange mass with the pore water (ERRATA.md).
//   Δt_sp = (γ_w/K_w) h² C_r / (2 K) (Eq. 40c with c_v = C_r, Eq. 41), γ_w = ρ_w0 g.
// A particle whose pressure the free-surface condition prescribes (ponded, drying) keeps its
// density: rate 0. This is the rigid-skeleton form (Section 4.1): ε̇_v = 0 and no soil motion.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/physics/soil_view.h"
#include "server/physics/water_continuity.h"

namespace cascade {

template <typename Real, int Dim>
struct PoreWaterContinuity {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;
  Real rho0;

  CASCADE_HD void operator()(std::uint32_t i) const {
    const SoilMaterial& m = soil.materials[soil.material[i]];
    const Vec<Real, Dim> x_i = p.position[i];
    const Vec<Real, Dim> q_i = soil.seepage[i];
    const Real rho_w_i = p.water_density[i];
    const Vec<Real, Dim> grad_rho_i = p.water_density_gradient[i];
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    const std::uint32_t water_end = grid.water_end, moving_end = grid.moving_end;
    Real seepage_divergence = 0;  // Σ V_j (q_j − q_i)·∇_i W_ij
    Real diffusion = 0;           // Σ V_j ψ_ij·∇_i W_ij over soil neighbours
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      if (j < water_end) continue;  // free water
      const Vec<Real, Dim> x_ij = grid.displacement(x_i, p.position[j]);
      const Real r2 = x_ij.squaredNorm();
      const Real volume_j = sph.mass / p.density[j];
      const Vec<Real, Dim> grad_w = sph.kernel.gradient_factor(std::sqrt(r2)) * x_ij;
      seepage_divergence += volume_j * (soil.seepage[j] - q_i).dot(grad_w);
      if (j < moving_end)
        diffusion += density_diffusion_pair(volume_j, rho_w_i, p.water_density[j], x_ij, Real(1) / (r2 + sph.eta2),
                                            grad_rho_i, p.water_density_gradient[j], grad_w);
    }
    const double p_c = -double(p.pressure[i]);
    const Real capacity = Real(m.hydraulic.capacity(p_c, double(soil.porosity[i]), m.water_bulk_modulus));
    const bool prescribed = soil.free_surface[i] && soil.surface_state[i] != std::uint8_t(SurfaceState::flux);
    const Real rate = -(rho_w_i * seepage_divergence - Real(m.delta) * sph.h * Real(m.pore_sound_speed) * diffusion) /
                      capacity;
    p.water_density_rate[i] = prescribed ? Real(0) : rate;
    p.density_rate[i] = 0;  // rigid skeleton: Eq. 22 with v = 0
    p.acceleration[i] = Vec<Real, Dim>::Zero();
    const Real conductivity = Real(m.saturated_conductivity * m.hydraulic.relative_conductivity(p_c));
    const Real gamma_w = rho0 * sph.gravity.norm();
    const Real dt_sp = gamma_w / Real(m.water_bulk_modulus) * sph.h * sph.h * capacity / (Real(2) * conductivity);
    const bool finite = std::isfinite(rate) && !std::isnan(dt_sp);
    p.step_limit[i] = finite ? dt_sp : Real(-1);  // a dry particle (K = 0) sets no limit: +∞
  }
};

}  // namespace cascade
