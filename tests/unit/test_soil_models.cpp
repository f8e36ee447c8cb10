// Soil constitutive models against analytic values: Hooke's law, the Jaumann rotation (Eq. 8 with
// Eqs. 9b/26d), Drucker–Prager yield, potential and return mapping (Eqs. 10, 11 with ERRATA.md),
// the apex treatment of Bui et al. (2008), strain softening (Eq. 12), suction hardening (Eq. 13),
// the plane-strain Mohr–Coulomb match, and the parameter check.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "server/core/small_matrix.h"
#include "server/physics/soil/soil_model.h"
#include "server/physics/soil_momentum.h"
#include "server/physics/soil_viscosity_switch.h"

namespace cascade {
namespace {

using Mat3 = Mat<double, 3>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

double j2_of(const Mat3& s) { return second_deviatoric_invariant(s); }
double j3_of(const Mat3& s) { return determinant(Mat3(deviator(s))); }

// Frobenius norm of the part of a orthogonal to b: 0 when a ∥ b, relative to |a|.
double misalignment(const Mat3& a, const Mat3& b) {
  const Mat3 bn = b / b.norm();
  return (a - a.cwiseProduct(bn).sum() * bn).norm() / a.norm();
}

Mat3 random_symmetric(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat3 m;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) m(a, b) = m(b, a) = u(rng);
  return m;
}

// A Table-3-like soil (E = 6 MPa is raised to 50 MPa so that elastic steps stay small).
SoilModel<double> table_soil() {
  SoilModel<double> m;
  m.kind = SoilModel<double>::Kind::drucker_prager;
  m.youngs_modulus = 50e6;
  m.poisson_ratio = 0.3;
  m.peak_cohesion = 10e3;
  m.residual_cohesion = 10e3;
  m.peak_friction_angle = 30 * kDeg;
  m.residual_friction_angle = 30 * kDeg;
  m.dilatancy_angle = 10 * kDeg;
  return m;
}

SoilModel<double> softening_soil() {
  SoilModel<double> m = table_soil();
  m.peak_cohesion = 6e3;
  m.residual_cohesion = 1e3;
  m.peak_friction_angle = 34 * kDeg;
  m.residual_friction_angle = 18 * kDeg;
  m.dilatancy_angle = 5 * kDeg;
  m.softening_coefficient = 4;
  m.suction_cohesion = 2e3;
  m.suction_cohesion_rate = 30;
  return m;
}

// ---- Hooke's law (elastic part of D^ep in Eq. 8; K and G as in Eq. 29) ----

TEST(LinearElastic, UniaxialStrainAndPureShearGiveHookesLaw) {
  const double e = 50e6, nu = 0.3;
  const auto el = LinearElastic<double>::from_young_poisson(e, nu);
  EXPECT_NEAR(el.bulk_modulus, e / (3 * (1 - 2 * nu)), 1e-6);
  EXPECT_NEAR(el.shear_modulus, e / (2 * (1 + nu)), 1e-6);
  // Uniaxial strain ε_zz: σ_zz = M ε with the constrained modulus M = E(1−ν)/((1+ν)(1−2ν)) = K + 4G/3,
  // σ_xx = σ_yy = ν/(1−ν) σ_zz = (K − 2G/3) ε.
  Mat3 de = Mat3::Zero();
  de(2, 2) = -1e-4;
  const Mat3 ds = el.stress_increment(de);
  const double m = e * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(ds(2, 2), m * de(2, 2), 1e-9 * m);
  EXPECT_NEAR(ds(0, 0), nu / (1 - nu) * ds(2, 2), 1e-9 * m);
  EXPECT_NEAR(ds(1, 1), nu / (1 - nu) * ds(2, 2), 1e-9 * m);
  EXPECT_NEAR(ds(2, 2), (el.bulk_modulus + 4 * el.shear_modulus / 3) * de(2, 2), 1e-9 * m);
  EXPECT_EQ(ds(0, 2), 0.0);
  // Pure shear, engineering strain γ = 2ε_xz: τ_xz = Gγ, no normal stress.
  Mat3 dg = Mat3::Zero();
  dg(0, 2) = dg(2, 0) = 0.5e-4;
  const Mat3 dt = el.stress_increment(dg);
  EXPECT_NEAR(dt(0, 2), e / (2 * (1 + nu)) * 1e-4, 1e-9 * m);
  EXPECT_NEAR(dt(2, 0), dt(0, 2), 1e-12 * m);
  EXPECT_NEAR(dt.diagonal().norm(), 0.0, 1e-12 * m);
  // The compliance inverts the stiffness.
  std::mt19937 rng(3);
  const Mat3 eps = random_symmetric(rng, 1e-3);
  EXPECT_LT((el.strain_increment(el.stress_increment(eps)) - eps).norm(), 1e-15);
}

// ---- Eq. 11 with ERRATA.md ----

TEST(DruckerPragerConstants, MatchTheErrataFormula) {
  for (double deg : {0.0, 18.0, 30.0, 34.0, 60.0, 89.0}) {
    const double phi = deg * kDeg, t = std::tan(phi);
    EXPECT_NEAR(drucker_prager_alpha(phi), t / std::sqrt(9 + 12 * t * t), 1e-14) << deg;
    EXPECT_NEAR(drucker_prager_kc(1e4, phi), 3e4 / std::sqrt(9 + 12 * t * t), 1e-9) << deg;
  }
  EXPECT_NEAR(drucker_prager_alpha(kPi / 2), 1 / std::sqrt(12.0), 1e-15);
}

// ---- Eq. 12: strain softening ----

TEST(Strength, SofteningFollowsEq12) {
  const DruckerPrager<double> p = softening_soil().drucker_prager();
  const auto at = [&](double kappa) { return p.strength(kappa, 0.0); };
  EXPECT_DOUBLE_EQ(at(0).cohesion, 6e3);
  EXPECT_DOUBLE_EQ(at(0).friction_angle, 34 * kDeg);
  // κ = 0.25 with η = 4: e^(−1).
  const double d = std::exp(-1.0);
  EXPECT_NEAR(at(0.25).cohesion, 1e3 + 5e3 * d, 1e-9);
  EXPECT_NEAR(at(0.25).friction_angle, (18 + 16 * d) * kDeg, 1e-14);
  EXPECT_NEAR(at(0.25).alpha_phi, drucker_prager_alpha((18 + 16 * d) * kDeg), 1e-15);
  EXPECT_NEAR(at(0.25).k_c, drucker_prager_kc(1e3 + 5e3 * d, (18 + 16 * d) * kDeg), 1e-9);
  // The law is exponential: residual values are approached, reached to round-off, never passed.
  EXPECT_NEAR(at(10).cohesion, 1e3, 1e-9);
  EXPECT_DOUBLE_EQ(at(1e4).cohesion, 1e3);
  EXPECT_DOUBLE_EQ(at(1e4).friction_angle, 18 * kDeg);
  double previous = at(0).k_c;
  for (double kappa = 0.01; kappa < 3; kappa += 0.01) {
    const Strength<double> s = at(kappa);
    EXPECT_LT(s.k_c, previous);
    EXPECT_GE(s.cohesion, 1e3);
    EXPECT_GE(s.friction_angle, 18 * kDeg);
    previous = s.k_c;
  }
  // η = 0: no softening.
  DruckerPrager<double> rigid = p;
  rigid.softening_coefficient = 0;
  EXPECT_DOUBLE_EQ(rigid.strength(5.0, 0.0).cohesion, 6e3);
}

// ---- Eq. 13: suction hardening ----

TEST(Strength, SuctionHardeningFollowsEq13) {
  SoilModel<double> m = softening_soil();
  m.suction_friction_rate = 5 * kDeg;
  const DruckerPrager<double> p = m.drucker_prager();
  const double p_atm = 101e3;
  // No suction: the effective cohesion alone (Eq. 12a with c_s = 0).
  EXPECT_DOUBLE_EQ(p.strength(0.0, 0.0).cohesion, 6e3);
  EXPECT_DOUBLE_EQ(p.strength(0.0, 0.0).friction_angle, 34 * kDeg);
  // p_c = 7 kPa (the initial suction of Section 5): c_s = c_sp (1 − e^(−B_s p_c/p_atm)), φ_s = A_s p_c/p_atm.
  const Strength<double> s7 = p.strength(0.0, 7e3);
  EXPECT_NEAR(s7.cohesion, 6e3 + 2e3 * (1 - std::exp(-30 * 7e3 / p_atm)), 1e-9);
  EXPECT_NEAR(s7.friction_angle, 34 * kDeg + 5 * kDeg * 7e3 / p_atm, 1e-14);
  // Larger suction, larger cohesion, bounded by c'_p + c_sp.
  double previous = 6e3;
  for (double pc = 1e3; pc <= 5e4; pc *= 1.5) {  // B_s p_c/p_atm up to 15
    const double c = p.strength(0.0, pc).cohesion;
    EXPECT_GT(c, previous) << pc;
    EXPECT_LE(c, 8e3);
    previous = c;
  }
  EXPECT_NEAR(p.strength(0.0, 1e8).cohesion, 8e3, 1e-9);
  // Softening and suction add: at κ = 0.25 and 7 kPa.
  EXPECT_NEAR(p.strength(0.25, 7e3).cohesion,
              1e3 + 5e3 * std::exp(-1.0) + 2e3 * (1 - std::exp(-30 * 7e3 / p_atm)), 1e-9);
  // Saturated (p_c = −p_w < 0): no suction contribution, not a negative one.
  EXPECT_DOUBLE_EQ(p.strength(0.0, -20e3).cohesion, 6e3);
  EXPECT_DOUBLE_EQ(p.strength(0.0, -20e3).friction_angle, 34 * kDeg);
  // φ is capped at 90° (Eq. 11's limit) however large A_s p_c/p_atm gets.
  EXPECT_DOUBLE_EQ(p.strength(0.0, 1e9).friction_angle, kPi / 2);
}

// ---- Return mapping (Eqs. 10a, 10b; Bui et al. 2008) ----

struct ReturnCounts {
  int elastic = 0, cone = 0, apex = 0;
};

// Random trial stresses around the yield surface: mean stress from deep compression to beyond
// the apex, deviators up to 150 kPa. Checks every returned stress lies on f = 0 of the strength
// at the new κ (|f| <= 1e-8 k_c), apex returns at the apex.
ReturnCounts check_returns_on_surface(const SoilModel<double>& model, double suction, std::uint32_t seed,
                                      double mean_lo, double mean_hi, double deviator_scale, int n) {
  const DruckerPrager<double> p = model.drucker_prager();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mean(mean_lo, mean_hi), kappa0(0.0, 0.2);
  ReturnCounts counts;
  for (int i = 0; i < n; ++i) {
    const Mat3 trial = random_symmetric(rng, deviator_scale) + mean(rng) * Mat3::Identity();
    const double kappa = model.softening_coefficient > 0 ? kappa0(rng) : 0.0;
    const StressUpdate<double> u = p.return_map(trial, suction, kappa);
    const Strength<double> s = p.strength(u.kappa, suction);
    const double f = drucker_prager_yield(u.stress, s);
    if (u.regime == PlasticRegime::elastic) {
      ++counts.elastic;
      EXPECT_LE(f, 0.0);
      EXPECT_EQ(u.stress, trial);
      EXPECT_EQ(u.kappa, kappa);
      continue;
    }
    EXPECT_GT(drucker_prager_yield(trial, p.strength(kappa, suction)), 0.0);
    EXPECT_LE(std::fabs(f), 1e-8 * s.k_c) << "trial " << i << " f " << f;
    EXPECT_GT(u.kappa, kappa);
    EXPECT_LT((u.stress - u.stress.transpose()).norm(), 1e-9 * s.k_c);
    if (u.regime == PlasticRegime::apex) {
      ++counts.apex;
      EXPECT_NEAR(first_invariant(u.stress), s.k_c / s.alpha_phi, 1e-10 * s.k_c / s.alpha_phi);
      EXPECT_EQ(j2_of(u.stress), 0.0);
    } else {
      ++counts.cone;
      EXPECT_GT(j2_of(u.stress), 0.0);
    }
  }
  return counts;
}

TEST(DruckerPragerReturn, LandsOnYieldSurfaceForRandomTrials) {
  // Perfectly plastic, non-associated (ψ = 10° < φ = 30°): k_c/α_φ = 3c/tanφ = 52 kPa.
  const ReturnCounts a = check_returns_on_surface(table_soil(), 0.0, 11, -300e3, 40e3, 150e3, 4000);
  EXPECT_GT(a.cone, 1000);
  EXPECT_GT(a.apex, 50);
  EXPECT_GT(a.elastic, 100);
  // With softening (implicit in κ) and suction hardening.
  const ReturnCounts b = check_returns_on_surface(softening_soil(), 7e3, 12, -300e3, 40e3, 150e3, 4000);
  EXPECT_GT(b.cone, 1000);
  EXPECT_GT(b.apex, 100);
  // Near the apex: mean stress within ±2 kPa of k_c/(3α_φ) = 17.3 kPa, small deviators.
  const ReturnCounts c = check_returns_on_surface(table_soil(), 0.0, 13, 15.3e3, 19.3e3, 2e3, 2000);
  EXPECT_GT(c.cone, 100);
  EXPECT_GT(c.apex, 100);
}

// The plastic strain dε^p = D⁻¹:(σ_tr − σ) of a cone return is parallel to ∂g/∂σ (Eq. 10b, α_ψ);
// only when ψ = φ is that ∂f/∂σ. The stress correction itself is parallel to D:∂g/∂σ.
TEST(DruckerPragerReturn, PlasticStrainFollowsPotentialGradient) {
  for (double psi_deg : {30.0, 10.0, 0.0}) {
    SoilModel<double> m = table_soil();
    m.dilatancy_angle = psi_deg * kDeg;
    const DruckerPrager<double> p = m.drucker_prager();
    const double alpha_psi = drucker_prager_alpha(m.dilatancy_angle), alpha_phi = drucker_prager_alpha(30 * kDeg);
    std::mt19937 rng(21);
    int cone = 0;
    double worst = 0, least_associated = 1;
    for (int i = 0; i < 2000; ++i) {
      const Mat3 trial = random_symmetric(rng, 150e3) + std::uniform_real_distribution<double>(-300e3, 0)(rng) *
                                                             Mat3::Identity();
      const StressUpdate<double> u = p.return_map(trial, 0.0, 0.0);
      if (u.regime != PlasticRegime::cone) continue;
      ++cone;
      const Mat3 plastic_strain = p.elastic.strain_increment(trial - u.stress);
      const Mat3 dg = drucker_prager_potential_gradient(u.stress, alpha_psi);
      worst = std::max(worst, misalignment(plastic_strain, dg));
      // At the trial stress too: the deviator keeps its direction.
      worst = std::max(worst, misalignment(plastic_strain, drucker_prager_potential_gradient(trial, alpha_psi)));
      worst = std::max(worst, misalignment(trial - u.stress, p.elastic.stress_increment(dg)));
      least_associated = std::min(least_associated,
                                  misalignment(plastic_strain, drucker_prager_potential_gradient(u.stress, alpha_phi)));
    }
    EXPECT_GT(cone, 500) << psi_deg;
    EXPECT_LT(worst, 1e-9) << psi_deg;
    if (psi_deg == 30.0)
      EXPECT_LT(least_associated, 1e-9);  // associated: along ∂f/∂σ
    else
      EXPECT_GT(least_associated, 1e-2) << psi_deg;  // non-associated: not along ∂f/∂σ
  }
}

TEST(DruckerPragerReturn, ApexReturnsToTensionLimit) {
  const DruckerPrager<double> p = table_soil().drucker_prager();
  const Strength<double> s = p.strength(0.0, 0.0);
  const double apex_i1 = s.k_c / s.alpha_phi;  // 3c/tanφ in plane strain matching
  EXPECT_NEAR(apex_i1, 3 * 10e3 / std::tan(30 * kDeg), 1e-8);
  // Hydrostatic tension beyond the apex, with a small deviator.
  Mat3 trial = (0.6 * apex_i1) * Mat3::Identity();
  trial(0, 2) = trial(2, 0) = 1e3;
  trial(1, 1) += 2e3;
  const StressUpdate<double> u = p.return_map(trial, 0.0, 0.0);
  ASSERT_EQ(u.regime, PlasticRegime::apex);
  EXPECT_LT((u.stress - (apex_i1 / 3) * Mat3::Identity()).norm(), 1e-10 * apex_i1);
  // All the trial deviator is plastic: Δκ = sqrt(J2_tr)/(√3 G).
  EXPECT_NEAR(u.kappa, std::sqrt(j2_of(trial)) / (std::sqrt(3.0) * p.elastic.shear_modulus), 1e-15);
  // Purely hydrostatic tension: the apex, no deviatoric plastic strain.
  const StressUpdate<double> h = p.return_map((apex_i1 / 2) * Mat3::Identity(), 0.0, 0.0);
  ASSERT_EQ(h.regime, PlasticRegime::apex);
  EXPECT_EQ(h.kappa, 0.0);
  EXPECT_NEAR(first_invariant(h.stress), apex_i1, 1e-10 * apex_i1);

  // c = 0: the apex is the zero stress.
  SoilModel<double> sand = table_soil();
  sand.peak_cohesion = sand.residual_cohesion = 0;
  const StressUpdate<double> z = sand.drucker_prager().return_map(trial, 0.0, 0.0);
  ASSERT_EQ(z.regime, PlasticRegime::apex);
  EXPECT_EQ(z.stress, Mat3::Zero());

  // ψ = 0: the apex region is exactly Bui et al.'s α_φ I1 − k_c > 0. Just inside it goes to the
  // apex, just outside the return is purely deviatoric (I1 kept).
  SoilModel<double> m0 = table_soil();
  m0.dilatancy_angle = 0;
  const DruckerPrager<double> p0 = m0.drucker_prager();
  Mat3 dev = Mat3::Zero();
  dev(0, 0) = 3e3;
  dev(2, 2) = -3e3;
  const StressUpdate<double> inside = p0.return_map(dev + (1.001 * apex_i1 / 3) * Mat3::Identity(), 0.0, 0.0);
  const StressUpdate<double> outside = p0.return_map(dev + (0.999 * apex_i1 / 3) * Mat3::Identity(), 0.0, 0.0);
  EXPECT_EQ(inside.regime, PlasticRegime::apex);
  ASSERT_EQ(outside.regime, PlasticRegime::cone);
  EXPECT_NEAR(first_invariant(outside.stress), 0.999 * apex_i1, 1e-9 * apex_i1);
  EXPECT_NEAR(std::sqrt(j2_of(outside.stress)), s.k_c - s.alpha_phi * 0.999 * apex_i1, 1e-9 * s.k_c);

  // ψ > 0: the return along ∂g lowers I1 as it removes the deviator, so the apex region is
  // I1_tr − 9Kα_ψ sqrt(J2_tr)/G > k_c/α_φ, smaller than Bui et al.'s. A trial beyond the apex
  // with a large deviator comes back onto the cone, below the apex ...
  const double alpha_psi = drucker_prager_alpha(10 * kDeg);
  const Mat3 beyond = dev * 4 + (1.1 * apex_i1 / 3) * Mat3::Identity();
  const StressUpdate<double> c = p.return_map(beyond, 0.0, 0.0);
  ASSERT_EQ(c.regime, PlasticRegime::cone);
  EXPECT_LT(first_invariant(c.stress), apex_i1);
  EXPECT_NEAR(drucker_prager_yield(c.stress, s), 0.0, 1e-9 * s.k_c);
  // ... and one with a small deviator goes to the apex, its plastic strain in the normal cone of g
  // there: dε^p = Δλ(α_ψ I + d) with |d| <= 1/√2, i.e. tr(dε^p)/(3α_ψ) >= |de^p| √2.
  const Mat3 far = dev * 0.5 + (1.2 * apex_i1 / 3) * Mat3::Identity();
  const StressUpdate<double> b = p.return_map(far, 0.0, 0.0);
  ASSERT_EQ(b.regime, PlasticRegime::apex);
  const Mat3 ep = p.elastic.strain_increment(far - b.stress);
  EXPECT_GE(ep.trace() / (3 * alpha_psi), deviator(ep).norm() * std::sqrt(2.0));
}

// κ is the equivalent deviatoric plastic strain, Δκ = sqrt(2/3 de^p:de^p), de^p the deviator of
// the plastic strain increment (here recovered from the stresses by the elastic compliance).
TEST(DruckerPragerReturn, KappaGrowsOnlyOnPlasticStepsByTheDeviatoricPlasticStrain) {
  const SoilModel<double> m = softening_soil();
  const DruckerPrager<double> p = m.drucker_prager();
  std::mt19937 rng(31);
  Mat3 stress = -50e3 * Mat3::Identity();
  double kappa = 0;
  int plastic = 0, elastic = 0;
  for (int step = 0; step < 3000; ++step) {
    // A wandering strain path: shear with some compression and unloading.
    Mat3 de = random_symmetric(rng, 2e-5);
    de(0, 2) = de(2, 0) = 3e-5 * std::sin(step * 0.01);
    const Mat3 trial = p.elastic.update(stress, de, Mat3::Zero());
    const StressUpdate<double> u = p.update(stress, de, Mat3::Zero(), 5e3, kappa);
    const Mat3 plastic_strain = p.elastic.strain_increment(trial - u.stress);
    const Mat3 dev = deviator(plastic_strain);
    const double expected = std::sqrt(2.0 / 3.0 * dev.cwiseProduct(dev).sum());
    if (u.yielded()) {
      ++plastic;
      EXPECT_NEAR(u.kappa - kappa, expected, 1e-9 * expected + 1e-15) << step;
      EXPECT_GT(u.kappa, kappa);
    } else {
      ++elastic;
      EXPECT_EQ(u.kappa, kappa);
      EXPECT_EQ(u.stress, trial);
    }
    stress = u.stress;
    kappa = u.kappa;
  }
  EXPECT_GT(plastic, 300);
  EXPECT_GT(elastic, 300);
  EXPECT_GT(kappa, 1e-3);
}

// ---- Jaumann rate (Eq. 8) ----

// Rodrigues: R = exp(θ [n]×).
Mat3 rotation(const Eigen::Vector3d& axis, double angle) {
  const Eigen::Vector3d n = axis.normalized();
  Mat3 k;
  k << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  return Mat3::Identity() + std::sin(angle) * k + (1 - std::cos(angle)) * k * k;
}

// A block spinning rigidly at Ω about n: v = Ω n × x, so L = ∂v/∂x = Ω [n]×, ε̇ = 0, ω = L.
// Integrated with SoilModel::update (forward Euler in the rotation term), the invariants stay put
// to O(Ω Δt) and the stress follows R σ₀ Rᵀ, not Rᵀ σ₀ R (the sign of Eq. 8 as printed).
// Returns the relative drift of J2, which the caller checks is first order in Δt.
double check_rigid_rotation(const Mat3& grad_v, const Eigen::Vector3d& axis, double omega, double angle_step) {
  SoilModel<double> m = table_soil();
  m.kind = SoilModel<double>::Kind::linear_elastic;
  Mat3 sigma0;
  sigma0 << -120e3, 15e3, -30e3, 15e3, -60e3, 8e3, -30e3, 8e3, -20e3;
  const double total_angle = 1.0, dt = angle_step / omega;
  const int steps = int(std::lround(total_angle / (omega * dt)));
  const Mat3 de = strain_rate(grad_v) * dt, dw = spin_rate(grad_v) * dt;
  EXPECT_EQ(de.norm(), 0.0);
  Mat3 sigma = sigma0;
  for (int n = 0; n < steps; ++n) sigma = m.update(sigma, de, dw, 0.0, 0.0).stress;
  const Mat3 r = rotation(axis, total_angle);
  const Mat3 exact = r * sigma0 * r.transpose();
  const double scale = sigma0.norm();
  // Forward Euler: a global error of a few θ ΩΔt |σ|.
  EXPECT_LT((sigma - exact).norm(), 5 * total_angle * angle_step * scale);
  EXPECT_GT((sigma - sigma0).norm(), 0.2 * scale);                           // it did rotate
  EXPECT_GT((sigma - r.transpose() * sigma0 * r).norm(), 0.2 * scale);       // the right way
  EXPECT_NEAR(first_invariant(sigma), first_invariant(sigma0), 1e-9 * scale);
  EXPECT_NEAR(j2_of(sigma), j2_of(sigma0), 5 * total_angle * angle_step * j2_of(sigma0));
  EXPECT_NEAR(j3_of(sigma), j3_of(sigma0), 8 * total_angle * angle_step * std::fabs(j3_of(sigma0)));
  EXPECT_LT((sigma - sigma.transpose()).norm(), 1e-9 * scale);
  return j2_of(sigma) / j2_of(sigma0) - 1;
}

// The drift halves with the step: it is the integration error, nothing systematic.
void check_rigid_rotation_converges(const Mat3& grad_v, const Eigen::Vector3d& axis, double omega) {
  const double coarse = check_rigid_rotation(grad_v, axis, omega, 2e-5);
  const double fine = check_rigid_rotation(grad_v, axis, omega, 1e-5);
  EXPECT_NEAR(coarse / fine, 2.0, 0.1);
}

TEST(JaumannRate, RigidRotationRotatesStressAndKeepsInvariants) {
  const double omega = 2.0;  // rad/s
  const Eigen::Vector3d n = Eigen::Vector3d(1, -2, 0.5).normalized();
  Mat3 k;
  k << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  check_rigid_rotation_converges(Mat3(omega * k), n, omega);
  // 2D plane (x, z): v = (Ω z, −Ω x) is a rotation about +y; the 2×2 gradient embedded by
  // velocity_gradient_3d.
  Mat<double, 2> g2;
  g2 << 0, omega, -omega, 0;
  check_rigid_rotation_converges(velocity_gradient_3d<double, 2>(g2), Eigen::Vector3d(0, 1, 0), omega);
}

TEST(JaumannRate, StrainRateAndSpinSplitTheVelocityGradient) {
  std::mt19937 rng(41);
  const Mat3 sigma = random_symmetric(rng, 1e5);
  Mat3 grad_v;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) grad_v(a, b) = std::uniform_real_distribution<double>(-1, 1)(rng);
  const Mat3 d = strain_rate(grad_v), w = spin_rate(grad_v);
  EXPECT_LT((d + w - grad_v).norm(), 1e-15);
  EXPECT_EQ(d, d.transpose());
  EXPECT_EQ(w, Mat3(-w.transpose()));
  EXPECT_DOUBLE_EQ(w(0, 2), 0.5 * (grad_v(0, 2) - grad_v(2, 0)));  // Eq. 26d: ½(∂v_x/∂z − ∂v_z/∂x)
  // σ·ωᵀ + ω·σ: symmetric and traceless (a rotation changes no mean stress).
  const Mat3 term = jaumann_rotation(sigma, w);
  EXPECT_LT((term - (sigma * w.transpose() + w * sigma)).norm(), 1e-10);
  EXPECT_LT((term - term.transpose()).norm(), 1e-10);
  EXPECT_NEAR(term.trace(), 0.0, 1e-10);
  EXPECT_EQ(jaumann_stress_rate(d, sigma, w), Mat3(d + term));
}

