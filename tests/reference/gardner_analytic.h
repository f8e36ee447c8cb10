// Closed-form transient solutions of the Richards equation for Gardner's exponential soil, the
// reference of the paper's Section 4.1 (1D infiltration/evaporation, Eq. 42; ERRATA.md, row
// "Section 4.1").
//
// Soil (Gardner 1958, in the form used by Srivastava & Yeh 1991), ψ the pressure head (m),
// negative in the unsaturated zone:
//
//     K(ψ) = K_s e^{αψ},        θ(ψ) = θ_r + (θ_s − θ_r) e^{αψ}.
//
// The paper's Eq. 42 is this model with ψ = −p_c/(ρ_w0 g): α = 2 1/m, θ_s = φ S_max = 0.4,
// θ_r = φ S_min = 0.4 · 0.23 = 0.092 (section_4_1_soil() below). Because dθ/dK = (θ_s − θ_r)/K_s
// is a constant and K ∂ψ/∂z = (1/α) ∂K/∂z, the Richards equation becomes *exactly* linear in K.
// In the dimensionless variables of Srivastava & Yeh,
//
//     z = α z*,  L = α L*,  K = K*/K_s,  q = q*/K_s,  t = α K_s t* / (θ_s − θ_r),
//
// with z measured upwards from the base of the column, it reads
//
//     ∂K/∂t = ∂²K/∂z² + ∂K/∂z,      downward flux q = ∂K/∂z + K.
//
// Linear does not mean the solution stays physical: K must stay positive (K → 0 is ψ → −∞, a
// surface that has dried out) and, for the soil of Eq. 42 whose S_w is capped at S_max for
// p_c <= 0, K must not exceed 1 (ψ > 0, which the exponential continues as θ > θ_s). valid()
// reports both; a Richards solver compared with these solutions must use the same, uncapped
// exponential curves where K > 1 occurs.
//
// Two problems, both starting from a steady state:
//
//  * ColumnBase::water_table — Srivastava & Yeh's problem: the base is a water table held at
//    pressure head ψ_0 (K(0, t) = e^{αψ_0}); the initial state is the steady profile for a surface
//    flux q_A; at t = 0 the surface flux becomes q_B. Solution (Srivastava & Yeh's homogeneous
//    soil solution, re-derived here by separation of variables with K = K_∞ + e^{−z/2 − t/4} v):
//
//      K = q_B − (q_B − e^{αψ_0}) e^{−z}
//          − 4 (q_B − q_A) e^{(L−z)/2} e^{−t/4} Σ_n sin(λ_n z) sin(λ_n L) e^{−λ_n² t}
//                                                   / (1 + L/2 + 2 L λ_n²),
//      λ_n the positive roots of tan(λL) + 2λ = 0, one in each ((n − ½)π/L, nπ/L).
//
//  * ColumnBase::no_flow — the paper's Section 4.1 set-up: an impermeable base (∂K/∂z + K = 0 at
//    z = 0) and a hydrostatic initial state K = e^{αψ_0} e^{−z} (ψ_0 the head at the base; the
//    paper's p_w = −ρ_w g z is ψ_0 = 0). No steady state exists: the column gains q_B per unit
//    time, and the mass goes into the zero-flux mode e^{−z}. Derived here the same way (Robin
//    conditions at both ends give λ_n = nπ/L and eigenfunctions
//    φ_n = λ_n cos(λ_n z) − ½ sin(λ_n z), all orthogonal to the mode e^{−z/2} that carries the
//    mass; Green's identity gives the coefficients):
//
//      K = e^{αψ_0} e^{−z} + q_B B [ t e^{−z} + 1 − z e^{−z} ] + q_B C e^{−z}
//          + e^{−z/2} e^{−t/4} Σ_n a_n φ_n(z) e^{−λ_n² t},
//      B = 1/(1 − e^{−L}),   C = −B (L − 1 + (1 + L) e^{−L})/(1 − e^{−L})
//      (C makes the integral of the t = 0 part over the column zero),
//      a_n = −q_B (−1)^n λ_n e^{L/2} / ((λ_n² + ¼)² L/2),
//      downward flux = q_B B (1 − e^{−z})
//                      − e^{−z/2} e^{−t/4} Σ_n a_n (λ_n² + ¼) sin(λ_n z) e^{−λ_n² t}.
//
// Series are summed until the bound on the next term is below series_tolerance (relative to 1,
// the scale of K); at t = 0 the initial state is returned exactly.
//
// Source: R. Srivastava and T.-C. J. Yeh (1991), "Analytical solutions for one-dimensional,
// transient infiltration toward the water table in homogeneous and layered soils", Water Resources
// Research 27(5):753–762, doi:10.1029/90WR02772. The dimensionless form, boundary conditions and
// the eigenvalue equation tan(λL) + 2λ = 0 were checked against the open implementation of
// T. Bandai and T. A. Ghezzehei, DD-PINNs-RRE (github.com/ToshiyukiBandai/DD-PINNs-RRE,
// analytical_solutions/Srivastava1991_homogeneous.ipynb, doi:10.5281/zenodo.6030635) and the
// paper's abstract; the paper's full text was not available here, so its equation numbers are
// not quoted.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace cascade::reference {

