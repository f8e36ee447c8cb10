// Drucker–Prager elasto-plasticity with a non-associated potential, strain softening and suction
// hardening (paper Eqs. 10–13 with ERRATA.md), integrated by a return mapping along the plastic
// potential with the apex (tension cut-off) treatment of Bui et al. (2008). Tension positive.
// docs/physics.md, "Soil constitutive models (Eqs. 8-13)", gives the algorithm step by step.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "server/core/types.h"
#include "server/physics/soil/jaumann_rate.h"
#include "server/physics/soil/linear_elastic.h"

namespace cascade {

// Eq. 11a with ERRATA.md (plane-strain match to Mohr–Coulomb): α = tanφ / sqrt(9 + 12 tan²φ),
// computed as sinφ / sqrt(9 + 3 sin²φ) (numerator and denominator times cosφ), which is finite
// at φ = 90° (α = 1/sqrt(12)). Also α_ψ with the dilatancy angle ψ (text after Eq. 11b).
template <typename Real>
CASCADE_HD inline Real drucker_prager_alpha(Real angle) {
  const Real s = std::sin(angle);
  return s / std::sqrt(Real(9) + Real(3) * s * s);
}

// Eq. 11b with ERRATA.md: k_c = 3c / sqrt(9 + 12 tan²φ) = 3c cosφ / sqrt(9 + 3 sin²φ).
template <typename Real>
CASCADE_HD inline Real drucker_prager_kc(Real cohesion, Real angle) {
  const Real s = std::sin(angle);
  return Real(3) * cohesion * std::cos(angle) / std::sqrt(Real(9) + Real(3) * s * s);
}

// I1 = tr σ.
template <typename Real>
CASCADE_HD inline Real first_invariant(const Mat<Real, 3>& stress) {
  return stress.trace();
}

// s = σ − (I1/3) I.
template <typename Real>
CASCADE_HD inline Mat<Real, 3> deviator(const Mat<Real, 3>& stress) {
  return stress - (stress.trace() / Real(3)) * Mat<Real, 3>::Identity();
}

// J2 = ½ s:s for a symmetric σ, written with differences of normal stresses so that a large
// mean stress does not cancel digits of a small deviator.
template <typename Real>
CASCADE_HD inline Real second_deviatoric_invariant(const Mat<Real, 3>& stress) {
  const Real dxy = stress(0, 0) - stress(1, 1), dyz = stress(1, 1) - stress(2, 2), dzx = stress(2, 2) - stress(0, 0);
  return (dxy * dxy + dyz * dyz + dzx * dzx) / Real(6) + stress(0, 1) * stress(0, 1) + stress(1, 2) * stress(1, 2) +
         stress(2, 0) * stress(2, 0);
}

// Strength at one state: c and φ of Eq. 12 and the Drucker–Prager constants of Eq. 11.
template <typename Real>
struct Strength {
  Real cohesion;        // c [Pa]
  Real friction_angle;  // φ [rad]
  Real alpha_phi;       // α_φ [-]
  Real k_c;             // k_c [Pa]
};

// Eq. 10a: f = α_φ I1 + sqrt(J2) − k_c; f <= 0 is elastic.
template <typename Real>
CASCADE_HD inline Real drucker_prager_yield(const Mat<Real, 3>& stress, const Strength<Real>& strength) {
  return strength.alpha_phi * first_invariant(stress) + std::sqrt(second_deviatoric_invariant(stress)) - strength.k_c;
}

// How close a stress is to yield: sqrt(J2) over the shear strength k_c − α_φ I1 at the same
// mean stress, 1 on the cone of Eq. 10a, below 1 inside it. Where the strength vanishes (at or
// beyond the apex, a tensile mean stress) it is kYieldRatioAtApex.
constexpr double kYieldRatioAtApex = 10.0;
template <typename Real>
CASCADE_HD inline Real yield_ratio(const Mat<Real, 3>& stress, const Strength<Real>& strength) {
  const Real shear_strength = strength.k_c - strength.alpha_phi * first_invariant(stress);
  const Real shear = std::sqrt(second_deviatoric_invariant(stress));
  if (!(shear_strength > Real(0))) return Real(kYieldRatioAtApex);
  const Real ratio = shear / shear_strength;
  return ratio < Real(kYieldRatioAtApex) ? ratio : Real(kYieldRatioAtApex);
}

// Eq. 10b: g = α_ψ I1 + sqrt(J2).
template <typename Real>
CASCADE_HD inline Real drucker_prager_potential(const Mat<Real, 3>& stress, Real alpha_psi) {
  return alpha_psi * first_invariant(stress) + std::sqrt(second_deviatoric_invariant(stress));
}

// ∂g/∂σ = α_ψ I + s / (2 sqrt(J2)) (Eq. 10b), defined off the hydrostatic axis (J2 > 0). With
// α_ψ = α_φ it is ∂f/∂σ.
template <typename Real>
CASCADE_HD inline Mat<Real, 3> drucker_prager_potential_gradient(const Mat<Real, 3>& stress, Real alpha_psi) {
  return alpha_psi * Mat<Real, 3>::Identity() +
         deviator(stress) / (Real(2) * std::sqrt(second_deviatoric_invariant(stress)));
}

// Which branch of the return mapping a stress update took.
enum class PlasticRegime : std::uint8_t {
  elastic,  // f(trial) <= 0: the trial stress stands
  cone,     // returned along ∂g/∂σ onto the cone f = 0
  apex,     // returned to the apex, I1 = k_c/α_φ, s = 0 (tension cut-off)
};

template <typename Real>
struct StressUpdate {
  Mat<Real, 3> stress;   // σ' at the end of the step [Pa]
  Real kappa;            // κ at the end of the step [-]
  PlasticRegime regime;  // the branch taken

