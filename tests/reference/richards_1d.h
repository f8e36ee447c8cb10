// Reference solver for transient flow in a vertical, rigid soil column: the 1D Richards equation
// on a fine grid, written for the validation tests and sharing no code with the SPH solver.
//
// Equation (z up, p = pore-water pressure p_w, p_c = −p the suction, pore air at zero pressure):
//
//     ∂Θ(p)/∂t + ∂q/∂z = 0,      q = −K(p) [ (1/(ρ_w g)) ∂p/∂z + 1 ]   (q > 0 upwards, m/s)
//
//     Θ(p) = φ S_w(−p) + (φ / K_w) ∫_0^p S_w(−p') dp'                   (m³ water / m³ soil)
//
// The second part of Θ is the storage of a weakly compressible pore water, so that
// dΘ/dp = φ (S_w/K_w + ∂S_w/∂p_w) = C_r / K_w with the C_r of the paper's Eq. 28b (ERRATA.md, row
// "Eq. 28b / 41"): the same storage coefficient as the SPH pore-water continuity (Eq. 3a, 27a), in
// which p_w = K_w/ρ_w0 (ρ_w − ρ_w0) (Eq. 6). The factors (1 + p/K_w) that the SPH equations carry
// through ρ_w/ρ_w0 are not modelled: they are relative corrections of order |p|/K_w. With
// K_w = ∞ (the default) Θ = φ S_w and the equation is the incompressible Richards equation.
//
// Discretisation: cell-centred finite volumes (N equal cells, cell 0 at the bottom), arithmetic
// mean of K on each face, and the mixed form of M. A. Celia, E. T. Bouloutas & R. L. Zarba (1990),
// "A general mass-conservative numerical solution for the unsaturated flow equation", Water
// Resour. Res. 26(7):1483–1496: the time derivative is the difference of Θ between time levels,
// so that water is conserved whatever the nonlinearity, with their modified Picard iteration (K
// frozen at the last iterate, the capacity dΘ/dp used only to linearise Θ). Time stepping is the
// θ-method on the fluxes (time_weight 1: backward Euler; 0.5: Crank–Nicolson). A step is accepted
// when the cell balance residual is below residual_tolerance in every cell; the boundary fluxes
// are summed with the same weights, so that (storage change) − (cumulative boundary inflow) is the
// sum of the accepted residuals, which a test can bound.
//
// Boundary conditions: top — a prescribed flux (positive into the soil), a prescribed pressure,
// or the adaptive ("atmospheric") switch of the paper's Eq. 39 and Section 3 (ERRATA.md, row
// "Eq. 39"): the flux until the surface could only take it at a pressure above p_max (ponding),
// then p = p_max; while evaporating, p = p_min once the surface cannot deliver the demand at
// p_min; back to the flux when the soil can take (or deliver) it again. Bottom — no flow or a fixed
// pressure. A Dirichlet value sits on the boundary face, half a cell from the nearest centre.
//
// Layered columns: a second constructor takes a list of layers (RichardsLayer, bottom to top, each
// with its own soil); a cell takes the soil of the layer holding its centre. Within a soil the
// face conductivity is the arithmetic mean of the two cells'; on a face between two different soils
// it is the harmonic mean 2 K_a K_b/(K_a + K_b), which is what eliminating the face pressure from
// the two half-cell Darcy fluxes (continuity of pressure and of flux through the face, each half
// cell with its centre's K) gives exactly, gravity term included. Put layer boundaries on cell
// faces (layer tops multiples of height/cells) for that to hold.
//
// Units: SI throughout (m, s, Pa, kg/m³); any consistent set works if every input uses it.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace cascade::reference {

// The soil and the pore water. The curves are callables of the suction p_c = −p_w (Pa): for
// p_c <= 0 (saturated) they should return S_w = S_max and K_rel = 1 unless a test wants otherwise.
struct RichardsSoil {
  double porosity = 0;                                                  // φ (-)
  double saturated_conductivity = 0;                                    // K_sat (m/s)
  std::function<double(double)> saturation;                             // S_w(p_c) (-)
  std::function<double(double)> relative_conductivity;                  // K_rel(p_c) = K/K_sat (-)
  double water_density = 1000.0;                                        // ρ_w (kg/m³)
  double gravity = 9.81;                                                // g (m/s²)
  double water_bulk_modulus = std::numeric_limits<double>::infinity();  // K_w (Pa)
};

