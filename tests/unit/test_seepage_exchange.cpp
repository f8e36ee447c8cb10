// The pairwise Darcy exchange of the pore-water continuity (seepage_exchange.h) on the particle
// lattice, with the engine's kernel scale and Laplacian scale (simulation.h): exact for a quadratic
// potential in the bulk, no flux for a hydrostatic pore pressure where the support is cut, damping
// of the odd-even mode at a step that Eq. 40c allows, and the column test of the rain source.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "server/core/kernel.h"
#include "server/physics/seepage_exchange.h"

namespace cascade {
namespace {

constexpr double kDp = 0.1, kRhoW = 1000.0, kG = 9.81;

// The lattice offsets (in dp) within the kernel support, n = (n_x, n_z), n ≠ 0.
std::vector<Vec<double, 2>> lattice_offsets(double h) {
  std::vector<Vec<double, 2>> out;
  const int reach = int(std::ceil(2.0 * h / kDp));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b) {
      const Vec<double, 2> x(a * kDp, b * kDp);
      if ((a != 0 || b != 0) && x.squaredNorm() < 4.0 * h * h) out.push_back(x);
    }
  return out;
}

// The engine's constants at h/dp: the kernel with its gradient scale and the Laplacian scale.
struct Lattice {
  WendlandC2<double, 2> kernel;
  double laplacian_scale, eta2;
  explicit Lattice(double h)
      : kernel(h, 1.0 / lattice_gradient_moment<2>(h, kDp)),
        laplacian_scale(lattice_gradient_moment<2>(h, kDp) / lattice_gradient_moment<2>(h, kDp, 0.01 * h * h)),
        eta2(0.01 * h * h) {}

