# shellcheck shell=bash
# shellcheck disable=SC2154  # study_* are set by the sourcing run script
# The part of cases/*/run that every study shares: options, set-up, the loop over moduli and
# models (under mpirun when asked, resumable, within a wall-clock limit) and the run ledger
# (cases/runs.py). Sourced by a study's run script, which first sets
#   study_scene        the scene file (its folder's name is the case's name)
#   study_key          the scene key that carries the modulus (materials.NAME.shear_modulus)
#   study_moduli       the default moduli (Pa), space-separated
#   study_quick_sets   array: overrides of the --quick version (cells, end time, outputs)
#   study_full_sets    array: overrides of the full version
#   study_quick_out    default output directory of --quick (full runs: $VOIGT_RUNS/<case>)
# then calls `study_main "$@"` and draws its own figures from the variables it leaves:
#   out, moduli, models, quick, figures, py, root, and study_figure_runs (below).
# The study's run script's comment header is its --help.

study_usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1' "$0"; }
study_value() { [ -n "${2-}" ] || { echo "run: $1 needs a value (see --help)" >&2; exit 2; }; }

study_parse() {
  quick=0 ranks=1 out="" moduli="$study_moduli" models=extend resume=0 figures=1 user_sets=() wall_limit=""
  while [ $# -gt 0 ]; do
    case "$1" in
      --quick) quick=1 ;;
      --ranks) study_value "$1" "${2-}"; ranks="$2"; shift ;;
      -o) study_value "$1" "${2-}"; out="$2"; shift ;;
      --moduli) study_value "$1" "${2-}"; moduli="$2"; shift ;;
      --models) study_value "$1" "${2-}"; models="$2"; shift ;;
      --resume) resume=1 ;;
      --wall-limit) study_value "$1" "${2-}"; wall_limit="$2"; shift ;;
      --no-figures) figures=0 ;;
      --set) study_value "$1" "${2-}"; user_sets+=(--set "$2"); shift ;;
      -h|--help) study_usage; exit 0 ;;
      *) echo "run: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
  done
  case "$ranks" in ''|*[!0-9]*|0*) echo "run: --ranks must be a positive integer, not '$ranks'" >&2; exit 2 ;; esac
}

# One command on a fresh machine: packages (and the figure packages), then the build.
study_setup() {
  root="$(cd "$(dirname "$0")/../.." && pwd)"
  voigt="${VOIGT:-$root/build/voigt}"
  py="${PYTHON:-/usr/bin/python3}"
  if [ "$figures" = 1 ]; then "$root/scripts/setup" --figures; else "$root/scripts/setup"; fi
  [ -x "$voigt" ] || [ -n "${VOIGT:-}" ] || "$root/scripts/build"
  [ -x "$voigt" ] || { echo "run: no voigt binary at $voigt (build first, or set VOIGT)" >&2; exit 1; }
}

# Whether another job holds run $1's lock (is running it) right now.
study_held() { ! (exec 9> "$out/$1.lock" && flock -n 9); }

