// Published run-out scaling of planar (quasi-two-dimensional channel) granular column collapse,
// the reference for the SPH soil model's large-deformation behaviour.
//
// A column of initial height H_0 and length L_0 along the channel is released and spreads to a
// final run-out L_∞; a = H_0/L_0. The normalised run-out (L_∞ − L_0)/L_0 is reported as a
// function of a alone, in two regimes:
//
//   Lube, Huppert, Sparks & Freundt (2005), "Collapses of two-dimensional granular columns",
//   Physical Review E 72, 041301 (doi:10.1103/PhysRevE.72.041301):
//       (L_∞ − L_0)/L_0 ≈ 1.2 a          for a < 1.8,
//       (L_∞ − L_0)/L_0 ≈ 1.9 a^{2/3}    for a > 2.8,
//   with a transition between 1.8 and 2.8 for which no fit is given. The two branches are NOT
//   continuous: at a = 1.8 they give 2.16 and 2.81, at a = 2.8 they give 3.36 and 3.78, and they
//   would only meet at a = (1.9/1.2)^3 ≈ 3.97. Within the transition the band between the two
//   branches is the reference (runout_band). The sources quoted below describe the fits as
//   holding for all their materials (sand, rice, sugar) and for rough and smooth floors.
//
//   Balmforth & Kerswell (2005), "Granular collapse in two dimensions", Journal of Fluid
//   Mechanics 538:399–428 (doi:10.1017/S0022112005005537), abstract: (l_∞ − L)/L ~ a^{0.9±0.1}
//   in wide channels and ~ a^{0.65±0.05} in narrow slots, with a material-dependent constant of
//   proportionality (none is given as universal).
//
// Provenance and doubts. The Balmforth & Kerswell exponents are from their abstract, read in a
// stored copy of the paper. The Lube et al. coefficients (1.2, 1.9, 2/3) and boundaries (1.8,
// 2.8) could not be read in the primary text here; they are as quoted, identically, by several
// independent secondary sources (a table citing Lagrée, Staron & Popinet 2011, J. Fluid Mech.
// 686:378–408, Eq. 3.1; and benchmark code quoting "their Eq. 4" for the a > 2.8 branch). The
// experimental scatter Lube et al. state was not available; a test should therefore use a
// tolerance of its own choosing (the exponents' published uncertainty above is a guide) and say
// so. L_0 is the length of the released column along the channel; for a column released on both
// sides, the half-length and the run-out on one side.
#pragma once

#include <algorithm>
#include <cmath>

namespace cascade::reference {

enum class CollapseRegime { linear, transition, power_law };

struct Lube2005Planar {
  static constexpr double linear_coefficient = 1.2;   // (L∞ − L0)/L0 = 1.2 a
  static constexpr double linear_upper_aspect = 1.8;  // linear fit for a < 1.8
  static constexpr double power_coefficient = 1.9;    // (L∞ − L0)/L0 = 1.9 a^{2/3}
  static constexpr double power_exponent = 2.0 / 3.0;
  static constexpr double power_lower_aspect = 2.8;  // power fit for a > 2.8
};

inline CollapseRegime collapse_regime(double aspect_ratio) {
  if (aspect_ratio < Lube2005Planar::linear_upper_aspect) return CollapseRegime::linear;
  if (aspect_ratio > Lube2005Planar::power_lower_aspect) return CollapseRegime::power_law;
  return CollapseRegime::transition;
}

// The two published branches, evaluated at any a (they are fits only in their own regime).
inline double lube2005_linear_runout(double aspect_ratio) {
  return Lube2005Planar::linear_coefficient * aspect_ratio;
}
inline double lube2005_power_runout(double aspect_ratio) {
  return Lube2005Planar::power_coefficient * std::pow(aspect_ratio, Lube2005Planar::power_exponent);
}

// The reference value of (L∞ − L0)/L0 as an interval: a point (low == high) in either regime,
// and the span between the branches in the transition 1.8 <= a <= 2.8.
struct RunoutBand {
  double low = 0, high = 0;
};

inline RunoutBand lube2005_runout_band(double aspect_ratio) {
  const double lin = lube2005_linear_runout(aspect_ratio),
               pow = lube2005_power_runout(aspect_ratio);
  switch (collapse_regime(aspect_ratio)) {
    case CollapseRegime::linear: return {lin, lin};
    case CollapseRegime::power_law: return {pow, pow};
    case CollapseRegime::transition: break;
  }
  return {std::min(lin, pow), std::max(lin, pow)};
}

// Balmforth & Kerswell (2005): run-out exponent and its stated uncertainty.
enum class ChannelWidth { wide, narrow };
struct PowerLawExponent {
  double value = 0, uncertainty = 0;
};
inline PowerLawExponent balmforth_kerswell_2005_runout_exponent(ChannelWidth width) {
  return width == ChannelWidth::wide ? PowerLawExponent{0.9, 0.1} : PowerLawExponent{0.65, 0.05};
}

}  // namespace cascade::reference