// One layer of a layered column: the soil from the top of the layer below (or the base) up to
// `top` (m above the base).
struct RichardsLayer {
  double top = 0;
  RichardsSoil soil;
};

// What the top face imposes during a step.
enum class TopState { flux, pressure, ponded, drying_limit };

struct TopBoundary {
  enum class Kind { flux, pressure, adaptive };
  Kind kind = Kind::flux;
  std::function<double(double)> flux_in;   // q_in(t) (m/s), > 0 infiltration, < 0 evaporation
  std::function<double(double)> pressure;  // p_w(t) on the surface (Pa), Kind::pressure
  double pressure_max = 0;                 // p_max (Pa): ponding pressure, Kind::adaptive
  double pressure_min = -std::numeric_limits<double>::infinity();  // p_min (Pa), Kind::adaptive

  static TopBoundary constant_flux(double q_in) {
    TopBoundary b;
    b.kind = Kind::flux;
    b.flux_in = [q_in](double) { return q_in; };
    return b;
  }
  static TopBoundary constant_pressure(double p) {
    TopBoundary b;
    b.kind = Kind::pressure;
    b.pressure = [p](double) { return p; };
    return b;
  }
  static TopBoundary adaptive(double q_in, double p_max, double p_min) {
    TopBoundary b;
    b.kind = Kind::adaptive;
    b.flux_in = [q_in](double) { return q_in; };
    b.pressure_max = p_max;
    b.pressure_min = p_min;
    return b;
  }
};

struct BottomBoundary {
  enum class Kind { no_flow, pressure };
  Kind kind = Kind::no_flow;
  double pressure = 0;  // p_w on the bottom face (Pa), Kind::pressure

  static BottomBoundary no_flow() { return {}; }
  static BottomBoundary fixed_pressure(double p) { return {Kind::pressure, p}; }
};

struct RichardsOptions {
  int cells = 300;              // N
  double max_time_step = 60.0;  // Δt_max (s)
  double min_time_step = 1e-6;  // below this a failing step is an error (s)
  // θ of the θ-method on the fluxes, in [0.5, 1]. 0.5 (Crank–Nicolson) is second order but rings
  // after a jump in the data (a sudden Dirichlet value) unless Δt K/(C dz²) is small; 1 does not.
  double time_weight = 1.0;
  int max_iterations = 60;            // Picard iterations before the step is halved
  double residual_tolerance = 1e-14;  // per-cell balance residual (m of water), accepted step
  double pressure_tolerance = 1e-6;   // last Picard update (Pa), accepted step
};

// A profile at one time. Cumulative inflows are in m of water per unit area since the start,
// positive into the soil; water_storage = Σ dz Θ (m); so storage − initial storage equals
// cumulative_top_inflow + cumulative_bottom_inflow up to the accepted residuals.
struct RichardsSnapshot {
  double time = 0;                      // s
  std::vector<double> z;                // cell centres (m)
  std::vector<double> pore_pressure;    // p_w at the centres (Pa)
  double surface_pressure = 0;          // p_w on the top face (Pa): imposed, or from the flux
  double water_storage = 0;             // m
  double cumulative_top_inflow = 0;     // m
  double cumulative_bottom_inflow = 0;  // m
  double accumulated_residual = 0;      // Σ |residual| over accepted steps and cells (m)
  TopState top_state = TopState::flux;
  long steps = 0;  // accepted time steps so far
};

class Richards1d {
 public:
  // height: column height L (m); initial_pressure(z): p_w at t = 0 (Pa), z in [0, L].
  Richards1d(RichardsSoil soil, double height,
             const std::function<double(double)>& initial_pressure, TopBoundary top,
             BottomBoundary bottom, RichardsOptions options = {})
      : Richards1d(std::vector<RichardsLayer>{{height, std::move(soil)}}, height, initial_pressure,
                   std::move(top), bottom, options) {}

