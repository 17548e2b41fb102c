# shellcheck shell=bash
# shellcheck disable=SC2154  # study_* are set by the sourcing run script
# The part of cases/*/run that every study shares: options, set-up, the loop over moduli
# (under mpirun when asked, resumable) and the run table runs.csv / runs.md. Sourced by a
# study's run script, which first sets
#   study_scene        the scene file
#   study_key          the scene key that carries the modulus (materials.NAME.shear_modulus)
#   study_moduli       the default moduli (Pa), space-separated
#   study_quick_sets   array: overrides of the --quick version (cells, end time, outputs)
#   study_full_sets    array: overrides of the full version
#   study_quick_out, study_full_out   default output directories
# then calls `study_main "$@"` and draws its own figures from the variables it leaves:
#   out, moduli, quick, figures, py, root.
# The study's run script's comment header is its --help.

study_usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1' "$0"; }
study_value() { [ -n "${2-}" ] || { echo "run: $1 needs a value (see --help)" >&2; exit 2; }; }

study_parse() {
  quick=0 ranks=1 out="" moduli="$study_moduli" resume=0 figures=1 user_sets=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --quick) quick=1 ;;
      --ranks) study_value "$1" "${2-}"; ranks="$2"; shift ;;
      -o) study_value "$1" "${2-}"; out="$2"; shift ;;
      --moduli) study_value "$1" "${2-}"; moduli="$2"; shift ;;
      --resume) resume=1 ;;
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

# Each modulus in turn; appends cells, steps and wall time (from summary.json) to runs.csv.
study_runs() {
  local sets launch mu dir extra start
  if [ "$quick" = 1 ]; then
    out="${out:-$root/$study_quick_out}"
    sets=("${study_quick_sets[@]}")
  else
    out="${out:-$root/$study_full_out}"
    sets=("${study_full_sets[@]}")
  fi
  mkdir -p "$out"
  launch=()
  [ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks" --allow-run-as-root --oversubscribe)
  if [ "$resume" = 0 ] || [ ! -f "$out/runs.csv" ]; then
    echo "mu_S,cells,ranks,end_time,steps,wall_seconds,started_utc" > "$out/runs.csv"
  fi
  for mu in $moduli; do
    dir="$out/mu_$mu"
    extra=(--overwrite)
    if [ "$resume" = 1 ] && [ -e "$dir/latest" ]; then extra=(--restart); fi
    echo "== mu_S = $mu Pa -> $dir (${ranks} rank(s))"
    start="$(date -u +%FT%TZ)"
    "${launch[@]}" "$voigt" run "$study_scene" -o "$dir" "${extra[@]}" \
      --set "$study_key=$mu" "${sets[@]}" "${user_sets[@]}"
    "$py" - "$dir/summary.json" "$mu" "$ranks" "$start" >> "$out/runs.csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
# A resumed run: steps from t = 0 and the wall time of all its segments (their checkpointed
# steps); a checkpoint older than that record gives only this segment's time.
wall = s.get("wall_seconds_total")
wall = s["wall_seconds"] if wall is None else wall
print("%s,%s,%s,%.6g,%d,%.1f,%s" % (sys.argv[2], "x".join(map(str, s["grid"]["cells"])), sys.argv[3],
                                    s["simulated_time"], s["steps"], wall, sys.argv[4]))
PY
  done
  awk -F, 'NR == 1 { print "| mu_S (Pa) | cells | ranks | end time (s) | steps | wall (s) | started (UTC) |"; print "|---|---|---|---|---|---|---|"; next }
           { printf "| %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7 }' "$out/runs.csv" > "$out/runs.md"
  cat "$out/runs.md"
}

study_main() {
  study_parse "$@"
  study_setup
  study_runs
}
