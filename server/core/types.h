// Small types shared by host and device code: the host/device marker, vectors and phases.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <cstring>

#if defined(__CUDACC__)
#define CASCADE_HD __host__ __device__
#else
#define CASCADE_HD
#endif

// A neighbour loop that the host compiler may vectorise (OpenMP SIMD), with the reductions of
// its sums named: CASCADE_SIMD(reduction(+ : a, b) reduction(max : c)). The order of the sums
// is fixed by the build, so runs stay deterministic. Nothing on the device, where each particle
// is a thread already.
#define CASCADE_PRAGMA(x) _Pragma(#x)
#if defined(_OPENMP) && !defined(__CUDA_ARCH__)
#define CASCADE_SIMD(...) CASCADE_PRAGMA(omp simd __VA_ARGS__)
#else
#define CASCADE_SIMD(...)
#endif

namespace cascade {

// Fixed-size vectors and matrices; Eigen's fixed-size types work in device code.
template <typename Real, int Dim>
using Vec = Eigen::Matrix<Real, Dim, 1>;
template <typename Real, int Dim>
using Mat = Eigen::Matrix<Real, Dim, Dim>;

// Component A of element j of an array of vectors (0 past the dimension), read through a 32-bit
// element index so that the host compiler turns the reads of a vectorised neighbour loop into
// gathers (base + 4·index).
template <int A, typename Real, int Dim>
CASCADE_HD inline Real gather_component(const Vec<Real, Dim>* array, std::uint32_t j) {
  if constexpr (A < Dim) return array->data()[std::uint32_t(Dim) * j + std::uint32_t(A)];
  else return Real(0);
}

// Component A of a vector, 0 past its dimension: a neighbour loop written once for 2D and 3D
// sums each component in a scalar of its own (OpenMP keeps scalar reductions in registers).
template <int A, typename Real, int Dim>
CASCADE_HD inline Real component(const Vec<Real, Dim>& v) {
  if constexpr (A < Dim) return v[A];
  else return Real(0);
}

// The bits of a non-negative float or double as an unsigned integer: for x, y >= 0 the integers
// order as the numbers do (IEEE 754), and a NaN compares above infinity. A neighbour loop takes
// the maximum of a non-negative quantity over these, since GCC vectorises an integer maximum
// but not a floating-point one that honours NaN.
CASCADE_HD inline std::uint32_t ordered_bits(float x) {
  std::uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
CASCADE_HD inline std::uint64_t ordered_bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
template <typename Real, typename Bits>
CASCADE_HD inline Real from_ordered_bits(Bits u) {
  static_assert(sizeof(Real) == sizeof(Bits), "bits and number differ in size");
  Real x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// Per-particle phase tag, as written to fields.h5 (docs/output.md).
enum class Phase : std::uint8_t { water = 0, soil = 1, boundary = 2 };

// Cell key of a particle that has left the domain along a non-periodic axis: it sorts after
// every real cell, belongs to no cell range and takes no further part in the computation.
constexpr std::uint32_t kOutsideKey = 0xffffffffu;

}  // namespace cascade
