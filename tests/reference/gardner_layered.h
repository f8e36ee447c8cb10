// Closed-form transient solution of the Richards equation in a column of two Gardner soils over a
// water table: the layered-soil problem of Srivastava & Yeh (1991), beside the homogeneous one in
// gardner_analytic.h (read that header first: same soil model, same variables, same sign
// conventions).
//
// Problem (z* up from the water table, ψ the pressure head, downward flux q* > 0 into the soil):
//
//   lower layer 1: 0 <= z* <= L1*,  upper layer 2: L1* <= z* <= L1* + L2* = L*,
//   K_i(ψ) = K_si e^{αψ},  θ_i(ψ) = θ_ri + Δθ_i e^{αψ},  Δθ_i = θ_si − θ_ri   (Gardner 1958),
//   ∂θ_i/∂t* = ∂q*/∂z*,   q* = K_i(ψ) (∂ψ/∂z* + 1)                           (Richards 1931),
//   ψ(0, t*) = ψ_0;  q*(L*, t*) = q_B* for t* > 0;  ψ, q* continuous at z* = L1*;
//   initial state: the steady profile for the surface flux q_A*.
//
// One α for both layers. With k = e^{αψ} (= K/K_si in either layer) continuity of ψ at the
// interface is continuity of k, which is linear; with α_1 ≠ α_2 it would be k_2 = k_1^{α_2/α_1}
// and the transformed problem would no longer be linear. The transient solution therefore needs
// α_1 = α_2 (the constructor throws otherwise). The open implementation cited below carries α_1 and
// α_2 separately in its scaling but uses α_1 = α_2 in its example; the paper's full text was not
// available here to say what Srivastava & Yeh assume. The steady profile alone has a closed form
// for any α_1, α_2 (layered_gardner_steady_pressure_head below).
//
// Dimensionless form (derived here; the scaling of z and t is Srivastava & Yeh's, layer 1 the
// reference): z = α z*, L1 = α L1*, L = α L*, T = α K_s1 t*/Δθ_1, q = q*/K_s1,
//   p_i = K_si/K_s1 (p_1 = 1),  ρ_i = Δθ_i/Δθ_1 (ρ_1 = 1),
//   ρ_i ∂k/∂T = p_i (∂²k/∂z² + ∂k/∂z),   q = p_i (∂k/∂z + k),
//   k(0) = k_0 = e^{αψ_0},  p_2 (∂k/∂z + k)(L) = q_B,  k and p (∂k/∂z + k) continuous at L1.
//
// Steady state for a flux q (each layer: p_i (k' + k) = q):
//   layer 1: k = q/p_1 + (k_0 − q/p_1) e^{−z},            k_I = k(L1),
//   layer 2: k = q/p_2 + (k_I − q/p_2) e^{−(z − L1)}.
//
// Transient (separation of variables, derived here): k = k_B(z) + e^{−z/2} v, which gives
//   ρ_i v_T = p_i (v_zz − v/4),  v(0) = 0,  v_z + v/2 = 0 at z = L,
//   v and p (v_z + v/2) continuous at L1.
// With v = X(z) e^{−σT}: p X'' − p X/4 + σ ρ X = 0, a Sturm–Liouville problem (weight ρ) with a
// point term at the interface ([p X'] = −½ [p] X); it is self-adjoint, so the eigenfunctions are
// orthogonal in ∫ρ X_m X_n dz, and multiplying by X and integrating by parts gives
//   σ ∫ρ X² dz = ∫ p (X' + X/2)² dz > 0,
// so every σ is positive (no zero or negative mode). With m_i = σ ρ_i/p_i − ¼ and
// S(m, x) = sin(√m x)/√m, C(m, x) = cos(√m x) (sinh, cosh for m < 0; x, 1 for m = 0):
//   layer 1: X = S(m_1, z);
//   layer 2: X = A C(m_2, z − L1) + B S(m_2, z − L1),
//            A = S(m_1, L1),  B = [C(m_1, L1) + ½ S(m_1, L1)]/p_2 − ½ A;
//   eigenvalue equation F(σ) = X'(L) + ½ X(L) = 0,
//            X'(L) = −A m_2 S(m_2, L2) + B C(m_2, L2).
// Where λ = √m_1 and μ = √m_2 are real, the roots are those of the two-layer characteristic
// equation as Bandai & Ghezzehei code it for the paper ("(21a)" in their notebook),
//   [sin λL1 + 2λ cos λL1][sin μL2 + 2μ cos μL2] − (1 + 4μ²)(K_s2/K_s1) sin λL1 sin μL2 = 0,
// μ² = βλ² + (β − 1)/4, β = ρ_2/p_2 (checked in the unit tests to 1e-9 relative); where m_1 or m_2
// is negative (their other cases) S and C above continue it through sinh and cosh.
// Coefficients: the initial v_0 = e^{z/2}(k_A − k_B) satisfies v_0'' = v_0/4, v_0(0) = 0, the
// interface conditions and v_0' + v_0/2 = e^{L/2}(q_A − q_B)/p_2 at L; Green's identity then gives
//   ∫ρ X_n v_0 dz = e^{L/2} (q_A − q_B) X_n(L)/σ_n,
// and with N_n = ∫ρ X_n² dz (closed form: ∫S² = (x − S C)/(2m), ∫C² = (x + S C)/2, ∫S C = S²/2)
//   k(z, T) = k_B(z) + e^{−z/2} Σ_n a_n X_n(z) e^{−σ_n T},
//   a_n = e^{L/2} (q_A − q_B) X_n(L)/(σ_n N_n),
//   q(z, T) = q_B + p_i e^{−z/2} Σ_n a_n (X_n' + ½ X_n) e^{−σ_n T}.
// For equal layers (p_2 = ρ_2 = 1), σ = λ² + ¼ and this is gardner_analytic.h's series term by
// term (tan λL + 2λ = 0, a_n = 4 (q_A − q_B) e^{L/2} sin λL/(1 + L/2 + 2Lλ²)).
//
// Roots: F is scanned in ω = √σ with a step of 1/64 of the mean spacing π/(L1 √(ρ_1/p_1) +
// L2 √(ρ_2/p_2)) (WKB phase of the two layers), each sign change refined by bisection. Roots of
// a Sturm–Liouville problem are simple, so every root changes the sign of F; two roots closer
// than a step would be missed, which the unit tests check through Parseval's identity
// Σ a_n² N_n = ∫ρ v_0² dz.
// Truncation: the series stops at the first n for which the bound b_n = |a_n|max|X_n| e^{−σ_n T}
// (or with max|X_n' + X_n/2| for the flux; a_n bounded with max|X_n| in place of X_n(L)), times
// the geometric tail factor 1 + 1/(1 − e^{−(σ_n − σ_{n−1}) T}), is below series_tolerance
// (absolute, on k, whose scale is 1; on q/K_s1 for the flux). At T = 0 the initial state is
// returned exactly.
//
// Sources: R. Srivastava and T.-C. J. Yeh (1991), "Analytical solutions for one-dimensional,
// transient infiltration toward the water table in homogeneous and layered soils", Water Resources
// Research 27(5):753–762, doi:10.1029/90WR02772 (problem statement, scaling, the layered problem's
// set-up; full text not available here, so no equation numbers are quoted, and the solution above
// is re-derived, not transcribed). The scaling z = α_1 z*, T = α_1 K_s1 t*/Δθ_1, β and the shape of
// the two-layer characteristic equation were compared with T. Bandai and T. A. Ghezzehei,
// DD-PINNs-RRE, analytical_solutions/Srivastava1991_heterogeneous.ipynb
// (github.com/ToshiyukiBandai/DD-PINNs-RRE, doi:10.5281/zenodo.6030635), read, not copied.
// Gardner's model: W. R. Gardner (1958), Soil Science 85(4):228–232.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "tests/reference/gardner_analytic.h"

