// Objectivity of the Jaumann update (Eq. 13/16 with NOTES.md errata 1-3); the
// scene plumbing is in test_elasticity_scene.cpp.
//
// A pre-stressed disk (cylinder along z) off the rotation centre is carried by
// a prescribed rigid rotation (prescribed_flow + level_set + elasticity) through
// 90, 360 and 720 degrees. In a rigid rotation D = 0 and the stress of a
// material element must be R tau0 R^T, R the rotation about z by theta =
// omega t. Measured on the cells at least 4 cells inside the exactly rotated
// disk, all six components.
//
// Transport and rotation separate exactly here: the velocity gradient is the
// same in every cell (the discrete gradient of a linear field is exact), so the
// Jaumann map acts identically everywhere, and the transport (linear, and the
// MinMod limiter is homogeneous: minmod(c a, c b) = c minmod(a, b)) acts the
// same way on every component. The field therefore stays s(x) M tau0, with
// s(x) the transported indicator of the initial disk (psi > 0) and M the
// Benson map; zz is not touched by a rotation about z, so s = zz / zz0. The
// MUSCL smearing of the stress jump at the interface reaches 4-6 cells in after
// a turn (s down to ~0.9 at r = R - 4h): it is reported (raw error, s range),
// and the Jaumann update is judged on tau / s.
//
// Both half-step rotations of kernels/elastic.hpp are tested (scene key
// elasticity.rotation).
//
// rotation: explicit (erratum 2 literally). Expected error (derived, not
// tuned): for a constant spin the Benson half-step multiplies the complex
// amplitude of the in-plane deviatoric part, (xx - yy)/2 + i xy, by
// (1 + i omega dt)^2 per step (exact: exp(2 i omega dt)), and (zx, yz) by
// (1 + i omega dt / 2)^2 (exact: exp(i omega dt)). The phase is right to
// O((omega dt)^3) per step, the modulus grows by 1 + (omega dt)^2 and
// 1 + (omega dt)^2 / 4: after N steps the amplitude is too large by
// prod (1 + (omega dt_n)^2) - 1 ~ theta omega dt, first order in dt. The test
// (a) replays that discrete map on the host with the simulation's dt sequence
//     and requires tau / s in the interior to match it to round-off (1e-9: the
//     field code is exactly the scheme), and
// (b) requires |tau / s - R tau0 R^T| <= 1.2 x that predicted amplitude error
//     (20% margin for the phase error and the clipped last step) and reports
//     the error; halving dt halves it (first order).
// The paper's W = L - L^T (spin scale 1 instead of 1/2) is replayed with the
// same map: it turns the stress through 2 theta, and at 90 degrees misses
// R tau0 R^T by O(|tau0|) (a 180-degree tensor rotation is the identity, so at
// 360 degrees both agree: the 90-degree case is the sharp one).
//
// rotation: cayley (the default). Each half step is tau -> Q tau Q^T with
// Q = (I - (dt/4) W)^{-1} (I + (dt/4) W). For W the spin of a rotation at rate
// omega about z, Q is exactly the rotation about z by 2 atan(omega dt / 4)
// (Cayley transform of the angle omega dt / 2: tan(phi / 2) = omega dt / 4), so
// after the steps dt_n the discrete map is exactly R(theta_d) tau0 R(theta_d)^T,
//   theta_d = sum_n 4 atan(omega dt_n / 4)
//           = theta - sum_n (omega dt_n)^3 / 48 + O(dt^5),
// with no amplitude error at all. The tensor's in-plane part turns at twice the
// angle, so |tau / s - R tau0 R^T| = |R(theta_d) tau0 R(theta_d)^T - R tau0 R^T|
// ~ 2 |theta - theta_d| |tau0| ~ theta (omega dt)^2 / 24 |tau0|: second order.
// The test requires, at 90, 360 and 720 degrees (cfl 0.5),
// (a) the Frobenius norm |tau / s| = |tau0| to round-off (1e-9 relative; the
//     explicit form is 4.7% high after a turn at this dt),
// (b) tau / s = the host replay of bensonUpdate and = R(theta_d) tau0
//     R(theta_d)^T, both to 1e-9 (the closed form is derived, not replayed),
// (c) |tau / s - R tau0 R^T| = |R(theta_d) tau0 R(theta_d)^T - R tau0 R^T| to
//     1e-9, and the observed order between cfl 0.5 and 0.25 (90 degrees) > 1.8.
// (the cfl 0.5 run leaves the key out: it is the scene default.)
// test_cayley_kernel.cpp checks the Cayley map for a spin about a general axis.
// Measured (64 cells; DISABLED_SweepBothSchemes prints the whole table):
//   error vs R tau0 R^T     90 deg    360 deg   720 deg
//   explicit, cfl 0.5       1.24e-2   5.04e-2   1.03e-1   (|tau| +1.2%, +4.7%, +9.7%)
//   explicit, cfl 0.25      6.16e-3   2.49e-2   5.04e-2   (order 1.01, 1.02, 1.04)
//   cayley,   cfl 0.5       3.99e-6   1.60e-5   3.19e-5   (|tau| to 9e-14, 3e-13, 7e-13)
//   cayley,   cfl 0.25      9.98e-7   3.99e-6   7.99e-6   (order 2.00 at each angle)
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "effects/elasticity/elasticity.hpp"
#include "kernels/elastic.hpp"
#include "scene/reader.hpp"
#include "elasticity/rotating_disk.hpp"
#include "elasticity/tensor_util.hpp"
#include "support/flow.hpp"