struct GardnerSoil {
  double alpha = 0;                   // α (1/m)
  double theta_s = 0;                 // saturated water content θ_s (-)
  double theta_r = 0;                 // residual water content θ_r (-)
  double saturated_conductivity = 0;  // K_s (m/s)
};

// The paper's Eq. 42 soil (Section 4.1): φ = 0.4, S_w = 0.23 + 0.77 exp(−2 p_c/(ρ_w0 g)),
// K = K_sat exp(−2 p_c/(ρ_w0 g)), K_sat = 1 m/day.
inline GardnerSoil section_4_1_soil() {
  return GardnerSoil{2.0, 0.4 * 1.0, 0.4 * 0.23, 1.0 / 86400.0};
}
constexpr double kSection41Height = 3.0;                    // m
constexpr double kSection41Infiltration = 0.1 / 86400.0;    // m/s, into the soil
constexpr double kSection41Evaporation = -0.002 / 86400.0;  // m/s, out of the soil

enum class ColumnBase { water_table, no_flow };

struct GardnerColumn {
  GardnerSoil soil;
  double height = 0;  // L* (m)
  ColumnBase base = ColumnBase::no_flow;
  double base_pressure_head = 0;  // ψ_0 (m): water-table head, or head at the base at t = 0
  double initial_flux_in = 0;     // q_A* (m/s, downward = into the soil); no_flow needs 0
  double flux_in = 0;             // q_B* (m/s, downward = into the soil), for t > 0
};

class GardnerColumnSolution {
 public:
  explicit GardnerColumnSolution(const GardnerColumn& column, double series_tolerance = 1e-15)
      : c_(column), tolerance_(series_tolerance) {
    const GardnerSoil& s = c_.soil;
    if (!(s.alpha > 0) || !(s.theta_s > s.theta_r) || !(s.saturated_conductivity > 0) ||
        !(c_.height > 0))
      throw std::invalid_argument("GardnerColumnSolution: bad soil or height");
    if (c_.base == ColumnBase::no_flow && c_.initial_flux_in != 0)
      throw std::invalid_argument("GardnerColumnSolution: a no-flow base starts hydrostatic");
    length_ = s.alpha * c_.height;
    k0_ = std::exp(s.alpha * c_.base_pressure_head);
    q_a_ = c_.initial_flux_in / s.saturated_conductivity;
    q_b_ = c_.flux_in / s.saturated_conductivity;
    time_scale_ = (s.theta_s - s.theta_r) / (s.alpha * s.saturated_conductivity);
    const double e_l = std::exp(-length_);
    no_flow_c_ = -(length_ - 1.0 + (1.0 + length_) * e_l) / ((1.0 - e_l) * (1.0 - e_l));
  }

  // Seconds per unit of dimensionless time, (θ_s − θ_r)/(α K_s).
  double time_scale() const { return time_scale_; }

  // K/K_s at height z (m above the base) and time t (s). May be <= 0 or > 1 (see valid()).
  double relative_conductivity(double z, double t) const {
    return evaluate(c_.soil.alpha * z, t / time_scale_, false);
  }

  // Downward Darcy flux (m/s) at height z and time t.
  double downward_flux(double z, double t) const {
    return c_.soil.saturated_conductivity * evaluate(c_.soil.alpha * z, t / time_scale_, true);
  }

  // Pressure head ψ (m); NaN where K <= 0.
  double pressure_head(double z, double t) const {
    const double k = relative_conductivity(z, t);
    return k > 0 ? std::log(k) / c_.soil.alpha : std::numeric_limits<double>::quiet_NaN();
  }

  // Pore-water pressure p_w = ρ_w g ψ (Pa).
  double pore_pressure(double z, double t, double water_density = 1000.0,
                       double gravity = 9.81) const {
    return water_density * gravity * pressure_head(z, t);
  }

  // θ = θ_r + (θ_s − θ_r) K/K_s (-), uncapped.
  double water_content(double z, double t) const {
    return c_.soil.theta_r + (c_.soil.theta_s - c_.soil.theta_r) * relative_conductivity(z, t);
  }

  // True where the linear solution is a solution of the physical problem: 0 < K, and K <= 1 when
  // the soil's saturation is capped at S_max (require_unsaturated).
  bool valid(double z, double t, bool require_unsaturated = true) const {
    const double k = relative_conductivity(z, t);
    return k > 0 && (!require_unsaturated || k <= 1.0 + 1e-12);
  }

