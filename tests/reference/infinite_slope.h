// Factor of safety of an infinite slope with suction stress, for steady or transient pressure-head
// profiles (e.g. the Srivastava–Yeh columns of gardner_analytic.h and gardner_layered.h): the
// reference for slope-failure checks of the implicit pore-water stage.
//
// Geometry and conventions. A planar slope of angle β; d is the depth below the ground surface
// measured VERTICALLY (the z of a vertical infiltration column, d = L − z); the trial slip plane is
// parallel to the surface at vertical depth H (its slope-normal depth is H cos β). Pore air at zero
// pressure (u_a = 0); u_w = γ_w ψ with ψ the pressure head at the slip plane (negative = suction).
// The unit weight γ(d) (N/m³) may vary with depth (e.g. with the water content); the overburden
// per unit horizontal area is W(H) = ∫_0^H γ(d) dd (= γ H for a constant γ).
//
// Stresses on the slip plane (equilibrium of a vertical slice of an infinite slope: weight W b on
// a base of length b/cos β): total normal σ_n = W cos²β, shear τ = W sin β cos β.
// Effective stress with the suction stress σ^s (Lu & Likos 2006; Lu, Godt & Wu 2010, their
// "suction stress characteristic curve", σ' = (σ − u_a) − σ^s, σ^s = −S_e (u_a − u_w)):
//   ψ < 0:  σ^s = S_e(ψ) u_w = S_e(ψ) γ_w ψ  (negative: suction adds to the normal stress),
//   ψ >= 0: σ^s = u_w = γ_w ψ                (Terzaghi, σ' = σ − u_w).
// (With σ' = σ − σ^s the saturated limit is σ^s = +u_w; "σ^s = −u_w" belongs to the opposite sign
// convention σ' = σ + σ^s. Either way suction raises σ' and positive pressure lowers it.)
// Mohr–Coulomb, τ_f = c' + σ' tan φ', gives
//   FS(H) = τ_f/τ = tan φ'/tan β + c'/(W sin β cos β) − σ^s tan φ'/(W sin β cos β),
// which for a constant γ (W = γH; 1/(sin β cos β) = 2/sin 2β = tan β + cot β) is Lu & Godt's
//   FS = tan φ'/tan β + 2 c'/(γ H sin 2β) − σ^s (tan β + cot β) tan φ'/(γ H)
// (N. Lu and J. Godt (2008), "Infinite slope stability under steady unsaturated seepage
// conditions", Water Resources Research 44, W11404, doi:10.1029/2008WR006976; the paper's text was
// not available here, so the expression is the one re-derived above, which agrees with the form
// quoted in the brief; no equation number is cited). For a transient ψ(d, t) the same expression
// holds at each depth and time with the local σ^s (quasi-static: the slip plane carries the weight
// of the slice above it; the flow enters only through u_w). γ(d) does not change with time here:
// the weight gained by wetting is left out (pass the wettest γ(d) for a conservative bound).
// Mapping a vertical infiltration column (gardner_analytic.h, gardner_layered.h, z up from the
// water table, height L) onto the slope, ψ(d, t) = ψ_column(L − d, t), assumes vertical flow in
// the unsaturated zone, the usual simplification for rain on a hillslope.
// Effective saturation S_e(ψ) for ψ < 0: van Genuchten (1980), S_e = [1 + (α|ψ|)^n]^{−(1−1/n)},
// the form of Lu, Godt & Wu (2010); or Gardner's exponential of Srivastava & Yeh (1991),
// S_e = (θ − θ_r)/(θ_s − θ_r) = e^{αψ}. Both give S_e = 1 at ψ = 0, so σ^s is continuous there.
//
// Checks in the unit tests: dry (u_w = 0) cohesionless FS = tan φ'/tan β at every depth;
// slope-parallel seepage with the water table at the surface, u_w = γ_w H cos²β, gives
// FS = (1 − γ_w/γ) tan φ'/tan β (the textbook submerged form with γ = γ_sat); the cohesion term by
// hand; suction raising FS.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace cascade::reference {

