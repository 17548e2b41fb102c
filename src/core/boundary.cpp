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
  markNodes(mask, val, r, full, v0, v1, v2);
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
  for (const Obstacle& o : obs) {
    ObstacleShape k;
    k.kind = o.kind == Obstacle::Kind::Sphere ? 0 : o.kind == Obstacle::Kind::Cylinder ? 1 : 2;
    k.axis = o.axis;
    k.r = o.radius;
    for (int d = 0; d < 3; ++d) k.c[d] = o.center[d], k.lo[d] = o.lo[d], k.hi[d] = o.hi[d], k.v[d] = o.velocity[d];
    addObstacleNodes(g, k, mask, val);
  }
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
      VOIGT_UNROLL
      for (int c = 0; c < 3; ++c)
        mirrorNodeGhosts(u.c[c], r, d, lb, dir, g.ng, g.ext[d], odd[c], outflow, "velocity_ghosts");
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
      mirrorNodeGhosts(f, r, d, lb, dir, g.ng, g.ext[d], 0, false, "node_ghosts_even");
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
      mirrorCellGhosts(f, r, d, M);
    }
  }
}

} // namespace voigt
