// Compression switch on the soil's artificial viscosity (the α c_s0 μ_ij term of Eq. 26b, μ_ij of
// Eq. 24c): the viscosity acts on particle i in proportion to how much of its velocity gradient is
// compression, after Balsara (1995, J. Comput. Phys. 121:357), restricted to ∇·v < 0 as in the
// compression-triggered switches of Cullen & Dehnen (2010, MNRAS 408:669):
//   f_i = max(−∇·v_i, 0) / (|∇·v_i| + |∇×v_i| + 10⁻⁴ c_s0/h),  0 <= f_i < 1.
// Why: the term is there to damp the skeleton's elastic noise (compression waves). Unswitched it
// is a shear viscosity ν ≈ α c_s0 h/8 of the elastic wave speed, and in a granular layer d thick
// flowing at v its shear stress ρ ν v/d against the frictional strength μ ρ g d is
// (α c_s0 h / 8)(v / d) / (μ g d); with d a few particles thick both h and d scale with dp, so the
// ratio does not fall with resolution. In the dry column collapse (c_s0 = 65 m/s, v ≈ 0.5 m/s,
// d ≈ 2h) it is about 6: the front stopped at the static slope, ΔL/L0 22% below Lube et al. (2005)
// at two resolutions (docs/cases.md). Shear and dilation, the granular flow itself, leave it off;
// compression, the elastic waves and impacts it is meant for, keeps most of it. The 10⁻⁴ c_s0/h
// is Balsara's guard against 0/0 at rest.
// The factor is particle i's own, from the velocity gradient of the same pass (Eq. 26c's L), so
// that the pass stays one loop with no neighbour's state read: the viscous pair forces are equal
// and opposite only between particles with equal f, and the term's momentum balance is no longer
// exact (the stress term's still is).
#pragma once

#include <cmath>

#include "server/core/types.h"

namespace cascade {

template <typename Real, int Dim>
CASCADE_HD inline Real soil_viscosity_switch(const Mat<Real, Dim>& velocity_gradient, Real sound_speed, Real h) {
  const Real divergence = velocity_gradient.trace();
  // |∇×v| from the antisymmetric part of L (L_ab = ∂v_a/∂x_b).
  const Mat<Real, Dim> spin = velocity_gradient - velocity_gradient.transpose();
  const Real curl = std::sqrt(Real(0.5) * spin.squaredNorm());
  const Real compression = divergence < Real(0) ? -divergence : Real(0);
  return compression / (std::fabs(divergence) + curl + Real(1e-4) * sound_speed / h);
}

}  // namespace cascade
