#pragma once
// Implicit initial shapes (src/levelset/shapes.hpp compiles a scene's `shape` into a
// postfix program of these ops): every cell centre evaluates the program on a small stack.
// Positive inside (phase 1, NOTES.md erratum 4).
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"

namespace voigt {

enum class ShapeKind : int { Plane, Wave, Sphere, Box, Cylinder, Superquadric, Packing, Union, Intersection, Complement };

struct ShapeOp {
  ShapeKind kind = ShapeKind::Sphere;
  double a[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}; // parameters, per kind (src/levelset/shapes.cpp)
  int n = 0;                                     // union/intersection: operands; packing: first sphere
  int m = 0;                                     // packing: sphere count; cylinder: axis
};

constexpr int kShapeStack = 32;

using ShapeOps = Kokkos::View<ShapeOp*, MemSpace>;
using ShapeSpheres = Kokkos::View<double* [4], MemSpace>; // packing centres and radii

// Value of one primitive at x (positive inside).
KOKKOS_INLINE_FUNCTION double primitive(const ShapeOp& op, const ShapeSpheres& sp,
                                        const double x[3]) {
  const double* a = op.a;
  switch (op.kind) {
    case ShapeKind::Plane:
      return -((x[0] - a[0]) * a[3] + (x[1] - a[1]) * a[4] + (x[2] - a[2]) * a[5]);
    case ShapeKind::Wave: {
      double dn = 0, ds = 0;
      for (int c = 0; c < 3; ++c) dn += (x[c] - a[c]) * a[3 + c], ds += (x[c] - a[c]) * a[7 + c];
      return -(dn - a[6] * km::cos(a[10] * ds));
    }
    case ShapeKind::Sphere: {
      const double d0 = x[0] - a[0], d1 = x[1] - a[1], d2 = x[2] - a[2];
      return a[3] - km::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    }
    case ShapeKind::Box: { // exact signed distance to a box
      double out = 0, in = -1e300;
      for (int c = 0; c < 3; ++c) {
        const double q = km::fabs(x[c] - a[c]) - a[3 + c];
        if (q > 0) out += q * q;
        in = q > in ? q : in;
      }
      return -(km::sqrt(out) + (in < 0 ? in : 0));
    }
    case ShapeKind::Cylinder: { // capped cylinder: a 2-D box in (radial, axial)
      double r2 = 0;
      for (int c = 0; c < 3; ++c)
        if (c != op.m) r2 += (x[c] - a[c]) * (x[c] - a[c]);
      const double qr = km::sqrt(r2) - a[3], qa = km::fabs(x[op.m] - a[op.m]) - a[4];
      const double out = km::sqrt((qr > 0 ? qr * qr : 0) + (qa > 0 ? qa * qa : 0));
      const double in = qr > qa ? qr : qa;
      return -(out + (in < 0 ? in : 0));
    }
    case ShapeKind::Superquadric: {
      // Same zero set as 1 - sum|x_i/a_i|^p (Eq. 22, negated), written as a
      // p-norm so |grad| ~ 1 near the surface: Fast Marching starts from a
      // linear interpolation of the crossing, which a steep x^8 would spoil.
      double s = 0, amin = a[3];
      for (int c = 0; c < 3; ++c) {
        s += km::pow(km::fabs(x[c] - a[c]) / a[3 + c], a[6]);
        amin = a[3 + c] < amin ? a[3 + c] : amin;
      }
      return amin * (1 - km::pow(s, 1 / a[6]));
    }
    case ShapeKind::Packing: {
      double best = -1e300;
      for (int q = op.n; q < op.n + op.m; ++q) {
        const double d0 = x[0] - sp(q, 0), d1 = x[1] - sp(q, 1), d2 = x[2] - sp(q, 2);
        const double v = sp(q, 3) - km::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        best = v > best ? v : best;
      }
      return best;
    }
    default:
      return 0;
  }
}

// f = the program's value at every cell centre of the local array (owned + ghosts).
inline void evaluateShapeOps(const Grid& g, const ShapeOps& ops, const ShapeSpheres& sp, const Field& f) {
  const int nops = int(ops.extent(0)), ng = g.ng;
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  Kokkos::parallel_for(
      "evaluate_shape", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x[3] = {lo0 + (i - ng + c0 + 0.5) * h0, lo1 + (j - ng + c1 + 0.5) * h1,
                             lo2 + (k - ng + c2 + 0.5) * h2};
        double st[kShapeStack];
        int top = 0;
        for (int q = 0; q < nops; ++q) {
          const ShapeOp& op = ops(q);
          if (op.kind == ShapeKind::Union || op.kind == ShapeKind::Intersection) {
            double v = st[top - op.n];
            for (int r = top - op.n + 1; r < top; ++r)
              v = op.kind == ShapeKind::Union ? (st[r] > v ? st[r] : v) : (st[r] < v ? st[r] : v);
            top -= op.n;
            st[top++] = v;
          } else if (op.kind == ShapeKind::Complement) {
            st[top - 1] = -st[top - 1];
          } else {
            st[top++] = primitive(op, sp, x);
          }
        }
        f(i, j, k) = st[0];
      });
}

} // namespace voigt
