#!/usr/bin/env bash
# voigt check --presets (README "Cost before the run", src/app/presets_estimate.hpp).
#   presets_test.sh VOIGT SOURCE_DIR RANKS
# On presets_cost.yaml (a uniform flow, no time.cfl, projection.tolerance written): the
# scene and the three presets each print their knob values and origins, an estimate, and
# the summary; the pointer to the measured errors names a section that exists. Then with
# the scene's own preset (--set preset=accurate) and a knob of its own (--set time.cfl):
# each variant replaces that preset, and the scene's knob still wins. No speed asserted.
set -u
VOIGT=$1
SRC=$2
NP=$3
SCENE=$SRC/tests/scene/presets_cost.yaml
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_presets_XXXXXX")
trap 'rm -rf "$WORK"' EXIT
FAIL_TAIL=40
# shellcheck source=../support/voigt_run.sh
. "$SRC/tests/support/voigt_run.sh"
has() { grep -Eq "$1" "$LOG" || fail "no line matching '$1' in $(basename "$LOG")"; }
count() { grep -Ec "$1" "$LOG"; }
steps() { sed -En "s/^           $1 +([0-9]+).*/\1/p" "$LOG"; } # from the summary table

LOG=$WORK/presets.log
run "$LOG" check "$SCENE" --presets --set "domain.cells=[16,16,2]"
[ "$RC" -eq 0 ] || fail "check --presets: exit code $RC"
[ "$(count '^summary ')" -eq 1 ] || fail "the report is not printed once (rank 0 only)"
has '^scene      as written \(no preset\)'
for p in fast balanced accurate; do
  has "^$p +preset: $p; keys written in the scene or --set win$"
  has "^  advection\.limiter +mc +preset $p$"
  has "^  reinit\.interval +[12] +preset $p$"
  has "^  projection\.tolerance +1e-07 +kept from the scene or --set; preset: "
  has "^           $p +[0-9]+ "
done
has '^  time\.cfl +0\.5 +default$'
has '^  time\.cfl +0\.9 +preset fast$'
has '^  time\.cfl +0\.7 +preset balanced$'
has '^  time\.cfl +0\.4 +preset accurate$'
[ "$(count '^  (time\.cfl|advection\.limiter|projection\.(operator|tolerance|preconditioner)|reinit\.(interval|iterations)) ')" -eq 28 ] ||
  fail "not 7 knob lines for each of the 4 variants"
[ "$(count '^  steps .*\(advective CFL\)$')" -eq 4 ] || fail "dt is not limited by the advective CFL in every variant"
# The scene's dt is cfl h / |u| (uniform |u| = 1.12, nothing else limits it), so the step
# count goes as 1 / time.cfl: fast (cfl 0.9) needs fewer steps than accurate (cfl 0.4),
# about 14 against 30 to t = 0.5 (0.4 / 0.9 of them); balanced (0.7) lies between.
f=$(steps fast) b=$(steps balanced) a=$(steps accurate)
[ -n "$f" ] && [ -n "$b" ] && [ -n "$a" ] || fail "no step counts in the summary"
[ "$f" -lt "$a" ] && [ "$f" -le "$b" ] && [ "$b" -le "$a" ] || fail "steps fast $f, balanced $b, accurate $a: not in CFL order"
has '^kept       the scene or --set writes projection\.tolerance:$'
has '^measured error of each preset: perf/accuracy/README\.md \(section "Presets"'
grep -q '^## Presets$' "$SRC/perf/accuracy/README.md" || fail "perf/accuracy/README.md has no section 'Presets'"
has 'scene is not measured'

# The scene's own preset and an explicit knob: each variant replaces the preset, the knob wins.
LOG=$WORK/own.log
run "$LOG" check "$SCENE" --presets --set preset=accurate --set time.cfl=0.6
[ "$RC" -eq 0 ] || fail "check --presets with a scene preset: exit code $RC"
has '^scene      as written, with its preset: accurate$'
has '^           the scene has preset: accurate'
has "^accurate +preset: accurate = the scene's own preset"
has "^fast +preset: fast in place of the scene's accurate"
has '^  projection\.preconditioner +sgs +preset fast$'       # fast's, not accurate's jacobi
has '^  projection\.preconditioner +jacobi +preset accurate$'
[ "$(count '^  time\.cfl +0\.6 +kept from the scene or --set; preset: ')" -eq 4 ] || fail "time.cfl=0.6 not kept everywhere"
[ "$(steps fast)" = "$(steps accurate)" ] || fail "same cfl, different step counts: $(steps fast) vs $(steps accurate)"

LOG=$WORK/bad.log
run "$LOG" check "$SCENE" --presets --set preset=fastest
[ "$RC" -eq 2 ] && grep -q "^error: .*preset" "$LOG" || fail "unknown preset: exit code $RC, no clear error"
echo PASS
