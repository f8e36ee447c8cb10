// Van Genuchten soil-water characteristic curve (paper Eq. 14) with Mualem's relative
// conductivity (Eq. 15), both as corrected by ERRATA.md (rows "Eq. 14" and "Eq. 15").
#pragma once

#include <cmath>

#include "server/core/types.h"

namespace cascade {

// Parameters as in Tables 2 and 3. p_c is the capillary pressure (suction) p_c = p_a − p_w with
// zero pore-air pressure, so p_c = −p_w (Section 2.2).
template <typename Real>
struct VanGenuchten {
  Real s_min;   // S_w,min, residual degree of saturation (-)
  Real s_max;   // S_w,max, maximum degree of saturation (-)
  Real lambda;  // λ, 0 < λ < 1 (-); the exponent of Eq. 14 is 1/(1 − λ) = n, so λ = 1 − 1/n
  Real p_ref;   // p_ref (Pa)

  CASCADE_HD Real saturation_min() const { return s_min; }
  CASCADE_HD Real saturation_max() const { return s_max; }

  // S_e = [1 + (p_c/p_ref)^(1/(1−λ))]^(−λ) (Eq. 14, ERRATA), S_e = 1 for p_c <= 0. Written as
  // exp(−λ log1p(x)) so that S_e keeps its relative accuracy for tiny x and goes to 0 rather than
  // NaN when x overflows.
  CASCADE_HD Real effective_saturation(Real p_c) const {
    if (p_c <= Real(0)) return Real(1);
    return std::exp(-lambda * std::log1p(scaled_suction(p_c)));
  }

  // S_w = S_min + (S_max − S_min) S_e (Eq. 14, ERRATA).
  CASCADE_HD Real saturation(Real p_c) const { return s_min + (s_max - s_min) * effective_saturation(p_c); }

  // dS_w/dp_c = −(S_max − S_min) λ/(1−λ) S_e x/(1+x) / p_c with x = (p_c/p_ref)^(1/(1−λ)), from
  // differentiating Eq. 14. The exponent 1/(1−λ) > 1 makes it vanish as p_c → 0+, so the curve
  // joins the saturated branch (derivative 0) smoothly. S_e·x/(1+x) is evaluated as one
  // exponential, which is 0, not inf·0, when x overflows.
  CASCADE_HD Real saturation_derivative(Real p_c) const {
    if (p_c <= Real(0)) return Real(0);
    const Real x = scaled_suction(p_c);
    if (x == Real(0)) return Real(0);  // underflow: indistinguishable from saturated
    const Real se_times_w = std::exp(-lambda * std::log1p(x) + log_w(x));
    return -(s_max - s_min) * lambda / (Real(1) - lambda) * se_times_w / p_c;
  }

  // Mualem: K_rel = sqrt(S_e) [1 − (1 − S_e^(1/λ))^λ]² (Eq. 15 with ERRATA's S_e). Since
  // S_e^(1/λ) = 1/(1+x), 1 − S_e^(1/λ) = x/(1+x) = w exactly, and 1 − w^λ = −expm1(λ log w):
  // this avoids the cancellation in 1 − S_e^(1/λ) near saturation and in 1 − w^λ far from it,
  // and keeps K_rel in [0, 1].
  CASCADE_HD Real relative_conductivity(Real p_c) const {
    if (p_c <= Real(0)) return Real(1);
    const Real x = scaled_suction(p_c);
    if (x == Real(0)) return Real(1);
    const Real se = std::exp(-lambda * std::log1p(x));
    const Real one_minus_w_lambda = -std::expm1(lambda * log_w(x));
    return std::sqrt(se) * one_minus_w_lambda * one_minus_w_lambda;
  }

  // x = (p_c/p_ref)^(1/(1−λ)) of Eq. 14; may overflow to +inf for huge p_c, which the callers
  // turn into S_e = 0.
  CASCADE_HD Real scaled_suction(Real p_c) const { return std::pow(p_c / p_ref, Real(1) / (Real(1) - lambda)); }

  // log(x/(1+x)) = −log1p(1/x), accurate for small and large x, 0 for x = +inf; x > 0.
  CASCADE_HD static Real log_w(Real x) { return -std::log1p(Real(1) / x); }
};

}  // namespace cascade
