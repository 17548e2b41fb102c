#!/usr/bin/env bash
# SIGKILL at random times while `voigt run` writes a checkpoint every step:
# after every kill the checkpoint `latest` names must open (h5ls) and hold the
# fields, the next run restarts from it, and after all the kills the run
# finishes bit-identical (h5diff, timeseries.csv) to one that was never killed.
#   kill_test.sh VOIGT SOURCE_DIR [RANKS [KILLS]]
set -u
VOIGT=$1
SRC=$2
NP=${3:-1}
KILLS=${4:-6}
SCENE=$SRC/cases/zalesak/zalesak.yaml
# Level set + re-initialisation under a prescribed rotation: cheap steps, so a
# large share of the wall time is spent writing checkpoints (14 MB each).
CELLS=${VOIGT_KILL_CELLS:-[384,384,2]}
SETS=(--set "domain.cells=$CELLS" --set output.enabled=false --set checkpoint.interval=1)
BIG=1000000 # the killed runs never finish on their own
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_kill_XXXXXX")
[ -n "${VOIGT_KEEP_WORK:-}" ] || trap 'rm -rf "$WORK"' EXIT

fail() {
  echo "FAIL: $*"
  for f in "$WORK"/*.log; do echo "--- $f"; tail -5 "$f"; done
  exit 1
}
launch() { # launch LOG ARGS...: runs voigt in the background; sets PID
  local log=$1
  shift
  if [ "$NP" -gt 1 ]; then
    mpirun --allow-run-as-root --oversubscribe -np "$NP" "$VOIGT" "$@" > "$log" 2>&1 &
  else
    "$VOIGT" "$@" > "$log" 2>&1 &
  fi
  PID=$!
}
KIDS=""
kill9() { # SIGKILL every rank (and mpirun), like a node failure
  if [ "$NP" -gt 1 ]; then
    local kids=$KIDS
    [ -n "$kids" ] || kids=$(pgrep -P "$1")
    [ -n "$kids" ] && kill -9 $kids 2>/dev/null
  fi
  kill -9 "$1" 2>/dev/null
  KIDS=""
}


killed=0
during=0
# KILLS kills, more (up to 6) until at least one landed inside a checkpoint write.
for i in $(seq 1 $((KILLS + 6))); do
  if [ "$i" -gt "$KILLS" ] && [ $during -ge 1 ]; then break; fi
  args=(run "$SCENE" -o "$WORK/k" --steps $BIG "${SETS[@]}")
  if [ -f "$WORK/k/latest" ]; then args+=(--restart); else args+=(--overwrite); fi
  # A temporary file a kill left behind means nothing to voigt (it is never
  # read, and truncated by the next write); remove it so a new one is seen.
  rm -f "$WORK/k/checkpoint.h5.tmp"
  launch "$WORK/run$i.log" "${args[@]}"
  if [ $((i % 2)) -eq 1 ]; then
    # Odd kills: a random moment 0 - 1 s after the run has written a checkpoint
    # of its own (`latest` changes). Waiting for that, not for a fixed start-up
    # time, keeps the test meaningful when CI runs it beside other tests.
    before=$(cat "$WORK/k/latest" 2>/dev/null || echo none)
    n=0
    while [ "$(cat "$WORK/k/latest" 2>/dev/null || echo none)" = "$before" ] && [ $n -lt 6000 ]; do
      sleep 0.01
      n=$((n + 1))
    done
    sleep "$(printf '0.%03d' $((RANDOM % 1000)))"
  else
    # Even kills: aimed at a write, 0-5 ms after checkpoint.h5.tmp appears
    # (a write takes 20-60 ms here).
    n=0
    while [ "$NP" -gt 1 ] && [ "$(pgrep -P $PID | wc -l)" -lt "$NP" ] && [ $n -lt 2000 ]; do
      sleep 0.01 # the ranks' pids, looked up before the write starts
      n=$((n + 1))
    done
    [ "$NP" -gt 1 ] && KIDS=$(pgrep -P $PID)
    n=0
    while [ ! -f "$WORK/k/checkpoint.h5.tmp" ] && [ $n -lt 20000 ]; do
      sleep 0.001
      n=$((n + 1))
    done
    sleep "$(printf '0.%03d' $((RANDOM % 6)))"
  fi
  kill9 $PID
  wait $PID 2>/dev/null
  rc=$?
  [ $rc -ne 0 ] || fail "kill $i: the run finished"
  killed=$((killed + 1))
  # Inside a write: the temporary file exists, or it was renamed but `latest`
  # not yet replaced (latest.tmp, or a newer checkpoint than `latest` names).
  mid=no
  newest=$(cd "$WORK/k" && ls checkpoint_*.h5 2>/dev/null | tail -1)
  if [ -f "$WORK/k/checkpoint.h5.tmp" ] || [ -f "$WORK/k/latest.tmp" ] ||
     { [ -n "$newest" ] && [ "$newest" != "$(cat "$WORK/k/latest" 2>/dev/null)" ]; }; then
    during=$((during + 1))
    mid=yes
  fi
  echo "kill $i: SIGKILL during a checkpoint write: $mid; latest: $(cat "$WORK/k/latest" 2>/dev/null || echo none)"
  if [ -f "$WORK/k/latest" ]; then
    name=$(cat "$WORK/k/latest")
    [ -f "$WORK/k/$name" ] || fail "kill $i: latest names $name, which does not exist"
    h5ls "$WORK/k/$name/fields" > "$WORK/ls$i.txt" 2>&1 || fail "kill $i: $name does not open"
    grep -q '^psi ' "$WORK/ls$i.txt" || fail "kill $i: $name has no psi"
    grep -q '^velocity ' "$WORK/ls$i.txt" || fail "kill $i: $name has no velocity"
    # The next run must restart from exactly this file.
    echo "$name" > "$WORK/expect_next"
  fi
done

# Finish a few steps past the newest checkpoint, then run the same number of
# steps uninterrupted and compare.
[ -f "$WORK/expect_next" ] || fail "no checkpoint was ever written"
expect=$(cat "$WORK/expect_next")
last=${expect#checkpoint_}
last=$((10#${last%.h5}))
N=$((last + 3))
launch "$WORK/final.log" run "$SCENE" -o "$WORK/k" --steps $N "${SETS[@]}" --restart
wait $PID || fail "final restart"
grep -q "restart: $WORK/k/$expect " "$WORK/final.log" || fail "final run did not restart from $expect"
t0=$(date +%s.%N)
launch "$WORK/ref.log" run "$SCENE" -o "$WORK/ref" --steps $N "${SETS[@]}" --set checkpoint.interval=$N
wait $PID || fail "reference run"
t1=$(date +%s.%N)
ref=$(printf "%s/ref/checkpoint_%09d.h5" "$WORK" $N)
[ -f "$ref" ] || fail "reference checkpoint missing"
got=$(printf "%s/k/checkpoint_%09d.h5" "$WORK" $N)
h5diff -q "$ref" "$got" /fields /fields || fail "fields after $killed kills differ from the uninterrupted run"
cmp -s "$WORK/ref/timeseries.csv" "$WORK/k/timeseries.csv" || fail "timeseries.csv differs"
[ ! -f "$WORK/k/checkpoint.h5.tmp" ] || fail "a temporary checkpoint was left behind after a clean finish"
size=$(stat -c %s "$got")
secs=$(python3 -c "import json;c=json.load(open('$WORK/k/summary.json')).get('checkpoints',{});print('%.4f'%(c['seconds']/c['written']) if c else 'n/a')" 2>/dev/null || echo n/a)
echo "[ measured ] ranks $NP: $killed SIGKILLs ($during during a checkpoint write), $N steps in the end, reference run $(awk "BEGIN{printf \"%.1f\", $t1 - $t0}") s, checkpoint $size bytes, $secs s per checkpoint; final fields bit-identical"
[ $during -ge 1 ] || fail "no kill landed inside a checkpoint write"
echo PASS