namespace cascade::reference {

struct LayeredGardnerColumn {
  GardnerSoil lower;             // layer 1, against the water table
  GardnerSoil upper;             // layer 2, at the surface
  double lower_thickness = 0;    // L1* (m)
  double upper_thickness = 0;    // L2* (m)
  double base_pressure_head = 0; // ψ_0 (m), the water table's head
  double initial_flux_in = 0;    // q_A* (m/s, downward = into the soil), before t = 0
  double flux_in = 0;            // q_B* (m/s), for t > 0
  double height() const { return lower_thickness + upper_thickness; }
};

// Steady pressure head ψ (m) at height z* (m above the water table) for a constant downward flux
// q* (m/s) through two Gardner layers; the α of the layers may differ. Derivation: in each layer
// q* = K_si e^{α_i ψ}(ψ' + 1) is constant, so k_i = e^{α_i ψ} solves k' + α_i k = α_i q*/K_si:
//   layer 1: e^{α_1 ψ} = q*/K_s1 + (e^{α_1 ψ_0} − q*/K_s1) e^{−α_1 z*},
//   layer 2: e^{α_2 ψ} = q*/K_s2 + (e^{α_2 ψ_I} − q*/K_s2) e^{−α_2 (z* − L1*)},
// ψ_I the head at the interface from layer 1 (continuity of ψ; the flux is q* on both sides).
// NaN where the right-hand side is <= 0 (no steady state with that flux: the surface dries out).
inline double layered_gardner_steady_pressure_head(const GardnerSoil& lower,
                                                   const GardnerSoil& upper, double lower_thickness,
                                                   double base_pressure_head, double flux,
                                                   double z) {
  auto head = [](double k, double alpha) {
    return k > 0 ? std::log(k) / alpha : std::numeric_limits<double>::quiet_NaN();
  };
  const double q1 = flux / lower.saturated_conductivity;
  auto layer1 = [&](double zz) {
    return q1 + (std::exp(lower.alpha * base_pressure_head) - q1) * std::exp(-lower.alpha * zz);
  };
  if (z <= lower_thickness) return head(layer1(z), lower.alpha);
  const double psi_i = head(layer1(lower_thickness), lower.alpha);
  const double q2 = flux / upper.saturated_conductivity;
  const double k2 =
      q2 + (std::exp(upper.alpha * psi_i) - q2) * std::exp(-upper.alpha * (z - lower_thickness));
  return head(k2, upper.alpha);
}

class LayeredGardnerSolution {
 public:
  struct Mode {
    double sigma = 0;        // σ_n (1/unit of T)
    double coefficient = 0;  // a_n
    double norm = 0;         // N_n = ∫ρ X_n² dz
    double bound = 0;        // max over the column of |X_n|
    double flux_bound = 0;   // max over the column of p |X_n' + X_n/2|
  };