// ---- Plane-strain strength: the Mohr–Coulomb match of Eq. 11 (ERRATA.md) ----

// Biaxial compression in the (x, z) plane: σ_xx = −p0 held (confinement), ε_yy = 0 (plane
// strain), ε_zz compressed in small steps; returns q = σ_xx − σ_zz at the end.
//
// At the limit state the stress stops changing, so the plastic strain rate equals the total one
// and ε̇^p_yy = 0. With in-plane principal stresses σ_1,3 = p_m ± t and σ_yy = p_m + d:
// J2 = t² + d²/3 and s_yy = 2d/3, and ε̇^p_yy = λ̇(α_ψ + s_yy/(2√J2)) = 0 gives
// d = −3α_ψ t/√(1 − 3α_ψ²), √J2 = t/√(1 − 3α_ψ²). f = 0 (Eq. 10a) with I1 = 3p_m + d then reads
// t = A (k_c − 3α_φ p_m), A = √(1 − 3α_ψ²)/(1 − 3α_φα_ψ).
// For ψ = φ, Eq. 11 makes this t = c cosφ − p_m sinφ: Mohr–Coulomb, the point of the match.
// With p_m = −p0 − q/2, t = q/2: q = 2A(k_c + 3α_φ p0)/(1 − 3Aα_φ), which for ψ = φ is
// q = 2(c cosφ + p0 sinφ)/(1 − sinφ) = p0(N_φ − 1) + 2c√N_φ.
template <typename Real>
Real biaxial_limit_deviator(const SoilModel<Real>& model, Real p0, int steps, Real axial_step) {
  using M = Mat<Real, 3>;
  const DruckerPrager<Real> p = model.drucker_prager();
  M stress = -p0 * M::Identity();
  Real kappa = 0;
  const Real lambda = p.elastic.lame_lambda(), m = lambda + 2 * p.elastic.shear_modulus;
  for (int n = 0; n < steps; ++n) {
    // Secant iteration on ε_xx so that σ_xx stays −p0.
    const auto sxx = [&](Real dx) {
      M de = M::Zero();
      de(0, 0) = dx;
      de(2, 2) = -axial_step;
      return p.update(stress, de, M::Zero(), Real(0), kappa);
    };
    Real x0 = lambda * axial_step / m, x1 = x0 * Real(1.01) + Real(1e-9);
    Real r0 = sxx(x0).stress(0, 0) + p0, r1 = sxx(x1).stress(0, 0) + p0;
    for (int it = 0; it < 50 && std::fabs(r1) > Real(1e-11) * p0 && r1 != r0; ++it) {
      const Real x2 = x1 - r1 * (x1 - x0) / (r1 - r0);
      x0 = x1;
      r0 = r1;
      x1 = x2;
      r1 = sxx(x1).stress(0, 0) + p0;
    }
    const StressUpdate<Real> u = sxx(x1);
    stress = u.stress;
    kappa = u.kappa;
  }
  EXPECT_LT(std::fabs(stress(0, 0) + p0), 1e-4 * p0);
  EXPECT_TRUE(std::isfinite(double(stress(1, 1))));
  return stress(0, 0) - stress(2, 2);
}

