#include "core/boundary.hpp"

namespace voigt {

namespace {
// Applies one face's condition to the nodes lying on it.
// A moving wall is one with a nonzero velocity (amplitude), whatever its value
// at time t, so that the edge priority does not change as an oscillating wall
// passes through zero.
void markFace(const Grid& g, int face, const FaceBc& bc, const IntField& mask, const VecField& val,
              bool movingOnly, bool stationaryOnly, double t) {
  const int d = face / 2, side = face % 2;
  if (side == 0 ? !g.atLo(d) : !g.atHi(d)) return;
  int full = 0;
  if (bc.type == BcType::NoSlip || bc.type == BcType::Inflow) full = 7;
  else if (bc.type == BcType::Slip) full = 1 << d;
  else return; // outflow: nothing prescribed
  const bool moving = bc.velocity[0] != 0 || bc.velocity[1] != 0 || bc.velocity[2] != 0;
  if ((movingOnly && !moving) || (stationaryOnly && moving)) return;
  const int l = side == 0 ? g.ng : g.local(d, g.n[d]);
  Range3 r{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}};
  r.b[d] = l;
  r.e[d] = l + 1;
  const Vec3 v = bc.velocityAt(t);
  const double v0 = bc.type == BcType::Slip ? 0 : v[0];
  const double v1 = bc.type == BcType::Slip ? 0 : v[1];
  const double v2 = bc.type == BcType::Slip ? 0 : v[2];
  for_each3("mark_face", r, KOKKOS_LAMBDA(int i, int j, int k) {
        mask(i, j, k) |= full;
        if (full & 1) val.c[0](i, j, k) = v0;
        if (full & 2) val.c[1](i, j, k) = v1;
        if (full & 4) val.c[2](i, j, k) = v2;
      });
}

void markFaces(const Grid& g, const Scene& s, const IntField& mask, const VecField& val, double t) {
  // Order sets priority at edges and corners: slip, then moving walls and
  // inflow, then stationary walls (a lid's corner nodes stay at rest).
  VOIGT_UNROLL
  for (int f = 0; f < 6; ++f)
    if (s.bc[f].type == BcType::Slip) markFace(g, f, s.bc[f], mask, val, false, false, t);
  VOIGT_UNROLL
  for (int f = 0; f < 6; ++f)
    if (s.bc[f].type != BcType::Slip) markFace(g, f, s.bc[f], mask, val, true, false, t);
  VOIGT_UNROLL
  for (int f = 0; f < 6; ++f)
    if (s.bc[f].type != BcType::Slip) markFace(g, f, s.bc[f], mask, val, false, true, t);
}
} // namespace

void buildFaceMask(const Grid& g, const Scene& s, const IntField& mask, const VecField& val, double t) {
  Kokkos::deep_copy(mask, 0);
  VOIGT_UNROLL
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(val.c[c], 0.0);
  markFaces(g, s, mask, val, t);
}

bool hasOscillatingWalls(const Scene& s) {
  for (const FaceBc& f : s.bc)
    if (f.oscillating) return true;
  return false;
}

void refreshWallValues(const Grid& g, const Scene& s, const IntField& mask, const VecField& val, double t) {
  if (!hasOscillatingWalls(s)) return;
  // Marking is idempotent on the mask (bits are OR-ed in), so re-marking every
  // face in the same order rewrites exactly the values buildFaceMask wrote, at t.
  markFaces(g, s, mask, val, t);
}

void addObstacleMask(const Grid& g, const std::vector<Obstacle>& obs, const IntField& mask,
                     const VecField& val) {
  const int ng = g.ng;
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2];
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int c00 = g.c0[0], c01 = g.c0[1], c02 = g.c0[2];
  for (const Obstacle& o : obs) {
    const int kind = static_cast<int>(o.kind), ax = o.axis;
    const double cx = o.center[0], cy = o.center[1], cz = o.center[2], r = o.radius;
    const double bx0 = o.lo[0], by0 = o.lo[1], bz0 = o.lo[2], bx1 = o.hi[0], by1 = o.hi[1], bz1 = o.hi[2];
    const double vx = o.velocity[0], vy = o.velocity[1], vz = o.velocity[2];
    Kokkos::parallel_for(
        "obstacle_mask", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}),
        KOKKOS_LAMBDA(int i, int j, int k) {
          const double x = lo0 + (i - ng + c00) * h0, y = lo1 + (j - ng + c01) * h1,
                       z = lo2 + (k - ng + c02) * h2;
          const double dx = x - cx, dy = y - cy, dz = z - cz;
          bool inside = false;
          if (kind == static_cast<int>(Obstacle::Kind::Sphere)) {
            inside = dx * dx + dy * dy + dz * dz <= r * r;
          } else if (kind == static_cast<int>(Obstacle::Kind::Cylinder)) {
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
}

void applyFixed(const IntField& mask, const VecField& val, const VecField& u, Range3 nodes) {
  for_each3("apply_fixed", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const int m = mask(i, j, k);
        if (m & 1) u.c[0](i, j, k) = val.c[0](i, j, k);
        if (m & 2) u.c[1](i, j, k) = val.c[1](i, j, k);
        if (m & 4) u.c[2](i, j, k) = val.c[2](i, j, k);
      });
}

