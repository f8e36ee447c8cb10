// Terzaghi's one-dimensional consolidation: a saturated layer of thickness H on an impermeable
// base, drained at the top, loaded at t = 0 by a constant vertical total stress Δσ.
//
// Excess pore pressure u(z, t) (Pa) solves the diffusion equation ∂u/∂t = c_v ∂²u/∂z² with
// u = 0 at the drained top and ∂u/∂z = 0 at the base, u(z, 0+) = u_0. With ζ = z/H measured
// upwards from the impermeable base and the time factor T_v = c_v t / H², the classical series
// solution (K. Terzaghi, Erdbaumechanik auf bodenphysikalischer Grundlage, Deuticke, Vienna, 1925;
// K. Terzaghi, Theoretical Soil Mechanics, Wiley, 1943, chapter on the theory of consolidation;
// written there in the distance from the drained face x = 1 − ζ, where (−1)^m cos(Mζ) = sin(Mx))
// reads:
//
//     u/u_0 = Σ_{m>=0} (−1)^m (2/M) cos(M ζ) e^{−M² T_v},   M = (2m + 1) π/2,     (Fourier)
//     U(T_v) = 1 − Σ_{m>=0} (2/M²) e^{−M² T_v}        (average degree of consolidation).
//
// For small T_v the same solution is summed as images of the error function (the drained face
// is a sink, the base a mirror; with x = 1 − ζ the distance from the drained face):
//
//     u/u_0 = 1 − Σ_{n>=0} (−1)^n [ erfc((2n + x)/(2√T_v)) + erfc((2n + 2 − x)/(2√T_v)) ],
//     U = 2 √(T_v/π) + 4 √T_v Σ_{n>=1} (−1)^n ierfc(n/√T_v),   ierfc(y) = e^{−y²}/√π − y erfc(y).
//
// The public functions use the image series below kSmallTimeFactor and the Fourier series
// above it; both are exposed so that a test can compare them where both converge.
//
// Coefficient of consolidation for the SPH model's pore water (weakly compressible, bulk modulus
// K_w, paper Eq. 6 and the storage of Eq. 3a/28b with S_w = 1): with incompressible grains
// (Biot coefficient 1), mass balance of the pore water and Darcy's law give
//
//     (φ/K_w) ∂u/∂t − ∂ε_vol/∂t = (k/γ_w) ∂²u/∂z²      (ε_vol > 0 in compression),
//
// and the oedometric skeleton ε_vol = m_v σ' = m_v (σ − u), σ constant for t > 0, so
//
//     (m_v + φ/K_w) ∂u/∂t = (k/γ_w) ∂²u/∂z²,   c_v = k / (γ_w (m_v + φ/K_w)),
//
// m_v = 1/E_oed, E_oed = E (1 − ν)/((1 + ν)(1 − 2ν)) the oedometric (constrained) modulus, k the
// hydraulic conductivity K_sat (m/s) and γ_w = ρ_w g. At t = 0+ no water has moved, so
// (φ/K_w) u_0 = ε_vol = m_v (Δσ − u_0): u_0 = Δσ m_v/(m_v + φ/K_w) (loading_efficiency). The
// settlement of the top is s(t) = m_v H (Δσ − ū(t)) with ū = u_0 (1 − U). The u-w-p model's
// inertia is not in this solution: compare at times long against the wave transit time H/c_p.
//
// Units: Pa, m, s; time factor and ratios dimensionless.
#pragma once

#include <cmath>

