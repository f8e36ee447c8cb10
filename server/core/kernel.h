// Wendland C2 smoothing kernel (paper Eq. 20 with ERRATA.md: factor 3/(4h), 7/(4πh²), 21/(16πh³)),
// its gradient optionally normalised on the particle lattice (lattice_gradient_moment below).
#pragma once

#include <cmath>
#include <stdexcept>

#include "server/core/types.h"

namespace cascade {

template <typename Real, int Dim>
struct WendlandC2 {
  Real h;         // smoothing length
  Real alpha_d;   // normalisation factor α_d of Eq. 20
  Real inv_h;
  Real support2;  // (2h)², the squared support radius
  Real gradient_scale;  // 1, or 1/m of the lattice (lattice_gradient_moment)

  WendlandC2() = default;
  explicit WendlandC2(Real smoothing_length, Real gradient_scale = Real(1))
      : h(smoothing_length), alpha_d(normalisation(smoothing_length)), inv_h(Real(1) / smoothing_length),
        support2(Real(4) * smoothing_length * smoothing_length), gradient_scale(gradient_scale) {}

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
  // the factor (dW/dr)/r = -5 α_d (1 - q/2)³ / h² needs no division by r; times gradient_scale.
  CASCADE_HD Real gradient_factor(Real r) const {
    const Real a = clamped(Real(1) - Real(0.5) * r * inv_h);
    return Real(-5) * gradient_scale * alpha_d * a * a * a * inv_h * inv_h;
  }

 private:
  CASCADE_HD static Real clamped(Real a) { return a > Real(0) ? a : Real(0); }
};

// The lattice moment m = tr(Σ_{j≠i} V_j x_ji ⊗ ∇_i W_ij) / d of the kernel without scale on the
// square (2D) or cubic (3D) lattice of spacing dp, V_j = dp^d: the discrete form of ∫ ∇W ⊗ x' dV = I,
// which the sums of SPH gradients and divergences take for 1. m is 0.974 in 2D and 0.979 in 3D at
// h/dp = 1.3 (docs/physics.md, "Lattice moment"). The engine divides the kernel gradient by it, so
// that every gradient and divergence of the particle sums is exact for a linear field on the
// lattice the particles start on. With η² > 0, each pair is weighted by r²/(r² + η²): the moment
// of the pairwise Laplacian's weights (seepage_exchange.h), whose flux through a lattice plane per
// unit potential gradient it is.
template <int Dim>
double lattice_gradient_moment(double h, double dp, double eta2 = 0) {
  if (!(h > 0 && dp > 0 && h < 1e3 * dp && eta2 >= 0))
    throw std::invalid_argument(
        "the smoothing length and the particle spacing must be positive, h/dp at most 1000, η² not negative");
  const WendlandC2<double, Dim> w(h);
  const int reach = int(std::ceil(2.0 * h / dp));
  const double volume = std::pow(dp, Dim);
  double sum = 0;
  int n[3] = {0, 0, 0};
  const int span[3] = {reach, Dim > 1 ? reach : 0, Dim > 2 ? reach : 0};
  for (n[0] = -span[0]; n[0] <= span[0]; ++n[0])
    for (n[1] = -span[1]; n[1] <= span[1]; ++n[1])
      for (n[2] = -span[2]; n[2] <= span[2]; ++n[2]) {
        const double r2 = dp * dp * double(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (r2 == 0 || r2 >= w.support2) continue;
        // V_j x_ij·∇_i W_ij with ∇_i W_ij = F x_ij, times r²/(r² + η²)
        sum -= volume * w.gradient_factor(std::sqrt(r2)) * r2 * r2 / (r2 + eta2);
      }
  return sum / Dim;
}

}  // namespace cascade
