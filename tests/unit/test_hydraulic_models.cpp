// Hydraulic models (paper Eqs. 14, 15, 42, 43, 28b with ERRATA.md): values against the paper's
// numbers and independently computed references, analytic derivatives against finite
// differences, limits, monotonicity, the capacity C_r, parameter validation and float builds.
// Reference values marked "mpmath" were computed with 30-digit arithmetic straight from the
// printed formulas, not from this code.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "server/physics/swcc/grain_bound_water.h"
#include "server/physics/swcc/hydraulic_model.h"
#include "server/physics/swcc/hydraulic_model_check.h"

namespace cascade {
namespace {

constexpr double kUnitWeight = 1000.0 * 9.81;  // ρ_w0 g of Sections 4.1 and 4.2 (Pa/m)

// Table 3 (rainfall-landslide-tsunami): S_min 0.087, S_max 1, λ 0.61, p_ref 4350 Pa.
template <typename Real = double>
HydraulicModel<Real> table3() {
  return HydraulicModel<Real>(VanGenuchten<Real>{Real(0.087), Real(1.0), Real(0.61), Real(4350.0)});
}
// Table 2 (Fei Tsui Road landslide): S_min 0.3, S_max 1, λ 0.447, p_ref 19.357 kPa.
template <typename Real = double>
HydraulicModel<Real> table2() {
  return HydraulicModel<Real>(VanGenuchten<Real>{Real(0.3), Real(1.0), Real(0.447), Real(19357.0)});
}
// Section 4.1, Eq. 42: S_min 0.23, S_max 1, α = 2 1/m.
template <typename Real = double>
HydraulicModel<Real> gardner_column() {
  return HydraulicModel<Real>(Gardner<Real>{Real(0.23), Real(1.0), Real(2.0), Real(kUnitWeight)});
}
// Section 4.2, Eq. 43.
template <typename Real = double>
HydraulicModel<Real> liakopoulos() {
  return HydraulicModel<Real>(Liakopoulos<Real>{Real(kUnitWeight)});
}

struct Named {
  const char* name;
  HydraulicModel<double> model;
  double s_min;  // the dry limit, typed in from the paper (or mpmath for Eq. 43's cut-off)
  double s_max;
};

// Liakopoulos' dry limit: 1 − 2.207^(−1/1.0121) (mpmath), where Eq. 43b reaches K = 0.
constexpr double kLiakopoulosSmin = 0.542587592596943507630613364115;
// ... reached at the head h = (0.457412407403056/0.10152)^(1/2.4279) m (mpmath).
constexpr double kLiakopoulosHeadCut = 1.85895222418554214792810115426;

std::vector<Named> all_models() {
  return {{"van Genuchten, Table 3", table3(), 0.087, 1.0},
          {"van Genuchten, Table 2", table2(), 0.3, 1.0},
          {"Gardner, Section 4.1", gardner_column(), 0.23, 1.0},
          {"Liakopoulos, Section 4.2", liakopoulos(), kLiakopoulosSmin, 1.0}};
}

// p_c from 10 Pa to ~10 MPa, 5% apart.
std::vector<double> suction_grid() {
  std::vector<double> p;
  for (double p_c = 10.0; p_c < 1e7; p_c *= 1.05) p.push_back(p_c);
  return p;
}

// ERRATA.md row "Eq. 14": Table 3 with p_c = 7 kPa gives S_w = 0.457 (the paper's Section 5 says
// S_w0 = 0.46). 0.457485860208779 is the mpmath value of Eq. 14.
TEST(VanGenuchten, Table3SaturationAtSevenKilopascals) {
  const double s_w = table3().saturation(7000.0);
  EXPECT_NEAR(s_w, 0.457, 5e-4);
  EXPECT_NEAR(s_w, 0.457485860208779356, 1e-14);
}

// Eq. 14 at p_c = p_ref: x = 1, so S_e = 2^(−λ) and, for Table 2, S_w = 0.3 + 0.7·2^(−0.447)
// = 0.813496670458563 (mpmath).
TEST(VanGenuchten, Table2SaturationAtReferencePressure) {
  EXPECT_NEAR(table2().saturation(19357.0), 0.813496670458563242, 1e-14);
  EXPECT_NEAR(table2().van_genuchten.effective_saturation(19357.0), std::pow(2.0, -0.447), 1e-15);
}

// Eq. 15 (Mualem) by hand for λ = 0.5, S_e = 0.5: S_e^(1/λ) = 0.25, 1 − 0.25 = 0.75,
// 0.75^0.5 = 0.8660254037844386, 1 − that = 0.1339745962155614, squared = 0.0179491924311227,
// times sqrt(0.5) = 0.7071067811865475 gives K_rel = 0.0126919956848691. With λ = 0.5 the exponent
// of Eq. 14 is 2, so S_e = (1 + (p_c/p_ref)²)^(−1/2) = 0.5 at p_c = sqrt(3) p_ref.
TEST(VanGenuchten, MualemConductivityAgainstHandValue) {
  const VanGenuchten<double> vg{0.0, 1.0, 0.5, 1000.0};
  const double p_c = std::sqrt(3.0) * 1000.0;
  EXPECT_NEAR(vg.effective_saturation(p_c), 0.5, 1e-15);
  EXPECT_NEAR(vg.relative_conductivity(p_c), 0.0126919956848691186, 1e-15);
  // Table 3 at 7 kPa: S_e = 0.405789551159671, K_rel = 0.0135785200182370 (mpmath, Eq. 15).
  EXPECT_NEAR(table3().relative_conductivity(7000.0), 0.0135785200182369912, 1e-15);
}

// Eq. 42 at heads h = 0.5 m and 1 m: S_w = 0.23 + 0.77 e^(−2h), K_rel = e^(−2h);
// e^(−1) = 0.367879441171442, e^(−2) = 0.135335283236613 (mpmath). Slope at h = 1 m:
// −0.77·2/9810·e^(−2) = −2.12452942083979e−5 1/Pa; just above p_c = 0: −0.77·2/9810 (the kink).
TEST(Gardner, ClosedFormAtKnownHeads) {
  const auto m = gardner_column();
  EXPECT_NEAR(m.saturation(0.5 * kUnitWeight), 0.513267169702010588, 1e-15);
  EXPECT_NEAR(m.relative_conductivity(0.5 * kUnitWeight), 0.367879441171442322, 1e-15);
  EXPECT_NEAR(m.saturation(kUnitWeight), 0.334208168092191773, 1e-15);
  EXPECT_NEAR(m.relative_conductivity(kUnitWeight), 0.135335283236612692, 1e-15);
  EXPECT_NEAR(m.saturation_derivative(kUnitWeight), -2.12452942083979149e-5, 1e-18);
  EXPECT_NEAR(m.saturation_derivative(1e-12), -1.56982670744138634e-4, 1e-17);
}

// Eq. 43 at h = 0.5, 1 and 1.8 m: S_w = 1 − 0.10152 h^2.4279, K_rel = 1 − 2.207 (1 − S_w)^1.0121
// (mpmath). Range: Eq. 43b reaches 0 at h = 1.858952 m, S_w = 0.542588; beyond it S_w is held
// there and K_rel = 0 (docs/physics.md).
TEST(Liakopoulos, PaperFormulaAndRange) {
  const auto m = liakopoulos();
  EXPECT_NEAR(m.saturation(0.5 * kUnitWeight), 0.981133954278250581, 1e-15);
  EXPECT_NEAR(m.relative_conductivity(0.5 * kUnitWeight), 0.960315678950420187, 1e-15);
  EXPECT_NEAR(m.saturation(kUnitWeight), 0.89848, 1e-15);
  EXPECT_NEAR(m.relative_conductivity(kUnitWeight), 0.782061871721809961, 1e-15);
  EXPECT_NEAR(m.saturation(1.8 * kUnitWeight), 0.577012314164729711, 1e-15);
  EXPECT_NEAR(m.relative_conductivity(1.8 * kUnitWeight), 0.0761347694386400193, 1e-14);
  // dS_w/dp_c = −a b h^(b−1)/γ_w at h = 1: −0.10152·2.4279/9810 (mpmath).
  EXPECT_NEAR(m.saturation_derivative(kUnitWeight), -2.51254238532110092e-5, 1e-18);

  EXPECT_NEAR(m.saturation_min(), kLiakopoulosSmin, 1e-15);
  const double p_cut = kLiakopoulosHeadCut * kUnitWeight;
  EXPECT_GT(m.relative_conductivity(0.999 * p_cut), 0.0);
  EXPECT_LT(m.saturation_derivative(0.999 * p_cut), 0.0);
  for (double f : {1.001, 2.0, 10.0, 1e6}) {
    EXPECT_NEAR(m.saturation(f * p_cut), kLiakopoulosSmin, 1e-15) << f;
    EXPECT_EQ(m.relative_conductivity(f * p_cut), 0.0) << f;
    EXPECT_EQ(m.saturation_derivative(f * p_cut), 0.0) << f;
  }
}

// Analytic dS_w/dp_c against a centred difference of S_w, step e = 1e−4 p_c: truncation
// O(1e−8) relative, round-off about ulp(1)/e since S_w <= 1. Points within one step of a kink of
// the model (Liakopoulos' cut-off) are skipped.
TEST(HydraulicModels, SaturationDerivativeMatchesCentredDifference) {
  for (const auto& [name, m, s_min, s_max] : all_models()) {
    int checked = 0;
    for (double p_c : suction_grid()) {
      const double e = 1e-4 * p_c;
      if (m.kind == HydraulicModel<double>::Kind::liakopoulos &&
          std::fabs(p_c - kLiakopoulosHeadCut * kUnitWeight) < 2 * e)
        continue;
      const double fd = (m.saturation(p_c + e) - m.saturation(p_c - e)) / (2 * e);
      const double d = m.saturation_derivative(p_c);
      EXPECT_LE(d, 0.0) << name << " p_c " << p_c;
      EXPECT_NEAR(d, fd, 1e-6 * std::fabs(fd) + 3e-16 / e) << name << " p_c " << p_c;
      ++checked;
    }
    EXPECT_GT(checked, 250) << name;
  }
  // The van Genuchten and Liakopoulos curves join the saturated branch smoothly: the slope
  // vanishes as p_c → 0+ (exponents 1/(1−λ) − 1 > 0 and b − 1 > 0).
  EXPECT_LT(std::fabs(table3().saturation_derivative(1e-3)), 1e-9 * std::fabs(table3().saturation_derivative(4350.0)));
  EXPECT_LT(std::fabs(liakopoulos().saturation_derivative(1e-3)),
            1e-9 * std::fabs(liakopoulos().saturation_derivative(kUnitWeight)));
}

// Saturated branch (ERRATA.md row "Eq. 14"): S_w = S_max, K_rel = 1, dS_w/dp_c = 0 for p_c <= 0.
// Dry limit: S_w → S_min, K_rel → 0. Bounds and monotonicity over the whole grid; no NaN at the
// edges.
TEST(HydraulicModels, LimitsBoundsAndMonotonicity) {
  const double huge = std::numeric_limits<double>::max(), inf = std::numeric_limits<double>::infinity();
  for (const auto& [name, m, s_min, s_max] : all_models()) {
    EXPECT_EQ(m.saturation_max(), s_max) << name;
    EXPECT_NEAR(m.saturation_min(), s_min, 1e-15) << name;
    for (double p_c : {-inf, -1e6, -1.0, -1e-300, 0.0}) {
      EXPECT_EQ(m.saturation(p_c), s_max) << name << " p_c " << p_c;
      EXPECT_EQ(m.relative_conductivity(p_c), 1.0) << name << " p_c " << p_c;
      EXPECT_EQ(m.saturation_derivative(p_c), 0.0) << name << " p_c " << p_c;
    }
    for (double p_c : {1e-300, 1e-12, 1e9, 1e12, huge, inf}) {
      EXPECT_TRUE(std::isfinite(m.saturation(p_c))) << name << " p_c " << p_c;
      EXPECT_TRUE(std::isfinite(m.saturation_derivative(p_c))) << name << " p_c " << p_c;
      EXPECT_TRUE(std::isfinite(m.relative_conductivity(p_c))) << name << " p_c " << p_c;
    }
    EXPECT_NEAR(m.saturation(1e-12), s_max, 1e-12) << name;
    EXPECT_NEAR(m.relative_conductivity(1e-12), 1.0, 1e-9) << name;
    // At 1 TPa Table 2 still has S_e = 5.8e−7 (slowest decay, exponent λ/(1−λ) = 0.81).
    EXPECT_NEAR(m.saturation(1e12), s_min, 1e-5 * (s_max - s_min)) << name;
    EXPECT_NEAR(m.relative_conductivity(1e12), 0.0, 1e-12) << name;
    for (double p_c : {huge, inf}) {
      EXPECT_NEAR(m.saturation(p_c), s_min, 1e-15) << name << " p_c " << p_c;
      EXPECT_NEAR(m.relative_conductivity(p_c), 0.0, 1e-12) << name << " p_c " << p_c;
      EXPECT_GE(m.saturation(p_c), m.saturation_min()) << name << " p_c " << p_c;
      EXPECT_GE(m.relative_conductivity(p_c), 0.0) << name << " p_c " << p_c;
    }
    double s_prev = m.saturation(0.0), k_prev = m.relative_conductivity(0.0);
    for (double p_c : suction_grid()) {
      const double s = m.saturation(p_c), k = m.relative_conductivity(p_c);
      EXPECT_LE(s, s_prev) << name << " p_c " << p_c;
      EXPECT_LE(k, k_prev) << name << " p_c " << p_c;
      EXPECT_GE(s, s_min - 1e-15) << name << " p_c " << p_c;
      EXPECT_LE(s, s_max) << name << " p_c " << p_c;
      EXPECT_GE(k, 0.0) << name << " p_c " << p_c;
      EXPECT_LE(k, 1.0) << name << " p_c " << p_c;
      s_prev = s;
      k_prev = k;
    }
    // The curve actually falls over the grid (monotone but not constant).
    EXPECT_LT(s_prev, 0.5 * (s_min + s_max)) << name;
  }
}

// A NaN pressure stays NaN (so the solver's non-finite checks see it) rather than turning into a
// plausible saturation.
TEST(HydraulicModels, NaNPressurePropagates) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [name, m, s_min, s_max] : all_models()) {
    EXPECT_TRUE(std::isnan(m.saturation(nan))) << name;
    EXPECT_TRUE(std::isnan(m.saturation_derivative(nan))) << name;
    EXPECT_TRUE(std::isnan(m.relative_conductivity(nan))) << name;
  }
}