using namespace voigt;
using test::frob;
using test::maxDiff;

namespace {

using namespace rotating_disk;

// rotation "" leaves the key out (the scene default).
// fluid_side: integrate (the paper's), so that the whole field is the rotated
// uniform prestress and the interior check below is exact; with extend (the
// default) the fluid side is an extrapolation that is uniform only to ~1e-9
// after 800 steps, and transport carries that into the interior (measured
// 1.4e-9 against the 1e-9 bound).
std::string rotationScene(int n, double cfl, const std::string& rotation) {
  return rotating_disk::scene(n, cfl, rotation, "integrate");
}

// R tau R^T for R the rotation about z by theta.
void rotateZ(const double t[6], double theta, double out[6]) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double R[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
  test::rotateSym(R, t, out);
}

// The Benson map replayed for a rigid rotation (L exact, D = 0) over the dt sequence.
void replay(const std::vector<double>& dts, double spinScale, elastic::Rotation rot, double out[6]) {
  const double L[3][3] = {{0, -kOmega, 0}, {kOmega, 0, 0}, {0, 0, 0}};
  for (int c = 0; c < 6; ++c) out[c] = kTau0[c];
  for (double dt : dts) elastic::bensonUpdate(out, L, 1.0, dt, spinScale, rot);
}

// The Cayley scheme's exact discrete rotation angle (header): each half step
// turns by 2 atan(omega dt / 4).
double cayleyAngle(const std::vector<double>& dts, double omega = kOmega) {
  double a = 0;
  for (double dt : dts) a += 4 * std::atan(omega * dt / 4);
  return a;
}

// Predicted amplitude error of the scheme (header comment): in-plane deviatoric
// amplitude times (prod(1 + (w dt)^2) - 1), out-of-plane times (prod(1 + (w dt)^2/4) - 1).
double predictedError(const std::vector<double>& dts) {
  double g2 = 1, g1 = 1;
  for (double dt : dts) {
    g2 *= 1 + std::pow(kOmega * dt, 2);
    g1 *= 1 + std::pow(kOmega * dt, 2) / 4;
  }
  const double a2 = std::hypot(0.5 * (kTau0[0] - kTau0[1]), kTau0[3]);
  const double a1 = std::hypot(kTau0[4], kTau0[5]);
  return a2 * (g2 - 1) + a1 * (g1 - 1);
}

struct Measured {
  double errRaw = 0;               // |tau - R tau0 R^T|, transport smearing included
  double errExact = 0, errReplay = 0; // after dividing by the transported indicator
  double errClosed = 0;            // vs a closed-form discrete solution (Cayley: R(theta_d))
  double normDev = 0;              // max | |tau / s|_F / |tau0|_F - 1 |
  double sMin = 1e300, sMax = -1e300;
  long long cells = 0;
};

// Max over interior cells of |tau - expected| (expected uniform), all ranks.
Measured measure(const Simulation& sim, double theta, const double replayed[6], const double closed[6]) {
  const State& st = sim.state();
  const Grid& g = st.grid;
  const SymTensorField t = solidStressField(st.fields);
  decltype(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.c[0])) h[6];
  for (int c = 0; c < 6; ++c) h[c] = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.c[c]);
  double exact[6];
  rotateZ(kTau0, theta, exact);
  // Disk centre rotated about (kCx, kCy).
  const double cx = kCx + std::cos(theta) * (kDx - kCx) - std::sin(theta) * (kDy - kCy);
  const double cy = kCy + std::sin(theta) * (kDx - kCx) + std::cos(theta) * (kDy - kCy);
  const double rIn = kR - 4 * g.h[0];
  Measured m;
  const Range3 r = cellRange(g);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        const double x = g.lo[0] + (g.global(0, i) + 0.5) * g.h[0];
        const double y = g.lo[1] + (g.global(1, j) + 0.5) * g.h[1];
        if (std::hypot(x - cx, y - cy) > rIn) continue;
        double v[6];
        for (int c = 0; c < 6; ++c) v[c] = h[c](i, j, k);
        m.errRaw = std::max(m.errRaw, maxDiff(v, exact));
        // Normalise by the transported indicator s = zz / zz0 (see the header).
        const double sc = v[2] / kTau0[2];
        m.sMin = std::min(m.sMin, sc);
        m.sMax = std::max(m.sMax, sc);
        for (int c = 0; c < 6; ++c) v[c] /= sc;
        m.errExact = std::max(m.errExact, maxDiff(v, exact));
        m.errReplay = std::max(m.errReplay, maxDiff(v, replayed));
        m.errClosed = std::max(m.errClosed, maxDiff(v, closed));
        m.normDev = std::max(m.normDev, std::abs(frob(v) / frob(kTau0) - 1));
        ++m.cells;
      }
  MPI_Allreduce(MPI_IN_PLACE, &m.errRaw, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.sMax, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.sMin, 1, MPI_DOUBLE, MPI_MIN, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.errExact, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.errReplay, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.errClosed, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.normDev, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m.cells, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
  return m;
}