# One run ($1: its id; $2: restart or fresh) and its ledger row, "running" before and the
# outcome after. Sets rc. $out/<id>.args: "modulus model grid", then voigt's arguments.
study_one() {
  local id=$1 dir="$out/$1" mode=$2 meta args extra limit since now
  if [ -n "$deadline" ]; then
    limit=$((deadline - $(date +%s)))
    # Less than a minute left is not worth a start-up: the next job continues.
    if [ "$limit" -lt 60 ]; then echo "== $id: not started, $limit s left of --wall-limit"; rc=75; return; fi
  fi
  # One writer per run: another job (a second script with --resume on the same DIR) that
  # holds the run's lock makes this one skip it (rc 0: not a failure).
  exec {study_lock}> "$dir.lock"
  if ! flock -n "$study_lock"; then
    echo "== $id: another job is running it (lock $dir.lock), skipped"
    exec {study_lock}>&-
    study_held_ids+=("$id")
    rc=0
    return
  fi
  # The list this job works through was made when it started: another job (two --resume jobs
  # both list every unfinished run) may have finished the run since, or begun it.
  now=$("$py" "$runs" state "$dir")
  if [ "$now" != "${study_listed[$id]:-$now}" ]; then
    case "$now" in
      finished | failed)
        echo "== $id: $now in another job since this one started, skipped"
        exec {study_lock}>&-
        rc=0
        return ;;
      unfinished) mode=restart ;;  # begun and stopped by another job: continue it, do not overwrite
    esac
  fi
  { read -r -a meta; mapfile -t args; } < "$out/$id.args"
  extra=(--overwrite)
  [ "$mode" = restart ] && extra=(--restart)
  [ -n "$deadline" ] && extra+=(--wall-limit "${limit}s")
  echo "== $id -> $dir (${ranks} rank(s), $mode)"
  "$py" "$runs" start "$ledger" "$id" "${meta[@]}" "$ranks"
  since=$(date +%s)
  # In the background, so that study_warn can pass a signal on while it runs; meanwhile the
  # ledger row gets the run's last checkpoint every 10 min (runs.py progress), so the ledger
  # says how far a long run got even if the job is killed without warning.
  "${launch[@]}" "$voigt" run "$study_scene" -o "$dir" "${extra[@]}" "${args[@]}" &
  study_child=$!
  (
    trap 'kill "$nap" 2> /dev/null; exit 0' TERM
    while :; do
      sleep "${VOIGT_LEDGER_INTERVAL:-600}" &
      nap=$!
      wait "$nap"
      "$py" "$runs" progress "$ledger" "$out" || true
    done
  ) > /dev/null 2>&1 &
  local ticker=$!
  study_wait
  kill "$ticker" 2> /dev/null || true
  wait "$ticker" 2> /dev/null || true
  "$py" "$runs" end "$ledger" "$id" "$dir" "$rc" "$since"
  exec {study_lock}>&-
}

# SIGUSR1 / SIGTERM / SIGINT to this script (a batch system's warning before its
# time limit, e.g. SLURM --signal=B:USR1@300, or a kill): passed on to the run as
# SIGUSR1, which checkpoints and exits 75 (mpirun forwards it to every rank; a
# SIGTERM to mpirun would kill the ranks after 1 s). The ledger then says
# wall_limit and the script exits 75: --resume continues.
study_child=""
study_warn() { if [ -n "$study_child" ]; then kill -USR1 "$study_child" 2> /dev/null || true; fi; }
trap study_warn USR1 TERM INT
# Sets rc to the run's exit code. A trapped signal interrupts `wait` (status > 128)
# while the run goes on: wait again until it has ended.
study_wait() {
  local s
  while :; do
    rc=0
    wait "$study_child" || rc=$? # (set -e)
    kill -0 "$study_child" 2> /dev/null || break
  done
  # Ended during the last interrupted wait: its own status is still to collect (127: collected).
  if [ "$rc" -gt 128 ]; then s=0; wait "$study_child" 2> /dev/null || s=$?; [ "$s" = 127 ] || rc=$s; fi
  study_child=""
}

# Out of time (75) or stopped by a signal: the unfinished runs continue with --resume.
study_stop() {
  "$py" "$runs" table "$ledger" "${todo[@]}" "${selected[@]}" > "$out/runs.md"
  echo "run: stopped (exit $1); ledger $ledger; continue with --resume" >&2
  exit "$1"
}