  CASCADE_HD bool yielded() const { return regime != PlasticRegime::elastic; }
};

// Material constants of one soil, SI units, angles in radians (case files give degrees; the
// scenario loader converts them). The member functions fix Real, so Eigen expressions and
// literals convert at the call without template deduction.
template <typename Real>
struct DruckerPrager {
  LinearElastic<Real> elastic;
  Real peak_cohesion;            // c'_p [Pa]
  Real residual_cohesion;        // c'_r [Pa]
  Real peak_friction_angle;      // φ'_p [rad]
  Real residual_friction_angle;  // φ'_r [rad]
  Real dilatancy_angle;          // ψ [rad], constant (the paper softens only c and φ)
  Real softening_coefficient;    // η [-] of Eq. 12
  Real suction_cohesion;         // c_sp of Eq. 13a, the tables' c_s0 (ERRATA.md, Eq. 13) [Pa]
  Real suction_cohesion_rate;    // B_s [-] of Eq. 13a
  Real suction_friction_rate;    // A_s [rad] of Eq. 13b (the tables give it in degrees)
  Real atmospheric_pressure;     // p_atm [Pa] of Eq. 13, "typically 101 kPa"

  // Eqs. 12a, 12b and 13a, 13b at equivalent deviatoric plastic strain κ and suction p_c [Pa]:
  //   c = c'_r + (c'_p − c'_r) e^(−ηκ) + c_sp (1 − e^(−B_s p_c/p_atm)),
  //   φ = φ'_r + (φ'_p − φ'_r) e^(−ηκ) + A_s p_c/p_atm.
  // The suction p_c = −p_w (ERRATA.md, Eq. 28b) counts only where it is positive: a saturated
  // particle (p_w >= 0) gains nothing from suction, where Eq. 13 as printed would make c_s and
  // φ_s negative. φ is capped at 90°, the limit of Eq. 11, should A_s p_c/p_atm push it further.
  CASCADE_HD Strength<Real> strength(Real kappa, Real suction) const {
    constexpr Real kRightAngle = Real(1.57079632679489661923);
    const Real relative_suction = suction > Real(0) ? suction / atmospheric_pressure : Real(0);
    const Real decay = std::exp(-softening_coefficient * kappa);
    // 1 − e^(−x) as −expm1(−x): exact for small suctions.
    const Real cohesion = residual_cohesion + (peak_cohesion - residual_cohesion) * decay -
                          suction_cohesion * std::expm1(-suction_cohesion_rate * relative_suction);
    Real friction = residual_friction_angle + (peak_friction_angle - residual_friction_angle) * decay +
                    suction_friction_rate * relative_suction;
    friction = friction < kRightAngle ? friction : kRightAngle;
    return {cohesion, friction, drucker_prager_alpha(friction), drucker_prager_kc(cohesion, friction)};
  }