namespace cascade::reference {

constexpr double kSmallTimeFactor = 0.05;

// Oedometric modulus E_oed (Pa) from Young's modulus E (Pa) and Poisson's ratio ν (-).
inline double oedometric_modulus(double youngs_modulus, double poisson_ratio) {
  const double nu = poisson_ratio;
  return youngs_modulus * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
}

// c_v (m²/s) = k / (γ_w (1/E_oed + φ/K_w)); k = K_sat (m/s), E_oed (Pa), φ (-), K_w (Pa, may be
// infinite: incompressible water), γ_w = ρ_w g (N/m³).
inline double consolidation_coefficient(double hydraulic_conductivity, double oedometric_modulus,
                                        double porosity, double water_bulk_modulus,
                                        double water_unit_weight = 1000.0 * 9.81) {
  const double storage = 1.0 / oedometric_modulus + porosity / water_bulk_modulus;
  return hydraulic_conductivity / (water_unit_weight * storage);
}

// u_0/Δσ for an instantaneous oedometric load: m_v/(m_v + φ/K_w) (-).
inline double loading_efficiency(double oedometric_modulus, double porosity,
                                 double water_bulk_modulus) {
  const double mv = 1.0 / oedometric_modulus;
  return mv / (mv + porosity / water_bulk_modulus);
}

// T_v = c_v t / H² (-); c_v (m²/s), t (s), H the drainage length = layer thickness (m).
inline double time_factor(double consolidation_coefficient, double time, double thickness) {
  return consolidation_coefficient * time / (thickness * thickness);
}

// u/u_0 by the Fourier series; zeta = z/H from the impermeable base, in [0, 1].
inline double terzaghi_pressure_fourier(double zeta, double tv, double tolerance = 1e-16) {
  if (tv <= 0) return zeta < 1 ? 1.0 : 0.0;
  constexpr double kPi = 3.14159265358979323846;
  double sum = 0;
  for (int m = 0; m < 1000000; ++m) {
    const double big_m = (2 * m + 1) * kPi / 2;
    const double term = 2.0 / big_m * std::exp(-big_m * big_m * tv);
    sum += (m % 2 == 0 ? 1.0 : -1.0) * term * std::cos(big_m * zeta);
    if (term < tolerance) break;
  }
  return sum;
}

// u/u_0 by the image (erfc) series.
inline double terzaghi_pressure_images(double zeta, double tv, double tolerance = 1e-16) {
  if (tv <= 0) return zeta < 1 ? 1.0 : 0.0;
  const double x = 1.0 - zeta, s = 2.0 * std::sqrt(tv);
  double sum = 0;
  for (int n = 0; n < 100000; ++n) {
    const double term = std::erfc((2 * n + x) / s) + std::erfc((2 * n + 2 - x) / s);
    sum += (n % 2 == 0 ? 1.0 : -1.0) * term;
    if (term < tolerance) break;
  }
  return 1.0 - sum;
}

inline double terzaghi_degree_fourier(double tv, double tolerance = 1e-16) {
  if (tv <= 0) return 0.0;
  constexpr double kPi = 3.14159265358979323846;
  double sum = 0;
  for (int m = 0; m < 1000000; ++m) {
    const double big_m = (2 * m + 1) * kPi / 2;
    const double term = 2.0 / (big_m * big_m) * std::exp(-big_m * big_m * tv);
    sum += term;
    if (term < tolerance) break;
  }
  return 1.0 - sum;
}

inline double terzaghi_degree_images(double tv, double tolerance = 1e-16) {
  if (tv <= 0) return 0.0;
  constexpr double kSqrtPi = 1.77245385090551602730;
  const double r = std::sqrt(tv);
  auto ierfc = [kSqrtPi](double y) { return std::exp(-y * y) / kSqrtPi - y * std::erfc(y); };
  double sum = 0;
  for (int n = 1; n < 100000; ++n) {
    const double term = ierfc(n / r);
    sum += (n % 2 == 0 ? 1.0 : -1.0) * term;
    if (term < tolerance) break;
  }
  return 2.0 * r / kSqrtPi + 4.0 * r * sum;
}

// u/u_0 at zeta = z/H (from the impermeable base) and time factor T_v.
inline double excess_pore_pressure_ratio(double zeta, double tv) {
  return tv < kSmallTimeFactor ? terzaghi_pressure_images(zeta, tv)
                               : terzaghi_pressure_fourier(zeta, tv);
}

// Average degree of consolidation U(T_v) = 1 − ū/u_0 (-).
inline double degree_of_consolidation(double tv) {
  return tv < kSmallTimeFactor ? terzaghi_degree_images(tv) : terzaghi_degree_fourier(tv);
}

// Settlement of the top (m, positive downwards) at time factor T_v for a load Δσ (Pa) on a layer
// of thickness H (m): m_v H (Δσ − u_0 (1 − U)), which includes the instantaneous part
// m_v H (Δσ − u_0) that a compressible pore water allows.
inline double consolidation_settlement(double tv, double load, double thickness,
                                       double oedometric_modulus, double porosity,
                                       double water_bulk_modulus) {
  const double u0 = load * loading_efficiency(oedometric_modulus, porosity, water_bulk_modulus);
  return thickness / oedometric_modulus * (load - u0 * (1.0 - degree_of_consolidation(tv)));
}

}  // namespace cascade::reference