double plane_strain_deviator(double alpha_phi, double alpha_psi, double k_c, double p0) {
  const double big_a = std::sqrt(1 - 3 * alpha_psi * alpha_psi) / (1 - 3 * alpha_phi * alpha_psi);
  return 2 * big_a * (k_c + 3 * alpha_phi * p0) / (1 - 3 * big_a * alpha_phi);
}

double expected_plane_strain_deviator(double c, double phi, double psi, double p0) {
  return plane_strain_deviator(drucker_prager_alpha(phi), drucker_prager_alpha(psi), drucker_prager_kc(c, phi), p0);
}

TEST(DruckerPragerPlaneStrain, BiaxialPeakMatchesMohrCoulomb) {
  const double c = 10e3, phi = 30 * kDeg, p0 = 100e3;
  SoilModel<double> m = table_soil();
  m.dilatancy_angle = phi;
  const double q_mc = 2 * (c * std::cos(phi) + p0 * std::sin(phi)) / (1 - std::sin(phi));
  EXPECT_NEAR(expected_plane_strain_deviator(c, phi, phi, p0), q_mc, 1e-9 * q_mc);
  // 8% axial strain: the limit state is reached to round-off (1e-14 measured; 4% leaves 1e-6).
  const double q = biaxial_limit_deviator(m, p0, 8000, 1e-5);
  EXPECT_NEAR(q, q_mc, 1e-9 * q_mc) << "Mohr-Coulomb q = " << q_mc;
  // Drucker–Prager constants matched to Mohr–Coulomb in triaxial compression instead (the outer
  // cone, α = 2 sinφ/(√3(3 − sinφ)), k = 6c cosφ/(√3(3 − sinφ))) would be > 10% stronger here:
  // the test tells the matches apart.
  const double a_tc = 2 * std::sin(phi) / (std::sqrt(3.0) * (3 - std::sin(phi)));
  const double k_tc = 6 * c * std::cos(phi) / (std::sqrt(3.0) * (3 - std::sin(phi)));
  EXPECT_GT(std::fabs(plane_strain_deviator(a_tc, a_tc, k_tc, p0) - q), 0.1 * q);
  // Non-associated flow (ψ < φ) is weaker in plane strain, as derived above.
  for (double psi_deg : {0.0, 10.0}) {
    m.dilatancy_angle = psi_deg * kDeg;
    const double expected = expected_plane_strain_deviator(c, phi, psi_deg * kDeg, p0);
    EXPECT_LT(expected, q_mc);
    EXPECT_NEAR(biaxial_limit_deviator(m, p0, 8000, 1e-5), expected, 1e-8 * expected) << psi_deg;
  }
}