  // Layered column: layers bottom to top, the last one's top at least `height`.
  Richards1d(std::vector<RichardsLayer> layers, double height,
             const std::function<double(double)>& initial_pressure, TopBoundary top,
             BottomBoundary bottom, RichardsOptions options = {})
      : height_(height), top_(std::move(top)), bottom_(bottom), options_(options) {
    if (!(height_ > 0) || options_.cells < 2) throw std::invalid_argument("Richards1d: bad grid");
    if (layers.empty() || !(layers.back().top >= height_ * (1 - 1e-12)))
      throw std::invalid_argument("Richards1d: the layers must reach the top of the column");
    for (std::size_t l = 0; l < layers.size(); ++l) {
      const RichardsSoil& s = layers[l].soil;
      if (!(s.porosity > 0) || !(s.saturated_conductivity > 0) || !s.saturation ||
          !s.relative_conductivity)
        throw std::invalid_argument("Richards1d: incomplete soil");
      if (s.water_density != layers[0].soil.water_density || s.gravity != layers[0].soil.gravity ||
          (l > 0 && !(layers[l].top > layers[l - 1].top)))
        throw std::invalid_argument("Richards1d: layers need one water and ascending tops");
      soils_.push_back(s);
    }
    if (options_.time_weight < 0.5 || options_.time_weight > 1.0)
      throw std::invalid_argument("Richards1d: time_weight must lie in [0.5, 1]");
    if ((top_.kind != TopBoundary::Kind::pressure && !top_.flux_in) ||
        (top_.kind == TopBoundary::Kind::pressure && !top_.pressure))
      throw std::invalid_argument("Richards1d: top boundary lacks its function");
    if (top_.kind == TopBoundary::Kind::adaptive && !(top_.pressure_min < top_.pressure_max))
      throw std::invalid_argument("Richards1d: need p_min < p_max");
    const int n = options_.cells;
    dz_ = height_ / n;
    rho_g_ = soils_[0].water_density * soils_[0].gravity;
    z_.resize(n);
    p_.resize(n);
    cell_soil_.resize(n);
    for (int i = 0; i < n; ++i) {
      z_[i] = (i + 0.5) * dz_;
      p_[i] = initial_pressure(z_[i]);
      int l = 0;
      while (layers[l].top < z_[i]) ++l;
      cell_soil_[i] = l;
    }
    state_ = top_.kind == TopBoundary::Kind::pressure ? TopState::pressure : TopState::flux;
    if (top_.kind == TopBoundary::Kind::adaptive) state_ = adaptive_state_for_start();
    theta_.resize(n);
    for (int i = 0; i < n; ++i) theta_[i] = storage(p_[i], i);
    initial_storage_ = total_storage();
    dt_ = options_.max_time_step;
    evaluate_explicit_fluxes();
  }

  // Advances to time t_end (s), with steps no longer than max_time_step; ends exactly on t_end.
  void advance_to(double t_end) {
    while (t_ < t_end) {
      const double remaining = t_end - t_;
      double dt = std::min(dt_, remaining);
      if (remaining - dt < 1e-9 * dt) dt = remaining;
      bool halved = false;
      while (!try_step(dt)) {
        dt *= 0.5;
        halved = true;
        if (dt < options_.min_time_step)
          throw std::runtime_error("Richards1d: no convergence at t = " + std::to_string(t_));
      }
      if (!halved && dt == remaining) t_ = t_end;  // no round-off sliver left over
      // After a failure keep the step that worked, then grow back towards the maximum.
      dt_ = halved ? dt : std::min(options_.max_time_step, 1.5 * dt_);
    }
  }

  RichardsSnapshot snapshot() const {
    RichardsSnapshot s;
    s.time = t_;
    s.z = z_;
    s.pore_pressure = p_;
    s.surface_pressure = surface_pressure();
    s.water_storage = total_storage();
    s.cumulative_top_inflow = top_inflow_;
    s.cumulative_bottom_inflow = bottom_inflow_;
    s.accumulated_residual = residual_sum_;
    s.top_state = state_;
    s.steps = steps_;
    return s;
  }

  double time() const { return t_; }
  double initial_storage() const { return initial_storage_; }
  double cell_size() const { return dz_; }
  const std::vector<double>& cell_centres() const { return z_; }
  const std::vector<double>& pore_pressure() const { return p_; }
  TopState top_state() const { return state_; }

  // p_w at height z (m), linear between centres and on to the faces (the imposed value on a
  // Dirichlet face).
  double pore_pressure_at(double z) const {
    const int n = options_.cells;
    if (z >= z_[n - 1]) {
      const double ps = surface_pressure();
      return p_[n - 1] + (ps - p_[n - 1]) * (z - z_[n - 1]) / (0.5 * dz_);
    }
    if (z <= z_[0]) {
      const double pb = bottom_.kind == BottomBoundary::Kind::pressure
                            ? bottom_.pressure
                            : p_[0] - (p_[1] - p_[0]) * 0.5;  // linear extrapolation
      return pb + (p_[0] - pb) * z / (0.5 * dz_);
    }
    const double s = z / dz_ - 0.5;
    const int i = std::min(n - 2, int(s));
    const double w = s - i;
    return (1 - w) * p_[i] + w * p_[i + 1];
  }

