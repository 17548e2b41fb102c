#!/usr/bin/env python3
"""Memory traffic and kernel launches of each pipeline stage, counted by the code itself
(issue 55): `voigt` under VOIGT_HOST_TOUCH_CHECK=pages (src/core/host_access.hpp) counts,
per stage, the top-level Kokkos kernels and the 4 KiB pages each kernel touched of the
arrays Voigt owns (fields and device scratch; not Tpetra's or Belos' vectors). Two runs of
N and 2N steps, differenced, give the per-step work without the set-up. From it, a floor
for a GPU step: bytes / bandwidth + launches x latency (stated, not measured).

    perf/portability/stage_work.py [--voigt build/voigt] [--cells 32] [--steps 3]
        [--bandwidth 3.35e12] [--launch 5e-6] [--out perf/portability/results/stage_work.md]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
# name, scene, extra --set values (the scenes' own defaults otherwise)
CASES = [
    ("falling_block", "cases/falling_block/falling_block.yaml", []),
    ("dam_break", "perf/scenes/dam_break.yaml", []),
    ("cavity (multigrid)", "perf/scaling/cavity.yaml", ["projection.preconditioner=multigrid"]),
]


def run(voigt, scene, cells, steps, sets, out):
    cmd = [voigt, "run", os.path.join(ROOT, scene), "-o", out, "--overwrite", "--steps", str(steps),
           "--set", f"domain.cells=[{cells},{cells},{cells}]", "--set", "output.enabled=false", "--set", "probes=[]"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, VOIGT_HOST_TOUCH_CHECK="pages")
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--voigt", default=os.path.join(ROOT, "build", "voigt"))
    ap.add_argument("--cells", type=int, default=32)
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--bandwidth", type=float, default=3.35e12, help="bytes/s (H100 SXM HBM3: 3.35e12)")
    ap.add_argument("--launch", type=float, default=5e-6, help="seconds a kernel launch")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    n, cells = a.steps, a.cells ** 3
    lines = [f"Per step, {a.cells}^3 cells, one rank, counted by `VOIGT_HOST_TOUCH_CHECK=pages` (runs of {n} and "
             f"{2 * n} steps differenced). Bytes: pages of Voigt's own arrays each kernel touched (4 KiB "
             "granularity, ghosts included; Tpetra's and Belos' vectors not seen). GPU floor: bytes / "
             f"{a.bandwidth / 1e12:.2f} TB/s + launches x {a.launch * 1e6:.0f} us (stated, not measured).", ""]
    for name, scene, sets in CASES:
        with tempfile.TemporaryDirectory() as tmp:
            s1 = run(a.voigt, scene, a.cells, n, sets, os.path.join(tmp, "a"))
            s2 = run(a.voigt, scene, a.cells, 2 * n, sets, os.path.join(tmp, "b"))
        w1, w2 = s1["host_touch_check"]["per_stage"], s2["host_touch_check"]["per_stage"]
        its = s2["poisson"].get("iterations_mean", 0)
        lines += [f"**{name}** ({scene}; CG iterations a step {its:.1f})", "",
                  "| stage | kernels/step | bytes/cell-step | floor at 128^3 (ms) |", "|---|---:|---:|---:|"]
        tk = tb = 0.0
        for st in sorted(w2, key=lambda k: -w2[k].get("bytes_touched", 0)):
            k = (w2[st]["kernels"] - w1.get(st, {}).get("kernels", 0)) / n
            b = (w2[st].get("bytes_touched", 0) - w1.get(st, {}).get("bytes_touched", 0)) / n / cells
            if k == 0 and b == 0:
                continue
            tk, tb = tk + k, tb + b
            floor = (b * 128 ** 3 / a.bandwidth + k * a.launch) * 1e3
            lines.append(f"| {st} | {k:.0f} | {b:.0f} | {floor:.2f} |")
        floor = (tb * 128 ** 3 / a.bandwidth + tk * a.launch) * 1e3
        lines += [f"| **step** | **{tk:.0f}** | **{tb:.0f}** | **{floor:.2f}** |", ""]
    text = "\n".join(lines)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
