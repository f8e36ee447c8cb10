// The implicit pore-water stage (docs/physics.md, "Implicit pore-water stage"): while the
// skeleton does not move, the pore water obeys Darcy's law with storage — Richards' equation, the
// quasi-static limit of Eqs. 3a-3b and 27a-27b (a_s = 0) — solved on the soil particles with
// backward Euler steps of seconds to hours.
//
// Per soil particle i, with the pair fluxes of pore_water_network.h and Q_i its boundary inflow:
//
//     V_i (Θ_i(p^{n+1}) − Θ_i(p^n)) / Δt = Σ_j G_ij K̄_ij (H_j − H_i) + Σ_b G_ib K_i (H_b − H_i) + Q_i,
//
//     Θ(p) = φ S_w(−p) (1 + p/K_w),    dΘ/dp = φ (S_w/K_w − (1 + p/K_w) ∂S_w/∂p_c),
//
// Θ the pore water's mass per unit volume over ρ_w0 (S_w of Eqs. 14, 42, 43; ρ_w = ρ_w0 (1 + p/K_w),
// Eqs. 6, 36b), so dΘ/dp is C_r/K_w of Eq. 28b to first order in p/K_w. The time derivative is the
// difference of Θ between time levels, the mixed form of Celia, Bouloutas & Zarba (1990), which
// conserves the water whatever the nonlinearity; their modified Picard iteration linearises Θ with
// dΘ/dp at the last iterate and freezes K there. Each iteration solves a symmetric positive definite
// system (Eigen's conjugate gradient, incomplete Cholesky).
//
// Free-surface conditions (Eq. 39, ERRATA.md), switched within the iterations as in the explicit
// scheme (pore_water_state.h): a free-surface particle takes its rain Q_i = i A_i (A_i its column's
// area, 0 on faces that the rain does not reach) until its pressure would exceed p_max; then it
// holds p_max (ponding, and on faces a seepage face: water leaves it at p_max) until the soil
// takes more than the rain again. Evaporating (i < 0), it holds p_min once it would fall below.
// A prescribed surface pressure (HydraulicForcing::surface_pressure) holds on every free-surface
// particle. The rain not taken by a ponded particle runs off.
//
// With the pore pressure, the saturation, the pore-water density and Bishop's effective stress
// follow: at constant total stress σ = σ' − S_w p_w I (Eq. 7), σ' changes by Δ(S_w p_w) I.
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/core/engine.h"
#include "server/quasistatic/pore_water_network.h"

namespace cascade {

struct ImplicitPoreWaterSettings {
  double initial_dt = 1.0;          // s
  double min_dt = 1e-3;             // s: a smaller step fails the stage
  double max_dt = 3600.0;           // s
  double pressure_tolerance = 1.0;  // Pa: the largest change of an iteration that ends it
  int max_iterations = 20;          // a step not converged by then is retried at half the step
  // The largest change of a particle's water content Θ in one step that the step control aims
  // at; a step that changes it by more than twice as much is retried at half the step.
  double water_content_change = 0.003;
};

// Volumes of pore water (m³ in 3D, m² in 2D: per metre of width) since the stage began, at ρ_w0.
struct WaterBalance {
  double rain = 0;            // fell on soil columns
  double infiltration = 0;    // entered through the free surface (rain taken and ponded inflow)
  double runoff = 0;          // rain that ponded particles did not take
  double exfiltration = 0;    // left through the free surface (seepage faces)
  double walls = 0;           // net inflow through drained walls
  double free_water = 0;      // net inflow from free water (lakes, channels)
  double storage = 0;         // change of the stored pore water
  // storage − (infiltration − exfiltration + walls + free_water): the sum of the iterations'
  // residuals, which the tolerance bounds.
  double error() const { return storage - (infiltration - exfiltration + walls + free_water); }
};

class ImplicitPoreWater {
 public:
  ImplicitPoreWater(const EngineConfig& config, const EngineState& start, ImplicitPoreWaterSettings settings);

  // One backward Euler step of `state` (the arrays of Engine::state(), changed in place: pressure,
  // water_density, saturation, effective_stress, surface_state; time and steps advance) under
  // `forcing`, of the adaptive step but at most `max_step`. Returns the step taken (s). Throws
  // SimulationFailure when the step falls below min_dt.
  double step(EngineState& state, const HydraulicForcing& forcing, double max_step);

  const WaterBalance& balance() const { return balance_; }
  double next_dt() const { return dt_; }
  void set_next_dt(double dt) { dt_ = dt; }

 private:
  struct Attempt;
  bool try_step(std::vector<double>& p, const std::vector<double>& p_start, const HydraulicForcing& forcing, double dt,
                Attempt& attempt);

  // The system's matrix: its pattern (the diagonal and both entries of every pair) is fixed for
  // the stage, so the incomplete Cholesky ordering is computed once; each iteration writes the
  // values through the slots below (a Dirichlet row keeps its pattern with explicit zeros).
  struct Slots {
    std::vector<std::int64_t> diagonal;  // per soil particle
    std::vector<std::int64_t> ij, ji;    // per pair
  };
  using Preconditioned =
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>>;
  void build_pattern();

  const EngineConfig& config_;
  ImplicitPoreWaterSettings settings_;
  PoreWaterNetwork network_;
  Eigen::SparseMatrix<double> matrix_;
  Slots slots_;
  std::unique_ptr<Preconditioned> solver_;
  std::vector<const SoilMaterial*> material_;  // per soil particle
  std::vector<double> porosity_;
  std::vector<std::uint8_t> state_;             // SurfaceState per soil particle
  WaterBalance balance_;
  double dt_;
};

}  // namespace cascade
