#!/usr/bin/env bash
# The same run at 1 rank and at NP ranks agrees to far below the solver tolerance: every
# kernel computes a cell from the same values in the same order on any decomposition, halo
# exchanges copy, the fast diagonalization transforms and solves each grid line alone on
# slabs or pencils (bit-identical at any layout: tests/solvers/test_fd_pencils.cpp), and the
# only sums whose order changes with the ranks are the global reductions (CG's dot products
# and norms in Belos/Tpetra: per-rank partial sums, then MPI_Allreduce). Those differ in
# the last bits, which CG's iterations carry into the fields.
#   ranks_bitwise_test.sh VOIGT SOURCE_DIR NP
# Bound: max |f_NP - f_1| <= 1e-5 max |f_1| for every output field at every output:
# 100x under the projection's tolerance (1e-3), 30x over the largest seen (3.3e-7 at 8
# ranks, 1.7e-7 at 2 and 4); a decomposition fault (a missing halo, a line moved to the
# wrong place) is O(1) where it acts. The scene: the falling block (two phases, elasticity,
# the obstacle, re-initialisation) on 12 x 12 x 6 cells, 10 steps: 6 planes along the fast
# diagonalization's c axis (z), so 8 ranks run it on 2 x 4 pencils, more ranks than planes.
set -u
VOIGT=$1
SRC=$2
NP=$3
/usr/bin/python3 -c "import h5py, numpy" 2>/dev/null || { echo "SKIP: needs python3-h5py (scripts/setup --figures)"; exit 77; }
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_ranks_XXXXXX")
[ -n "${VOIGT_KEEP_WORK:-}" ] || trap 'rm -rf "$WORK"' EXIT
# shellcheck source=../support/voigt_run.sh
. "$SRC/tests/support/voigt_run.sh"
SETS=(--set "domain.cells=[12,12,6]" --set output.interval=0.0005 --set "probes=[]" --steps 10)
SCENE=$SRC/cases/falling_block/falling_block.yaml
if [ "${4:-}" = multigrid ]; then
  run "$WORK/mg.log" run "$SRC/perf/scenes/dam_break.yaml" -o "$WORK/mg" --set "domain.cells=[24,24,24]" \
    --set output.enabled=false --set time.dt=0 --set projection.operator=exact --set projection.preconditioner=multigrid \
    --steps 3
  [ "$RC" -eq 0 ] || fail "$NP ranks, multigrid: exit code $RC"
  b=$(json "$WORK/mg/summary.json" "['poisson']['breakdowns']")
  u=$(json "$WORK/mg/summary.json" "['poisson']['unconverged']")
  [ "$b" = 0.0 ] && [ "$u" = 0.0 ] || fail "multigrid at $NP ranks: $b CG breakdowns, $u solves unconverged"
  echo "PASS: multigrid at $NP ranks: no breakdown, every solve converged"
  exit 0
fi
RANKS=$NP
NP=1 run "$WORK/one.log" run "$SCENE" -o "$WORK/one" "${SETS[@]}"
[ "$RC" -eq 0 ] || fail "1 rank: exit code $RC"
NP=$RANKS
run "$WORK/many.log" run "$SCENE" -o "$WORK/many" "${SETS[@]}"
[ "$RC" -eq 0 ] || fail "$NP ranks: exit code $RC"
/usr/bin/python3 - "$WORK/one" "$WORK/many" "$NP" <<'PY' || fail "fields differ at $NP ranks"
import glob, os, sys
import h5py, numpy as np
one, many, np_ = sys.argv[1], sys.argv[2], sys.argv[3]
files = sorted(glob.glob(one + "/fields_*.h5"))
assert len(files) >= 3, "only %d outputs" % len(files)
worst, where = 0.0, ""
for f in files:
    with h5py.File(f) as a, h5py.File(os.path.join(many, os.path.basename(f))) as b:
        for k in a:
            x, y = a[k][()], b[k][()]
            scale = np.abs(x).max()
            d = np.abs(x - y).max() / (scale if scale > 0 else 1.0)
            if d > worst: worst, where = d, "%s %s" % (os.path.basename(f), k)
print("max |f_%s - f_1| / max |f_1| = %.2e (%s) over %d outputs" % (np_, worst, where, len(files)))
sys.exit(0 if worst <= 1e-5 else 1)
PY
echo "PASS: $NP ranks agree with 1 rank"