  explicit LayeredGardnerSolution(const LayeredGardnerColumn& column,
                                  double series_tolerance = 1e-13)
      : c_(column), tolerance_(series_tolerance) {
    for (const GardnerSoil* s : {&c_.lower, &c_.upper})
      if (!(s->alpha > 0) || !(s->theta_s > s->theta_r) || !(s->saturated_conductivity > 0))
        throw std::invalid_argument("LayeredGardnerSolution: bad soil");
    if (!(c_.lower_thickness > 0) || !(c_.upper_thickness > 0))
      throw std::invalid_argument("LayeredGardnerSolution: bad layer thickness");
    if (c_.lower.alpha != c_.upper.alpha)
      throw std::invalid_argument("LayeredGardnerSolution: the layers need the same alpha");
    alpha_ = c_.lower.alpha;
    l1_ = alpha_ * c_.lower_thickness;
    l2_ = alpha_ * c_.upper_thickness;
    length_ = l1_ + l2_;
    p2_ = c_.upper.saturated_conductivity / c_.lower.saturated_conductivity;
    rho2_ = (c_.upper.theta_s - c_.upper.theta_r) / (c_.lower.theta_s - c_.lower.theta_r);
    k0_ = std::exp(alpha_ * c_.base_pressure_head);
    q_a_ = c_.initial_flux_in / c_.lower.saturated_conductivity;
    q_b_ = c_.flux_in / c_.lower.saturated_conductivity;
    time_scale_ =
        (c_.lower.theta_s - c_.lower.theta_r) / (alpha_ * c_.lower.saturated_conductivity);
    const double phase = l1_ + l2_ * std::sqrt(rho2_ / p2_);
    scan_step_ = kPi / phase / 64.0;
  }

