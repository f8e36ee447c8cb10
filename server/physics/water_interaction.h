// The water particle's right-hand side: one pass over its neighbours sums the numerical density
// rate (Eq. 22), the water continuity with δ-SPH diffusion (Eq. 23a), the momentum with
// artificial viscosity (Eq. 23b) and the per-particle time-step limit (Eq. 40a, 40b).
//
// A soil neighbour j enters Eq. 23b with the pressure it shows the water (soil_shown_pressure,
// water_momentum.h): saturated, its pore water's S_w,j p_w,j (Bishop's pore stress of Eq. 7);
// unsaturated, at least the water's own pressure carried to it, as a solid's. The soil particle's
// own pair with this water particle takes the same pressure (soil_interaction.h), so the two pair
// forces are equal and opposite; the suction of a dry skeleton (p_w = −10 kPa at S_w = 0.001)
// neither pulls free water into it nor lets the water press into it as into a void
// (docs/physics.md, "Soil-water interface"). The pair's pressure is held at zero or above: the
// contact between free water and the skeleton carries no tension (interface_contact_pressure,
// water_momentum.h). So is a dummy particle's pair, p_i + p_b >= 0: a wall pushes water, it never
// pulls it in (a water particle in tension next to the slope under a sliding mass was drawn through
// the dummy layers; with the impenetrable walls of wall_contact.h and the pair in tension, the
// storm demo's channel water blew up 38 s after the failure: docs/physics.md, "Solid boundary").
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/physics/equation_of_state.h"
#include "server/physics/numerical_density.h"
#include "server/physics/water_continuity.h"
#include "server/physics/water_momentum.h"

namespace cascade {

template <typename Real, int Dim>
struct WaterInteraction {
  ParticleView<Real, Dim> p;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;
  WaterConstants<Real> water;
  const Real* saturation;  // S_w per particle (SoilView::saturation); nullptr in a case without soil

  CASCADE_HD void operator()(std::uint32_t i) const {
    if (p.phase[i] != Phase::water) return;
    // Compiled twice: without soil (saturation == nullptr) the loop drops the soil's terms.
    if (saturation != nullptr) interact<true>(i);
    else interact<false>(i);
  }

