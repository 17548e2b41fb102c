#pragma once
// Host helpers for the elasticity tests: symmetric tensors as six components
// (xx yy zz xy yz zx), rotated, compared and measured.
#include <algorithm>
#include <cmath>

#include "kernels/elastic.hpp"

namespace voigt::test {

// out = R t R^T.
inline void rotateSym(const double R[3][3], const double t[6], double out[6]) {
  double T[3][3], M[3][3];
  elastic::unpackSym(t, T);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double v = 0;
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) v += R[a][p] * T[p][q] * R[b][q];
      M[a][b] = v;
    }
  out[0] = M[0][0]; out[1] = M[1][1]; out[2] = M[2][2];
  out[3] = M[0][1]; out[4] = M[1][2]; out[5] = M[2][0];
}

// Frobenius norm of a symmetric tensor given by its six components.
inline double frob(const double t[6]) {
  return std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2] + 2 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
}

inline double maxDiff(const double a[6], const double b[6]) {
  double m = 0;
  for (int c = 0; c < 6; ++c) m = std::max(m, std::abs(a[c] - b[c]));
  return m;
}

} // namespace voigt::test