  // Seconds per unit of dimensionless time T, Δθ_1/(α K_s1).
  double time_scale() const { return time_scale_; }
  double height() const { return c_.height(); }
  double interface_height() const { return c_.lower_thickness; }

  // Layer index at height z (m): 1 below the interface, 2 above, 1 on it.
  int layer_at(double z) const { return z <= c_.lower_thickness ? 1 : 2; }

  // e^{αψ} = K/K_si at height z (m above the water table) and time t (s), both layers. At the
  // interface, layer (1 or 2) selects which layer's expression is evaluated (0: layer_at(z)).
  double relative_conductivity(double z, double t, int layer = 0) const {
    return evaluate(alpha_ * z, t / time_scale_, false, layer == 0 ? layer_at(z) : layer);
  }

  // Downward Darcy flux (m/s). At the interface, layer selects the side whose K_s is used (the two
  // agree when the solution is right: that is what the tests check).
  double downward_flux(double z, double t, int layer = 0) const {
    return c_.lower.saturated_conductivity *
           evaluate(alpha_ * z, t / time_scale_, true, layer == 0 ? layer_at(z) : layer);
  }

  // Pressure head ψ (m); NaN where e^{αψ} <= 0.
  double pressure_head(double z, double t) const {
    const double k = relative_conductivity(z, t);
    return k > 0 ? std::log(k) / alpha_ : std::numeric_limits<double>::quiet_NaN();
  }

  // θ (-) of the layer at z, uncapped (θ > θ_s where ψ > 0, as in gardner_analytic.h).
  double water_content(double z, double t) const {
    const GardnerSoil& s = layer_at(z) == 1 ? c_.lower : c_.upper;
    return s.theta_r + (s.theta_s - s.theta_r) * relative_conductivity(z, t);
  }

  // Steady profile of this column for a surface flux q* (m/s): the t = 0 state for q_A*, the
  // t → ∞ state for q_B*.
  double steady_pressure_head(double z, double flux) const {
    return layered_gardner_steady_pressure_head(c_.lower, c_.upper, c_.lower_thickness,
                                                c_.base_pressure_head, flux, z);
  }

  // The n-th mode (n >= 1), for diagnostics and the Parseval test.
  const Mode& mode(int n) const {
    ensure_modes(n);
    return modes_[n - 1];
  }

  // ∫ρ v_0² dz over the column, v_0 = e^{z/2}(k_A − k_B) (dimensionless; Parseval's right side),
  // by composite Gauss–Legendre on each layer.
  double initial_energy() const {
    double sum = 0;
    const int pieces = 400;
    for (int layer = 1; layer <= 2; ++layer) {
      const double a = layer == 1 ? 0.0 : l1_, b = layer == 1 ? l1_ : length_;
      const double rho = layer == 1 ? 1.0 : rho2_, h = (b - a) / pieces;
      for (int i = 0; i < pieces; ++i)
        for (int j = 0; j < 4; ++j)
          for (int sgn : {-1, 1}) {
            const double zz = a + (i + 0.5) * h + sgn * 0.5 * h * kGaussX[j];
            const double v0 =
                std::exp(0.5 * zz) * (steady_k(zz, q_a_, layer) - steady_k(zz, q_b_, layer));
            sum += rho * kGaussW[j] * 0.5 * h * v0 * v0;
          }
    }
    return sum;
  }

  // Terms the series used in the last evaluation.
  int last_term_count() const { return last_terms_; }