 private:
  template <bool WithSoil>
  CASCADE_HD void interact(std::uint32_t i) const {
    const Vec<Real, Dim> x_i = p.position[i];
    const Vec<Real, Dim> v_i = p.velocity[i];
    const Real rho_i = p.density[i];
    const Real rho_w_i = p.water_density[i];
    const Real p_i = p.pressure[i];
    const Vec<Real, Dim> grad_rho_i = p.water_density_gradient[i];
    const Real alpha_c0 = water.alpha * water.c0;
    const Real inv_rho_i = Real(1) / rho_i;
    // The loop reads these as scalars: components of Eigen vectors are not hoisted out of it.
    const Real v_i0 = component<0>(v_i), v_i1 = component<1>(v_i), v_i2 = component<2>(v_i);
    const Real grad_rho_i0 = component<0>(grad_rho_i), grad_rho_i1 = component<1>(grad_rho_i),
               grad_rho_i2 = component<2>(grad_rho_i);
    const Real g0 = component<0>(sph.gravity), g1 = component<1>(sph.gravity), g2 = component<2>(sph.gravity);

    // Each sum is a scalar of its own and the loop holds no Eigen vector: GCC then vectorises it
    // with the sums in registers (docs/performance.md, "The neighbour loops"). ∇_i W_ij = F x_ij.
    Real divergence = 0;  // Σ V_j (v_i − v_j)·∇_i W_ij
    Real diffusion = 0;   // Σ V_j ψ_ij·∇_i W_ij over water neighbours
    Real a0 = 0, a1 = 0, a2 = 0;  // Σ [−V_j (p_i + p_j)/ρ_i + Π_ij] ∇_i W_ij, Eq. 23b without gravity
    auto max_mu_bits = ordered_bits(Real(0));  // max_j |μ_ij| within the support

    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    CASCADE_SIMD(reduction(+ : divergence, diffusion, a0, a1, a2) reduction(max : max_mu_bits))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const auto [x0, x1, x2, r2] = grid.offset(x_i, p.position, j);
      const Real rho_j = p.density[j];
      const Real volume_j = sph.mass / rho_j;
      // Zero beyond the support 2h, so the list's skin entries add nothing below.
      const Real factor = sph.kernel.gradient_factor(std::sqrt(r2));
      const Real v_ij_dot_x_ij = (v_i0 - gather_component<0>(p.velocity, j)) * x0 +
                                 (v_i1 - gather_component<1>(p.velocity, j)) * x1 +
                                 (v_i2 - gather_component<2>(p.velocity, j)) * x2;
      divergence += velocity_divergence_pair(volume_j, factor, v_ij_dot_x_ij);
      const bool soil_j = WithSoil && j >= grid.water_end && j < grid.moving_end;
      const Real saturation_j = soil_j ? saturation[j] : Real(1);
      // g·(x_j − x_i) = −g·x_ij
      const Real gravity_along = -(g0 * x0 + g1 * x1 + g2 * x2);
      const Real shown_pressure_j =
          soil_j ? soil_shown_pressure(saturation_j, p.pressure[j], p_i, water.rho0, gravity_along) : p.pressure[j];
      // A soil pair's p_i + p̂_j and a wall pair's p_i + p_b are held at >= 0 (compression
      // only), written as p_i + p_j'.
      const bool wall_j = j >= grid.moving_end;
      const Real seen_pressure_j =
          (soil_j || wall_j) ? interface_contact_pressure(p_i + shown_pressure_j) - p_i : p.pressure[j];
      const Real inv_r2_eta2 = Real(1) / (r2 + sph.eta2);
      const Real mu = viscosity_mu(sph.h, v_ij_dot_x_ij, inv_r2_eta2);
      // |μ_ij| within the support, 0 for the list's skin entries (a mask, not a branch).
      auto mu_bits = ordered_bits(std::fabs(mu));
      mu_bits &= decltype(mu_bits)(0) - decltype(mu_bits)(r2 < sph.kernel.support2);
      max_mu_bits = max_mu_bits > mu_bits ? max_mu_bits : mu_bits;
      const Real force = (pressure_force_coefficient(volume_j, p_i, seen_pressure_j) * inv_rho_i +
                          artificial_viscosity_coefficient(alpha_c0, sph.mass, rho_i, rho_j, mu)) *
                         factor;
      a0 += force * x0;
      a1 += force * x1;
      a2 += force * x2;
      // Dummy particles take no part in the diffusion: it would move water mass into walls.
      const Real water_j = j < grid.water_end ? Real(1) : Real(0);
      const Real gradient_sum_along =
          (grad_rho_i0 + gather_component<0>(p.water_density_gradient, j)) * x0 +
          (grad_rho_i1 + gather_component<1>(p.water_density_gradient, j)) * x1 +
          (grad_rho_i2 + gather_component<2>(p.water_density_gradient, j)) * x2;
      diffusion += water_j * density_diffusion_pair(volume_j, factor, rho_w_i, p.water_density[j], r2, inv_r2_eta2,
                                                    gradient_sum_along);
    }
    const Real max_mu = from_ordered_bits<Real>(max_mu_bits);
    const Real a[3] = {a0, a1, a2};

    p.density_rate[i] = rho_i * divergence;
    p.water_density_rate[i] = rho_w_i * divergence + water.delta * sph.h * water.c0 * diffusion;
    Vec<Real, Dim> acceleration = sph.gravity;
    for (int d = 0; d < Dim; ++d) acceleration[d] += a[d];
    p.acceleration[i] = acceleration;
    // Eq. 40b (sound speed and the largest pair μ) and Eq. 40a (force); C0 applies after the min.
    const Real dt_cv = sph.h / (water.c0 + max_mu);
    const Real force = acceleration.norm();
    const Real dt_f = force > Real(0) ? std::sqrt(sph.h / force) : dt_cv;
    // A non-finite rate marks the limit negative, which fails the step (time_step.h).
    const bool finite = std::isfinite(force) && std::isfinite(p.water_density_rate[i]) && std::isfinite(max_mu);
    p.step_limit[i] = finite ? (dt_cv < dt_f ? dt_cv : dt_f) : Real(-1);
  }
};

}  // namespace cascade
