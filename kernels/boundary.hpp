#pragma once
// Boundary kernels (src/core/boundary.cpp decides which faces, ranges and values):
// marking prescribed node components, obstacle masks, re-imposing prescribed values,
// and the ghost layers' reflections about a wall.
#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

// mask |= full on the nodes of r; val's components in `full` set to (v0, v1, v2).
inline void markNodes(const IntField& mask, const VecField& val, Range3 r, int full, double v0, double v1,
                      double v2) {
  for_each3("mark_face", r, KOKKOS_LAMBDA(int i, int j, int k) {
    mask(i, j, k) |= full;
    if (full & 1) val.c[0](i, j, k) = v0;
    if (full & 2) val.c[1](i, j, k) = v1;
    if (full & 4) val.c[2](i, j, k) = v2;
  });
}

// An obstacle as the kernel sees it: kind 0 sphere, 1 cylinder (about `axis`), 2 box
// [lo, hi]; its nodes move with velocity v.
struct ObstacleShape {
  int kind = 0, axis = 2;
  double c[3] = {0, 0, 0}, r = 0, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, v[3] = {0, 0, 0};
};

// Every node of the array (ghosts included) inside o: all three components prescribed.
inline void addObstacleNodes(const Grid& g, const ObstacleShape& o, const IntField& mask, const VecField& val) {
  const int ng = g.ng;
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2];
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int c00 = g.c0[0], c01 = g.c0[1], c02 = g.c0[2];
  const int kind = o.kind, ax = o.axis;
  const double cx = o.c[0], cy = o.c[1], cz = o.c[2], r = o.r;
  const double bx0 = o.lo[0], by0 = o.lo[1], bz0 = o.lo[2], bx1 = o.hi[0], by1 = o.hi[1], bz1 = o.hi[2];
  const double vx = o.v[0], vy = o.v[1], vz = o.v[2];
  Kokkos::parallel_for(
      "obstacle_mask", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = lo0 + (i - ng + c00) * h0, y = lo1 + (j - ng + c01) * h1, z = lo2 + (k - ng + c02) * h2;
        const double dx = x - cx, dy = y - cy, dz = z - cz;
        bool inside = false;
        if (kind == 0) {
          inside = dx * dx + dy * dy + dz * dz <= r * r;
        } else if (kind == 1) {
          const double d2 = ax == 0 ? dy * dy + dz * dz : ax == 1 ? dx * dx + dz * dz : dx * dx + dy * dy;
          inside = d2 <= r * r;
        } else {
          inside = x >= bx0 && x <= bx1 && y >= by0 && y <= by1 && z >= bz0 && z <= bz1;
        }
        if (inside) {
          mask(i, j, k) = 7;
          val.c[0](i, j, k) = vx;
          val.c[1](i, j, k) = vy;
          val.c[2](i, j, k) = vz;
        }
      });
}

// u's prescribed components (mask bits) re-imposed from val.
inline void applyFixed(const IntField& mask, const VecField& val, const VecField& u, Range3 nodes) {
  for_each3("apply_fixed", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const int m = mask(i, j, k);
    if (m & 1) u.c[0](i, j, k) = val.c[0](i, j, k);
    if (m & 2) u.c[1](i, j, k) = val.c[1](i, j, k);
    if (m & 4) u.c[2](i, j, k) = val.c[2](i, j, k);
  });
}

// Node ghosts along axis d beyond the boundary node lb (dir -1: low side, +1: high),
// for every point of the face plane r (r's extent along d is 1): ghost lb + dir m gets
// the interior node lb - dir m reflected evenly (odd = 0), oddly about the boundary value
// (odd = 1: 2 u_b - u_i), or u_b itself (outflow).
// The axis is a template parameter (mirrorNodeGhosts dispatches on it), so each access
// is a plain index instead of a run-time select; the x faces, one node thick, run one
// task per z plane (the gain measured: perf/README.md, "fifth part").
template <int D>
inline void mirrorNodeGhostsAxis(const Field& f, Range3 r, int lb, int dir, int ng, int ext, int odd, bool outflow,
                                 const char* name) {
  const auto point = KOKKOS_LAMBDA(int i, int j, int k) {
    const double ub = f(D == 0 ? lb : i, D == 1 ? lb : j, D == 2 ? lb : k);
    for (int m = 1; m <= ng; ++m) {
      const int lg = lb + dir * m, li = lb - dir * m;
      if (lg < 0 || lg >= ext) continue;
      const double ui = f(D == 0 ? li : i, D == 1 ? li : j, D == 2 ? li : k);
      f(D == 0 ? lg : i, D == 1 ? lg : j, D == 2 ? lg : k) = outflow ? ub : (odd ? 2 * ub - ui : ui);
    }
  };
  if constexpr (D == 0 && !kOnDevice) { // one task per z plane (see mirrorCellGhostsAxis)
    const int b1 = r.b[1], e1 = r.e[1], i0 = r.b[0];
    Kokkos::parallel_for(
        name, Kokkos::RangePolicy<ExecSpace>(r.b[2], r.e[2]), KOKKOS_LAMBDA(int k) {
          for (int j = b1; j < e1; ++j) point(i0, j, k);
        });
    return;
  }
  for_each3(name, r, point);
}

inline void mirrorNodeGhosts(const Field& f, Range3 r, int d, int lb, int dir, int ng, int ext, int odd,
                             bool outflow, const char* name = "node_ghosts") {
  if (d == 0) mirrorNodeGhostsAxis<0>(f, r, lb, dir, ng, ext, odd, outflow, name);
  else if (d == 1) mirrorNodeGhostsAxis<1>(f, r, lb, dir, ng, ext, odd, outflow, name);
  else mirrorNodeGhostsAxis<2>(f, r, lb, dir, ng, ext, odd, outflow, name);
}

// Cell ghosts in r mirror the owned cells along d: f(idx) = f(M - idx along d).
// The axis is a template parameter, as in mirrorNodeGhostsAxis.
template <int D>
inline void mirrorCellGhostsAxis(const Field& f, Range3 r, int M) {
  if constexpr (D == 0 && !kOnDevice) {
    // An x face is ng cells thick: one task per z plane, so the short i loops do not
    // each pay a task's overhead (for_each3 runs one task per (j, k) row).
    const int b0 = r.b[0], e0 = r.e[0], b1 = r.b[1], e1 = r.e[1];
    Kokkos::parallel_for(
        "cell_ghosts", Kokkos::RangePolicy<ExecSpace>(r.b[2], r.e[2]), KOKKOS_LAMBDA(int k) {
          for (int j = b1; j < e1; ++j)
            for (int i = b0; i < e0; ++i) f(i, j, k) = f(M - i, j, k);
        });
    return;
  }
  for_each3("cell_ghosts", r, KOKKOS_LAMBDA(int i, int j, int k) {
    f(i, j, k) = f(D == 0 ? M - i : i, D == 1 ? M - j : j, D == 2 ? M - k : k);
  });
}

inline void mirrorCellGhosts(const Field& f, Range3 r, int d, int M) {
  if (d == 0) mirrorCellGhostsAxis<0>(f, r, M);
  else if (d == 1) mirrorCellGhostsAxis<1>(f, r, M);
  else mirrorCellGhostsAxis<2>(f, r, M);
}

} // namespace voigt
