// Determinant and inverse of 2×2, 3×3 and 4×4 matrices by cofactors, callable in device code
// (Eigen 3.4's determinant() and inverse() are host-only for these sizes under nvcc).
#pragma once

#include "server/core/types.h"

namespace cascade {

// Position of element (a, b) of a symmetric 3×3 matrix stored as its six sums xx, xy, xz, yy, yz,
// zz (the neighbour loops' moments, which are symmetric since ∇_i W_ij = F x_ij).
CASCADE_HD constexpr int symmetric_index(int a, int b) {
  const int low = a < b ? a : b, high = a < b ? b : a;
  return low == 0 ? high : low == 1 ? 2 + high : 5;
}

template <typename Real>
CASCADE_HD inline Real determinant(const Eigen::Matrix<Real, 2, 2>& m) {
  return m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
}

template <typename Real>
CASCADE_HD inline Real determinant(const Eigen::Matrix<Real, 3, 3>& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

// Minor of a 4×4 matrix without row r and column c.
template <typename Real>
CASCADE_HD inline Real minor4(const Eigen::Matrix<Real, 4, 4>& m, int r, int c) {
  Eigen::Matrix<Real, 3, 3> s;
  for (int i = 0, si = 0; i < 4; ++i) {
    if (i == r) continue;
    for (int j = 0, sj = 0; j < 4; ++j) {
      if (j == c) continue;
      s(si, sj++) = m(i, j);
    }
    ++si;
  }
  return determinant(s);
}

template <typename Real>
CASCADE_HD inline Real determinant(const Eigen::Matrix<Real, 4, 4>& m) {
  Real det = 0;
  for (int c = 0; c < 4; ++c) det += ((c % 2) ? -m(0, c) : m(0, c)) * minor4(m, 0, c);
  return det;
}

// Inverse from the adjugate; the caller checks the determinant first.
template <typename Real>
CASCADE_HD inline Eigen::Matrix<Real, 2, 2> inverse(const Eigen::Matrix<Real, 2, 2>& m, Real det) {
  Eigen::Matrix<Real, 2, 2> inv;
  inv << m(1, 1), -m(0, 1), -m(1, 0), m(0, 0);
  return inv / det;
}

template <typename Real>
CASCADE_HD inline Eigen::Matrix<Real, 3, 3> inverse(const Eigen::Matrix<Real, 3, 3>& m, Real det) {
  Eigen::Matrix<Real, 3, 3> inv;
  inv(0, 0) = m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1);
  inv(0, 1) = m(0, 2) * m(2, 1) - m(0, 1) * m(2, 2);
  inv(0, 2) = m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1);
  inv(1, 0) = m(1, 2) * m(2, 0) - m(1, 0) * m(2, 2);
  inv(1, 1) = m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0);
  inv(1, 2) = m(0, 2) * m(1, 0) - m(0, 0) * m(1, 2);
  inv(2, 0) = m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0);
  inv(2, 1) = m(0, 1) * m(2, 0) - m(0, 0) * m(2, 1);
  inv(2, 2) = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  return inv / det;
}

template <typename Real>
CASCADE_HD inline Eigen::Matrix<Real, 4, 4> inverse(const Eigen::Matrix<Real, 4, 4>& m, Real det) {
  Eigen::Matrix<Real, 4, 4> inv;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const Real cofactor = ((r + c) % 2 ? -Real(1) : Real(1)) * minor4(m, r, c);
      inv(c, r) = cofactor / det;  // adjugate is the transposed cofactor matrix
    }
  return inv;
}

}  // namespace cascade