// C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eq. 28b, ERRATA.md row "Eq. 28b / 41"): C_r >= φ S_w
// everywhere, = φ S_max when saturated. Table 3 at 7 kPa with φ = 0.3, K_w = 2×10⁶ Pa
// (Tables 1–3): ∂S_w/∂p_c = −6.39109389796183e−5 1/Pa, C_r = 38.4838091458336 (mpmath, numerical
// derivative of Eq. 14).
TEST(HydraulicModels, CapacityAtLeastPorosityTimesSaturation) {
  const double phi = 0.3, k_w = 2e6;
  EXPECT_NEAR(table3().saturation_derivative(7000.0), -6.39109389796182566e-5, 1e-18);
  EXPECT_NEAR(pore_water_capacity(table3(), phi, 7000.0, phi, k_w), 38.4838091458335878, 1e-11);
  for (const auto& [name, m, s_min, s_max] : all_models()) {
    EXPECT_EQ(pore_water_capacity(m, phi, -1000.0, phi, k_w), phi * s_max) << name;
    for (double p_c : suction_grid()) {
      const double c_r = pore_water_capacity(m, phi, p_c, phi, k_w);
      EXPECT_GE(c_r, phi * m.saturation(p_c)) << name << " p_c " << p_c;
    }
    // Somewhere on the curve the saturation term adds storage (strictly more than φ S_w).
    EXPECT_GT(pore_water_capacity(m, phi, 5000.0, phi, k_w), phi * m.saturation(5000.0) + 1e-3) << name;
  }
}

