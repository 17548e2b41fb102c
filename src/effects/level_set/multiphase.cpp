// Several level sets: fluids under solid bodies (kernels/multiphase.hpp).
//   Extension (after reinit, Corrections stage): for a fluid's psi_f and a body's psi_b, the
//   cells -(kappa_b + h) < psi_b <= kappa_b + 2 h take psi_f extended along grad psi_b from
//   the cells farther out, in Jacobi sweeps (one cell deeper each). The body's smoothing
//   zone and a cell beyond then see the fluid that surrounds the body; deeper inside psi_f
//   is covered (H_b = 1) and left as it is. The sweeps run on the box of the cells to fill.
//   Covered volume: V_f = INT H(psi_f) PROD_{j>f} (1 - H(psi_j)) dV, what the blend gives the fluid.
#include <mpi.h>

#include <climits>
#include <cmath>
#include <vector>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/level_set/level_set.hpp"
#include "kernels/multiphase.hpp"

namespace voigt {

// On the fluid's box: outside a later level set's box its psi is <= -reach, so 1 - H = 1 exactly.
Field LevelSet::cover(State& st, size_t i) const {
  const Grid& g = st.grid;
  Field c = st.fields.scalar("level_set_cover");
  const Range3 r = within(box(st, ls_[i]), 0, cellRange(g));
  for (size_t j = i + 1; j < ls_.size(); ++j)
    multiphase::cover(st.fields.scalar(ls_[j].info.field), ls_[j].info.geometry.kappa(g), c, j == i + 1, r);
  return c;
}

void LevelSet::updateBoxes(State& st, bool everywhere) {
  if (single()) return; // one level set: every kernel on every cell, as always
  const Grid& g = st.grid;
  const double h = LevelSetGeometry::hMin(g);
  std::vector<int> lohi(6 * ls_.size()); // per level set: lo[3], -hi[3] (one MIN reduction)
  for (size_t i = 0; i < ls_.size(); ++i) {
    const LevelSetInstance& l = ls_[i];
    const double reach = (l.info.geometry.bandCells + 1) * h; // the band and far_bound's neighbours
    const Range3* old = box(st, l);
    const Range3 search = everywhere || !old ? cellRange(g) : within(old, 0, cellRange(g));
    const Range3 b = multiphase::boxWhere(st.fields.scalar(l.info.field), -reach, search);
    const bool empty = b.e[0] <= b.b[0];
    for (int d = 0; d < 3; ++d) { // local -> global cell index: + c0 - ng
      lohi[6 * i + d] = empty ? INT_MAX : b.b[d] + g.c0[d] - g.ng;
      lohi[6 * i + 3 + d] = empty ? INT_MAX : -(b.e[d] + g.c0[d] - g.ng);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, lohi.data(), int(lohi.size()), MPI_INT, MPI_MIN, g.comm);
  for (size_t i = 0; i < ls_.size(); ++i) {
    LevelSetInstance& l = ls_[i];
    Range3 local{{0, 0, 0}, {0, 0, 0}};
    if (lohi[6 * i] != INT_MAX) {
      for (int d = 0; d < 3; ++d) {
        l.global.b[d] = lohi[6 * i + d];
        l.global.e[d] = -lohi[6 * i + 3 + d];
        local.b[d] = l.global.b[d] - g.c0[d] + g.ng;
        local.e[d] = l.global.e[d] - g.c0[d] + g.ng;
      }
      local = within(&local, 2, cellRange(g)); // may be empty on this rank
    } else {
      l.global = Range3{{0, 0, 0}, {0, 0, 0}};
    }
    st.activeBoxes[l.info.field] = local;
  }
}

void LevelSet::hideUnderSolids(State& st) {
  if (!hides_) return;
  const Grid& g = st.grid;
  const double h = LevelSetGeometry::hMin(g);
  const Range3 cells = cellRange(g);
  Field known = st.fields.scalar("level_set_known"), knownTmp = st.fields.scalar("level_set_known_tmp");
  Field tmp = st.fields.scalar("psi_old"); // free outside the advection
  for (const LevelSetInstance& body : ls_) {
    if (!body.info.solid) continue;
    const Field pb = st.fields.scalar(body.info.field);
    const double kappa = body.info.geometry.kappa(g), outside = kappa + h, inside = kappa + 2 * h;
    const int sweeps = int(std::ceil((outside + inside) / h)) + 1;
    for (const LevelSetInstance& fl : ls_) {
      if (fl.info.solid) continue;
      Field pf = st.fields.scalar(fl.info.field);
      multiphase::markSources(pb, outside, known, within(box(st, body), g.ng, cellRange(g, g.ng)));
      const Range3 fill = multiphase::boxWhere(pb, -outside, within(box(st, body), 0, cells)); // this rank's cells to fill
      for (int s = 0; s < sweeps; ++s) { // every rank: the exchanges are collective
        multiphase::extendSweep(pb, outside, inside, pf, known, tmp, knownTmp, fill);
        copyCells(pf, tmp, fill);
        copyCells(known, knownTmp, fill);
        st.halo->exchange(std::vector<Field>{pf, known});
        fillCellGhostsEven(g, pf);
        fillCellGhostsEven(g, known);
      }
    }
  }
}

} // namespace voigt