 private:
  // S(m, x), C(m, x) and ∫_0^x S², continuous in m through m = 0.
  static double s_fn(double m, double x) {
    if (m > 0) {
      const double r = std::sqrt(m);
      return std::sin(r * x) / r;
    }
    if (m < 0) {
      const double r = std::sqrt(-m);
      return std::sinh(r * x) / r;
    }
    return x;
  }
  static double c_fn(double m, double x) {
    if (m > 0) return std::cos(std::sqrt(m) * x);
    if (m < 0) return std::cosh(std::sqrt(-m) * x);
    return 1.0;
  }
  static double int_ss(double m, double x) {
    const double y = m * x * x;
    if (std::fabs(y) < 1e-4)  // series of sin²(√m x)/m: x³/3 − m x⁵/15 + 2 m² x⁷/315 − …
      return x * x * x * (1.0 / 3.0 - y / 15.0 + 2.0 * y * y / 315.0);
    return (x - s_fn(m, x) * c_fn(m, x)) / (2.0 * m);
  }
  // Bounds of |a C + b S| over [0, x] and of |a C + b S| (derivative form uses a → b, b → −m a).
  static double envelope(double m, double a, double b, double x) {
    if (m > 0) return std::sqrt(a * a + b * b / m);
    return std::fabs(a) * c_fn(m, x) + std::fabs(b) * s_fn(m, x);  // C >= 1, S >= 0 increasing
  }

  double m1(double sigma) const { return sigma - 0.25; }
  double m2(double sigma) const { return sigma * rho2_ / p2_ - 0.25; }

  // Layer-2 coefficients A, B of the eigenfunction for σ.
  void upper_coefficients(double sigma, double& a, double& b) const {
    const double m = m1(sigma);
    a = s_fn(m, l1_);
    b = (c_fn(m, l1_) + 0.5 * a) / p2_ - 0.5 * a;
  }

  double characteristic(double sigma) const {
    double a, b;
    upper_coefficients(sigma, a, b);
    const double m = m2(sigma);
    const double s = s_fn(m, l2_), c = c_fn(m, l2_);
    return (-a * m * s + b * c) + 0.5 * (a * c + b * s);
  }

  // X_n (derivative = false) or X_n' + X_n/2 at z in the given layer.
  double shape(double sigma, double z, int layer, bool derivative) const {
    if (layer == 1) {
      const double m = m1(sigma);
      const double s = s_fn(m, z);
      return derivative ? c_fn(m, z) + 0.5 * s : s;
    }
    double a, b;
    upper_coefficients(sigma, a, b);
    const double m = m2(sigma), x = z - l1_;
    const double s = s_fn(m, x), c = c_fn(m, x);
    const double value = a * c + b * s;
    return derivative ? (-a * m * s + b * c) + 0.5 * value : value;
  }

  void ensure_modes(int n) const {
    while (int(modes_.size()) < n) {
      // Scan F in ω = √σ from the last root (or 0; F(0) ≠ 0 since σ = 0 is no eigenvalue).
      double w_lo = modes_.empty() ? 0.0 : std::sqrt(modes_.back().sigma);
      double f_lo = characteristic(w_lo * w_lo);
      if (!modes_.empty()) {  // step off the previous root
        w_lo += 1e-3 * scan_step_;
        f_lo = characteristic(w_lo * w_lo);
      }
      double w_hi = w_lo + scan_step_, f_hi = characteristic(w_hi * w_hi);
      while ((f_lo > 0) == (f_hi > 0) && f_hi != 0) {
        w_lo = w_hi;
        f_lo = f_hi;
        w_hi += scan_step_;
        f_hi = characteristic(w_hi * w_hi);
      }
      for (int k = 0; k < 200 && w_hi - w_lo > 4 * std::numeric_limits<double>::epsilon() * w_hi;
           ++k) {
        const double mid = 0.5 * (w_lo + w_hi), f_mid = characteristic(mid * mid);
        if ((f_mid > 0) == (f_lo > 0)) {
          w_lo = mid;
          f_lo = f_mid;
        } else {
          w_hi = mid;
        }
      }
      const double w = 0.5 * (w_lo + w_hi), sigma = w * w;
      Mode mode;
      mode.sigma = sigma;
      double a, b;
      upper_coefficients(sigma, a, b);
      const double ma = m1(sigma), mb = m2(sigma);
      const double s2 = s_fn(mb, l2_), c2 = c_fn(mb, l2_);
      const double i_cc = 0.5 * (l2_ + s2 * c2), i_sc = 0.5 * s2 * s2, i_ss = int_ss(mb, l2_);
      mode.norm = int_ss(ma, l1_) + rho2_ * (a * a * i_cc + 2 * a * b * i_sc + b * b * i_ss);
      const double x_top = a * c2 + b * s2;
      mode.coefficient = std::exp(0.5 * length_) * (q_a_ - q_b_) * x_top / (sigma * mode.norm);
      const double env1 = envelope(ma, 0.0, 1.0, l1_), env2 = envelope(mb, a, b, l2_);
      mode.bound = std::max(env1, env2);
      // X' + X/2 = (derivative combination) + half the value: bound each part by its envelope.
      const double denv1 = envelope(ma, 1.0, 0.0, l1_);  // X' = C(m_1, z) in layer 1
      const double denv2 = envelope(mb, b, -mb * a, l2_);
      mode.flux_bound = std::max(denv1 + 0.5 * env1, p2_ * (denv2 + 0.5 * env2));
      modes_.push_back(mode);
    }
  }