// S_e(ψ) callables (ψ in m, α in 1/m of head).
inline std::function<double(double)> van_genuchten_effective_saturation(double alpha, double n) {
  if (!(alpha > 0) || !(n > 1)) throw std::invalid_argument("van Genuchten: need alpha > 0, n > 1");
  return [alpha, n](double psi) {
    return psi >= 0 ? 1.0 : std::pow(1.0 + std::pow(alpha * -psi, n), -(1.0 - 1.0 / n));
  };
}
inline std::function<double(double)> gardner_effective_saturation(double alpha) {
  if (!(alpha > 0)) throw std::invalid_argument("Gardner: need alpha > 0");
  return [alpha](double psi) { return psi >= 0 ? 1.0 : std::exp(alpha * psi); };
}

struct InfiniteSlope {
  double slope_angle = 0;     // β (rad), in (0, π/2)
  double cohesion = 0;        // c' (Pa)
  double friction_angle = 0;  // φ' (rad)
  // The soil's unit weight: a constant γ (N/m³), W = γ H exactly; or, when unit_weight_profile
  // is set (it then takes precedence), γ(d) at vertical depth d (m), W by quadrature.
  double unit_weight = std::numeric_limits<double>::quiet_NaN();
  std::function<double(double)> unit_weight_profile;
  // S_e(ψ) for ψ < 0 (van_genuchten_… or gardner_…); ψ >= 0 is saturated whatever it returns.
  std::function<double(double)> effective_saturation;
  double water_unit_weight = 9810.0;  // γ_w (N/m³)
};

// ψ(d, t): pressure head (m) at vertical depth d (m) and time t (s).
using HeadField = std::function<double(double, double)>;

struct SlopeDepthMinimum {
  double depth = 0;  // m
  double factor_of_safety = std::numeric_limits<double>::infinity();
};
struct SlopeCriticalState {
  bool found = false;  // min FS reached 1 within [t_start, t_end]
  double time = 0;     // s: earliest time with min FS <= 1, to the bisection tolerance
  double depth = 0;    // m: where the minimum sits then
  double factor_of_safety = 0;
};
struct SlopeSearchOptions {
  int depth_samples = 200;      // equal steps on [d_min, d_max], then golden-section refinement
  int time_samples = 100;       // equal steps on [t_start, t_end] to bracket the first crossing
  double time_tolerance = 1.0;  // s, width of the final bisection bracket
};

class InfiniteSlopeStability {
 public:
  explicit InfiniteSlopeStability(InfiniteSlope slope) : s_(std::move(slope)) {
    if (!(s_.slope_angle > 0) || !(s_.slope_angle < 0.5 * kPi) || !(s_.friction_angle >= 0) ||
        !(s_.cohesion >= 0) || !(s_.water_unit_weight > 0))
      throw std::invalid_argument("InfiniteSlopeStability: bad angles or strengths");
    if (!s_.unit_weight_profile && !(s_.unit_weight > 0))
      throw std::invalid_argument("InfiniteSlopeStability: no unit weight");
    if (!s_.effective_saturation)
      throw std::invalid_argument("InfiniteSlopeStability: no effective saturation curve");
  }

