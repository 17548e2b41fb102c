// Volume of a sphere inside an axis-aligned box, for voidage measurements.
//
// V = integral over y of A(y), where A is the area of the disc of radius
// rho(y) = sqrt(r^2 - (y - c_y)^2) inside the rectangle [x0,x1] x [z0,z1]; A is computed in
// closed form (disc-quadrant areas). A(y) is analytic between the heights where the disc
// becomes tangent to a rectangle edge or passes a corner; the integral is split there and each
// piece done by 16-point Gauss-Legendre. At a tangency A - A_smooth ~ (y - y*)^{3/2}, so the
// relative error per sphere is below 1e-6 (test_pack checks against exact cases); a sphere
// whose disc stays horizontally inside the rectangle uses the exact spherical-slab formula.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace pack {

struct Box {
  double lo[3], hi[3];
};

namespace detail {

constexpr double kPiG = 3.14159265358979323846;

// Integral of sqrt(rho^2 - x^2) from 0 to x (|x| <= rho).
inline double halfChordIntegral(double x, double rho) {
  x = std::clamp(x, -rho, rho);
  const double h = std::sqrt(std::max(0.0, rho * rho - x * x));
  return 0.5 * (x * h + rho * rho * std::asin(x / rho));
}

// Area of the disc of radius rho centred at the origin within {X <= a, Z <= b}.
inline double quadrantArea(double a, double b, double rho) {
  if (rho <= 0 || a <= -rho || b <= -rho) return 0;
  const double A = std::min(a, rho);
  auto full = [&](double x1, double x2) { // integral of the whole chord 2h over [x1, x2] ∩ [-rho, A]
    x2 = std::min(x2, A);
    return x2 > x1 ? 2 * (halfChordIntegral(x2, rho) - halfChordIntegral(x1, rho)) : 0.0;
  };
  if (b >= rho) return full(-rho, rho);
  const double c = std::sqrt(rho * rho - b * b);
  double s = 0;
  // |X| <= c: chord clipped at Z = b, length b + h.
  {
    const double x1 = -c, x2 = std::min(c, A);
    if (x2 > x1) s += b * (x2 - x1) + halfChordIntegral(x2, rho) - halfChordIntegral(x1, rho);
  }
  if (b > 0) s += full(-rho, -c) + full(c, rho); // |X| > c: the whole chord lies below Z = b
  return s;
}

// Area of the disc (centre (cx, cz), radius rho) within [x0,x1] x [z0,z1].
inline double discRectArea(double cx, double cz, double rho, double x0, double x1, double z0, double z1) {
  if (rho <= 0 || x1 <= x0 || z1 <= z0) return 0;
  const double a0 = x0 - cx, a1 = x1 - cx, b0 = z0 - cz, b1 = z1 - cz;
  if (a0 <= -rho && a1 >= rho && b0 <= -rho && b1 >= rho) return kPiG * rho * rho;
  return quadrantArea(a1, b1, rho) - quadrantArea(a0, b1, rho) - quadrantArea(a1, b0, rho) +
         quadrantArea(a0, b0, rho);
}

// Exact volume of the sphere (centre c_y, radius r) between heights ya < yb, whole discs.
inline double slabVolume(double cy, double r, double ya, double yb) {
  const double ta = std::clamp(ya - cy, -r, r), tb = std::clamp(yb - cy, -r, r);
  if (tb <= ta) return 0;
  auto F = [&](double t) { return r * r * t - t * t * t / 3; };
  return kPiG * (F(tb) - F(ta));
}

} // namespace detail

// Volume of the sphere (c, r) inside the box.
inline double sphereBoxVolume(const double c[3], double r, const Box& b) {
  const double ya = std::max(b.lo[1], c[1] - r), yb = std::min(b.hi[1], c[1] + r);
  if (yb <= ya) return 0;
  if (c[0] - r >= b.lo[0] && c[0] + r <= b.hi[0] && c[2] - r >= b.lo[2] && c[2] + r <= b.hi[2])
    return detail::slabVolume(c[1], r, ya, yb);
  if (c[0] + r <= b.lo[0] || c[0] - r >= b.hi[0] || c[2] + r <= b.lo[2] || c[2] - r >= b.hi[2]) return 0;
  // Break points: heights where the disc radius equals the distance to an edge or corner.
  std::vector<double> br{ya, yb};
  const double ex[2] = {c[0] - b.lo[0], b.hi[0] - c[0]}, ez[2] = {c[2] - b.lo[2], b.hi[2] - c[2]};
  auto addDist = [&](double d) {
    if (d < 0) d = -d;
    if (d < r) {
      const double s = std::sqrt(r * r - d * d);
      for (double y : {c[1] - s, c[1] + s})
        if (y > ya && y < yb) br.push_back(y);
    }
  };
  for (double d : ex) addDist(d);
  for (double d : ez) addDist(d);
  for (double dx : ex)
    for (double dz : ez) addDist(std::sqrt(dx * dx + dz * dz));
  std::sort(br.begin(), br.end());
  // 16-point Gauss-Legendre nodes and weights on [-1, 1] (positive half).
  static const double gx[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                               0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  static const double gw[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                               0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  double v = 0;
  for (std::size_t k = 0; k + 1 < br.size(); ++k) {
    const double y0 = br[k], y1 = br[k + 1];
    if (y1 <= y0) continue;
    const double m = 0.5 * (y0 + y1), h = 0.5 * (y1 - y0);
    for (int q = 0; q < 8; ++q)
      for (double s : {-1.0, 1.0}) {
        const double y = m + s * h * gx[q], t = y - c[1];
        const double rho = std::sqrt(std::max(0.0, r * r - t * t));
        v += h * gw[q] * detail::discRectArea(c[0], c[2], rho, b.lo[0], b.hi[0], b.lo[2], b.hi[2]);
      }
  }
  return v;
}

} // namespace pack
