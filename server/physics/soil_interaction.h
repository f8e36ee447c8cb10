// The soil particle's right-hand side: one pass over its neighbours sums the numerical density rate
// (Eq. 22), the momentum with Bishop's total stress and artificial viscosity (Eqs. 7, 26b), the
// velocity gradient of the strain and spin rates (Eqs. 26c, 26d), the pore-water continuity (Eq.
// 27a, pore_water_continuity.h) and the porosity rate (Eq. 26a), then the time-step limits (Eqs.
// 40a-c). A material with damping adds the skeleton's velocity damping (soil_damping.h).
//
// Neighbours: every phase counts in Eq. 22. Soil and dummy neighbours (the dummy's soil side: total
// stress of Eq. 32a, velocity −v_g of Eq. 35a) add their total stress, the viscosity, the velocity
// gradient and the pore water. A water neighbour j meets the soil particle i at the soil-water
// interface (Section 3.3: the pressure condition there follows from the momentum equations) through
// the pressures only: in Eq. 26b its pair is −(p̂_i + p_j) I, with −p_j I the water's total stress
// (Eq. 4) and p̂_i the pressure the soil shows the water (soil_shown_pressure, water_momentum.h):
// where saturated S_w,i p_w,i, the pressure part of σ_i, so that the skeleton's σ'_i acts only
// between soil particles and the skeleton is traction-free at the interface; where unsaturated at
// least the water's own pressure, so that the skeleton carries it. The pore-water continuity (Eq.
// 27a) takes the volume change of its pair, V_j (v_j − v_i)·∇_i W_ij, beside the skeleton's ε̇_v.
// Each saturated pair's pressure force and volume change are then the adjoint pair of the water's
// own Eqs. 23a-b, so the pressure work across the interface is conserved; with σ'_i in the pair and
// the water's velocity left out, a lateral mode of the interface grew from round-off at a rate that
// rose with K_w and E (docs/physics.md, "Soil-water interface"). The pair carries compression only
// (interface_contact_pressure, water_momentum.h), and the water's volume change enters the pore
// water in proportion to S_w,i, the wetted fraction of the pores. A rigid skeleton (Section 4.1)
// keeps v = 0, its stress and porosity: only the pore water flows. The seepage divergence of Eq.
// 27a is a sum of pairwise Darcy exchanges, with the rain of Eq. 39 a source on the particle that
// tops its column (seepage_exchange.h). In the geostatic stage (local_damping.h) the pore water is
// held: its density rate is zero, and the seepage limit of Eq. 40c, for a diffusion not integrated
// then, does not bound the step.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/core/small_matrix.h"
#include "server/physics/numerical_density.h"
#include "server/physics/pore_water_continuity.h"
#include "server/physics/pore_water_state.h"
#include "server/physics/seepage_exchange.h"
#include "server/physics/soil_damping.h"
#include "server/physics/soil_momentum.h"
#include "server/physics/soil_view.h"
#include "server/physics/soil_viscosity_switch.h"
#include "server/physics/swcc/grain_bound_water.h"
#include "server/physics/water_continuity.h"
#include "server/physics/water_momentum.h"

namespace cascade {

template <typename Real, int Dim>
struct SoilInteraction {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;
  SurfaceForcing<Real, Dim> forcing;
  Real rho0;
  bool hold_pore_water;  // the geostatic stage: dρ_w/dt = 0