  // ⟨∇·q_w⟩ at the origin for a pore pressure p(x) and conductivity K (constant), over the
  // neighbours that `keep` admits; gravity (0, −g), no skeleton acceleration.
  template <typename Pressure, typename Keep>
  double divergence(Pressure p, double conductivity, Keep keep) const {
    const Vec<double, 2> driving(0.0, -kG);
    double sum = 0;
    for (const auto& x_j : lattice_offsets(kernel.h)) {
      if (!keep(x_j)) continue;
      const Vec<double, 2> x_ij = -x_j;
      const double r2 = x_ij.squaredNorm();
      const Vec<double, 2> grad_w = kernel.gradient_factor(std::sqrt(r2)) * x_ij;
      const double potential =
          seepage_potential_difference<double, 2>(p(Vec<double, 2>::Zero()), p(x_j), kRhoW, driving, x_ij);
      sum += seepage_exchange_pair<double, 2>(kDp * kDp, 2.0 * conductivity / kG, potential, x_ij, 1.0 / (r2 + eta2),
                                              grad_w);
    }
    return -laplacian_scale * sum;
  }
};

TEST(SeepageExchange, ExactForAQuadraticHeadOnTheLattice) {
  // H = p/(ρ_w g) + z = (x² + 3 z²)/2 (m): ∇·q = −K ∇²H = −4 K.
  constexpr double kConductivity = 1e-5;
  for (double h_over_dp : {1.3, 1.5, 1.8}) {
    const Lattice lattice(h_over_dp * kDp);
    const auto pressure = [](const Vec<double, 2>& x) {
      return kRhoW * kG * (0.5 * (x[0] * x[0] + 3.0 * x[1] * x[1]) - x[1]);
    };
    const double divergence = lattice.divergence(pressure, kConductivity, [](const Vec<double, 2>&) { return true; });
    EXPECT_NEAR(divergence, -4.0 * kConductivity, 1e-12 * kConductivity) << "h/dp " << h_over_dp;
  }
}

TEST(SeepageExchange, HydrostaticPressureHasNoFluxWhereTheSupportIsCut) {
  // p = ρ_w g (z_0 − z) with the particle at the top of the soil: only neighbours below.
  const Lattice lattice(1.3 * kDp);
  const auto hydrostatic = [](const Vec<double, 2>& x) { return kRhoW * kG * (2.0 - x[1]); };
  const double divergence =
      lattice.divergence(hydrostatic, 1e-5, [](const Vec<double, 2>& x) { return x[1] <= 0.0; });
  EXPECT_NEAR(divergence, 0.0, 1e-18);
  // A unit head gradient, p = 0 and H = z (steady infiltration at q_z = −K): the rows under the
  // cut carry out through the deepest plane their pairs cross K per unit area, K dp per column,
  // which is the rain of K dp that the column's top particle takes: the rows together balance it
  // exactly (each alone only to O(dp), the pairs of the top row reaching past the plane below it).
  const auto draining = [](const Vec<double, 2>&) { return 0.0; };
  for (double h_over_dp : {1.3, 1.5, 1.8}) {
    const Lattice cut(h_over_dp * kDp);
    const int rows = int(std::ceil(2.0 * h_over_dp));
    double outflow = 0;  // Σ V_i ⟨∇·q⟩_i over the rows 0 .. −rows + 1 of one column
    for (int row = 0; row < rows; ++row)
      outflow += kDp * kDp * cut.divergence(draining, 1e-5, [&](const Vec<double, 2>& x) {
        return x[1] <= row * kDp + 1e-9;  // the neighbours at or below the surface row
      });
    EXPECT_NEAR(outflow, 1e-5 * kDp, 1e-15) << "h/dp " << h_over_dp;
  }
}

TEST(SeepageExchange, OddEvenModeDecaysAtTheStepEq40cAllows) {
  // The largest eigenvalue λ of the operator (the checkerboard's) against the seepage step of
  // Eq. 40c, Δt = C0 h² C_r γ_w / (2 K K_w): the explicit midpoint integration of the symplectic
  // scheme damps a mode while λ Δt ≤ 2. At the default C0 = 0.2 the product is about 0.65 (so C0
  // up to about 0.6 keeps the seepage stable).
  for (double h_over_dp : {1.3, 1.5, 1.8}) {
    const double h = h_over_dp * kDp;
    const Lattice lattice(h);
    const auto checkerboard = [](const Vec<double, 2>& x) {
      const long a = std::lround(x[0] / kDp), b = std::lround(x[1] / kDp);
      return ((a + b) % 2 == 0 ? 1.0 : -1.0) * kRhoW * kG;  // head ±1 m about a hydrostatic column
    };
    const auto keep_all = [](const Vec<double, 2>&) { return true; };
    const double conductivity = 1e-5;
    // With the capacity C_r γ_w/K_w = 1, dH/dt = −∇·q, and at a particle of the mode's +1 m the
    // decay rate of the mode is ∇·q per metre of head.
    const double rate =
        lattice.divergence([&](const Vec<double, 2>& x) { return checkerboard(x) - kRhoW * kG * x[1]; },
                           conductivity, keep_all);
    const double step = 0.2 * h * h / (2.0 * conductivity);  // Eq. 40c at C0 = 0.2
    EXPECT_GT(rate * step, 0.5) << "h/dp " << h_over_dp;  // the mode is damped, and strongly
    EXPECT_LT(rate * step, 2.0) << "h/dp " << h_over_dp;  // and the integration stays stable
  }
}

TEST(SeepageExchange, RainFallsOnTheParticleThatTopsItsColumn) {
  EXPECT_TRUE((covers_from_rain<double, 2>(Vec<double, 2>(0.0, -kDp), kDp)));          // right above
  EXPECT_TRUE((covers_from_rain<double, 2>(Vec<double, 2>(0.4 * kDp, -2 * kDp), kDp)));  // above, within dp/2
  EXPECT_FALSE((covers_from_rain<double, 2>(Vec<double, 2>(kDp, -kDp), kDp)));          // the next column
  EXPECT_FALSE((covers_from_rain<double, 2>(Vec<double, 2>(0.0, kDp), kDp)));           // below
  EXPECT_TRUE((covers_from_rain<double, 3>(Vec<double, 3>(0.1 * kDp, -0.2 * kDp, -kDp), kDp)));
  EXPECT_FALSE((covers_from_rain<double, 3>(Vec<double, 3>(0.1 * kDp, 0.6 * kDp, -kDp), kDp)));
}

}  // namespace
}  // namespace cascade
