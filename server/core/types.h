// Small types shared by host and device code: the host/device marker, vectors and phases.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#if defined(__CUDACC__)
#define CASCADE_HD __host__ __device__
#else
#define CASCADE_HD
#endif

namespace cascade {

// Fixed-size vectors and matrices; Eigen's fixed-size types work in device code.
template <typename Real, int Dim>
using Vec = Eigen::Matrix<Real, Dim, 1>;
template <typename Real, int Dim>
using Mat = Eigen::Matrix<Real, Dim, Dim>;

// Per-particle phase tag, as written to fields.h5 (docs/output.md).
enum class Phase : std::uint8_t { water = 0, soil = 1, boundary = 2 };

// Cell key of a particle that has left the domain along a non-periodic axis: it sorts after
// every real cell, belongs to no cell range and takes no further part in the computation.
constexpr std::uint32_t kOutsideKey = 0xffffffffu;

}  // namespace cascade