// ---- The compression switch on the soil's artificial viscosity ----

// L_ab = ∂v_a/∂x_b: on a particle at yield, simple shear and dilation switch the viscosity off,
// compression keeps it.
TEST(SoilViscositySwitch, OffInShearAndDilationOnInCompression) {
  const double c = 65, h = 0.0075;  // the column collapse's c_s0 and h
  const double guard = 1e-4 * c / h;
  const auto switch_2d = [&](const Mat<double, 2>& l) { return soil_viscosity_switch<double, 2>(l, c, h, 1.0); };
  const auto switch_3d = [&](const Mat<double, 3>& l) { return soil_viscosity_switch<double, 3>(l, c, h, 1.0); };
  Mat<double, 2> shear, compression, dilation, shear_compression;
  shear << 0, 50, 0, 0;                  // v_x = 50 z: |∇×v| = 50, ∇·v = 0
  compression << -50, 0, 0, -50;         // ∇·v = −100
  dilation << 50, 0, 0, 50;
  shear_compression << -25, 50, 0, -25;  // ∇·v = −50, |∇×v| = 50
  EXPECT_EQ(switch_2d(shear), 0.0);
  EXPECT_EQ(switch_2d(dilation), 0.0);
  EXPECT_DOUBLE_EQ(switch_2d(compression), 100 / (100 + guard));
  EXPECT_DOUBLE_EQ(switch_2d(shear_compression), 50 / (100 + guard));
  EXPECT_EQ(switch_2d(Mat<double, 2>::Zero()), 0.0);  // at rest: 0, not 0/0
  // 3D: a rigid rotation about z is all curl (|∇×v| = 20).
  Mat<double, 3> rotation = Mat<double, 3>::Zero();
  rotation(0, 1) = -10;
  rotation(1, 0) = 10;
  EXPECT_EQ(switch_3d(rotation), 0.0);
  EXPECT_DOUBLE_EQ(switch_3d(rotation - 10 * Mat<double, 3>::Identity()), 30 / (30 + 20 + guard));
}

