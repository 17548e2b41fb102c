#!/usr/bin/env bash
# Runs the README's walk-through ("Your first scene") as written: the scene block after
# <!-- walkthrough: scene FILE --> is saved as FILE, the commands block after
# <!-- walkthrough: commands --> is run line by line in a fresh directory where build/ is this
# build and scripts/ the repository's. Then checks what the README says the commands leave.
#   walkthrough_test.sh REPO BUILD_DIR
set -euo pipefail
repo=$1 bdir=$2
readme="$repo/README.md"
work="$bdir/walkthrough"
rm -rf "$work" && mkdir -p "$work"
fail() { echo "walkthrough: FAIL: $*" >&2; exit 1; }

# The fenced block that follows the marker line $1 (without the fences).
block() {
  awk -v m="$1" 'index($0, m) == 1 { found = 1; next }
                 found && /^```/ { if (inside) exit; inside = 1; next }
                 inside { print }' "$readme"
}
scene_file=$(grep -o '<!-- walkthrough: scene [^ ]* -->' "$readme" | awk '{print $4}')
[ -n "$scene_file" ] || fail "README.md has no '<!-- walkthrough: scene FILE -->' marker"
block "<!-- walkthrough: scene $scene_file -->" > "$work/$scene_file"
block "<!-- walkthrough: commands -->" > "$work/commands.sh"
[ -s "$work/$scene_file" ] || fail "empty scene block"
[ "$(grep -c . "$work/commands.sh")" -ge 4 ] || fail "fewer than 4 commands in the commands block"

ln -s "$bdir" "$work/build"
ln -s "$repo/scripts" "$work/scripts"
cd "$work"
# As root, Open MPI needs --allow-run-as-root (the README says so); 2 ranks may oversubscribe CI.
{ echo 'set -euxo pipefail'
  echo 'mpirun() { command mpirun --allow-run-as-root --oversubscribe "$@"; }'
  cat commands.sh; } > run.sh
bash run.sh > run.log 2>&1 || { tail -40 run.log; fail "a command of the walk-through failed (log: $work/run.log)"; }
grep -q "^estimate" run.log || fail "'voigt check --estimate' printed no estimate"
grep -q "wall time" run.log || fail "the estimate has no wall time"

out=output/ball
[ -s "$out/summary.json" ] || fail "no $out/summary.json"
[ -s "$out/fields.xdmf" ] || fail "no $out/fields.xdmf"
head -c 8 output/ball.png | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" || fail "output/ball.png is not a PNG"
[ "$(stat -c %s output/ball.png)" -gt 10000 ] || fail "output/ball.png is suspiciously small"

# What the README says of the run: the ball sinks. Bounds from the scene's numbers, not tuned:
# - it sinks more than 2 smoothing widths (2 x 2 cells x 2.5 mm = 1 cm) by t = 0.3 s: less
#   would be motion within the smeared interface, not of the ball;
# - it never falls faster than without any fluid force but buoyancy: drop <= g (1 - rho_w /
#   rho_b) t^2 / 2 = 3.27 t^2 / 2 m (drag and added mass only slow a body falling from rest).
python3 - "$out" <<'PY'
import csv, json, sys
out = sys.argv[1]
s = json.load(open(out + "/summary.json"))
assert s["state"] == "finished", "summary.json state: %s" % s["state"]
rows = list(csv.DictReader(open(out + "/timeseries.csv")))
y0 = 0.06
g_eff = 9.81 * (1 - 1000 / 1500)
for r in rows:
    t, drop = float(r["t"]), y0 - float(r["solid_cy"])
    assert drop <= 0.5 * g_eff * t * t + 2.5e-4, "t = %g: fell %g m, faster than buoyant free fall" % (t, drop)
r3 = min(rows, key=lambda r: abs(float(r["t"]) - 0.3))
assert y0 - float(r3["solid_cy"]) > 0.01, "the ball sank only %g m by t = 0.3 s" % (y0 - float(r3["solid_cy"]))
print("walkthrough: %d steps, ball sank %.4f m by t = %.3g s, lowest centroid %.4f m"
      % (s["steps"], y0 - float(r3["solid_cy"]), float(r3["t"]), min(float(r["solid_cy"]) for r in rows)))
PY
echo "walkthrough: every command of README.md's walk-through ran ($work)"
