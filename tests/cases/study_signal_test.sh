#!/usr/bin/env bash
# The study scripts pass a batch system's warning on (cases/study.sh, study_warn):
# SIGNAL (USR1, as SLURM's --signal=B:USR1@T sends it, or TERM) to
# `cases/falling_block/run` while one of its runs is going reaches the run as SIGUSR1
# (through mpirun at 2 ranks), which checkpoints and exits 75; the ledger row says
# wall_limit with the t reached, the script exits 75, and --resume finishes the run
# from that checkpoint (a second segment) with the ledger row finished. While the run goes,
# the ledger row follows its checkpoints (VOIGT_LEDGER_INTERVAL=1 s here), and a second
# --resume script on the same DIR skips the run the first one holds, and a job that reaches a
# run another job has finished since its list was made skips it.
#   study_signal_test.sh VOIGT SOURCE_DIR RANKS SIGNAL
set -u
export VOIGT=$1
SRC=$2
NP=$3
SIG=$4
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voigt_study_XXXXXX")
trap 'rm -rf "$WORK"' EXIT
export VOIGT_LEDGER=$WORK/runs.csv
export VOIGT_LEDGER_INTERVAL=1 # the ledger row follows the run's checkpoints every second
RUN=(bash "$SRC/cases/falling_block/run" --quick -o "$WORK/out" --moduli 1000 --ranks "$NP" --no-figures
     --set "domain.cells=[24,24,24]" --set output.interval=1 --set checkpoint.interval=5)
fail() {
  echo "FAIL: $*"
  tail -n 8 "$WORK"/*.log
  cat "$VOIGT_LEDGER" 2> /dev/null
  exit 1
}
ledger() { # ledger COLUMN: the one row's value
  python3 -c "import csv,sys;print(list(csv.DictReader(open(sys.argv[1])))[0][sys.argv[2]])" "$VOIGT_LEDGER" "$1"
}

"${RUN[@]}" > "$WORK/first.log" 2>&1 &
pid=$!
# Signal once a run is stepping (its timeseries.csv has rows).
for _ in $(seq 1 1200); do
  rows=$(cat "$WORK"/out/*/timeseries.csv 2> /dev/null | wc -l)
  [ "$rows" -ge 5 ] && break
  sleep 0.05
done
[ "$rows" -ge 5 ] || fail "the run did not start stepping"
# While it runs, the ledger row gets its last checkpoint (runs.py progress).
for _ in $(seq 1 100); do
  [ "$(ledger state)" = running ] && [ -n "$(ledger steps)" ] && break
  sleep 0.05
done
[ -n "$(ledger steps)" ] || fail "the running row was not given its last checkpoint"
running_steps=$(ledger steps)
# One writer per run: a second script on the same DIR (a second --resume job) skips the run
# the first holds (its lock, DIR/<run id>.lock) and leaves it going.
"${RUN[@]}" --resume > "$WORK/second.log" 2>&1 || fail "a second --resume exited with $? while the first ran"
grep -q "another job is running it" "$WORK/second.log" || fail "the second script did not skip the held run"
grep -q "^== .*->" "$WORK/second.log" && fail "the second script started the held run"
kill -0 "$pid" 2> /dev/null || fail "the first script ended while the second ran"
[ "$(ledger state)" = running ] || fail "ledger state '$(ledger state)' after the second script, expected running"
kill -s "$SIG" "$pid"
wait "$pid"
rc=$?
[ "$rc" = 75 ] || fail "the script exited with $rc after SIG$SIG, expected 75"
grep -q "stopped by SIGUSR1" "$WORK/first.log" || fail "the run was not stopped by SIGUSR1"
[ "$(ledger state)" = wall_limit ] || fail "ledger state '$(ledger state)', expected wall_limit"
t1=$(ledger t_reached)
python3 -c "import sys; sys.exit(not 0 < float(sys.argv[1]) < 0.13)" "$t1" || fail "t_reached $t1 not in (0, 0.13)"

# study_one alone, as a job reaches a run on the list it made when it started (two --resume
# jobs both list every unfinished run): late_job MODE LISTED_STATE LEDGER VOIGT > LOG.
run_dir=$(ls -d "$WORK"/out/*/)
run_dir=${run_dir%/}
late_job() {
  bash -c 'set -euo pipefail; . "$1/cases/study.sh"; out=$(dirname "$2"); id=$(basename "$2"); py=/usr/bin/python3
           runs=$1/cases/runs.py; ledger=$5; deadline=""; ranks=1; launch=(); voigt=$6
           study_scene=$1/cases/falling_block/falling_block.yaml; declare -A study_listed=([$id]=$4)
           study_held_ids=(); study_one "$id" "$3"; echo "rc=$rc"' _ "$SRC" "$run_dir" "$@"
}
# Listed as new, begun and stopped by another job since: continued, not overwritten (voigt
# replaced by echo, its own ledger: only the arguments it would get are checked).
late_job fresh new "$WORK/echo_ledger.csv" echo > "$WORK/begun.log" 2>&1 || fail "study_one on a begun run exited with $?"
grep -q -- "--restart" "$WORK/begun.log" || fail "a run begun by another job was not continued with --restart"
grep -q -- "--overwrite" "$WORK/begun.log" && fail "a run begun by another job would be overwritten"

"${RUN[@]}" --resume > "$WORK/resume.log" 2>&1 || fail "--resume exited with $?"
grep -q "restart: " "$WORK/resume.log" || fail "--resume did not restart from the checkpoint"
[ "$(ledger state)" = finished ] || fail "ledger state after --resume '$(ledger state)'"
# Listed as unfinished, finished by another job since: skipped, not restarted.
before=$(md5sum < "$run_dir/summary.json")
late_job restart unfinished "$VOIGT_LEDGER" "$VOIGT" > "$WORK/late.log" 2>&1 || fail "study_one on a finished run exited with $?"
grep -q "finished in another job" "$WORK/late.log" || fail "a finished run on a job's list was not skipped"
grep -q "^rc=0" "$WORK/late.log" || fail "skipping a finished run is not rc 0"
[ "$(md5sum < "$run_dir/summary.json")" = "$before" ] || fail "the finished run's summary.json changed"
[ "$(ledger state)" = finished ] || fail "ledger state '$(ledger state)' after the late job"
echo "while running the ledger had step $running_steps and a second script skipped the run; SIG$SIG to the study script (ranks $NP): the run stopped at t = $t1 with exit 75 (ledger wall_limit); --resume finished it"
echo PASS