# Every modulus x model. Full runs live outside the work tree (VOIGT_RUNS), in the committed
# ledger cases/<name>/runs.csv; --resume continues the unfinished runs there first (selected
# or not: their .args say how), then starts those not begun, and skips the finished.
study_runs() {
  local sets mu model id grid tagged name st rec all wl fresh=() failed=0
  todo=()  # also read by study_stop
  declare -gA study_listed=()  # each listed run's state when listed (study_one checks it again)
  study_held_ids=()            # runs skipped because another job held them
  name="$(basename "$(dirname "$study_scene")")"
  runs="$root/cases/runs.py"
  if [ "$quick" = 1 ]; then
    out="${out:-$root/$study_quick_out}"
    sets=("${study_quick_sets[@]}")
    ledger="${VOIGT_LEDGER:-$out/runs.csv}"
  else
    out="${out:-${VOIGT_RUNS:-$HOME/voigt-runs}/$name}"
    sets=("${study_full_sets[@]}")
    ledger="${VOIGT_LEDGER:-$root/cases/$name/runs.csv}"
  fi
  mkdir -p "$out"
  deadline=""
  if [ -n "$wall_limit" ]; then
    wl=$("$py" "$runs" seconds "$wall_limit") || exit 2
    deadline=$(($(date +%s) + wl))
  fi
  launch=()
  [ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks" --allow-run-as-root --oversubscribe)
  if [ "$resume" = 1 ]; then
    for d in "$out"/*/; do
      id="$(basename "$d")"
      if [ -f "$out/$id.args" ] && [ "$("$py" "$runs" state "$d")" = unfinished ]; then
        todo+=("$id")
        study_listed[$id]=unfinished
      fi
    done
  fi
  for mu in $moduli; do
    for model in $models; do
      all=(--set "$study_key=$mu" --set "elasticity.fluid_side=$model" "${sets[@]}" "${user_sets[@]}")
      read -r id grid tagged < <("$py" "$runs" id "$study_scene" "$mu" "$model" "${all[@]}")
      selected+=("$id")
      st=$("$py" "$runs" state "$out/$id")
      if [ "$resume" = 1 ] && [ "$st" = finished ]; then echo "== $id: finished, skipped"; continue; fi
      # A machine that did not keep the outputs: the committed ledger still knows.
      if [ "$resume" = 1 ] && [ "$st" = new ]; then
        rec=$("$py" "$runs" recorded "$ledger" "$id")
        if [ "$rec" = finished ]; then echo "== $id: finished (ledger; its output is not on this machine), skipped"; continue; fi
        if [ -n "$rec" ]; then echo "== $id: ledger says '$rec', but no checkpoint in $out/$id: starting again"; fi
      fi
      if [ "$resume" = 1 ] && [ "$st" = unfinished ] && [ -f "$out/$id.args" ]; then continue; fi
      # Another job is running it: leave its .args as that job wrote them.
      if study_held "$id"; then echo "== $id: another job is running it, skipped"; study_held_ids+=("$id"); continue; fi
      study_listed[$id]=$st
      printf '%s\n' "$mu $tagged $grid" "${all[@]}" > "$out/$id.args"
      if [ "$resume" = 1 ] && [ "$st" = unfinished ]; then todo+=("$id"); else fresh+=("$id"); fi
    done
  done
  for id in "${todo[@]}" "${fresh[@]}"; do
    if [[ " ${todo[*]} " == *" $id "* ]]; then study_one "$id" restart; else study_one "$id" fresh; fi
    case "$rc" in 0) ;; 75|130|143) study_stop "$rc" ;; *) failed=1 ;; esac
  done
  "$py" "$runs" table "$ledger" "${todo[@]}" "${selected[@]}" | tee "$out/runs.md"
  if [ "$failed" = 1 ]; then echo "run: a run failed (ledger $ledger); no figures" >&2; exit 1; fi
  # The job that holds a run draws the figures when it ends; here they would show it unfinished.
  if [ "${#study_held_ids[@]}" -gt 0 ]; then
    echo "run: ${study_held_ids[*]} held by another job (it draws the figures when it ends); no figures here"
    figures=0
  fi
}

# The figure inputs of one model ($1): fig_runs=(--run DIR LABEL ...) in moduli order, LABEL
# from the printf format $2 and the modulus; fig_dir: $out, or $out/figures_<model> when the
# study ran more than one model.
# A run whose folder is not on this machine is drawn from its committed digest
# (cases/<name>/digests/<id>.npz) when the case keeps them (python/voigt_post/porous_bed.py).
study_figure_runs() {
  local mu id src digests
  digests="$root/cases/$(basename "$(dirname "$study_scene")")/digests"
  fig_runs=()
  for mu in $moduli; do
    for id in "${selected[@]}"; do
      src="$out/$id"
      [ -d "$src" ] || [ ! -f "$digests/$id.npz" ] || src="$digests/$id.npz"
      # shellcheck disable=SC2059
      if [[ "$id" == "mu${mu}_$1+"* ]]; then fig_runs+=(--run "$src" "$(printf "$2" "$mu")"); fi
    done
  done
  fig_dir="$out"
  if [ "$(wc -w <<< "$models")" -gt 1 ]; then fig_dir="$out/figures_$1"; mkdir -p "$fig_dir"; fi
}

study_main() {
  study_parse "$@"
  study_setup
  selected=()
  study_runs
}
