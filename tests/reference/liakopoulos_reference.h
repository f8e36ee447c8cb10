// Reference results for the Liakopoulos drainage test, the paper's Section 4.2 (Table 1, Eq. 43,
// Figs. 8–10): a 1 m column of sand, initially saturated with p_w = 0 everywhere (steady downward
// flow at unit gradient), drains through its base (p_w = 0 there) once the inflow at the top
// stops (no flow through the top), under gravity, with the skeleton deforming elastically.
//
// What this file holds, and where each number comes from:
//
//  1. The material of Table 1 and the hydraulic curves of Eq. 43 (typed from the paper).
//
//  2. Numerical reference profiles of pore-water pressure p_w (Pa) and vertical displacement u_z
//     (m, negative = downwards, relative to the state at the start of drainage) along the column
//     axis at t = 300, 600 and 7200 s, from OpenGeoSys (OGS), benchmark "A test based on the
//     Liakopoulos experiment" (W. Wang, 2020), RICHARDS_MECHANICS process:
//       project  ufz/ogs Tests/Data/RichardsMechanics/LiakopoulosHM/liakopoulos.prj
//                (commit 4b49d74246ce2332c008bb2ce64273a2e7357f76),
//       results  liakopoulos_t_300.vtu and liakopoulos_t_7200.vtu (same commit) and
//                liakopoulos_t_600.vtu (commit 50190ddc08fe21750dbd52ef192ed58dad2ab355),
//                written by OGS 6.3.3-260 and used by OGS's own regression test (vtkdiff,
//                absolute tolerance 1e-10 Pa on pressure, 1e-15 m on displacement).
//     How they were obtained: the VTU files store their arrays as zlib-compressed base64; the
//     arrays "Points", "pressure" and "displacement" were decoded (the zlib checksums pass) and
//     the 41 corner nodes on the axis x = 0 (every 0.025 m; pressure is linear, order 1, so it
//     lives on corner nodes only) were tabulated below, rounded to 0.01 Pa and 6 digits.
//     The OGS model: a 0.1 m wide, 1 m high axisymmetric column of 40 eight-node elements,
//     Richards flow (gas phase at zero pressure) coupled to linear elasticity through Bishop's
//     effective stress with χ = S_w, Biot coefficient 1, E = 1.3 MPa, ν = 0.4, φ = 0.2975,
//     intrinsic permeability 4.5e-13 m² with μ_w = 1e-3 Pa s (K_sat = k ρ_w g/μ_w = 4.41e-6 m/s at
//     g = 9.81), ρ_s = 2000 kg/m³, ρ_w = 1000 kg/m³ with compressibility 5e-10 1/Pa (K_w = 2 GPa),
//     gravity 9.81 m/s², lateral and bottom displacement fixed normal to the walls, geostatic
//     initial stress and zero initial displacement; S_w(p_c) = 1 − 1.9722e-11 p_c^2.4279 (p_c in
//     Pa, OGS "SaturationLiakopoulos", floor 0.2) and K_rel tabulated from
//     1 − 2.207 (1 − S_w)^1.0121; backward Euler with steps of 1 s (10), 10 s (9), 100 s (11),
//     200 s (3), 400 s (3) and 600 s (7).
//     Differences from the paper's SPH set-up to keep in mind: K_w = 2e6 Pa in Table 1 against
//     2e9 Pa here; the SPH model's u-w-p inertia; and Eq. 43a, which equals the OGS curve only if
//     ρ_w0 g = 10^4 Pa/m (0.10152 = 1.9722e-11 · (10^4)^2.4279), about 5 % more saturation
//     deficit than with ρ_w0 g = 9810 Pa/m.
//
// Not here, because no trustworthy numbers were found: the measured water pressures of
// Liakopoulos (1964, PhD thesis, University of California, Berkeley) that the paper's Fig. 9
// shows, and the displacement profiles of Wang et al. (2018) of its Fig. 10. Published numerical
// references for the same test are B. A. Schrefler & R. Scotta (2001), Comput. Methods Appl.
// Mech. Eng. 190(24–25):3223–3246, and R. W. Lewis & B. A. Schrefler (1998), The Finite Element
// Method in the Static and Dynamic Deformation and Consolidation of Porous Media, Wiley; their
// curves were not available in tabulated form.
#pragma once

#include <algorithm>
#include <cmath>