// The measurements both rotation tests report, under key_*.
void reportMeasured(const std::string& key, const Measured& m, double pred) {
  test::report(key + "_raw_error_vs_exact", m.errRaw);
  test::report(key + "_indicator_min", m.sMin);
  test::report(key + "_indicator_max", m.sMax);
  test::report(key + "_error_vs_exact", m.errExact);
  test::report(key + "_predicted_scheme_error", pred);
  test::report(key + "_error_vs_replayed_scheme", m.errReplay);
  test::report(key + "_norm_relative_deviation", m.normDev);
}

// The steps' sizes, recorded as the engine takes them (StepEngine::advanceTo lands on t).
StepEngine::Each recordDt(std::vector<double>& dts) {
  return [&dts](const State& st) { dts.push_back(st.dt); };
}

// rotation: explicit (erratum 2 literally): first order, amplitude grows.
void rotate(int n, double cfl, const std::string& tag, bool checkPaper, std::vector<double> degrees) {
  Simulation sim(test::scene(rotationScene(n, cfl, "explicit")), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  auto* el = dynamic_cast<Elasticity*>(sim.effect("elasticity"));
  ASSERT_NE(el, nullptr);
  ASSERT_EQ(el->rotation(), elastic::Rotation::Explicit);
  std::vector<double> dts;
  for (double deg : degrees) {
    const double theta = deg * M_PI / 180;
    sim.advanceTo(theta / kOmega, recordDt(dts));
    double rep[6];
    replay(dts, 0.5, elastic::Rotation::Explicit, rep);
    const Measured m = measure(sim, theta, rep, rep);
    const double pred = predictedError(dts);
    const std::string key = tag + "_" + std::to_string(int(deg)) + "deg";
    reportMeasured(key, m, pred);
    test::report(key + "_steps", double(dts.size()));
    test::report(key + "_interior_cells", double(m.cells));
    ASSERT_GT(m.cells, 100);
    EXPECT_LT(m.errReplay, 1e-9) << "interior cells must follow the Benson map exactly";
    EXPECT_LT(m.errExact, 1.2 * pred) << "error beyond the half-step scheme's amplitude error";
    if (checkPaper) {
      double paper[6], exact[6];
      replay(dts, 1.0, elastic::Rotation::Explicit, paper);
      rotateZ(kTau0, theta, exact);
      const double e = maxDiff(paper, exact);
      test::report(key + "_paper_W_error_vs_exact", e);
      if (deg == 90.0) EXPECT_GT(e, 10 * 1.2 * pred) << "the paper's W must fail the same tolerance";
    }
  }
}

// rotation: cayley (default): norm kept to round-off, exact discrete angle,
// second order. Returns |tau / s - R tau0 R^T| at each angle.
std::vector<double> rotateCayley(int n, double cfl, const std::string& tag, std::vector<double> degrees,
                                 bool sceneDefault = false) {
  std::vector<double> errs;
  Simulation sim(test::scene(rotationScene(n, cfl, sceneDefault ? "" : "cayley")), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  auto* el = dynamic_cast<Elasticity*>(sim.effect("elasticity"));
  EXPECT_NE(el, nullptr);
  if (!el) return errs;
  EXPECT_EQ(el->rotation(), elastic::Rotation::Cayley);
  std::vector<double> dts;
  for (double deg : degrees) {
    const double theta = deg * M_PI / 180;
    sim.advanceTo(theta / kOmega, recordDt(dts));
    double rep[6], closed[6], exact[6];
    replay(dts, 0.5, elastic::Rotation::Cayley, rep);
    const double thetaD = cayleyAngle(dts);
    rotateZ(kTau0, thetaD, closed);
    rotateZ(kTau0, theta, exact);
    const Measured m = measure(sim, theta, rep, closed);
    const double pred = maxDiff(closed, exact); // the scheme's exact error (header)
    double sumCube = 0;
    for (double dt : dts) sumCube += std::pow(kOmega * dt, 3);
    const std::string key = tag + "_" + std::to_string(int(deg)) + "deg";
    reportMeasured(key, m, pred);
    test::report(key + "_discrete_angle_lag_rad", theta - thetaD);
    test::report(key + "_discrete_angle_lag_leading_term_rad", sumCube / 48);
    test::report(key + "_error_vs_closed_form_discrete_rotation", m.errClosed);
    test::report(key + "_steps", double(dts.size()));
    test::report(key + "_interior_cells", double(m.cells));
    EXPECT_GT(m.cells, 100);
    EXPECT_LT(m.normDev, 1e-9) << "a rigid rotation must keep |tau| (Cayley Q is orthogonal)";
    EXPECT_LT(m.errReplay, 1e-9) << "interior cells must follow the Cayley-Benson map exactly";
    EXPECT_LT(m.errClosed, 1e-9) << "the discrete map must be the rotation by theta_d";
    EXPECT_LT(std::abs(m.errExact - pred), 1e-9) << "error must be the discrete angle lag's, nothing else";
    EXPECT_NEAR(theta - thetaD, sumCube / 48, 1e-3 * sumCube / 48); // the leading term (O(dt^5) rest)
    errs.push_back(m.errExact);
  }
  return errs;
}

} // namespace

TEST(Objectivity, RigidRotationOfPrestressedDisk) { rotate(64, 0.5, "n64_cfl0.5", true, {90, 360}); }

// Half the time step: the scheme's amplitude error halves (first order; 90
// degrees only, to keep the 2-rank run short).
TEST(Objectivity, RigidRotationHalfStep) { rotate(64, 0.25, "n64_cfl0.25", false, {90}); }

// The default rotation (Cayley): |tau| kept to round-off through two turns, the
// exact discrete angle, and second order between cfl 0.5 and 0.25 at 90 degrees.
TEST(Objectivity, CayleyRigidRotationKeepsNormSecondOrder) {
  const std::vector<double> e1 = rotateCayley(64, 0.5, "cayley_n64_cfl0.5", {90, 360, 720}, true);
  const std::vector<double> e2 = rotateCayley(64, 0.25, "cayley_n64_cfl0.25", {90});
  ASSERT_EQ(e1.size(), 3u);
  ASSERT_EQ(e2.size(), 1u);
  const double order = std::log2(e1[0] / e2[0]);
  test::report("cayley_n64_90deg_observed_order_cfl0.5_vs_0.25", order);
  EXPECT_GT(order, 1.8);
  EXPECT_LT(order, 2.2);
}

// The full table (both schemes, cfl 0.5 and 0.25, 90 / 360 / 720 degrees),
// about a minute on one rank; not in the suite. Run with
//   test_objectivity --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
TEST(Objectivity, DISABLED_SweepBothSchemes) {
  for (double cfl : {0.5, 0.25}) {
    const std::string c = cfl == 0.5 ? "cfl0.5" : "cfl0.25";
    rotate(64, cfl, "sweep_explicit_n64_" + c, false, {90, 360, 720});
    rotateCayley(64, cfl, "sweep_cayley_n64_" + c, {90, 360, 720});
  }
}

// Kernel level: the spin of a rotation, standard vs the paper's W, one turn in
// many small steps: the standard W gives R tau0 R^T, the paper's gives R(2 theta).
// (Explicit half steps: predictedError is that map's amplitude error.)
TEST(Objectivity, PaperSpinTurnsTwiceAsFast) {
  const int steps = 20000;
  const double theta = 0.5 * M_PI, dt = theta / kOmega / steps;
  std::vector<double> dts(steps, dt);
  double std_[6], paper[6], exact1[6], exact2[6];
  replay(dts, 0.5, elastic::Rotation::Explicit, std_);
  replay(dts, 1.0, elastic::Rotation::Explicit, paper);
  rotateZ(kTau0, theta, exact1);
  rotateZ(kTau0, 2 * theta, exact2);
  const double pred = predictedError(dts); // ~ theta omega dt |tau0| ~ 1.2e-4
  test::report("kernel_standard_W_error_90deg", maxDiff(std_, exact1));
  test::report("kernel_paper_W_error_vs_2theta", maxDiff(paper, exact2));
  test::report("kernel_paper_W_error_vs_theta", maxDiff(paper, exact1));
  EXPECT_LT(maxDiff(std_, exact1), 1.2 * pred);
  EXPECT_LT(maxDiff(paper, exact2), 4 * 1.2 * pred); // spin twice as large: 4x the amplitude error
  EXPECT_GT(maxDiff(paper, exact1), 1.0);
  // The same with Cayley half steps (2000 steps: the O(dt^2) lag is well above
  // round-off): the paper's W still turns through 2 theta. Both follow the
  // closed-form discrete angle (header; the paper's spin is 2 omega) to
  // round-off; vs the exact angle they lag by O(dt^2).
  const std::vector<double> dts2(2000, theta / kOmega / 2000);
  double cstd[6], cpaper[6], dstd[6], dpaper[6];
  replay(dts2, 0.5, elastic::Rotation::Cayley, cstd);
  replay(dts2, 1.0, elastic::Rotation::Cayley, cpaper);
  rotateZ(kTau0, cayleyAngle(dts2), dstd);
  rotateZ(kTau0, cayleyAngle(dts2, 2 * kOmega), dpaper);
  test::report("kernel_cayley_2000_steps_standard_W_error_90deg", maxDiff(cstd, exact1));
  test::report("kernel_cayley_2000_steps_standard_W_error_vs_discrete_angle", maxDiff(cstd, dstd));
  test::report("kernel_cayley_2000_steps_paper_W_error_vs_2theta", maxDiff(cpaper, exact2));
  test::report("kernel_cayley_2000_steps_paper_W_error_vs_discrete_angle", maxDiff(cpaper, dpaper));
  test::report("kernel_explicit_2000_steps_predicted_error", predictedError(dts2));
  EXPECT_LT(maxDiff(cstd, dstd), 1e-11);
  EXPECT_LT(maxDiff(cpaper, dpaper), 1e-11);
  EXPECT_LT(maxDiff(cstd, exact1), 1e-3 * predictedError(dts2)); // far below the explicit map's error
  EXPECT_GT(maxDiff(cpaper, exact1), 1.0);
}
