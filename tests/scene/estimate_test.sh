#!/usr/bin/env bash
# voigt check --estimate and voigt run --estimate (README "Cost before the run").
#   estimate_test.sh VOIGT SOURCE_DIR RANKS
# A fixed-dt scene: the step count is exactly time.end / time.dt; the wall time and
# memory are printed and positive (never compared with a speed); `run --estimate`
# records the estimate in summary.json beside the measured steps. A scene that fails
# to load gives the usual error, exit code 2.
set -u
VOIGT=$1
SRC=$2
NP=$3
SCENE=$SRC/tests/scene/tiny.yaml
SETS=(--set "domain.cells=[8,8,8]" --set time.dt=0.005 --set time.end=0.2 --set output.interval=0.05)
STEPS=40 # 0.2 / 0.005
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_estimate_XXXXXX")
trap 'rm -rf "$WORK"' EXIT
FAIL_TAIL=20
# shellcheck source=../support/voigt_run.sh
. "$SRC/tests/support/voigt_run.sh"
positive() { python3 -c "import sys;sys.exit(0 if float(sys.argv[1]) > 0 else 1)" "$1" 2>/dev/null; }

run "$WORK/check.log" check "$SCENE" --estimate "${SETS[@]}"
[ "$RC" -eq 0 ] || fail "check --estimate: exit code $RC"
grep -q "^  steps      $STEPS to t = 0.2 with the fixed dt 0.005 " "$WORK/check.log" || fail "step count is not $STEPS"
wall=$(sed -n 's/^  wall time  \([0-9.e+-]*\) .*/\1/p' "$WORK/check.log")
positive "$wall" || fail "wall time '$wall' is not positive"
mem=$(sed -n 's/^  memory     \([0-9.e+-]*\) [MG]iB per rank in fields.*/\1/p' "$WORK/check.log")
positive "$mem" || fail "memory '$mem' is not positive"
grep -q "^  disk       .*: 5 outputs x " "$WORK/check.log" || fail "not 5 outputs (t = 0, 0.05, ..., 0.2)"
grep -q "^  assumes    the calibration rate holds" "$WORK/check.log" || fail "assumptions not stated"
[ -e "$WORK/out" ] && fail "check --estimate wrote output"

run "$WORK/run.log" run "$SCENE" --estimate "${SETS[@]}" -o "$WORK/out"
[ "$RC" -eq 0 ] || fail "run --estimate: exit code $RC"
S=$WORK/out/summary.json
[ "$(json "$S" "['steps']")" = $STEPS ] || fail "the run took $(json "$S" "['steps']") steps"
[ "$(json "$S" "['estimate']['steps']")" = $STEPS ] || fail "summary.json estimate.steps is not $STEPS"
for k in wall_seconds rate_cell_steps_per_second memory_bytes_per_rank disk_bytes; do
  positive "$(json "$S" "['estimate']['$k']")" || fail "summary.json estimate.$k is not positive"
done
# The disk estimate counts the HDF5 payload: it is within 10 % of the files written.
disk=$(json "$S" "['estimate']['disk_bytes']")
real=$(cat "$WORK"/out/fields_*.h5 | wc -c)
python3 -c "import sys;sys.exit(0 if abs($disk-$real) < 0.1*$real else 1)" || fail "disk estimate $disk vs $real bytes written"

run "$WORK/bad.log" check "$SCENE" --estimate --set time.end=-1
[ "$RC" -eq 2 ] && grep -q "^error: .*time.end" "$WORK/bad.log" || fail "bad scene: exit code $RC, no clear error"
echo PASS
