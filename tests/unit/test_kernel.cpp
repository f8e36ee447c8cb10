// Wendland C2 kernel (paper Eq. 20, ERRATA.md): normalisation, values and gradient against the
// analytic expressions, in 1D, 2D and 3D, and its gradient normalised on the particle lattice.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "server/core/kernel.h"

namespace cascade {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ∫ W dV over the support, by the midpoint rule on a fine lattice (spacing h/40).
template <int Dim>
double integral(const WendlandC2<double, Dim>& w) {
  const double h = w.h, step = h / 40.0;
  const int n = int(std::ceil(2.0 * h / step));
  double sum = 0;
  if constexpr (Dim == 1) {
    for (int i = -n; i < n; ++i) sum += w.value(std::fabs((i + 0.5) * step));
    return sum * step;
  } else if constexpr (Dim == 2) {
    for (int i = -n; i < n; ++i)
      for (int k = -n; k < n; ++k) sum += w.value(std::hypot((i + 0.5) * step, (k + 0.5) * step));
    return sum * step * step;
  } else {
    for (int i = -n; i < n; ++i)
      for (int j = -n; j < n; ++j)
        for (int k = -n; k < n; ++k) {
          const double x = (i + 0.5) * step, y = (j + 0.5) * step, z = (k + 0.5) * step;
          sum += w.value(std::sqrt(x * x + y * y + z * z));
        }
    return sum * step * step * step;
  }
}

TEST(WendlandC2, NormalisationFactorsMatchEq20) {
  const double h = 0.37;
  EXPECT_DOUBLE_EQ((WendlandC2<double, 1>(h).alpha_d), 3.0 / (4.0 * h));
  EXPECT_DOUBLE_EQ((WendlandC2<double, 2>(h).alpha_d), 7.0 / (4.0 * kPi * h * h));
  EXPECT_DOUBLE_EQ((WendlandC2<double, 3>(h).alpha_d), 21.0 / (16.0 * kPi * h * h * h));
}

TEST(WendlandC2, IntegratesToOne) {
  EXPECT_NEAR(integral(WendlandC2<double, 1>(0.8)), 1.0, 1e-5);
  EXPECT_NEAR(integral(WendlandC2<double, 2>(0.013)), 1.0, 1e-4);
  EXPECT_NEAR(integral(WendlandC2<double, 3>(2.5)), 1.0, 1e-3);
}

TEST(WendlandC2, ValuesAtKnownPoints) {
  const double h = 0.1;
  const WendlandC2<double, 2> w(h);
  EXPECT_DOUBLE_EQ(w.value(0.0), w.alpha_d);
  // q = 1: (1 - 1/2)^4 (2 + 1) = 3/16
  EXPECT_NEAR(w.value(h), w.alpha_d * 3.0 / 16.0, 1e-12 * w.alpha_d);
  EXPECT_EQ(w.value(2.0 * h), 0.0);
  EXPECT_EQ(w.value(2.5 * h), 0.0);
  EXPECT_EQ(w.gradient_factor(2.0 * h), 0.0);
}

// dW/dr from the kernel against a central difference of its value, and the gradient vector
// ∇_i W(x_i − x_j) = F(r) x_ij against finite differences in each direction.
TEST(WendlandC2, GradientMatchesFiniteDifferences) {
  const double h = 0.02;
  const WendlandC2<double, 3> w(h);
  for (double q = 0.05; q < 2.0; q += 0.05) {
    const double r = q * h, e = 1e-7 * h;
    const double derivative = (w.value(r + e) - w.value(r - e)) / (2 * e);
    EXPECT_NEAR(w.gradient_factor(r) * r, derivative, 1e-6 * std::fabs(w.alpha_d / h)) << "q = " << q;
  }
  const Vec<double, 3> x_ij(0.011, -0.007, 0.013);
  const double r = x_ij.norm();
  const Vec<double, 3> gradient = w.gradient_factor(r) * x_ij;
  for (int a = 0; a < 3; ++a) {
    Vec<double, 3> plus = x_ij, minus = x_ij;
    const double e = 1e-8;
    plus[a] += e;
    minus[a] -= e;
    EXPECT_NEAR(gradient[a], (w.value(plus.norm()) - w.value(minus.norm())) / (2 * e), 1e-5 * w.alpha_d / h);
  }
}

// Σ_j V_j ∇_i W_ij ⊗ x_ji over a full lattice is close to the identity: the kernel gradient reproduces
// linear fields in the interior (the basis of Eq. 25).
TEST(WendlandC2, LatticeGradientMomentIsIdentity) {
  const double dp = 0.01, h = 1.3 * dp;
  const WendlandC2<double, 2> w(h);
  Mat<double, 2> m = Mat<double, 2>::Zero();
  for (int i = -5; i <= 5; ++i)
    for (int k = -5; k <= 5; ++k) {
      const Vec<double, 2> x_ij(-i * dp, -k * dp);
      const double r = x_ij.norm();
      if (r == 0) continue;
      m += dp * dp * (w.gradient_factor(r) * x_ij) * (-x_ij).transpose();
    }
  // A lattice at h/dp = 1.3 reproduces the integral (exactly I) to about 3%.
  EXPECT_NEAR(m(0, 0), 1.0, 0.03);
  EXPECT_NEAR(m(1, 1), 1.0, 0.03);
  EXPECT_NEAR(m(0, 1), 0.0, 1e-12);
}

// The kernel gradient divided by the lattice moment m (lattice_gradient_moment) makes the plain SPH
// gradient Σ_j V_j (f_j − f_i) ∇_i W_ij exact for a linear field f at a lattice point with a full
// support, in every direction, at the smoothing lengths of the cases; m itself is the figure
// docs/physics.md quotes ("Lattice moment").
template <int Dim>
void expect_exact_linear_gradient(double h_over_dp) {
  const double dp = 0.02, h = h_over_dp * dp;
  const double m = lattice_gradient_moment<Dim>(h, dp);
  const WendlandC2<double, Dim> w(h, 1.0 / m);
  Vec<double, Dim> slope;
  for (int a = 0; a < Dim; ++a) slope[a] = 0.7 - 1.9 * a;  // f(x) = slope · x
  Vec<double, Dim> gradient = Vec<double, Dim>::Zero();
  const int reach = int(std::ceil(2 * h_over_dp));
  int n[3] = {0, 0, 0}, count = 0;
  for (n[0] = -reach; n[0] <= reach; ++n[0])
    for (n[1] = Dim > 1 ? -reach : 0; n[1] <= (Dim > 1 ? reach : 0); ++n[1])
      for (n[2] = Dim > 2 ? -reach : 0; n[2] <= (Dim > 2 ? reach : 0); ++n[2]) {
        Vec<double, Dim> x_ji;
        for (int a = 0; a < Dim; ++a) x_ji[a] = n[a] * dp;
        const double r = x_ji.norm();
        if (r == 0 || r >= 2 * h) continue;
        gradient += std::pow(dp, Dim) * slope.dot(x_ji) * w.gradient_factor(r) * (-x_ji);
        ++count;
      }
  EXPECT_GT(count, 0);
  for (int a = 0; a < Dim; ++a)
    EXPECT_NEAR(gradient[a], slope[a], 1e-12) << Dim << "D, h/dp = " << h_over_dp << ", component " << a;
}

TEST(WendlandC2, GradientNormalisedOnTheLatticeIsExactForLinearFields) {
  for (double h_over_dp : {1.3, 1.5, 1.8}) {
    expect_exact_linear_gradient<1>(h_over_dp);
    expect_exact_linear_gradient<2>(h_over_dp);
    expect_exact_linear_gradient<3>(h_over_dp);
  }
  EXPECT_NEAR(lattice_gradient_moment<2>(0.013, 0.01), 0.974, 5e-4);
  EXPECT_NEAR(lattice_gradient_moment<3>(0.013, 0.01), 0.979, 5e-4);
  EXPECT_NEAR(lattice_gradient_moment<2>(0.015, 0.01), 0.997, 5e-4);
  EXPECT_NEAR(lattice_gradient_moment<3>(0.015, 0.01), 1.0006, 5e-5);
  // An engine configured without a spacing gets an error, not a loop over 2h/0 lattice points.
  EXPECT_THROW(lattice_gradient_moment<2>(0.013, 0.0), std::invalid_argument);
  EXPECT_THROW(lattice_gradient_moment<3>(-0.013, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace cascade
