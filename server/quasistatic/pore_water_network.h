// The fixed skeleton seen by the implicit pore-water stage: which particle exchanges pore water
// with which, and how easily (docs/physics.md, "Implicit pore-water stage").
//
// Between two soil particles the flux into i is G_ij K̄_ij (H_j − H_i), H = p_w/γ_w + z the
// hydraulic head (z the elevation against gravity, γ_w = ρ_w0 |g|; H_j − H_i with z_j − z_i along
// the pair, which across a periodic axis is not the difference of the stored positions' z when
// gravity has a component along it, e.g. a tilted infinite slope), K̄_ij = (K_i + K_j)/2 and
//
//     G_ij = 2 V_i V_j (−x_ij·∇_i W_ij) / (|x_ij|² + η²),    η² = 0.01 h²,
//
// the pair weight of the SPH Laplacian of Brookshaw (1985) and Cleary & Monaghan (1999),
// ∇·(K∇H)_i ≈ Σ_j V_j (K_i + K_j)(H_i − H_j) x_ij·∇_i W_ij/(|x_ij|² + η²), times V_i. The pair
// fluxes are antisymmetric, so the stage conserves the pore water to round-off, and the matrix
// they make is symmetric positive definite.
//
// Fixed heads: a free-water particle next to the soil (a lake or a channel at rest over the
// stage) shows its own head p_j/γ_w + z_j; a dummy particle of a drained wall (Eqs. 36, 37) shows
// the head of the prescribed pressure at the wall face, extrapolated to the dummy along the
// wall's normal from the soil particle of the pair (Morris, Fox & Zhu 1997):
//     H_b − H_i = (1 + d_b/d_i)(H_face − H_i),  d_b, d_i the distances to the face, d_i >= dp/2,
// so that a head varying linearly across the face has its exact flux there. Dummies of
// impermeable walls take no part: no flux crosses them. Each fixed pair's conductivity is K_i.
//
// Rain: each vertical column of the lattice (dp wide, dp × dp in 3D) takes i dp^(d−1) on its
// highest particle when that is a soil particle: the rain volume that reaches the soil is
// exactly i times its horizontal area, whatever the slope. Rain on a column topped by water or
// by a wall is not the soil's.
#pragma once

#include <cstdint>
#include <vector>

#include "server/core/engine.h"

namespace cascade {

struct PoreWaterNetwork {
  struct Pair {
    std::uint32_t i, j;  // indices into `soil` (i < j)
    double weight;       // G_ij (m^(2d−2))
    double rise;         // z_i − z_j along the pair, x_ij the minimum image on periodic axes (m)
  };
  struct FixedPair {
    std::uint32_t i;     // index into `soil`
    double weight;       // G_ib times the extrapolation factor (1 + d_b/d_i) for a wall
    double head;         // H of the fixed side (m), at its periodic image next to i
    bool wall;           // a drained wall's dummy (else free water)
  };

  std::vector<std::uint32_t> soil;     // state index of each soil particle, in state order
  std::vector<double> volume;          // V_i = m/ρ_i (m^d)
  std::vector<double> elevation;       // z_i against gravity (m)
  std::vector<Pair> pairs;
  std::vector<FixedPair> fixed;
  std::vector<double> rain_area;       // horizontal area that rains on soil particle i (m^(d−1)); 0 for most
  std::vector<std::uint8_t> free_surface;  // Eq. 38, as the engine found it
  double gamma_w = 0;                  // ρ_w0 |g| (Pa/m)
};

// Builds the network of the particles in `state` (an Engine::state() of the case). Positions do
// not change during the stage, so this is done once per stage.
PoreWaterNetwork build_pore_water_network(const EngineConfig& config, const EngineState& state);

}  // namespace cascade
