// Wendland C2 smoothing kernel (paper Eq. 20 with ERRATA.md: factor 3/(4h), 7/(4πh²), 21/(16πh³)).
#pragma once

#include "server/core/types.h"

namespace cascade {

template <typename Real, int Dim>
struct WendlandC2 {
  Real h;         // smoothing length
  Real alpha_d;   // normalisation factor α_d of Eq. 20
  Real inv_h;
  Real support2;  // (2h)², the squared support radius

  WendlandC2() = default;
  explicit WendlandC2(Real smoothing_length)
      : h(smoothing_length), alpha_d(normalisation(smoothing_length)), inv_h(Real(1) / smoothing_length),
        support2(Real(4) * smoothing_length * smoothing_length) {}

  static Real normalisation(Real h) {
    constexpr double pi = 3.14159265358979323846;
    if constexpr (Dim == 1) return Real(3.0 / (4.0 * h));
    if constexpr (Dim == 2) return Real(7.0 / (4.0 * pi * h * h));
    return Real(21.0 / (16.0 * pi * h * h * h));
  }

  // W(r) = α_d (1 - q/2)⁴ (2q + 1), q = r/h, for r < 2h.
  // Both without branches (a clamped at 0 beyond the support), so that neighbour loops vectorise.
  CASCADE_HD Real value(Real r) const {
    const Real q = r * inv_h;
    const Real a = clamped(Real(1) - Real(0.5) * q);
    const Real a2 = a * a;
    return alpha_d * a2 * a2 * (Real(2) * q + Real(1));
  }

  // ∇_i W(x_i - x_j) = gradient_factor(r) · x_ij. From dW/dr = -5 α_d q (1 - q/2)³ / h, so
  // the factor (dW/dr)/r = -5 α_d (1 - q/2)³ / h² needs no division by r.
  CASCADE_HD Real gradient_factor(Real r) const {
    const Real a = clamped(Real(1) - Real(0.5) * r * inv_h);
    return Real(-5) * alpha_d * a * a * a * inv_h * inv_h;
  }

 private:
  CASCADE_HD static Real clamped(Real a) { return a > Real(0) ? a : Real(0); }
};

}  // namespace cascade