  // Steady k for the dimensionless flux q (= q*/K_s1) in a layer (header comment).
  double steady_k(double z, double q, int layer) const {
    if (layer == 1) return q + (k0_ - q) * std::exp(-z);
    const double k_interface = q + (k0_ - q) * std::exp(-l1_), q2 = q / p2_;
    return q2 + (k_interface - q2) * std::exp(-(z - l1_));
  }

  // k (derivative = false) or q/K_s1 (derivative = true) at dimensionless (z, T) in a layer.
  double evaluate(double z, double time, bool derivative, int layer) const {
    last_terms_ = 0;
    if (time <= 0) return derivative ? q_a_ : steady_k(z, q_a_, layer);
    const double p = layer == 1 ? 1.0 : p2_;
    double sum = 0;
    const double amplitude = std::fabs(q_a_ - q_b_) * std::exp(0.5 * length_);
    double previous_sigma = 0;
    for (int n = 1;; ++n) {
      const Mode& m = mode(n);
      const double decay = std::exp(-0.5 * z - m.sigma * time);
      sum += m.coefficient * shape(m.sigma, z, layer, derivative) * decay;
      last_terms_ = n;
      // |a_n| <= amplitude max|X_n| / (σ_n N_n); times max|X_n| or max p |X_n' + X_n/2|.
      const double bound = amplitude * m.bound / (m.sigma * m.norm) *
                           (derivative ? m.flux_bound : m.bound) * std::exp(-m.sigma * time);
      const double ratio = std::exp(-(m.sigma - previous_sigma) * time);
      previous_sigma = m.sigma;
      if ((n > 2 && bound * (1.0 + 1.0 / (1.0 - ratio)) < tolerance_) || n >= kMaxTerms) break;
    }
    return derivative ? q_b_ + p * sum : steady_k(z, q_b_, layer) + sum;
  }

  static constexpr double kPi = 3.14159265358979323846;
  static constexpr int kMaxTerms = 200000;
  static constexpr double kGaussX[4] = {0.1834346424956498, 0.5255324099163290,
                                        0.7966664774136267, 0.9602898564975363};
  static constexpr double kGaussW[4] = {0.3626837833783620, 0.3137066458778873,
                                        0.2223810344533745, 0.1012285362903763};

  LayeredGardnerColumn c_;
  double tolerance_;
  double alpha_ = 1, l1_ = 0, l2_ = 0, length_ = 0, p2_ = 1, rho2_ = 1, k0_ = 1, q_a_ = 0, q_b_ = 0;
  double time_scale_ = 1, scan_step_ = 0;
  // Lazily computed modes and a diagnostic counter: evaluation is not thread-safe.
  mutable std::vector<Mode> modes_;
  mutable int last_terms_ = 0;
};

}  // namespace cascade::reference