// grain_bound_water.h: at the reference porosity the curve is unchanged; the residual water per
// unit volume of grains, S_b e, does not change with the porosity; and the skeleton's share of the
// pore water, S_w + e ∂S_w/∂e at constant p_c, is S_max S_e. By central differences in e: with
// S_w = (e_wr/e)(1 − S_e) + S_max S_e, the truncation e (h²/6) ∂³S_w/∂e³ = e h² e_wr (1 − S_e)/e⁴
// is at most 4e−8 here (h = 1e−4, e_wr = 0.3 × 2/3, e >= 3/7).
TEST(GrainBoundWater, ResidualWaterMovesWithTheGrains) {
  const double phi0 = 0.4;
  const auto void_ratio = [](double phi) { return phi / (1 - phi); };
  const auto porosity = [](double e) { return e / (1 + e); };
  for (const auto& [name, m, s_min, s_max] : all_models()) {
    const double bound0 = grain_bound_saturation(m, phi0, phi0);
    EXPECT_NEAR(bound0, m.bound_saturation(), 1e-15) << name;
    for (double phi : {0.2, 0.3, 0.5, 0.6, 0.7})
      EXPECT_NEAR(grain_bound_saturation(m, phi0, phi) * void_ratio(phi), bound0 * void_ratio(phi0), 1e-15) << name;
    for (double p_c : suction_grid()) {
      EXPECT_NEAR(saturation_at_porosity(m, phi0, p_c, phi0), m.saturation(p_c), 1e-14) << name << " p_c " << p_c;
      EXPECT_NEAR(saturation_derivative_at_porosity(m, phi0, p_c, phi0), m.saturation_derivative(p_c),
                  1e-14 * std::fabs(m.saturation_derivative(p_c)))
          << name << " p_c " << p_c;
      for (double phi : {0.3, 0.4, 0.5}) {
        const double e = void_ratio(phi), step = 1e-4;
        const double s_plus = saturation_at_porosity(m, phi0, p_c, porosity(e + step));
        const double s_minus = saturation_at_porosity(m, phi0, p_c, porosity(e - step));
        const double share = saturation_at_porosity(m, phi0, p_c, phi) + e * (s_plus - s_minus) / (2 * step);
        EXPECT_NEAR(share, skeleton_water_share(m, p_c), 1e-7) << name << " p_c " << p_c << " φ " << phi;
      }
    }
  }
  // Saturated: the share is S_max, Eq. 27a's S_w as printed.
  for (const auto& [name, m, s_min, s_max] : all_models()) EXPECT_EQ(skeleton_water_share(m, -1.0), s_max) << name;
}