  // W(H) = ∫_0^H γ dd (Pa): γ H for a constant γ, else composite 8-point Gauss–Legendre
  // (64 pieces: exact for polynomials of degree 15 in d; smooth γ(d) to round-off).
  double overburden(double depth) const {
    if (!s_.unit_weight_profile) return s_.unit_weight * depth;
    static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                    0.9602898564975363};
    static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                    0.1012285362903763};
    const int pieces = 64;
    const double h = depth / pieces;
    double sum = 0;
    for (int i = 0; i < pieces; ++i)
      for (int j = 0; j < 4; ++j)
        sum += w[j] * (s_.unit_weight_profile((i + 0.5 + 0.5 * x[j]) * h) +
                       s_.unit_weight_profile((i + 0.5 - 0.5 * x[j]) * h));
    return 0.5 * h * sum;
  }

  // σ^s (Pa) for a pressure head ψ (m): S_e γ_w ψ for ψ < 0, γ_w ψ for ψ >= 0.
  double suction_stress(double psi) const {
    const double u_w = s_.water_unit_weight * psi;
    return psi < 0 ? s_.effective_saturation(psi) * u_w : u_w;
  }

  // FS on the slip plane at vertical depth H (m) with pressure head ψ (m) there.
  double factor_of_safety(double depth, double pressure_head) const {
    if (!(depth > 0)) throw std::invalid_argument("factor_of_safety: depth must be positive");
    const double b = s_.slope_angle, tan_phi = std::tan(s_.friction_angle);
    const double w_sc = overburden(depth) * std::sin(b) * std::cos(b);  // τ on the plane
    return tan_phi / std::tan(b) + (s_.cohesion - suction_stress(pressure_head) * tan_phi) / w_sc;
  }

  // FS at depth H for a head profile ψ(d) (m), or a field ψ(d, t) at time t.
  double factor_of_safety(double depth, const std::function<double(double)>& profile) const {
    return factor_of_safety(depth, profile(depth));
  }
  double factor_of_safety(double depth, double t, const HeadField& field) const {
    return factor_of_safety(depth, field(depth, t));
  }

  // Minimum of FS over depths in [d_min, d_max] at time t: scan, then golden-section search
  // between the neighbours of the best sample (NaN heads, e.g. a dried-out linear solution, are
  // skipped).
  SlopeDepthMinimum minimum_over_depth(const HeadField& field, double t, double d_min, double d_max,
                                  int samples = 200) const {
    if (!(d_min > 0) || !(d_max > d_min) || samples < 2)
      throw std::invalid_argument("minimum_over_depth: need 0 < d_min < d_max");
    auto fs = [&](double d) {
      const double f = factor_of_safety(d, t, field);
      return std::isnan(f) ? std::numeric_limits<double>::infinity() : f;
    };
    const double h = (d_max - d_min) / samples;
    auto sample = [&](int i) { return i >= samples ? d_max : d_min + i * h; };  // no overshoot
    SlopeDepthMinimum best;
    int i_best = 0;
    for (int i = 0; i <= samples; ++i) {
      const double d = sample(i), f = fs(d);
      if (f < best.factor_of_safety) {
        best = {d, f};
        i_best = i;
      }
    }
    double a = sample(std::max(0, i_best - 1)), b = sample(std::min(samples, i_best + 1));
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = fs(x1), f2 = fs(x2);
    for (int k = 0; k < 80 && b - a > 1e-10 * (1.0 + d_max); ++k) {
      if (f1 < f2) {
        b = x2;
        x2 = x1;
        f2 = f1;
        x1 = b - g * (b - a);
        f1 = fs(x1);
      } else {
        a = x1;
        x1 = x2;
        f1 = f2;
        x2 = a + g * (b - a);
        f2 = fs(x2);
      }
    }
    const double d = 0.5 * (a + b), f = fs(d);
    if (f < best.factor_of_safety) best = {d, f};
    return best;
  }

  // Earliest time in [t_start, t_end] at which min over depth of FS reaches 1: the time grid
  // brackets the first sample with min FS <= 1, bisection narrows it to time_tolerance, and the
  // returned time is the bracket's upper end (min FS <= 1 there). A dip below 1 and back within one
  // time step of the grid is not seen: choose time_samples for the problem.
  SlopeCriticalState critical_depth_and_time(const HeadField& field, double d_min, double d_max,
                                        double t_start, double t_end,
                                        const SlopeSearchOptions& options = {}) const {
    auto minimum = [&](double t) {
      return minimum_over_depth(field, t, d_min, d_max, options.depth_samples);
    };
    SlopeCriticalState out;
    SlopeDepthMinimum m = minimum(t_start);
    if (m.factor_of_safety <= 1.0) return {true, t_start, m.depth, m.factor_of_safety};
    double t_lo = t_start, t_hi = t_start;
    bool bracketed = false;
    for (int k = 1; k <= options.time_samples; ++k) {
      t_hi = t_start + (t_end - t_start) * k / options.time_samples;
      m = minimum(t_hi);
      if (m.factor_of_safety <= 1.0) {
        bracketed = true;
        break;
      }
      t_lo = t_hi;
    }
    if (!bracketed) return out;
    SlopeDepthMinimum m_hi = m;
    while (t_hi - t_lo > options.time_tolerance) {
      const double t_mid = 0.5 * (t_lo + t_hi);
      const SlopeDepthMinimum mm = minimum(t_mid);
      if (mm.factor_of_safety <= 1.0) {
        t_hi = t_mid;
        m_hi = mm;
      } else {
        t_lo = t_mid;
      }
    }
    return {true, t_hi, m_hi.depth, m_hi.factor_of_safety};
  }

  const InfiniteSlope& slope() const { return s_; }

 private:
  static constexpr double kPi = 3.14159265358979323846;
  InfiniteSlope s_;
};

}  // namespace cascade::reference