  // Θ(p): water volume per soil volume, including the compressible-storage part, for the soil of
  // cell `cell` (default: the bottom cell's, the only soil of a homogeneous column).
  double storage(double p, int cell = 0) const {
    const RichardsSoil& soil = soils_[cell_soil_[cell]];
    const double phi = soil.porosity;
    double theta = phi * soil.saturation(-p);
    if (std::isfinite(soil.water_bulk_modulus))
      theta += phi / soil.water_bulk_modulus * saturation_integral(p, soil);
    return theta;
  }

  double total_storage() const {
    double sum = 0;
    for (double th : theta_) sum += th * dz_;
    return sum;
  }

 private:
  // ∫_0^p S_w(−p') dp' by composite 8-point Gauss–Legendre; a fixed rule, so storage() is a
  // single-valued function of p and the discrete water balance closes exactly.
  double saturation_integral(double p, const RichardsSoil& soil) const {
    static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                    0.9602898564975363};
    static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                    0.1012285362903763};
    const int pieces = std::clamp(int(std::ceil(std::fabs(p) / (0.5 * rho_g_))), 1, 64);
    const double h = p / pieces;
    double sum = 0;
    for (int k = 0; k < pieces; ++k) {
      const double mid = (k + 0.5) * h, half = 0.5 * h;
      for (int j = 0; j < 4; ++j)
        sum += w[j] *
               (soil.saturation(-(mid + half * x[j])) + soil.saturation(-(mid - half * x[j])));
    }
    return sum * 0.5 * h;
  }

  double conductivity(double p, int cell) const {
    const RichardsSoil& soil = soils_[cell_soil_[cell]];
    return soil.saturated_conductivity * std::max(0.0, soil.relative_conductivity(-p));
  }

  // dΘ/dp by a central difference (used only to linearise; the balance uses Θ itself).
  double capacity(double p, int cell) const {
    const double h = 1e-4 * rho_g_;
    const double c = (storage(p + h, cell) - storage(p - h, cell)) / (2 * h);
    return std::max(c, 1e-14 / rho_g_);
  }

  // Upward Darcy flux between pressures p_lo (below) and p_hi (above) a distance apart, through
  // a face of conductivity k.
  double face_flux(double p_lo, double p_hi, double distance, double k) const {
    return -k * ((p_hi - p_lo) / (rho_g_ * distance) + 1.0);
  }

  // Flux into the soil through the top face for surface pressure ps and top-cell pressure pc.
  double dirichlet_inflow(double ps, double pc) const {
    const int top = options_.cells - 1;
    const double k = 0.5 * (conductivity(ps, top) + conductivity(pc, top));
    return -face_flux(pc, ps, 0.5 * dz_, k);
  }

  double top_pressure_for(TopState s, double t) const {
    switch (s) {
      case TopState::pressure: return top_.pressure(t);
      case TopState::ponded: return top_.pressure_max;
      case TopState::drying_limit: return top_.pressure_min;
      case TopState::flux: break;
    }
    return 0;
  }

  TopState adaptive_state_for_start() const {
    const double q = top_.flux_in(t_), pc = p_.back();
    if (q > 0 && dirichlet_inflow(top_.pressure_max, pc) < q) return TopState::ponded;
    if (q < 0 && dirichlet_inflow(top_.pressure_min, pc) > q) return TopState::drying_limit;
    return TopState::flux;
  }

  // Surface pressure: the imposed value, or in flux mode the p_s for which the Dirichlet face
  // formula gives the prescribed flux (bisection; clamped to [p_c − 1e3 ρg, p_c + 1e3 ρg]).
  double surface_pressure() const {
    if (state_ != TopState::flux) return top_pressure_for(state_, t_);
    const double q = top_.flux_in(t_), pc = p_.back();
    double lo = pc - 1e3 * rho_g_, hi = pc + 1e3 * rho_g_;
    if (dirichlet_inflow(lo, pc) > q) return lo;
    if (dirichlet_inflow(hi, pc) < q) return hi;
    for (int k = 0; k < 200 && hi - lo > 1e-9 * (1 + std::fabs(pc)); ++k) {
      const double mid = 0.5 * (lo + hi);
      (dirichlet_inflow(mid, pc) < q ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  // Cell flux balances F_i = q_{i−½} − q_{i+½} of state p with the boundary conditions of state s
  // at time t; also the boundary inflows and, if wanted, the frozen-K Picard coefficients.
  struct Fluxes {
    std::vector<double> balance;  // m/s per cell
    std::vector<double> a_face;   // K_f/(ρ g d) on faces 0..N (boundary faces included)
    double top_inflow = 0, bottom_inflow = 0;
  };

  Fluxes fluxes(const std::vector<double>& p, TopState s, double t) const {
    const int n = options_.cells;
    Fluxes f;
    f.balance.assign(n, 0.0);
    f.a_face.assign(n + 1, 0.0);
    std::vector<double> k(n);
    for (int i = 0; i < n; ++i) k[i] = conductivity(p[i], i);
    // Interior faces: face i between cells i−1 and i.
    for (int i = 1; i < n; ++i) {
      double kf = 0.5 * (k[i - 1] + k[i]);
      if (cell_soil_[i - 1] != cell_soil_[i])  // a layer boundary: harmonic mean (header)
        kf = k[i - 1] + k[i] > 0 ? 2 * k[i - 1] * k[i] / (k[i - 1] + k[i]) : 0.0;
      const double q = face_flux(p[i - 1], p[i], dz_, kf);
      f.balance[i - 1] -= q;
      f.balance[i] += q;
      f.a_face[i] = kf / (rho_g_ * dz_);
    }
    // Bottom face.
    if (bottom_.kind == BottomBoundary::Kind::pressure) {
      const double kf = 0.5 * (conductivity(bottom_.pressure, 0) + k[0]);
      const double q = face_flux(bottom_.pressure, p[0], 0.5 * dz_, kf);
      f.bottom_inflow = q;
      f.balance[0] += q;
      f.a_face[0] = kf / (rho_g_ * 0.5 * dz_);
    }
    // Top face.
    if (s == TopState::flux) {
      f.top_inflow = top_.flux_in(t);
    } else {
      const double ps = top_pressure_for(s, t);
      const double kf = 0.5 * (conductivity(ps, n - 1) + k[n - 1]);
      f.top_inflow = -face_flux(p[n - 1], ps, 0.5 * dz_, kf);
      f.a_face[n] = kf / (rho_g_ * 0.5 * dz_);
    }
    f.balance[n - 1] += f.top_inflow;
    return f;
  }

  void evaluate_explicit_fluxes() { explicit_ = fluxes(p_, state_, t_); }

  // One step of length dt in the current top state, switching the adaptive state (and redoing
  // the step) when the converged solution says the other condition holds. False: no convergence.
  bool try_step(double dt) {
    TopState s = state_;
    std::vector<double> p_new;
    Fluxes f_new;
    double residual = 0;
    for (int attempt = 0; attempt < 4; ++attempt) {
      if (!solve_step(dt, s, p_new, f_new, residual)) return false;
      if (top_.kind != TopBoundary::Kind::adaptive || attempt == 3) break;
      const TopState next = adaptive_state_after(s, t_ + dt, p_new, f_new);
      if (next == s) break;
      s = next;
    }
    const double w = options_.time_weight;
    top_inflow_ += dt * (w * f_new.top_inflow + (1 - w) * explicit_.top_inflow);
    bottom_inflow_ += dt * (w * f_new.bottom_inflow + (1 - w) * explicit_.bottom_inflow);
    residual_sum_ += residual;
    p_ = std::move(p_new);
    for (int i = 0; i < options_.cells; ++i) theta_[i] = storage(p_[i], i);
    t_ += dt;
    state_ = s;
    ++steps_;
    explicit_ = std::move(f_new);
    return true;
  }

  TopState adaptive_state_after(TopState s, double t, const std::vector<double>& p,
                                const Fluxes& f) const {
    const double q = top_.flux_in(t), pc = p.back();
    switch (s) {
      case TopState::flux:
        if (q > 0 && dirichlet_inflow(top_.pressure_max, pc) < q) return TopState::ponded;
        if (q < 0 && dirichlet_inflow(top_.pressure_min, pc) > q) return TopState::drying_limit;
        return s;
      case TopState::ponded: return (q <= 0 || f.top_inflow > q) ? TopState::flux : s;
      case TopState::drying_limit: return (q >= 0 || f.top_inflow < q) ? TopState::flux : s;
      case TopState::pressure: break;
    }
    return s;
  }

  // Modified Picard iteration for one step (Celia et al. 1990): solve
  //   dz (Θ(p^{m+1}) − Θ^n)/dt = w F(p^{m+1}) + (1 − w) F^n
  // linearised with K frozen at p^m and Θ(p^{m+1}) ≈ Θ(p^m) + C(p^m) δ.
  bool solve_step(double dt, TopState s, std::vector<double>& p, Fluxes& f, double& residual_out) {
    const int n = options_.cells;
    const double w = options_.time_weight, t_new = t_ + dt;
    p = p_;
    std::vector<double> lower(n), diag(n), upper(n), rhs(n), th(n);
    double last_update = std::numeric_limits<double>::infinity();
    for (int it = 0; it <= options_.max_iterations; ++it) {
      f = fluxes(p, s, t_new);
      double max_residual = 0, sum_residual = 0;
      for (int i = 0; i < n; ++i) {
        th[i] = storage(p[i], i);
        const double r =
            dz_ * (th[i] - theta_[i]) - dt * (w * f.balance[i] + (1 - w) * explicit_.balance[i]);
        rhs[i] = -r;
        max_residual = std::max(max_residual, std::fabs(r));
        sum_residual += std::fabs(r);
      }
      if (!std::isfinite(sum_residual)) return false;
      if (max_residual <= options_.residual_tolerance &&
          last_update <= options_.pressure_tolerance) {
        residual_out = sum_residual;
        return true;
      }
      if (it == options_.max_iterations) break;
      for (int i = 0; i < n; ++i) {
        const double a_lo = f.a_face[i], a_hi = f.a_face[i + 1];
        diag[i] = dz_ * capacity(p[i], i) + dt * w * (a_lo + a_hi);
        lower[i] = i > 0 ? -dt * w * a_lo : 0.0;
        upper[i] = i < n - 1 ? -dt * w * a_hi : 0.0;
      }
      solve_tridiagonal(lower, diag, upper, rhs);  // rhs becomes δ
      last_update = 0;
      for (int i = 0; i < n; ++i) {
        p[i] += rhs[i];
        last_update = std::max(last_update, std::fabs(rhs[i]));
      }
    }
    return false;
  }

  // Thomas algorithm; the matrix is symmetric and diagonally dominant.
  static void solve_tridiagonal(std::vector<double>& a, std::vector<double>& b,
                                std::vector<double>& c, std::vector<double>& d) {
    const int n = int(d.size());
    for (int i = 1; i < n; ++i) {
      const double m = a[i] / b[i - 1];
      b[i] -= m * c[i - 1];
      d[i] -= m * d[i - 1];
    }
    d[n - 1] /= b[n - 1];
    for (int i = n - 2; i >= 0; --i) d[i] = (d[i] - c[i] * d[i + 1]) / b[i];
  }

  std::vector<RichardsSoil> soils_;  // one per layer, bottom to top
  std::vector<int> cell_soil_;        // layer of each cell
  double height_;
  TopBoundary top_;
  BottomBoundary bottom_;
  RichardsOptions options_;
  double dz_ = 0, rho_g_ = 0, t_ = 0, dt_ = 0;
  std::vector<double> z_, p_, theta_;
  TopState state_ = TopState::flux;
  Fluxes explicit_;
  double top_inflow_ = 0, bottom_inflow_ = 0, residual_sum_ = 0, initial_storage_ = 0;
  long steps_ = 0;
};

// Runs a column and returns the profiles at the requested times (s, ascending).
inline std::vector<RichardsSnapshot> solve_richards_1d(
    const RichardsSoil& soil, double height, const std::function<double(double)>& initial_pressure,
    const TopBoundary& top, const BottomBoundary& bottom, const std::vector<double>& output_times,
    const RichardsOptions& options = {}) {
  Richards1d solver(soil, height, initial_pressure, top, bottom, options);
  std::vector<RichardsSnapshot> out;
  out.reserve(output_times.size());
  for (double t : output_times) {
    solver.advance_to(t);
    out.push_back(solver.snapshot());
  }
  return out;
}

}  // namespace cascade::reference
