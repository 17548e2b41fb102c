// Kernel level (kernels/elastic.hpp): the Cayley half-step rotation for a spin
// about a general axis; the field-level objectivity tests (test_objectivity.cpp)
// only turn about z.
#include <gtest/gtest.h>

#include <cmath>

#include "elasticity/tensor_util.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {
const double kTau0[6] = {1, -1, 0.3, 0.5, 0.2, -0.1}; // xx yy zz xy yz zx (Pa)
} // namespace

// Kernel level, Cayley half steps for a spin about a general axis (the field
// test only turns about z): L with a symmetric part but mu = 0, so the update is
// two Cayley rotations by the spin w of W = (L - L^T)/2. Q must be orthogonal;
// after N steps tau = R(n, N 4 atan(|w| dt / 4)) tau0 R^T (Rodrigues, axis
// n = w / |w|), and |tau|_F = |tau0|_F; the explicit map's norm grows by
// (1 + (|w| dt)^2)^N on the part that turns at twice the rate.
TEST(CayleyKernel, GeneralAxis) {
  const double L[3][3] = {{0.3, -1.1, 0.7}, {0.9, -0.2, -0.4}, {-0.5, 1.3, -0.1}};
  double W[3][3];
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) W[p][q] = 0.5 * (L[p][q] - L[q][p]);
  const double w[3] = {W[2][1], W[0][2], W[1][0]}; // W v = w x v
  const double wn = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const double dt = 0.01;
  double Q[3][3];
  elastic::cayleyTransform(W, 0.25 * dt, Q);
  double orth = 0;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      double v = 0;
      for (int r = 0; r < 3; ++r) v += Q[p][r] * Q[q][r];
      orth = std::max(orth, std::abs(v - (p == q ? 1.0 : 0.0)));
    }
  test::report("kernel_cayley_Q_orthogonality_error", orth);
  EXPECT_LT(orth, 1e-15);
  const int steps = 2000;
  double c[6], e[6];
  for (int k = 0; k < 6; ++k) c[k] = e[k] = kTau0[k];
  for (int s = 0; s < steps; ++s) {
    elastic::bensonUpdate(c, L, 0.0, dt, 0.5, elastic::Rotation::Cayley);
    elastic::bensonUpdate(e, L, 0.0, dt, 0.5, elastic::Rotation::Explicit);
  }
  // Rodrigues rotation by the discrete angle.
  const double phi = steps * 4 * std::atan(wn * dt / 4);
  const double n[3] = {w[0] / wn, w[1] / wn, w[2] / wn};
  const double K[3][3] = {{0, -n[2], n[1]}, {n[2], 0, -n[0]}, {-n[1], n[0], 0}};
  double R[3][3];
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      double K2 = 0;
      for (int r = 0; r < 3; ++r) K2 += K[p][r] * K[r][q];
      R[p][q] = (p == q ? 1.0 : 0.0) + std::sin(phi) * K[p][q] + (1 - std::cos(phi)) * K2;
    }
  double closed[6];
  test::rotateSym(R, kTau0, closed);
  test::report("kernel_cayley_general_axis_angle_rad", phi);
  test::report("kernel_cayley_general_axis_error_vs_closed_form", test::maxDiff(c, closed));
  test::report("kernel_cayley_general_axis_norm_relative_deviation", test::frob(c) / test::frob(kTau0) - 1);
  test::report("kernel_explicit_general_axis_norm_relative_deviation", test::frob(e) / test::frob(kTau0) - 1);
  EXPECT_LT(test::maxDiff(c, closed), 1e-11);
  EXPECT_LT(std::abs(test::frob(c) / test::frob(kTau0) - 1), 1e-12);
  EXPECT_GT(test::frob(e) / test::frob(kTau0) - 1, 0.1 * (std::pow(1 + wn * wn * dt * dt / 4, steps) - 1));
}
