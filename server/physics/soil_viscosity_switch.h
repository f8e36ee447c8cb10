// Compression switch on the soil's artificial viscosity (the α c_s0 μ_ij term of Eq. 26b, μ_ij of
// Eq. 24c), for the particles that flow: on a particle at yield the viscosity acts in proportion to
// how much of its velocity gradient is compression, after Balsara (1995, J. Comput. Phys. 121:357),
// restricted to ∇·v < 0 as in the compression-triggered switches of Cullen & Dehnen (2010,
// MNRAS 408:669):
//   f_i = max(−∇·v_i, 0) / (|∇·v_i| + |∇×v_i| + 10⁻⁴ c_s0/h),  0 <= f_i < 1;
// on a particle inside the yield surface f_i = 1, the paper's Eq. 26b.
// Why a switch: the term is there to damp the skeleton's elastic noise. Unswitched it is a shear
// viscosity ν ≈ α c_s0 h/8 of the elastic wave speed, and in a granular layer d thick flowing at v
// its shear stress ρ ν v/d against the frictional strength μ ρ g d is (α c_s0 h / 8)(v / d) /
// (μ g d); with d a few particles thick both h and d scale with dp, so the ratio does not fall
// with resolution. In the dry column collapse (c_s0 = 65 m/s, v ≈ 0.5 m/s, d ≈ 2h) it is about 6:
// the front stopped at the static slope, ΔL/L0 22% below Lube et al. (2005) at two resolutions
// (docs/cases.md). Why only at yield: granular flow is plastic flow, and an elastic particle's
// shear and dilation are the elastic noise the term is for. Switched on elastic particles too,
// an elastic mode grew from the relaxation's residue in Fei Tsui Road's slope at rest (e-folding
// in about 0.3 s where its soil is one to three particles thick on the bedrock, yield ratio
// 0.3–0.5: 0.97 m/s and Δκ 0.16 in 10 s; docs/physics.md, "Geostatic start"). The 10⁻⁴ c_s0/h is
// Balsara's guard against 0/0 at rest; "at yield" is a yield ratio (drucker_prager.h) of at least
// 1 − 10⁻⁴: on the cone of Eq. 10a to the return map's rounding, as the relaxation's tolerance.
// The factor is particle i's own, from the velocity gradient of the same pass (Eq. 26c's L), so
// that the pass stays one loop with no neighbour's state read: the viscous pair forces are equal
// and opposite only between particles with equal f, and the term's momentum balance is no longer
// exact (the stress term's still is).
#pragma once

#include <cmath>

#include "server/core/types.h"

namespace cascade {

constexpr double kAtYield = 1.0 - 1e-4;  // yield ratio from which a particle counts as flowing

template <typename Real, int Dim>
CASCADE_HD inline Real soil_viscosity_switch(const Mat<Real, Dim>& velocity_gradient, Real sound_speed, Real h,
                                             double yield_ratio) {
  if (yield_ratio < kAtYield) return Real(1);
  const Real divergence = velocity_gradient.trace();
  // |∇×v| from the antisymmetric part of L (L_ab = ∂v_a/∂x_b).
  const Mat<Real, Dim> spin = velocity_gradient - velocity_gradient.transpose();
  const Real curl = std::sqrt(Real(0.5) * spin.squaredNorm());
  const Real compression = divergence < Real(0) ? -divergence : Real(0);
  return compression / (std::fabs(divergence) + curl + Real(1e-4) * sound_speed / h);
}

}  // namespace cascade