  CASCADE_HD void operator()(std::uint32_t i) const {
    using V = Vec<Real, Dim>;
    using M = Mat<Real, Dim>;
    const SoilMaterial& m = soil.materials[soil.material[i]];
    const bool rigid = m.rigid;
    const V x_i = p.position[i];
    const V v_i = p.velocity[i];
    const Real rho_i = p.density[i];
    const Real rho_w_i = p.water_density[i];
    const V grad_rho_i = p.water_density_gradient[i];
    const M stress_i = in_plane<Real, Dim>(total_stress(soil.effective_stress[i], soil.saturation[i], p.pressure[i]));
    const Real c_s0 = Real(soil_sound_speed(m));
    const Real alpha_c0 = Real(m.viscosity_alpha) * c_s0;
    const std::uint32_t water_end = grid.water_end, moving_end = grid.moving_end;

    Real divergence = 0;          // Σ V_j (v_i − v_j)·∇_i W_ij, every neighbour (Eq. 22)
    Real pair_sum = 0;            // Σ_j of ⟨∇·q_w⟩_i over the soil neighbours (seepage_exchange.h)
    Real wall_sum = 0;            // and over a drained wall's dummies
    bool covered = false;         // a particle above i in its lattice column (seepage_exchange.h)
    V first_moment = V::Zero();   // Σ_j w_ij x_ij of the pair weights, not 0 where the support is cut
    bool near_prescribed = false;  // a soil neighbour holds a prescribed p_w (Eq. 39)
    const Real conductivity_i = soil.conductivity[i];
    const Real inv_g = Real(1) / sph.gravity.norm();
    const V driving_i = sph.gravity - soil.skeleton_acceleration[i];  // g − a_s of Eq. 27b
    Real diffusion = 0;           // Σ V_j ψ_ij·∇_i W_ij, soil (Eq. 27a)
    V force = V::Zero();          // Σ V_j (σ_i + σ_j)·∇_i W_ij (Eq. 26b)
    V viscous = V::Zero();
    M gradient = M::Zero();       // Σ V_j (v_j − v_i) ⊗ ∇_i W_ij (Eqs. 26c, 26d)
    Real max_mu = 0;
    Real interface_divergence = 0;  // Σ_water V_j (v_j − v_i)·∇_i W_ij (Eq. 27a at the interface)
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const V x_ij = grid.displacement(x_i, p.position[j]);
      const Real r2 = x_ij.squaredNorm();
      if (!(r2 < sph.kernel.support2)) continue;
      const Real volume_j = sph.mass / p.density[j];
      const Real gradient_factor = sph.kernel.gradient_factor(std::sqrt(r2));
      const V grad_w = gradient_factor * x_ij;
      const bool water = j < water_end, dummy = j >= moving_end;
      const V v_j = dummy ? soil.dummy_velocity[j - moving_end] : p.velocity[j];
      const V v_ij = v_i - v_j;
      divergence += velocity_divergence_pair(volume_j, v_ij, grad_w);
      covered = covered || covers_from_rain<Real, Dim>(x_ij, sph.dp);
      const Real inv_r2_eta2 = Real(1) / (r2 + sph.eta2);
      // The pair weight of the Darcy exchange with K_i on both sides, for a drained wall and for the
      // moment of the sides without flux (free water, an impermeable wall).
      const auto own_weight = [&] {
        return seepage_exchange_pair<Real, Dim>(volume_j, Real(2) * conductivity_i * inv_g, Real(1), x_ij,
                                                inv_r2_eta2, grad_w);
      };
      if (water) {
        first_moment += own_weight() * x_ij;  // no mass exchange with free water: a side that is there
        const Real shown_i = soil_shown_pressure<Real, Dim>(soil.saturation[i], p.pressure[i], p.pressure[j], rho0,
                                                             sph.gravity, x_ij);
        const Real contact_pressure = interface_contact_pressure(shown_i + p.pressure[j]);
        force += stress_force_pair<Real, Dim>(volume_j, -contact_pressure * M::Identity(), grad_w);
        interface_divergence -= volume_j * v_ij.dot(grad_w);
        continue;
      }
      const Voigt<Real> stress_j = dummy ? soil.dummy_stress[j - moving_end]
                                         : total_stress(soil.effective_stress[j], soil.saturation[j], p.pressure[j]);
      const M stress_sum = stress_i + in_plane<Real, Dim>(stress_j);
      force += stress_force_pair<Real, Dim>(volume_j, stress_sum, grad_w);
      const Real mu = viscosity_mu(sph.h, v_ij, x_ij, inv_r2_eta2);
      max_mu = std::fmax(max_mu, std::fabs(mu));
      viscous += artificial_viscosity_pair(alpha_c0, sph.mass, rho_i, p.density[j], mu, grad_w);
      gradient -= volume_j * v_ij * grad_w.transpose();
      if (!dummy) {
        diffusion += density_diffusion_pair(volume_j, gradient_factor, rho_w_i, p.water_density[j], r2, inv_r2_eta2,
                                            (grad_rho_i + p.water_density_gradient[j]).dot(x_ij));
        const V driving = driving_i + Real(0.5) * (soil.skeleton_acceleration[i] - soil.skeleton_acceleration[j]);
        const Real potential = seepage_potential_difference<Real, Dim>(
            p.pressure[i], p.pressure[j], Real(0.5) * (rho_w_i + p.water_density[j]), driving, x_ij);
        const Real weight = seepage_exchange_pair<Real, Dim>(volume_j, (conductivity_i + soil.conductivity[j]) * inv_g,
                                                             Real(1), x_ij, inv_r2_eta2, grad_w);
        pair_sum += weight * potential;
        first_moment += weight * x_ij;
        near_prescribed =
            near_prescribed || (soil.free_surface[j] && soil.surface_state[j] != std::uint8_t(SurfaceState::flux));
      } else if (soil.wall[j] != 0) {  // a drained wall (Eq. 36)
        const Real p_w_b = soil.dummy_pore_pressure[j - moving_end];
        const Real potential = seepage_potential_difference<Real, Dim>(
            p.pressure[i], p_w_b, Real(0.5) * (rho_w_i + pore_density_of(m, rho0, p_w_b)), driving_i, x_ij);
        const Real weight = own_weight();
        wall_sum += weight * potential;
        first_moment += weight * x_ij;
      } else {
        first_moment += own_weight() * x_ij;  // an impermeable wall: a side that is there, without flux
      }
    }