// Inside the yield surface the particle is elastic, and its shear and dilation are the elastic
// noise the viscosity damps: the factor is 1 there (Eq. 26b as printed), and the switch acts from
// a yield ratio of 1 − 10⁻⁴ (on the cone to the return map's rounding) up to the apex's 10.
TEST(SoilViscositySwitch, FullViscosityInsideTheYieldSurface) {
  const double c = 65, h = 0.0075;
  Mat<double, 2> shear;
  shear << 0, 50, 0, 0;
  for (double elastic : {0.0, 0.5, 0.9998})
    EXPECT_EQ((soil_viscosity_switch<double, 2>(shear, c, h, elastic)), 1.0) << elastic;
  for (double yielding : {0.99995, 1.0, kYieldRatioAtApex})
    EXPECT_EQ((soil_viscosity_switch<double, 2>(shear, c, h, yielding)), 0.0) << yielding;
  Mat<double, 3> shear_3d = Mat<double, 3>::Zero();
  shear_3d(0, 2) = 50;
  EXPECT_EQ((soil_viscosity_switch<double, 3>(shear_3d, c, h, 0.5)), 1.0);
  EXPECT_EQ((soil_viscosity_switch<double, 3>(shear_3d, c, h, 1.0)), 0.0);
}

// ---- SoilModel ----