  // Return mapping of a trial stress (already rotated and elastically loaded) at hardening state
  // κ and suction p_c [Pa]. Backward Euler with the flow rule dε^p = Δλ ∂g/∂σ:
  //  1. f_tr = f(σ_tr; κ_n) (Eq. 10a); f_tr <= 0: elastic.
  //  2. σ = σ_tr − Δλ D:∂g/∂σ = σ_tr − Δλ (3Kα_ψ I + G s_tr/sqrt(J2_tr)). The deviator keeps its
  //     direction, so I1 = I1_tr − 9Kα_ψΔλ, sqrt(J2) = sqrt(J2_tr) − GΔλ, and f = 0 is one scalar
  //     equation in Δλ. Without softening (η = 0) it is linear, Δλ = f_tr / (9Kα_φα_ψ + G), the
  //     denominator of Bui et al.'s (2008) plastic multiplier; with softening it is solved by a
  //     bracketed false-position (Illinois) iteration, whose first step is that same value. For
  //     ψ = 0 the return keeps I1 and scales s by (k_c − α_φ I1)/sqrt(J2_tr): Bui et al.'s stress
  //     scaling exactly.
  //  3. If the deviator would vanish before f = 0 (f > 0 still at Δλ_max = sqrt(J2_tr)/G), the
  //     trial lies beyond the apex: the stress goes to the apex σ = k_c/(3α_φ) I, the end state of
  //     Bui et al.'s tension-cracking treatment (mean stress shifted to I1 = k_c/α_φ) followed by
  //     their stress scaling (deviator scaled by (k_c − α_φ I1)/sqrt(J2) = 0). The region is
  //     I1_tr − 9Kα_ψ sqrt(J2_tr)/G > k_c/α_φ: for ψ = 0 exactly their α_φ I1 − k_c > 0; for
  //     ψ > 0 smaller, since the return along ∂g lowers I1 while it removes the deviator, and
  //     exactly the trials whose plastic strain D⁻¹:(σ_tr − σ_apex) lies in the cone of normals
  //     of g at the apex.
  // κ, the equivalent deviatoric plastic strain, grows by sqrt(2/3 de^p:de^p) with de^p the
  // deviator of dε^p: Δλ/√3 on the cone, sqrt(J2_tr)/(√3 G) (all of s_tr/(2G) is plastic) at the
  // apex, which is the cone value at Δλ_max, so κ is continuous across the two branches.
  CASCADE_HD StressUpdate<Real> return_map(const Mat<Real, 3>& trial, Real suction, Real kappa) const {
    constexpr Real kInvSqrt3 = Real(0.57735026918962576451);
    const Strength<Real> strength_n = strength(kappa, suction);
    const Real i1 = first_invariant(trial);
    const Real sqrt_j2 = std::sqrt(second_deviatoric_invariant(trial));
    const Real f_trial = strength_n.alpha_phi * i1 + sqrt_j2 - strength_n.k_c;
    if (!(f_trial > Real(0))) return {trial, kappa, PlasticRegime::elastic};

    const Real shear = elastic.shear_modulus;
    const Real volumetric_rate = Real(9) * elastic.bulk_modulus * drucker_prager_alpha(dilatancy_angle);
    const Real dl_max = sqrt_j2 / shear;
    const Real r_max = cone_residual(strength_n, suction, kappa, i1, sqrt_j2, volumetric_rate, dl_max);
    if (r_max > Real(0)) {
      const Real kappa_apex = kappa + dl_max * kInvSqrt3;
      const Strength<Real> s = strength(kappa_apex, suction);
      // r_max > 0 with k_c >= 0 implies α_φ > 0: the apex is finite.
      return {(s.k_c / (Real(3) * s.alpha_phi)) * Mat<Real, 3>::Identity(), kappa_apex, PlasticRegime::apex};
    }

    // Root of the residual in (0, Δλ_max]: r(0) = f_tr > 0 >= r(Δλ_max).
    const Real tolerance = Real(8) * std::numeric_limits<Real>::epsilon() *
                           (strength_n.k_c + std::fabs(strength_n.alpha_phi * i1) + sqrt_j2);
    Real lo = 0, r_lo = f_trial, hi = dl_max, r_hi = r_max;
    Real dl = hi;
    int kept = 0;  // +1: the last step moved lo, −1: hi (Illinois rule)
    for (int iteration = 0; iteration < 64; ++iteration) {
      dl = (lo * r_hi - hi * r_lo) / (r_hi - r_lo);
      const Real r = cone_residual(strength_n, suction, kappa, i1, sqrt_j2, volumetric_rate, dl);
      if (std::fabs(r) <= tolerance) break;
      if (r > Real(0)) {
        lo = dl;
        r_lo = r;
        if (kept == 1) r_hi *= Real(0.5);
        kept = 1;
      } else {
        hi = dl;
        r_hi = r;
        if (kept == -1) r_lo *= Real(0.5);
        kept = -1;
      }
      if (hi - lo <= std::numeric_limits<Real>::epsilon() * hi) break;
    }

    const Real mean = (i1 - volumetric_rate * dl) / Real(3);
    const Real deviator_scale = sqrt_j2 > Real(0) ? Real(1) - shear * dl / sqrt_j2 : Real(0);
    const Mat<Real, 3> stress = deviator_scale * deviator(trial) + mean * Mat<Real, 3>::Identity();
    return {stress, kappa + dl * kInvSqrt3, PlasticRegime::cone};
  }