    // ⟨∇·q_w⟩_i with the rain of Eq. 39 on the particle that tops its column, and beside a
    // prescribed pressure the flux of the pairs its cut support lacks (seepage_exchange.h).
    const bool flux_surface = soil.free_surface[i] && soil.surface_state[i] == std::uint8_t(SurfaceState::flux);
    Real missing_pairs = 0;  // the pairs a cut support lacks beside a prescribed pressure
    if (near_prescribed && !flux_surface && conductivity_i > Real(0))
      missing_pairs = first_moment.dot(soil.seepage[i]) / (conductivity_i * inv_g);  // −∇Φ_i·Σ w x, ∇Φ_i = −g q_i/K_i
    Real seepage_divergence = -sph.laplacian_scale * (pair_sum + wall_sum + missing_pairs);
    Real rain = 0;  // i dp^(d−1), m³/s into the particle
    if (flux_surface && !covered) {
      rain = forcing.intensity_at(x_i);
      for (int a = 0; a + 1 < Dim; ++a) rain *= sph.dp;
      seepage_divergence -= rain * rho_i / sph.mass;
    }
    const Real porosity = soil.porosity[i];
    const Real saturation = soil.saturation[i];
    const Real volumetric = rigid ? Real(0) : gradient.trace();  // ε̇_v of the skeleton
    const double p_c = -double(p.pressure[i]);
    const Real capacity =
        Real(pore_water_capacity(m.hydraulic, m.reference_porosity, p_c, double(porosity), m.water_bulk_modulus));
    // The skeleton's volume change moves the free pore water only (grain_bound_water.h).
    const Real skeleton_share = Real(skeleton_water_share(m.hydraulic, p_c));
    const bool prescribed = soil.free_surface[i] && soil.surface_state[i] != std::uint8_t(SurfaceState::flux);
    // The free water meets the pore water over the wetted fraction S_w of the pores (the adjoint
    // of the S_w,i p_w,i that the water sees, water_interaction.h): a dry skeleton's residual
    // water is neither squeezed nor sucked by the water moving past it.
    const Real pore_volumetric = rigid ? Real(0) : volumetric + saturation * interface_divergence;
    const Real pore_rate =
        pore_water_density_rate(rho_w_i, capacity, seepage_divergence, skeleton_share, pore_volumetric,
                                Real(m.delta) * sph.h * Real(m.pore_sound_speed), diffusion);
    p.water_density_rate[i] = prescribed || hold_pore_water ? Real(0) : pore_rate;
    // What crosses the boundaries here (pore_water_account.h): a particle that holds its pressure
    // passes on through its surface what its soil pairs bring it; its own wall and missing pairs
    // then lead from outside to outside.
    const Real volume_scale = sph.laplacian_scale * sph.mass / rho_i;  // s V_i
    PoreWaterInflow<Real> inflow{rain, volume_scale * wall_sum, volume_scale * missing_pairs};
    if (prescribed) inflow = {Real(0), Real(0), -volume_scale * pair_sum};
    soil.pore_water_inflow[i] = hold_pore_water ? PoreWaterInflow<Real>{Real(0), Real(0), Real(0)} : inflow;
    const Real dt_sp = hold_pore_water ? std::numeric_limits<Real>::max()
                                       : seepage_time_step(rho0 * sph.gravity.norm(), Real(m.water_bulk_modulus),
                                                           sph.h, capacity, conductivity_i);
    bool finite = std::isfinite(pore_rate) && !std::isnan(dt_sp);
    if (rigid) {
      p.density_rate[i] = 0;
      p.acceleration[i] = V::Zero();
      soil.velocity_gradient[i] = M::Zero();
      soil.porosity_rate[i] = 0;
      p.step_limit[i] = finite ? dt_sp : Real(-1);
      return;
    }
    const Real rho_s = mixture_density(m, porosity, saturation, rho0);
    // A material with the compression switch scales the viscosity by it where the particle is at
    // yield (soil_viscosity_switch.h); the suction p_c = −p_w as in the frames' yield ratio.
    const Real viscosity_switch =
        m.viscosity_switch
            ? soil_viscosity_switch<Real, Dim>(
                  gradient, c_s0, sph.h,
                  m.mechanical.yield_ratio(tensor_of(Voigt<double>(soil.effective_stress[i].template cast<double>())),
                                           -double(p.pressure[i]), double(soil.plastic_strain[i])))
            : Real(1);
    const V acceleration = force / rho_s + viscosity_switch * viscous + sph.gravity +
                           soil_damping_acceleration(m, rho_s, sph.h, v_i);
    p.density_rate[i] = rho_i * divergence;
    p.acceleration[i] = acceleration;
    soil.velocity_gradient[i] = gradient;
    soil.porosity_rate[i] = (Real(1) - porosity) * volumetric;  // Eq. 26a
    // Eq. 40b with the P-wave speed of the soil and its pore water (soil_momentum.h), Eq. 40a,
    // Eq. 40c; C0 applies after the minimum.
    const Real c_s =
        Real(undrained_sound_speed(m, double(saturation), double(skeleton_share), double(capacity), double(rho_s)));
    const Real dt_cv = sph.h / (c_s + max_mu);
    const Real magnitude = acceleration.norm();
    const Real dt_f = magnitude > Real(0) ? std::sqrt(sph.h / magnitude) : dt_cv;
    finite = finite && std::isfinite(magnitude) && std::isfinite(max_mu);
    const Real limit = dt_cv < dt_f ? dt_cv : dt_f;
    p.step_limit[i] = finite ? (limit < dt_sp ? limit : dt_sp) : Real(-1);
  }
};

}  // namespace cascade
