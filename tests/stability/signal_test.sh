#!/usr/bin/env bash
# SIGINT / SIGTERM: `voigt run` finishes the step, writes a checkpoint of it,
# writes summary.json ("stopped"), and exits with 128 + signal; --restart then
# finishes bit-identical to an uninterrupted run. With 2 ranks the signal goes
# to ONE rank only: all must stop at the same step (the stop is collective).
# SIGUSR1 (a batch system's time-limit warning) is sent to mpirun itself, as
# SLURM's --signal does: Open MPI forwards it to every rank, and the run stops
# as at --wall-limit (exit 75, summary state wall_limit), then restarts the same.
#   signal_test.sh VOIGT SOURCE_DIR [RANKS]
set -u
VOIGT=$1
SRC=$2
NP=${3:-1}
SCENE=$SRC/cases/taylor_green/taylor_green.yaml
SETS=(--set "domain.cells=[16,16,4]" --set output.interval=0.5 --set time.end=1000)
# Long enough (~0.4 s at 1 ms a step) that the signal lands while it steps: at 40 steps the
# run could finish between the poll below and the kill.
N=${VOIGT_SIGNAL_STEPS:-400}
SETS+=(--set checkpoint.interval=$N) # a final checkpoint to compare
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_signal_XXXXXX")
trap 'rm -rf "$WORK"' EXIT

fail() {
  echo "FAIL: $*"
  for f in "$WORK"/*.log; do echo "--- $f"; tail -5 "$f"; done
  exit 1
}
launch() { # launch LOG ARGS...
  local log=$1
  shift
  if [ "$NP" -gt 1 ]; then
    mpirun --allow-run-as-root --oversubscribe -np "$NP" "$VOIGT" "$@" > "$log" 2>&1 &
  else
    "$VOIGT" "$@" > "$log" 2>&1 &
  fi
  PID=$!
}
json() { python3 -c "import json,sys;print(json.load(open(sys.argv[1]))$2)" "$1"; }

launch "$WORK/ref.log" run "$SCENE" -o "$WORK/ref" --steps $N "${SETS[@]}"
wait $PID || fail "reference run"
ref=$(printf "%s/ref/checkpoint_%09d.h5" "$WORK" $N)

for sig in INT TERM USR1; do
  dir="$WORK/s$sig"
  launch "$WORK/$sig.log" run "$SCENE" -o "$dir" --steps $N "${SETS[@]}"
  # Wait until it is stepping (timeseries.csv has rows), then signal.
  for _ in $(seq 1 500); do
    rows=$({ wc -l < "$dir/timeseries.csv"; } 2>/dev/null || echo 0)
    [ "$rows" -ge 4 ] && break
    sleep 0.01
  done
  if [ "$NP" -gt 1 ] && [ "$sig" = USR1 ]; then
    target=$PID # mpirun, which forwards SIGUSR1 to the ranks
  elif [ "$NP" -gt 1 ]; then
    target=$(pgrep -P $PID | tail -1) # the last rank only
  else
    target=$PID
  fi
  [ -n "$target" ] || fail "SIG$sig: no process to signal"
  kill -s "$sig" "$target"
  # A warning may arrive twice (to the study script, which passes it on, and to the run):
  # the second must not kill the run before its checkpoint.
  if [ "$sig" = USR1 ]; then kill -s USR1 "$target" 2> /dev/null || true; fi
  wait $PID
  rc=$?
  want=$((128 + $(kill -l "$sig")))
  [ "$sig" = USR1 ] && want=75
  if [ "$sig" = USR1 ]; then
    [ $rc -eq 75 ] || fail "SIGUSR1: exit code $rc, expected 75"
    grep -q "stopped by SIGUSR1 .* at step" "$WORK/$sig.log" || fail "SIGUSR1: no stop message"
    [ "$(json "$dir/summary.json" "['state']")" = wall_limit ] || fail "SIGUSR1: summary.json state is not wall_limit"
  elif [ "$NP" -gt 1 ]; then
    # mpirun reports a failing rank's status as its own (non-zero); the rank's code is in the log.
    [ $rc -ne 0 ] || fail "SIG$sig: exit code 0"
    grep -q "Exit code:    $want" "$WORK/$sig.log" || fail "SIG$sig: no rank exited with $want"
  else
    [ $rc -eq $want ] || fail "SIG$sig: exit code $rc, expected $want"
  fi
  [ "$sig" = USR1 ] || grep -q "stopped by signal $(kill -l "$sig") at step" "$WORK/$sig.log" || fail "SIG$sig: no stop message"
  stopped=$(json "$dir/summary.json" "['stopped']")
  [ "$stopped" = "signal SIG$sig" ] || fail "SIG$sig: summary.json stopped = '$stopped'"
  steps=$(json "$dir/summary.json" "['steps']")
  [ "$steps" -lt $N ] || fail "SIG$sig: the run was not interrupted (steps $steps)"
  latest=$(cat "$dir/latest")
  [ "$latest" = "$(printf 'checkpoint_%09d.h5' "$steps")" ] || fail "SIG$sig: latest is $latest, stopped at step $steps"
  # timeseries.csv has exactly one row per step done.
  [ "$(($(wc -l < "$dir/timeseries.csv") - 1))" -eq "$steps" ] || fail "SIG$sig: timeseries rows != $steps"
  launch "$WORK/${sig}_restart.log" run "$SCENE" -o "$dir" --steps $N "${SETS[@]}" --restart
  wait $PID || fail "SIG$sig: restart failed"
  grep -q "restart: $dir/$latest (step $steps," "$WORK/${sig}_restart.log" || fail "SIG$sig: did not restart from $latest"
  got=$(printf "%s/checkpoint_%09d.h5" "$dir" $N)
  h5diff -q "$ref" "$got" /fields /fields || fail "SIG$sig: fields differ from the uninterrupted run"
  cmp -s "$WORK/ref/timeseries.csv" "$dir/timeseries.csv" || fail "SIG$sig: timeseries.csv differs"
  cmp -s "$WORK/ref/fields.xdmf" "$dir/fields.xdmf" || fail "SIG$sig: fields.xdmf differs"
  cmp -s "$WORK/ref/probe_quarter.csv" "$dir/probe_quarter.csv" || fail "SIG$sig: probe_quarter.csv differs"
  for f in "$WORK"/ref/fields_*.h5; do
    h5diff -q "$f" "$dir/$(basename "$f")" || fail "SIG$sig: $(basename "$f") differs"
  done
  echo "SIG$sig (ranks $NP): stopped at step $steps with exit $want, checkpoint $latest; restart bit-identical at step $N"
done
echo PASS