TEST(SoilModel, DispatchesOnKind) {
  SoilModel<double> dp = table_soil();
  SoilModel<double> el = dp;
  el.kind = SoilModel<double>::Kind::linear_elastic;
  Mat3 de = Mat3::Zero();
  de(0, 2) = de(2, 0) = 5e-3;  // far beyond the strength
  const Mat3 sigma = -50e3 * Mat3::Identity();
  const StressUpdate<double> ue = el.update(sigma, de, Mat3::Zero(), 0.0, 0.1);
  EXPECT_EQ(ue.regime, PlasticRegime::elastic);
  EXPECT_EQ(ue.kappa, 0.1);
  EXPECT_LT((ue.stress - (sigma + el.elastic().stress_increment(de))).norm(), 1e-6);
  const StressUpdate<double> up = dp.update(sigma, de, Mat3::Zero(), 0.0, 0.1);
  EXPECT_EQ(up.regime, PlasticRegime::cone);
  const StressUpdate<double> direct = dp.drucker_prager().update(sigma, de, Mat3::Zero(), 0.0, 0.1);
  EXPECT_EQ(up.stress, direct.stress);
  EXPECT_EQ(up.kappa, direct.kappa);
  // Inside the yield surface the two kinds agree.
  const Mat3 small = de * 1e-3;
  const StressUpdate<double> inside = dp.update(sigma, small, Mat3::Zero(), 0.0, 0.0);
  EXPECT_EQ(inside.regime, PlasticRegime::elastic);
  EXPECT_EQ(inside.stress, el.update(sigma, small, Mat3::Zero(), 0.0, 0.0).stress);
}