void expect_rejected(const HydraulicModel<double>& m, const std::string& parameter) {
  const std::string message = check_hydraulic_model(m);
  EXPECT_EQ(message.rfind(parameter + " ", 0), 0u) << "expected an error naming " << parameter << ", got '"
                                                   << message << "'";
}

TEST(HydraulicModelCheck, AcceptsThePapersParameters) {
  for (const auto& [name, m, s_min, s_max] : all_models()) EXPECT_EQ(check_hydraulic_model(m), "") << name;
  EXPECT_EQ(check_hydraulic_model(HydraulicModel<float>(VanGenuchten<float>{0.0f, 1.0f, 0.5f, 1.0f})), "");
}

TEST(HydraulicModelCheck, RejectsEachBadParameterByName) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  using VG = VanGenuchten<double>;
  using G = Gardner<double>;
  using M = HydraulicModel<double>;
  expect_rejected(M(VG{0.5, 0.5, 0.61, 4350.0}), "s_min");   // S_min >= S_max
  expect_rejected(M(VG{0.6, 0.5, 0.61, 4350.0}), "s_min");
  expect_rejected(M(VG{-0.01, 1.0, 0.61, 4350.0}), "s_min");  // S_min < 0
  expect_rejected(M(VG{nan, 1.0, 0.61, 4350.0}), "s_min");
  expect_rejected(M(VG{0.087, 1.01, 0.61, 4350.0}), "s_max");  // S_max > 1
  expect_rejected(M(VG{0.087, nan, 0.61, 4350.0}), "s_max");
  expect_rejected(M(VG{0.087, -inf, 0.61, 4350.0}), "s_min");  // nothing is below −inf
  for (double lambda : {0.0, -0.3, 1.0, 1.5, nan}) expect_rejected(M(VG{0.087, 1.0, lambda, 4350.0}), "lambda");
  for (double p_ref : {0.0, -4350.0, nan, inf}) expect_rejected(M(VG{0.087, 1.0, 0.61, p_ref}), "p_ref");

  expect_rejected(M(G{0.23, 0.23, 2.0, kUnitWeight}), "s_min");
  expect_rejected(M(G{-0.1, 1.0, 2.0, kUnitWeight}), "s_min");
  expect_rejected(M(G{0.23, 2.0, 2.0, kUnitWeight}), "s_max");
  for (double alpha : {0.0, -2.0, nan, inf}) expect_rejected(M(G{0.23, 1.0, alpha, kUnitWeight}), "alpha");
  for (double w : {0.0, -kUnitWeight, nan, inf}) expect_rejected(M(G{0.23, 1.0, 2.0, w}), "unit_weight");
  for (double w : {0.0, -kUnitWeight, nan, inf}) expect_rejected(M(Liakopoulos<double>{w}), "unit_weight");

  M unknown = table3();
  unknown.kind = static_cast<M::Kind>(7);
  expect_rejected(unknown, "model");
  // An unvalidated kind poisons the values instead of picking some model.
  EXPECT_TRUE(std::isnan(unknown.saturation(7000.0)));

  // The message carries the offending value for the user.
  EXPECT_NE(check_hydraulic_model(M(VG{0.087, 1.0, 1.5, 4350.0})).find("1.5"), std::string::npos);
}