void fillVelocityGhosts(const Grid& g, const Scene& s, const VecField& u) {
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) {
    VOIGT_UNROLL
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? !g.atLo(d) : !g.atHi(d)) continue;
      const FaceBc& bc = s.bc[2 * d + side];
      const int lb = side == 0 ? g.ng : g.local(d, g.n[d]); // boundary node
      const int dir = side == 0 ? -1 : 1;
      // odd[c]: reflect component c oddly about the boundary node value.
      int odd[3] = {0, 0, 0};
      if (bc.type == BcType::NoSlip || bc.type == BcType::Inflow) odd[0] = odd[1] = odd[2] = 1;
      if (bc.type == BcType::Slip) odd[d] = 1;
      const bool outflow = bc.type == BcType::Outflow;
      Range3 r{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}};
      r.b[d] = 0;
      r.e[d] = 1; // iterate the face plane; ghosts handled inside
      const int ng = g.ng, ext = g.ext[d];
      VOIGT_UNROLL
      for (int c = 0; c < 3; ++c) {
        auto f = u.c[c];
        const int oddc = odd[c];
        for_each3("velocity_ghosts", r, KOKKOS_LAMBDA(int i, int j, int k) {
              int idx[3] = {i, j, k};
              auto at = [&](int l) -> double& {
                idx[d] = l;
                return f(idx[0], idx[1], idx[2]);
              };
              const double ub = at(lb);
              for (int m = 1; m <= ng; ++m) {
                const int lg = lb + dir * m, li = lb - dir * m;
                if (lg < 0 || lg >= ext) continue;
                const double ui = at(li);
                at(lg) = outflow ? ub : (oddc ? 2 * ub - ui : ui);
              }
            });
      }
    }
  }
}

void fillNodeGhostsEven(const Grid& g, const Field& f) {
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) {
    VOIGT_UNROLL
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? !g.atLo(d) : !g.atHi(d)) continue;
      const int lb = side == 0 ? g.ng : g.local(d, g.n[d]), dir = side == 0 ? -1 : 1;
      Range3 r{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}};
      r.b[d] = 0;
      r.e[d] = 1;
      const int ng = g.ng, ext = g.ext[d];
      for_each3("node_ghosts_even", r, KOKKOS_LAMBDA(int i, int j, int k) {
            int idx[3] = {i, j, k};
            for (int m = 1; m <= ng; ++m) {
              const int lg = lb + dir * m, li = lb - dir * m;
              if (lg < 0 || lg >= ext) continue;
              idx[d] = li;
              const double v = f(idx[0], idx[1], idx[2]);
              idx[d] = lg;
              f(idx[0], idx[1], idx[2]) = v;
            }
          });
    }
  }
}

void fillCellGhostsEven(const Grid& g, const Field& f) {
  fillCellGhostsEven(g, f, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}});
}

void fillCellGhostsEven(const Grid& g, const Field& f, const Range3& reads) {
  // Each ghost layer mirrors the owned cells: ghost first - m <- first + m - 1,
  // last + m <- last - m + 1, i.e. src = M - idx along d. One loop over the
  // ghost slab, across it only where `reads` lies (the whole extent by default,
  // so edges and corners follow the d order; within `reads` the values are the
  // same as those of the full fill, since the mirrors of its ghosts lie in it).
  Range3 across;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) {
    across.b[d] = reads.b[d] > 0 ? reads.b[d] : 0;
    across.e[d] = reads.e[d] < g.ext[d] ? reads.e[d] : g.ext[d];
    if (across.b[d] >= across.e[d]) return;
  }
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) {
    VOIGT_UNROLL
    for (int side = 0; side < 2; ++side) {
      if (side == 0 ? !g.atLo(d) : !g.atHi(d)) continue;
      const int first = g.ng, last = g.ng + g.ln[d] - 1;
      Range3 r = across;
      r.b[d] = side == 0 ? first - g.ng : last + 1;
      r.e[d] = side == 0 ? first : last + 1 + g.ng;
      if (side == 0 ? across.b[d] >= first : across.e[d] <= last + 1) continue; // no ghost of this side read
      const int M = side == 0 ? 2 * first - 1 : 2 * last + 1;
      for_each3("cell_ghosts", r, KOKKOS_LAMBDA(int i, int j, int k) {
            f(i, j, k) = f(d == 0 ? M - i : i, d == 1 ? M - j : j, d == 2 ? M - k : k);
          });
    }
  }
}

} // namespace voigt