  // Terms the series needed at (z, t) for the last evaluation (diagnostics for the tests).
  int last_term_count() const { return last_terms_; }

 private:
  // K (derivative = false) or ∂K/∂z + K (derivative = true), dimensionless, at (z, t).
  double evaluate(double z, double t, bool derivative) const {
    const double L = length_;
    last_terms_ = 0;
    if (c_.base == ColumnBase::water_table) {
      const double qa = q_a_, qb = q_b_;
      if (t <= 0) {  // steady profile for q_A
        const double k = qa - (qa - k0_) * std::exp(-z);
        return derivative ? qa : k;
      }
      const double steady_k = qb - (qb - k0_) * std::exp(-z);
      double sum = 0;
      const double amplitude = 4.0 * (qb - qa);
      for (int n = 1;; ++n) {
        const double lam = water_table_root(n);
        const double denominator = 1.0 + 0.5 * L + 2.0 * L * lam * lam;
        const double decay = std::exp(0.5 * (L - z) - 0.25 * t - lam * lam * t);
        const double s = std::sin(lam * z), cz = std::cos(lam * z), sl = std::sin(lam * L);
        // d/dz [e^{−z/2} sin λz] + e^{−z/2} sin λz = e^{−z/2} (λ cos λz + ½ sin λz)
        const double shape = derivative ? lam * cz + 0.5 * s : s;
        sum += decay * shape * sl / denominator;
        last_terms_ = n;
        const double bound = std::fabs(amplitude) * decay * (1.0 + lam) / denominator;
        if ((bound < tolerance_ && n > 2) || n >= kMaxTerms) break;
      }
      return derivative ? qb - amplitude * sum : steady_k - amplitude * sum;
    }
    // No-flow base.
    const double qb = q_b_;
    const double hydrostatic = k0_ * std::exp(-z);
    if (t <= 0) return derivative ? 0.0 : hydrostatic;
    const double b = 1.0 / (1.0 - std::exp(-L));
    const double particular =
        qb * (b * (t * std::exp(-z) + 1.0 - z * std::exp(-z)) + no_flow_c_ * std::exp(-z));
    const double particular_flux = qb * b * (1.0 - std::exp(-z));
    double sum = 0;
    const double e_half = std::exp(0.5 * L);
    for (int n = 1;; ++n) {
      const double lam = n * kPi / L, lam2 = lam * lam + 0.25;
      const double sign = (n % 2 == 0) ? 1.0 : -1.0;
      const double a_n = -qb * sign * lam * e_half / (lam2 * lam2 * 0.5 * L);
      const double decay = std::exp(-0.5 * z - 0.25 * t - lam * lam * t);
      const double s = std::sin(lam * z);
      // (∂/∂z + 1)[e^{−z/2} φ_n] = −e^{−z/2} (λ² + ¼) sin λz.
      const double shape = derivative ? -lam2 * s : lam * std::cos(lam * z) - 0.5 * s;
      sum += a_n * decay * shape;
      last_terms_ = n;
      const double bound = std::fabs(a_n) * std::exp(-0.25 * t - lam * lam * t) * (lam2 + lam);
      if ((bound < tolerance_ && n > 2) || n >= kMaxTerms) break;
    }
    return derivative ? particular_flux + sum : hydrostatic + particular + sum;
  }

  // n-th positive root of sin(λL) + 2λ cos(λL) = 0 (that is tan λL + 2λ = 0), which lies in
  // ((n − ½)π/L, nπ/L); bisection, cached.
  double water_table_root(int n) const {
    while (int(roots_.size()) < n) {
      const int m = int(roots_.size()) + 1;
      const double L = length_;
      double lo = (m - 0.5) * kPi / L, hi = m * kPi / L;
      auto g = [L](double x) { return std::sin(x * L) + 2.0 * x * std::cos(x * L); };
      const double g_lo = g(lo);
      for (int k = 0; k < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((g(mid) > 0) == (g_lo > 0) ? lo : hi) = mid;
      }
      roots_.push_back(0.5 * (lo + hi));
    }
    return roots_[n - 1];
  }

  static constexpr double kPi = 3.14159265358979323846;
  static constexpr int kMaxTerms = 400000;

  GardnerColumn c_;
  double tolerance_;
  double length_ = 0, k0_ = 1, q_a_ = 0, q_b_ = 0, time_scale_ = 1, no_flow_c_ = 0;
  // Lazily computed eigenvalues and a diagnostic counter: evaluation is not thread-safe.
  mutable std::vector<double> roots_;
  mutable int last_terms_ = 0;
};

}  // namespace cascade::reference