// The float instantiation compiles and agrees with double to ~1e−5 relative at moderate suctions
// (where no value is a small difference of large ones), and is well defined at the edges.
TEST(HydraulicModels, FloatAgreesWithDouble) {
  const std::vector<std::pair<HydraulicModel<float>, HydraulicModel<double>>> pairs = {
      {table3<float>(), table3<double>()},
      {table2<float>(), table2<double>()},
      {gardner_column<float>(), gardner_column<double>()},
      {liakopoulos<float>(), liakopoulos<double>()}};
  for (const auto& [f, d] : pairs) {
    EXPECT_NEAR(f.saturation_min(), d.saturation_min(), 1e-6);
    for (double p_c : {100.0, 1000.0, 3000.0, 7000.0, 15000.0}) {
      const auto close = [](double a, double b) { return std::fabs(a - b) <= 1e-5 * std::fabs(b); };
      const float pf = float(p_c);
      EXPECT_PRED2(close, f.saturation(pf), d.saturation(p_c)) << p_c;
      EXPECT_PRED2(close, f.saturation_derivative(pf), d.saturation_derivative(p_c)) << p_c;
      EXPECT_PRED2(close, f.relative_conductivity(pf), d.relative_conductivity(p_c)) << p_c;
      EXPECT_PRED2(close, pore_water_capacity(f, 0.3f, pf, 0.3f, 2e6f), pore_water_capacity(d, 0.3, p_c, 0.3, 2e6)) << p_c;
    }
    // Edges in float: finite, within bounds, no NaN from underflow (x = 0) or overflow (x = inf).
    const float huge = std::numeric_limits<float>::max(), inf = std::numeric_limits<float>::infinity();
    for (float p_c : {0.0f, 1e-30f, 1e-12f, 1e12f, huge, inf}) {
      EXPECT_GE(f.saturation(p_c), f.saturation_min()) << p_c;
      EXPECT_LE(f.saturation(p_c), f.saturation_max()) << p_c;
      EXPECT_TRUE(std::isfinite(f.saturation_derivative(p_c))) << p_c;
      EXPECT_LE(f.saturation_derivative(p_c), 0.0f) << p_c;
      EXPECT_GE(f.relative_conductivity(p_c), 0.0f) << p_c;
      EXPECT_LE(f.relative_conductivity(p_c), 1.0f) << p_c;
    }
  }
}

}  // namespace
}  // namespace cascade
