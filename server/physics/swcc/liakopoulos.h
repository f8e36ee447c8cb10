// The fit of Liakopoulos' (1964) drainage test (paper Eq. 43, Section 4.2, Table 1; Schrefler
// and Scotta 2001): power-law saturation and conductivity in the suction head.
#pragma once

#include <cmath>

#include "server/core/types.h"

namespace cascade {

// S_w = 1 − a h^b (Eq. 43a), K_rel = 1 − c (1 − S_w)^d (Eq. 43b), h = p_c/(ρ_w0 g).
//
// Range: the experiment's 1 m column reaches h ≈ 1 m (S_w ≈ 0.9). Eq. 43b becomes negative once
// the saturation deficit 1 − S_w exceeds D = c^(−1/d) ≈ 0.4574, i.e. for h > (D/a)^(1/b) ≈ 1.859 m.
// Beyond that suction the model holds S_w at 1 − D ≈ 0.5426 (its residual saturation) with
// K_rel = 0 and dS_w/dp_c = 0, so that S_w stays continuous and monotone and K_rel in [0, 1].
template <typename Real>
struct Liakopoulos {
  Real unit_weight;  // γ_w = ρ_w0 g, converts p_c to the head p_c/γ_w (Pa/m)

  static constexpr double kA = 0.10152;  // a of Eq. 43a (m^−b)
  static constexpr double kB = 2.4279;   // b of Eq. 43a
  static constexpr double kC = 2.207;    // c of Eq. 43b
  static constexpr double kD = 1.0121;   // d of Eq. 43b

  // D = c^(−1/d), the deficit at which Eq. 43b reaches K = 0: the end of the fit's range.
  CASCADE_HD static Real max_deficit() { return std::pow(Real(kC), Real(-1) / Real(kD)); }

  CASCADE_HD Real saturation_min() const { return Real(1) - max_deficit(); }
  CASCADE_HD Real saturation_max() const { return Real(1); }

  // 1 − S_w = a h^b (Eq. 43a) for p_c > 0, capped at D; 0 for p_c <= 0. Kept as the deficit, not
  // as S_w, so Eq. 43b does not lose digits to 1 − S_w near saturation.
  CASCADE_HD Real deficit(Real p_c) const {
    if (p_c <= Real(0)) return Real(0);
    const Real d = Real(kA) * std::pow(p_c / unit_weight, Real(kB));
    const Real d_max = max_deficit();
    return d > d_max ? d_max : d;  // written so that a NaN p_c stays NaN
  }

  CASCADE_HD Real saturation(Real p_c) const { return Real(1) - deficit(p_c); }

  // dS_w/dp_c = −a b h^(b−1)/γ_w = −b (1 − S_w)/p_c inside the range (Eq. 43a); b > 1 makes it
  // vanish as p_c → 0+, joining the saturated branch smoothly. 0 beyond the range, where S_w is
  // held.
  CASCADE_HD Real saturation_derivative(Real p_c) const {
    if (p_c <= Real(0)) return Real(0);
    const Real d = Real(kA) * std::pow(p_c / unit_weight, Real(kB));
    if (d >= max_deficit()) return Real(0);
    return -Real(kB) * d / p_c;
  }

  // K_rel = 1 − c (1 − S_w)^d (Eq. 43b), floored at 0; exactly 0 at the capped deficit, where
  // the formula gives 0 only up to the rounding of pow.
  CASCADE_HD Real relative_conductivity(Real p_c) const {
    const Real d = deficit(p_c);
    if (d >= max_deficit()) return Real(0);
    const Real k = Real(1) - Real(kC) * std::pow(d, Real(kD));
    return k < Real(0) ? Real(0) : k;  // NaN stays NaN
  }
};

}  // namespace cascade
