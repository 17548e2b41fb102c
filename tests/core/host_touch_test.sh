#!/usr/bin/env bash
# The host-touch check on whole runs (issue 55): every effect's steps, output, a checkpoint
# and a restart run with VOIGT_HOST_TOUCH_CHECK=1 (core/host_access.hpp: every field and
# device scratch array is mprotect-ed outside Kokkos kernels and deep copies), so host code
# that dereferences device data outside toHost/toDevice kills the run (exit 86, the field's
# name and a backtrace). What crosses between device and host memory is counted by reason
# (summary.json "host_copies") and must be on the allowed list below; with output off and
# one rank, a run copies nothing but its tables, the fast-marching re-initialisation's level
# set and the solid-body diagnostics' column sums (a few kB a step).
#   host_touch_test.sh VOIGT SOURCE_DIR NP
set -u
VOIGT=$1
SRC=$2
NP=$3
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_host_touch_XXXXXX")
[ -n "${VOIGT_KEEP_WORK:-}" ] || trap 'rm -rf "$WORK"' EXIT
# shellcheck source=../support/voigt_run.sh
. "$SRC/tests/support/voigt_run.sh"
export VOIGT_HOST_TOUCH_CHECK=1
# Reasons a copy may cross, each with where it happens (grep the reason in src/):
#   hdf5_write / hdf5_read   output, checkpoints and restarts (io/h5_util.hpp)
#   fast_marching            the re-initialisation's marching runs on the host (levelset/)
#   halo_staging             halo exchange between ranks: MPI is not device-aware (core/halo.cpp)
#   fd_transpose_staging     the fast diagonalization's transposes, same reason
#   hydrostatic_columns      gravity's column sums passed between ranks (effects/gravity.cpp)
#   probes                   probe samples, at their interval (io/probes.cpp)
#   solid_body_columns       the solid-body diagnostics' column sums, summed over ranks
#   blow_up_report           the value of a non-finite field, once, when a run stops
#   setup                    tables built once on the host (shapes, probes, the blow-up scan's)
#   solver_setup             the Poisson solver's and fast diagonalization's tables, again only
#                            when the operator's zero pattern changes
#   null_space               a few coefficients a solve, where the null space is more than the
#                            constant
ALLOWED="hdf5_write hdf5_read probes solid_body_columns fast_marching halo_staging"
ALLOWED+=" fd_transpose_staging hydrostatic_columns blow_up_report setup solver_setup null_space"

# name scene steps extra sets (one case a line): every effect and both preconditioners.
CASES="falling_block cases/falling_block/falling_block.yaml 3 domain.cells=[16,16,8]
dam_break_multigrid perf/scenes/dam_break.yaml 3 domain.cells=[16,16,16] projection.operator=exact projection.preconditioner=multigrid
static_drop cases/rising_bubble/static_drop.yaml 2
porous_bed cases/porous_bed/porous_bed.yaml 2 domain.cells=[10,30,10]
ball_pool cases/ball_pool/ball_pool.yaml 2
column cases/rest_tank/column.yaml 3 domain.cells=[16,16,16]
cavity_disk cases/cavity_disk/cavity_disk.yaml 3
taylor_green cases/taylor_green/taylor_green.yaml 3
cylinder cases/cylinder/cylinder.yaml 3
sphere_collision cases/sphere_collision/sphere_collision.yaml 3 domain.cells=[48,24,24]"

check_copies() { # summary name: every reason allowed; prints the counts
  local r
  for r in $(json "$1" "['host_copies'].keys()" | tr -d "[]',()" | sed 's/dict_keys//'); do
    case " $ALLOWED " in *" $r "*) ;; *) fail "$2: a copy to or from the host for '$r', not on the allowed list" ;; esac
  done
  [ "$(json "$1" "['host_touch_check']['kernels'] > 0")" = True ] || fail "$2: the check did not see a kernel"
}

while read -r name scene steps sets; do
  args=()
  for s in $sets; do args+=(--set "$s"); done
  run "$WORK/$name.log" run "$SRC/$scene" -o "$WORK/$name" "${args[@]}" --steps "$steps"
  [ "$RC" -eq 0 ] || fail "$name: exit code $RC (86: host code touched a field; the log names it)"
  check_copies "$WORK/$name/summary.json" "$name"
  echo "ok $name ($NP ranks): $(json "$WORK/$name/summary.json" "['host_touch_check']") $(json "$WORK/$name/summary.json" "['host_copies']")"
done <<<"$CASES"

# A checkpoint and a restart from it (hdf5_read), then output and probes off at one rank:
# nothing crosses but tables, the fast marching and the solid-body columns.
fb=(--set "domain.cells=[16,16,8]" --set checkpoint.interval=2)
run "$WORK/ck.log" run "$SRC/cases/falling_block/falling_block.yaml" -o "$WORK/ck" "${fb[@]}" --steps 2
[ "$RC" -eq 0 ] || fail "checkpoint run: exit code $RC"
run "$WORK/rs.log" run "$SRC/cases/falling_block/falling_block.yaml" -o "$WORK/ck" "${fb[@]}" --steps 4 --restart
[ "$RC" -eq 0 ] || fail "restart: exit code $RC"
check_copies "$WORK/ck/summary.json" restart
[ "$(json "$WORK/ck/summary.json" "['host_copies'].get('hdf5_read', {}).get('count', 0) > 0")" = True ] ||
  fail "restart: no hdf5_read counted"
echo "ok restart: $(json "$WORK/ck/summary.json" "['host_copies']")"
if [ "$NP" -eq 1 ]; then
  run "$WORK/quiet.log" run "$SRC/cases/falling_block/falling_block.yaml" -o "$WORK/quiet" --set "domain.cells=[16,16,8]" \
    --set output.enabled=false --set "probes=[]" --steps 4
  [ "$RC" -eq 0 ] || fail "output off: exit code $RC"
  other=$(python3 -c "import json, sys
c = json.load(open(sys.argv[1]))['host_copies']
print(' '.join(k for k in c if k not in ('fast_marching', 'solid_body_columns', 'setup', 'solver_setup', 'null_space')))
" "$WORK/quiet/summary.json")
  [ -z "$other" ] || fail "one rank, output off: copies for '$other'"
  echo "ok one rank, output off: $(json "$WORK/quiet/summary.json" "['host_copies']")"
  # Page mode (perf/portability/stage_work.py): the same kernels per stage, and every stage
  # that launched a kernel touched memory.
  VOIGT_HOST_TOUCH_CHECK=pages run "$WORK/pages.log" run "$SRC/cases/falling_block/falling_block.yaml" -o "$WORK/pages" \
    --set "domain.cells=[16,16,8]" --set output.enabled=false --set "probes=[]" --steps 4
  [ "$RC" -eq 0 ] || fail "page mode: exit code $RC"
  python3 - "$WORK/quiet/summary.json" "$WORK/pages/summary.json" <<'PY' || fail "page mode: counts disagree"
import json, sys
a, b = (json.load(open(f))["host_touch_check"]["per_stage"] for f in sys.argv[1:])
assert {k: v["kernels"] for k, v in a.items()} == {k: v["kernels"] for k, v in b.items()}, (a, b)
assert all(v["bytes_touched"] > 0 for v in b.values() if v["kernels"] > 0), b
assert all("bytes_touched" not in v for v in a.values()), a
PY
  echo "ok page mode: $(json "$WORK/pages/summary.json" "['host_touch_check']['per_stage']['projection']")"
fi
echo "PASS: no host touch of a field at $NP ranks; copies only for: $ALLOWED"