TEST(SoilModel, ValidateRejectsEachBadParameterByName) {
  using Model = SoilModel<double>;
  EXPECT_EQ(table_soil().validate(), "");
  EXPECT_EQ(softening_soil().validate(), "");
  struct Case {
    const char* name;
    void (*spoil)(Model&);
  };
  const std::vector<Case> cases = {
      {"youngs_modulus", [](Model& m) { m.youngs_modulus = 0; }},
      {"youngs_modulus", [](Model& m) { m.youngs_modulus = -1e6; }},
      {"youngs_modulus", [](Model& m) { m.youngs_modulus = std::nan(""); }},
      {"youngs_modulus", [](Model& m) { m.youngs_modulus = INFINITY; }},
      {"poisson_ratio", [](Model& m) { m.poisson_ratio = 0.5; }},
      {"poisson_ratio", [](Model& m) { m.poisson_ratio = -1; }},
      {"poisson_ratio", [](Model& m) { m.poisson_ratio = std::nan(""); }},
      {"peak_cohesion", [](Model& m) { m.peak_cohesion = -1; }},
      {"residual_cohesion", [](Model& m) { m.residual_cohesion = -1; }},
      {"residual_cohesion", [](Model& m) { m.residual_cohesion = m.peak_cohesion * 1.01; }},
      {"peak_friction_angle", [](Model& m) { m.peak_friction_angle = kPi / 2; }},
      {"peak_friction_angle", [](Model& m) { m.peak_friction_angle = -kDeg; }},
      {"residual_friction_angle", [](Model& m) { m.residual_friction_angle = -kDeg; }},
      {"residual_friction_angle", [](Model& m) { m.residual_friction_angle = m.peak_friction_angle + kDeg; }},
      {"dilatancy_angle", [](Model& m) { m.dilatancy_angle = m.peak_friction_angle + kDeg; }},
      {"dilatancy_angle", [](Model& m) { m.dilatancy_angle = -kDeg; }},
      {"softening_coefficient", [](Model& m) { m.softening_coefficient = -1; }},
      {"suction_cohesion", [](Model& m) { m.suction_cohesion = -1; }},
      {"suction_cohesion_rate", [](Model& m) { m.suction_cohesion_rate = -1; }},
      {"suction_friction_rate", [](Model& m) { m.suction_friction_rate = -kDeg; }},
      {"atmospheric_pressure", [](Model& m) { m.atmospheric_pressure = 0; }},
  };
  for (const Case& c : cases) {
    Model m = softening_soil();
    c.spoil(m);
    const std::string message = m.validate();
    EXPECT_EQ(message.rfind(c.name, 0), 0u) << c.name << ": " << message;
  }
  // Degrees in the message for angles: the unit case files use.
  Model steep = softening_soil();
  steep.peak_friction_angle = 95 * kDeg;
  EXPECT_NE(steep.validate().find("95.0"), std::string::npos) << steep.validate();
  // The strength parameters do not matter to a linear-elastic soil.
  Model el = softening_soil();
  el.kind = Model::Kind::linear_elastic;
  el.peak_cohesion = -1;
  EXPECT_EQ(el.validate(), "");
  el.poisson_ratio = 0.7;
  EXPECT_EQ(el.validate().rfind("poisson_ratio", 0), 0u);
}