namespace cascade::reference {

// Table 1 of the paper (SI units).
struct LiakopoulosMaterial {
  static constexpr double grain_density = 2000.0;            // ρ_s0 (kg/m³)
  static constexpr double water_density = 1000.0;            // ρ_w0 (kg/m³)
  static constexpr double porosity = 0.2975;                 // φ (-)
  static constexpr double water_bulk_modulus = 2e6;          // K_w (Pa), the paper's SPH value
  static constexpr double saturated_conductivity = 4.41e-6;  // K_sat (m/s)
  static constexpr double youngs_modulus = 1.3e6;            // E (Pa)
  static constexpr double poisson_ratio = 0.4;               // ν (-)
  static constexpr double height = 1.0;                      // column height (m)
};

// Eq. 43a as printed: S_w = 1 − 0.10152 (p_c/(ρ_w0 g))^2.4279, p_c in Pa, gravity in m/s².
inline double liakopoulos_saturation_eq43(double suction, double gravity = 9.81) {
  if (suction <= 0) return 1.0;
  const double head = suction / (LiakopoulosMaterial::water_density * gravity);
  return 1.0 - 0.10152 * std::pow(head, 2.4279);
}

// The curve of the OGS reference: S_w = 1 − 1.9722e-11 p_c^2.4279 (p_c in Pa), not below 0.2.
inline double liakopoulos_saturation_ogs(double suction) {
  if (suction <= 0) return 1.0;
  return std::max(0.2, 1.0 - 1.9722e-11 * std::pow(suction, 2.4279));
}

// Eq. 43b: K/K_sat = 1 − 2.207 (1 − S_w)^1.0121, not below zero.
inline double liakopoulos_relative_conductivity(double saturation) {
  return std::max(0.0, 1.0 - 2.207 * std::pow(std::max(0.0, 1.0 - saturation), 1.0121));
}

// OGS RICHARDS_MECHANICS reference profiles along the axis (see 2. above).
struct LiakopoulosOgsProfiles {
  static constexpr int points = 41;
  static constexpr double times[3] = {300.0, 600.0, 7200.0};  // s after drainage starts
  // Height above the drained base (m).
  static constexpr double height[41] = {
      0.000, 0.025, 0.050, 0.075, 0.100, 0.125, 0.150, 0.175, 0.200, 0.225, 0.250,
      0.275, 0.300, 0.325, 0.350, 0.375, 0.400, 0.425, 0.450, 0.475, 0.500, 0.525,
      0.550, 0.575, 0.600, 0.625, 0.650, 0.675, 0.700, 0.725, 0.750, 0.775, 0.800,
      0.825, 0.850, 0.875, 0.900, 0.925, 0.950, 0.975, 1.000};
  // p_w (Pa) at t = 300, 600, 7200 s.
  static constexpr double pressure_t300[41] = {
      0.00,     -56.64,   -113.36,  -170.26,  -227.41,  -284.94,  -342.93,  -401.51,  -460.78,
      -520.89,  -581.95,  -644.11,  -707.51,  -772.32,  -838.70,  -906.82,  -976.89,  -1049.11,
      -1123.68, -1200.84, -1280.85, -1363.96, -1450.47, -1540.69, -1634.94, -1733.59, -1837.02,
      -1945.67, -2059.99, -2180.46, -2307.64, -2442.12, -2584.53, -2735.57, -2896.00, -3066.66,
      -3248.44, -3442.33, -3649.41, -3870.82, -4107.82};
  static constexpr double pressure_t600[41] = {
      0.00,     -92.32,   -184.68,  -277.13,  -369.73,  -462.55,  -555.66,  -649.13,  -743.05,
      -837.51,  -932.63,  -1028.50, -1125.26, -1223.05, -1322.00, -1422.28, -1524.06, -1627.53,
      -1732.87, -1840.31, -1950.07, -2062.39, -2177.55, -2295.81, -2417.48, -2542.87, -2672.34,
      -2806.24, -2944.97, -3088.93, -3238.59, -3394.41, -3556.90, -3726.60, -3904.10, -4090.02,
      -4285.01, -4489.78, -4705.10, -4931.75, -5170.60};
  static constexpr double pressure_t7200[41] = {
      0.00,     -224.74,  -449.48,  -674.22,  -898.96,  -1123.71, -1348.48, -1573.26, -1798.07,
      -2022.91, -2247.80, -2472.75, -2697.77, -2922.88, -3148.10, -3373.46, -3598.97, -3824.65,
      -4050.55, -4276.70, -4503.11, -4729.85, -4956.93, -5184.42, -5412.35, -5640.78, -5869.75,
      -6099.33, -6329.58, -6560.56, -6792.33, -7024.98, -7258.57, -7493.19, -7728.91, -7965.83,
      -8204.04, -8443.63, -8684.71, -8927.37, -9171.73};
  // Vertical displacement u_z (m) at t = 300, 600, 7200 s.
  static constexpr double displacement_t300[41] = {
      0.00000e+00,  -2.00586e-07, -9.09859e-07, -2.12893e-06, -3.85975e-06, -6.10514e-06,
      -8.86885e-06, -1.21556e-05, -1.59712e-05, -2.03223e-05, -2.52171e-05, -3.06646e-05,
      -3.66754e-05, -4.32613e-05, -5.04355e-05, -5.82130e-05, -6.66101e-05, -7.56452e-05,
      -8.53382e-05, -9.57112e-05, -1.06788e-04, -1.18596e-04, -1.31164e-04, -1.44522e-04,
      -1.58706e-04, -1.73753e-04, -1.89702e-04, -2.06599e-04, -2.24492e-04, -2.43431e-04,
      -2.63474e-04, -2.84681e-04, -3.07118e-04, -3.30857e-04, -3.55976e-04, -3.82559e-04,
      -4.10695e-04, -4.40483e-04, -4.72028e-04, -5.05443e-04, -5.40850e-04};
  static constexpr double displacement_t600[41] = {
      0.00000e+00,  -3.49553e-07, -1.52773e-06, -3.53509e-06, -6.37264e-06, -1.00419e-05,
      -1.45452e-05, -1.98850e-05, -2.60651e-05, -3.30897e-05, -4.09639e-05, -4.96939e-05,
      -5.92867e-05, -6.97508e-05, -8.10955e-05, -9.33316e-05, -1.06471e-04, -1.20529e-04,
      -1.35519e-04, -1.51459e-04, -1.68369e-04, -1.86268e-04, -2.05181e-04, -2.25133e-04,
      -2.46151e-04, -2.68266e-04, -2.91512e-04, -3.15924e-04, -3.41541e-04, -3.68406e-04,
      -3.96564e-04, -4.26064e-04, -4.56960e-04, -4.89307e-04, -5.23166e-04, -5.58603e-04,
      -5.95687e-04, -6.34490e-04, -6.75092e-04, -7.17573e-04, -7.62022e-04};
  static constexpr double displacement_t7200[41] = {
      0.00000e+00,  -3.94690e-07, -2.80618e-06, -7.23419e-06, -1.36782e-05, -2.21373e-05,
      -3.26102e-05, -4.50955e-05, -5.95909e-05, -7.60941e-05, -9.46022e-05, -1.15112e-04,
      -1.37619e-04, -1.62120e-04, -1.88609e-04, -2.17081e-04, -2.47531e-04, -2.79952e-04,
      -3.14337e-04, -3.50679e-04, -3.88971e-04, -4.29203e-04, -4.71368e-04, -5.15455e-04,
      -5.61455e-04, -6.09357e-04, -6.59150e-04, -7.10822e-04, -7.64361e-04, -8.19755e-04,
      -8.76989e-04, -9.36049e-04, -9.96920e-04, -1.05959e-03, -1.12403e-03, -1.19024e-03,
      -1.25819e-03, -1.32786e-03, -1.39924e-03, -1.47230e-03, -1.54702e-03};

  static const double* pressure(int time_index) {
    const double* table[3] = {pressure_t300, pressure_t600, pressure_t7200};
    return table[time_index];
  }
  static const double* displacement(int time_index) {
    const double* table[3] = {displacement_t300, displacement_t600, displacement_t7200};
    return table[time_index];
  }
  // Linear interpolation of a tabulated profile at height z (m), clamped to [0, 1].
  static double interpolate(const double* values, double z) {
    const double s = std::clamp(z, 0.0, 1.0) / 0.025;
    const int i = std::min(points - 2, int(s));
    const double w = s - i;
    return (1 - w) * values[i] + w * values[i + 1];
  }
};

}  // namespace cascade::reference