  // One stress update of a soil particle: Eq. 8 integrated over the step with the strain
  // increment dε = ε̇ Δt (Eq. 26c) and spin increment dω = ω̇ Δt (Eq. 26d). The Jaumann rotation
  // is applied here, explicitly with the stress at the start of the step, before the elastic
  // trial and the return mapping, as Bui et al. (2008) do: σ_tr = σ_n + dω·σ_n − σ_n·dω + D^e:dε.
  CASCADE_HD StressUpdate<Real> update(const Mat<Real, 3>& stress, const Mat<Real, 3>& strain_increment,
                                       const Mat<Real, 3>& spin_increment, Real suction, Real kappa) const {
    return return_map(elastic.update(stress, strain_increment, spin_increment), suction, kappa);
  }

 private:
  // f at the end of a cone return with multiplier Δλ, as a function of Δλ alone: along the return
  // I1 = I1_tr − 9Kα_ψ Δλ, sqrt(J2) = sqrt(J2_tr) − GΔλ, and κ = κ_n + Δλ/√3 sets the strength
  // (Eq. 12), so the return is implicit in the softening as well.
  CASCADE_HD Real cone_residual(const Strength<Real>& strength_n, Real suction, Real kappa_n, Real i1_trial,
                                Real sqrt_j2_trial, Real volumetric_rate, Real dl) const {
    constexpr Real kInvSqrt3 = Real(0.57735026918962576451);
    const Strength<Real> s = softening_coefficient > Real(0) ? strength(kappa_n + dl * kInvSqrt3, suction) : strength_n;
    return s.alpha_phi * (i1_trial - volumetric_rate * dl) + (sqrt_j2_trial - elastic.shear_modulus * dl) - s.k_c;
  }
};

}  // namespace cascade
