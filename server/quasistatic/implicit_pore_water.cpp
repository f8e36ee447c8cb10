#include "server/quasistatic/implicit_pore_water.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "server/core/types.h"
#include "server/physics/pore_water_state.h"
#include "server/physics/soil_view.h"
#include "server/physics/swcc/grain_bound_water.h"

namespace cascade {

namespace {

// Θ = φ S_w (1 + p/K_w) and dΘ/dp (implicit_pore_water.h), S_w at the particle's porosity
// (grain_bound_water.h).
double water_content(const SoilMaterial& m, double porosity, double p) {
  return porosity * saturation_at_porosity(m.hydraulic, m.reference_porosity, -p, porosity) *
         (1.0 + p / m.water_bulk_modulus);
}
double water_capacity(const SoilMaterial& m, double porosity, double p) {
  return porosity * (saturation_at_porosity(m.hydraulic, m.reference_porosity, -p, porosity) / m.water_bulk_modulus -
                     (1.0 + p / m.water_bulk_modulus) *
                         saturation_derivative_at_porosity(m.hydraulic, m.reference_porosity, -p, porosity));
}
double conductivity(const SoilMaterial& m, double p) {
  return m.saturated_conductivity * m.hydraulic.relative_conductivity(-p);
}

// K̄_ij of a pair: the logarithmic mean (K_i − K_j)/ln(K_i/K_j). Across a pair of Gardner's soil,
// K = K_s e^{αψ}, Kirchhoff's potential Φ = ∫K dψ = K/α makes the flux without gravity
// −(Φ_j − Φ_i)/r exactly, which is K̄ (ψ_j − ψ_i)/r with this mean; the arithmetic mean, which
// exceeds it, runs a wetting front ahead into dry soil, the more so the longer the pair (up to
// 2h here against dp in a finite-volume grid).
double pair_conductivity(double k_i, double k_j) {
  const double ratio = k_i / k_j;
  if (!(k_i > 0 && k_j > 0)) return 0.0;
  if (std::fabs(ratio - 1.0) < 1e-6) return 0.5 * (k_i + k_j);  // the limit, without 0/0
  return (k_i - k_j) / std::log(ratio);
}

std::vector<double>& reals(EngineState& s, const char* name) { return s.reals.at(name); }

bool holds_pressure(std::uint8_t state) { return state != std::uint8_t(SurfaceState::flux); }

std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace

struct ImplicitPoreWater::Attempt {
  std::vector<double> supply;       // Q_i the forcing offers (m^d/s): rain i A_i, or evaporation
  std::vector<std::uint8_t> state;  // surface states, updated by the iterations
  int iterations = 0;
  double largest_change = 0;        // max |Θ − Θ^n| over the particles
  WaterBalance increment;           // this step's volumes
};

ImplicitPoreWater::ImplicitPoreWater(const EngineConfig& config, const EngineState& start,
                                     ImplicitPoreWaterSettings settings)
    : config_(config), settings_(settings), network_(build_pore_water_network(config, start)), dt_(settings.initial_dt) {
  const auto& material = start.integers.at("soil_material");
  const auto& porosity = start.reals.at("porosity");
  const auto& surface = start.integers.at("surface_state");
  for (const std::uint32_t k : network_.soil) {
    material_.push_back(&config.soils.at(material[k]));
    porosity_.push_back(porosity[k]);
    state_.push_back(std::uint8_t(surface[k]));
  }
  build_pattern();
}

void ImplicitPoreWater::build_pattern() {
  const auto n = Eigen::Index(network_.soil.size());
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(std::size_t(n) + 2 * network_.pairs.size());
  for (Eigen::Index i = 0; i < n; ++i) pattern.emplace_back(i, i, 0.0);
  for (const auto& pair : network_.pairs) {
    pattern.emplace_back(pair.i, pair.j, 0.0);
    pattern.emplace_back(pair.j, pair.i, 0.0);
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();
  // The position of (row, col) in the compressed column-major arrays.
  const auto slot = [&](Eigen::Index row, Eigen::Index col) {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
    return std::int64_t(std::lower_bound(begin, end, int(row)) - matrix_.innerIndexPtr());
  };
  slots_.diagonal.resize(std::size_t(n));
  for (Eigen::Index i = 0; i < n; ++i) slots_.diagonal[std::size_t(i)] = slot(i, i);
  slots_.ij.clear(), slots_.ji.clear();
  for (const auto& pair : network_.pairs) {
    slots_.ij.push_back(slot(pair.i, pair.j));
    slots_.ji.push_back(slot(pair.j, pair.i));
  }
  solver_ = std::make_unique<Preconditioned>();
  solver_->setTolerance(1e-12);
  solver_->analyzePattern(matrix_);
}

double ImplicitPoreWater::step(EngineState& s, const HydraulicForcing& forcing, double max_step) {
  const std::size_t n = network_.soil.size();
  auto& pressure = reals(s, "pressure");
  std::vector<double> p_start(n);
  for (std::size_t i = 0; i < n; ++i) p_start[i] = pressure[network_.soil[i]];

  Attempt attempt;
  attempt.supply.assign(n, 0.0);
  const auto surface = SurfaceForcing<double, 3>::from(forcing);
  const auto& position = s.reals.at("position");
  const int dim = s.dimensions;
  for (std::size_t i = 0; i < n; ++i) {
    if (network_.rain_area[i] <= 0) continue;
    Vec<double, 3> x = Vec<double, 3>::Zero();
    for (int a = 0; a < dim; ++a) x[a] = position[network_.soil[i] * dim + a];
    // SurfaceForcing's region test in the engine's own axes: 2D cases compare (x, z) only.
    auto in_plane = surface;
    if (dim == 2) in_plane.region_min[2] = -1e300, in_plane.region_max[2] = 1e300;
    attempt.supply[i] = in_plane.intensity_at(x) * network_.rain_area[i];
  }

  double dt = std::min(dt_, max_step);
  std::vector<double> p;
  while (true) {
    if (!(dt >= settings_.min_dt))
      throw SimulationFailure("the implicit pore-water step fell below min_dt " + text(settings_.min_dt) +
                              " s at t = " + text(s.time) + " s: the Picard iterations do not converge");
    p = p_start;
    attempt.state = state_;
    if (try_step(p, p_start, forcing, dt, attempt) &&
        attempt.largest_change <= 2 * settings_.water_content_change)
      break;
    dt *= 0.5;
  }

  // The arrays the engine carries (Engine::state), at the new pressure.
  auto& water_density = reals(s, "water_density");
  auto& saturation = reals(s, "saturation");
  auto& stress = reals(s, "effective_stress");
  auto& surface_state = s.integers.at("surface_state");
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = network_.soil[i];
    const SoilMaterial& m = *material_[i];
    const double s_old = saturation[k];
    const double s_new = saturation_at_porosity(m.hydraulic, m.reference_porosity, -p[i], porosity_[i]);
    pressure[k] = p[i];
    water_density[k] = pore_density_of(m, config_.water_density, p[i]);  // Eqs. 6, 36b
    saturation[k] = s_new;
    // σ' = σ + S_w p_w I at constant σ (Eq. 7).
    if (!m.rigid)
      for (int c = 0; c < 3; ++c) stress[6 * k + c] += s_new * p[i] - s_old * p_start[i];
    surface_state[k] = network_.free_surface[i] ? attempt.state[i] : std::uint8_t(SurfaceState::flux);
  }
  state_ = attempt.state;
  const WaterBalance& d = attempt.increment;
  balance_.rain += d.rain, balance_.infiltration += d.infiltration, balance_.runoff += d.runoff;
  balance_.exfiltration += d.exfiltration, balance_.walls += d.walls, balance_.free_water += d.free_water;
  balance_.storage += d.storage;
  // The run's account (engine_state.h): rain that entered, the rest of the surface's exchange (ponded
  // inflow, seepage faces, free water), drained walls; together the stage's storage change.
  s.pore_water.rain += d.rain - d.runoff;
  s.pore_water.surface += d.infiltration - (d.rain - d.runoff) - d.exfiltration + d.free_water;
  s.pore_water.walls += d.walls;

  // The next step: scaled towards the aimed change of water content, at most 1.5 times longer,
  // shorter after a step that needed many iterations (a step cut short by max_step leaves the
  // adaptive value as it was, unless it changed the water content too much).
  const double by_change = attempt.largest_change > 0 ? settings_.water_content_change / attempt.largest_change : 1.5;
  double next = dt * std::min(1.5, by_change);
  if (attempt.iterations >= settings_.max_iterations / 2) next = std::min(next, 0.7 * dt);
  if (dt >= std::min(dt_, max_step) * (1 - 1e-12) && dt < dt_) next = std::min(next, dt_);  // cut by max_step
  if (dt < std::min(dt_, max_step) * (1 - 1e-12)) next = std::min(next, dt);                   // halved above
  if (dt >= dt_ * (1 - 1e-12) || next < dt_) dt_ = next;
  dt_ = std::clamp(dt_, settings_.min_dt, settings_.max_dt);

  s.time += dt;
  s.last_dt = dt;
  s.steps += 1;
  return dt;
}

bool ImplicitPoreWater::try_step(std::vector<double>& p, const std::vector<double>& p_start,
                                 const HydraulicForcing& forcing, double dt, Attempt& attempt) {
  const std::size_t n = p.size();
  const double gamma = network_.gamma_w;
  std::vector<double> theta_start(n), theta(n), capacity(n), k(n), head(n), outflow(n);
  for (std::size_t i = 0; i < n; ++i) theta_start[i] = water_content(*material_[i], porosity_[i], p_start[i]);

  // The pressure a particle holds in a Dirichlet state.
  const auto held_pressure = [&](std::uint8_t state) {
    switch (SurfaceState(state)) {
      case SurfaceState::ponded: return forcing.ponding_pressure;
      case SurfaceState::drying: return forcing.drying_pressure;
      case SurfaceState::held: return forcing.surface_pressure;
      case SurfaceState::flux: break;
    }
    return 0.0;
  };
  // Fluxes at pressure p with conductivities k: `outflow` = Σ of what leaves each particle to its
  // neighbours and fixed heads (the negative of the pair sums of the header).
  const auto net_outflow = [&](WaterBalance* fixed_flows) {
    std::fill(outflow.begin(), outflow.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) head[i] = p[i] / gamma + network_.elevation[i];
    for (const auto& pair : network_.pairs) {
      const double flux =
          pair.weight * pair_conductivity(k[pair.i], k[pair.j]) * ((p[pair.i] - p[pair.j]) / gamma + pair.rise);
      outflow[pair.i] += flux, outflow[pair.j] -= flux;
    }
    for (const auto& f : network_.fixed) {
      const double flux = f.weight * k[f.i] * (head[f.i] - f.head);
      outflow[f.i] += flux;
      if (fixed_flows) (f.wall ? fixed_flows->walls : fixed_flows->free_water) -= flux * dt;
    }
  };
  const auto update_coefficients = [&]() {
    for (std::size_t i = 0; i < n; ++i) {
      const SoilMaterial& m = *material_[i];
      theta[i] = water_content(m, porosity_[i], p[i]);
      capacity[i] = water_capacity(m, porosity_[i], p[i]);
      k[i] = conductivity(m, p[i]);
    }
  };

  // The surface states at the start: a prescribed surface pressure holds everywhere on the surface.
  for (std::size_t i = 0; i < n; ++i) {
    if (!network_.free_surface[i]) attempt.state[i] = std::uint8_t(SurfaceState::flux);
    else if (forcing.has_surface_pressure) attempt.state[i] = std::uint8_t(SurfaceState::held);
    else if (attempt.state[i] == std::uint8_t(SurfaceState::held)) attempt.state[i] = std::uint8_t(SurfaceState::flux);
  }

  Eigen::VectorXd rhs(n), delta(n);
  std::vector<double> fixed_delta(n);
  std::vector<bool> dirichlet(n);
  double* value = matrix_.valuePtr();
  for (attempt.iterations = 1; attempt.iterations <= settings_.max_iterations; ++attempt.iterations) {
    update_coefficients();
    net_outflow(nullptr);
    // The increment δ = p^{m+1} − p^m of the modified Picard iteration:
    //   (V C/Δt) δ_i + Σ_j a_ij (δ_i − δ_j) + Σ_b a_ib δ_i = −R_i,   a = G K/γ_w,
    //   R_i = V (Θ_i − Θ_i^n)/Δt + outflow_i − Q_i; a Dirichlet particle's δ is known.
    std::fill(fixed_delta.begin(), fixed_delta.end(), 0.0);
    std::fill(dirichlet.begin(), dirichlet.end(), false);
    for (std::size_t i = 0; i < n; ++i)
      if (holds_pressure(attempt.state[i])) dirichlet[i] = true, fixed_delta[i] = held_pressure(attempt.state[i]) - p[i];
    std::fill(value, value + matrix_.nonZeros(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (dirichlet[i]) {
        value[slots_.diagonal[i]] = 1.0;
        rhs[Eigen::Index(i)] = fixed_delta[i];
        continue;
      }
      value[slots_.diagonal[i]] = network_.volume[i] * capacity[i] / dt;
      rhs[Eigen::Index(i)] = -(network_.volume[i] * (theta[i] - theta_start[i]) / dt + outflow[i] - attempt.supply[i]);
    }
    for (std::size_t q = 0; q < network_.pairs.size(); ++q) {
      const auto& pair = network_.pairs[q];
      const double a = pair.weight * pair_conductivity(k[pair.i], k[pair.j]) / gamma;
      const bool fixed_i = dirichlet[pair.i], fixed_j = dirichlet[pair.j];
      if (!fixed_i) value[slots_.diagonal[pair.i]] += a;
      if (!fixed_j) value[slots_.diagonal[pair.j]] += a;
      if (!fixed_i && !fixed_j) {
        value[slots_.ij[q]] = -a;
        value[slots_.ji[q]] = -a;
      } else if (!fixed_i) {
        rhs[Eigen::Index(pair.i)] += a * fixed_delta[pair.j];
      } else if (!fixed_j) {
        rhs[Eigen::Index(pair.j)] += a * fixed_delta[pair.i];
      }
    }
    for (const auto& f : network_.fixed)
      if (!dirichlet[f.i]) value[slots_.diagonal[f.i]] += f.weight * k[f.i] / gamma;
    // The preconditioner of the step's first iteration serves its later ones (the conjugate
    // gradient reads the matrix's current values; only its convergence rate depends on it).
    if (attempt.iterations == 1) {
      solver_->factorize(matrix_);
      if (solver_->info() != Eigen::Success) return false;
    }
    delta = solver_->solve(rhs);
    if (solver_->info() != Eigen::Success || !delta.allFinite()) return false;

    double largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      p[i] += delta[Eigen::Index(i)];
      largest = std::max(largest, std::fabs(delta[Eigen::Index(i)]));
    }

    // Eq. 39's switch at the new iterate: the water a Dirichlet particle takes through the surface
    // is its residual without Q, V (Θ − Θ^n)/Δt + outflow.
    update_coefficients();
    net_outflow(nullptr);
    bool switched = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!network_.free_surface[i] || forcing.has_surface_pressure) continue;
      const double supply = attempt.supply[i];
      const double taken = network_.volume[i] * (theta[i] - theta_start[i]) / dt + outflow[i];
      std::uint8_t next = attempt.state[i];
      switch (SurfaceState(attempt.state[i])) {
        case SurfaceState::flux:
          if (p[i] > forcing.ponding_pressure) next = std::uint8_t(SurfaceState::ponded);
          else if (supply < 0 && p[i] < forcing.drying_pressure) next = std::uint8_t(SurfaceState::drying);
          break;
        case SurfaceState::ponded:
          if (taken > supply) next = std::uint8_t(SurfaceState::flux);  // the soil takes more than the rain
          break;
        case SurfaceState::drying:
          if (supply >= 0 || taken < supply) next = std::uint8_t(SurfaceState::flux);  // delivers the demand
          break;
        case SurfaceState::held:
          next = std::uint8_t(SurfaceState::flux);
          break;
      }
      switched |= next != attempt.state[i];
      attempt.state[i] = next;
    }
    if (largest > settings_.pressure_tolerance || switched) continue;

    // Converged: this step's volumes, at the final pressures.
    WaterBalance& b = attempt.increment;
    b = WaterBalance{};
    net_outflow(&b);
    attempt.largest_change = 0;
    for (std::size_t i = 0; i < n; ++i) {
      attempt.largest_change = std::max(attempt.largest_change, std::fabs(theta[i] - theta_start[i]));
      b.storage += network_.volume[i] * (theta[i] - theta_start[i]);
      const double supply = attempt.supply[i];
      if (supply > 0) b.rain += supply * dt;
      const double taken = holds_pressure(attempt.state[i])
                               ? network_.volume[i] * (theta[i] - theta_start[i]) / dt + outflow[i]
                               : supply;
      if (taken >= 0) b.infiltration += taken * dt;
      else b.exfiltration -= taken * dt;
      if (supply > 0 && holds_pressure(attempt.state[i])) b.runoff += (supply - std::max(taken, 0.0)) * dt;
    }
    return true;
  }
  return false;
}

}  // namespace cascade
