#pragma once
// The pre-stressed disk carried by a prescribed rigid rotation (test_objectivity.cpp,
// test_stress_jump.cpp): a cylinder along z off the rotation centre, uniform
// initial stress kTau0, on [0, 1]^2 x 2 cells (periodic z).
#include <cstdio>
#include <string>

namespace rotating_disk {

constexpr double kOmega = 2 * 3.14159265358979323846; // one turn per unit time
constexpr double kCx = 0.5, kCy = 0.5;                  // rotation centre
constexpr double kDx = 0.5, kDy = 0.7, kR = 0.2;        // disk centre and radius at t = 0
const double kTau0[6] = {1, -1, 0.3, 0.5, 0.2, -0.1};  // xx yy zz xy yz zx (Pa)

// rotation / limiter "" leave the key out (the scene default); fluid_side is
// always written; the smoothing is the default's 2 cells, written out.
inline std::string scene(int n, double cfl, const std::string& rotation, const std::string& fluidSide,
                         const std::string& limiter = "") {
  const std::string rot = rotation.empty() ? "" : "rotation: " + rotation + ",";
  const std::string adv = limiter.empty() ? "" : "advection: {limiter: " + limiter + "}\n";
  char buf[2048];
  std::snprintf(buf, sizeof buf,
                "name: objectivity\n"
                "domain: {lo: [0, 0, 0], hi: [1, 1, %.17g], cells: [%d, %d, 2], ranks: [0, 0, 1]}\n"
                "boundaries: {default: {type: slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
                "time: {end: 1, cfl: %.17g}\n"
                "materials: {disk: {density: 1, shear_modulus: 1.0e-3}, air: {density: 1}}\n"
                "fluid: air\n"
                "effects: [prescribed_flow, level_set, elasticity]\n"
                "prescribed_flow: {type: rotation, center: [%g, %g, 0], omega: [0, 0, %.17g]}\n"
                "level_set: {phase: disk, fast_marching: false, smoothing: 2,\n"
                "            shape: {type: cylinder, center: [%g, %g, 0], radius: %g, axis: z}}\n"
                "elasticity: {fluid_side: %s, %s\n"
                "             initial_stress: {xx: %g, yy: %g, zz: %g, xy: %g, yz: %g, zx: %g}}\n"
                "%s"
                "output: {enabled: false}\n",
                2.0 / n, n, n, cfl, kCx, kCy, kOmega, kDx, kDy, kR, fluidSide.c_str(), rot.c_str(), kTau0[0],
                kTau0[1], kTau0[2], kTau0[3], kTau0[4], kTau0[5], adv.c_str());
  return buf;
}

} // namespace rotating_disk
