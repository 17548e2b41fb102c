# Shared by the shell tests that run the voigt binary (source it after setting VOIGT, NP and
# WORK): run LOG ARGS... runs voigt (under mpirun when NP > 1) with its output in LOG and sets
# RC (stdin is /dev/null: mpirun would eat a loop's here-document); fail MSG prints MSG and
# the last FAIL_TAIL (default 20) lines of each WORK/*.log, exits 1;
# json FILE EXPR prints a value of a JSON file (python3).
fail() {
  echo "FAIL: $*"
  for f in "$WORK"/*.log; do echo "--- $f"; tail -n "${FAIL_TAIL:-20}" "$f"; done
  exit 1
}
run() {
  local log=$1
  shift
  if [ "$NP" -gt 1 ]; then
    mpirun --allow-run-as-root --oversubscribe -np "$NP" "$VOIGT" "$@" > "$log" 2>&1 < /dev/null
  else
    "$VOIGT" "$@" > "$log" 2>&1 < /dev/null
  fi
  RC=$?
}
json() { python3 -c "import json,sys;print(json.load(open(sys.argv[1]))$2)" "$1"; }