// ---- float ----

TEST(SoilModelFloat, AgreesWithDouble) {
  const SoilModel<double> md = softening_soil();
  SoilModel<float> mf;
  mf.kind = SoilModel<float>::Kind::drucker_prager;
  mf.youngs_modulus = float(md.youngs_modulus);
  mf.poisson_ratio = float(md.poisson_ratio);
  mf.peak_cohesion = float(md.peak_cohesion);
  mf.residual_cohesion = float(md.residual_cohesion);
  mf.peak_friction_angle = float(md.peak_friction_angle);
  mf.residual_friction_angle = float(md.residual_friction_angle);
  mf.dilatancy_angle = float(md.dilatancy_angle);
  mf.softening_coefficient = float(md.softening_coefficient);
  mf.suction_cohesion = float(md.suction_cohesion);
  mf.suction_cohesion_rate = float(md.suction_cohesion_rate);
  EXPECT_EQ(mf.validate(), "");
  std::mt19937 rng(51);
  int plastic = 0;
  for (int i = 0; i < 500; ++i) {
    const Mat3 trial = random_symmetric(rng, 150e3) +
                       std::uniform_real_distribution<double>(-300e3, 40e3)(rng) * Mat3::Identity();
    const StressUpdate<double> ud = md.drucker_prager().return_map(trial, 7e3, 0.05);
    const StressUpdate<float> uf = mf.drucker_prager().return_map(Mat<float, 3>(trial.cast<float>()), 7e3f, 0.05f);
    if (ud.regime != uf.regime) continue;  // a trial within round-off of a region boundary
    plastic += ud.yielded();
    const double scale = trial.norm();
    EXPECT_LT((uf.stress.cast<double>() - ud.stress).norm(), 1e-5 * scale) << i;
    EXPECT_NEAR(uf.kappa, ud.kappa, 1e-5 * ud.kappa + 1e-7) << i;
    const Strength<float> s = mf.drucker_prager().strength(uf.kappa, 7e3f);
    if (uf.yielded()) {
      EXPECT_LE(std::fabs(drucker_prager_yield(uf.stress, s)), 1e-4f * s.k_c) << i;
    }
  }
  EXPECT_GT(plastic, 200);
  // The biaxial path in float reaches the double peak.
  SoilModel<float> mf0 = mf;
  mf0.softening_coefficient = 0;
  mf0.residual_cohesion = mf0.peak_cohesion;
  mf0.residual_friction_angle = mf0.peak_friction_angle;
  SoilModel<double> md0 = md;
  md0.softening_coefficient = 0;
  md0.residual_cohesion = md0.peak_cohesion;
  md0.residual_friction_angle = md0.peak_friction_angle;
  const double qd = biaxial_limit_deviator<double>(md0, 100e3, 1500, 2e-5);
  const double qf = biaxial_limit_deviator<float>(mf0, 100e3f, 1500, 2e-5f);
  EXPECT_NEAR(qf, qd, 1e-3 * qd);
}

}  // namespace
}  // namespace cascade
