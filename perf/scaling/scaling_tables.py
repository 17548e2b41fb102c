"""The tables of the scaling study (perf/scaling/run.py): Poisson iterations and their fits, the
step split, MPI strong scaling and the cost model, from the CSVs the parts wrote."""
import os
import re
import subprocess

from scaling_common import (CONSERVATIVE_FIELDS, GHOST, HALO_FIELDS, HALO_KIND, NESTED, SCENES, TOP_STAGES, VOIGT,
                    best_rounds, cells_of, fit, read_csv, write_csv)


def poisson_tables(out):
    rows = read_csv(os.path.join(out, "poisson.csv"))
    L = ["### Poisson: iterations and time against n (cavity n^3, tolerance 1e-8, 1 rank)", "",
         "Step 1 starts from x0 = 0; at step M the same right-hand side is solved twice: warm (x0 = the "
         "previous step's increment, what a run does) and cold (x0 = 0). Set-up: matrix refill + "
         "preconditioner compute (a run repeats it every step in which the density changes).", "",
         "| n | operator | pc | step 1 its | step 1 s | step M | warm its | warm s | cold its | cold s | s/it (warm) | set-up s |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        its = float(r["warm_its"])
        L.append("| %s | %s | %s | %s | %.3g | %s | %s | %.3g | %s | %.3g | %.2e | %.3g |" % (
            r["n"], r["operator"], r["preconditioner"], r["cold1_its"], float(r["cold1_s"]), r["step"], r["warm_its"],
            float(r["warm_s"]), r["cold_its"], float(r["cold_s"]), float(r["warm_s"]) / its if its else float("nan"),
            float(r["setup_s"])))
    fits = []
    L += ["", "Fits its = C n^alpha (least squares in log-log over all n; 'large n': the three largest) "
          "and time per solve = C' n^beta (cells = n^3: beta = 3 is linear in the cells):", "",
          "| operator | pc | start | n range | alpha | alpha (large n) | C | beta (time) |",
          "|---|---|---|---|---|---|---|---|"]
    for op in ["approximate", "exact"]:
        for pc in ["sgs", "multigrid"]:
            sel = [r for r in rows if r["operator"] == op and r["preconditioner"] == pc]
            if len(sel) < 2:
                continue
            ns = [int(r["n"]) for r in sel]
            for start, key in [("cold (step 1)", "cold1"), ("warm (step M)", "warm"), ("cold (step M)", "cold")]:
                its = [float(r[key + "_its"]) for r in sel]
                secs = [float(r[key + "_s"]) for r in sel]
                a, c = fit(ns, its)
                a3, _ = fit(ns[-3:], its[-3:])
                b, _ = fit(ns, secs)
                fits.append({"operator": op, "preconditioner": pc, "start": key, "alpha": a, "alpha_large": a3,
                             "C": c, "beta": b, "nmin": min(ns), "nmax": max(ns)})
                L.append("| %s | %s | %s | %d-%d | %.2f | %.2f | %.3g | %.2f |" % (op, pc, start, min(ns), max(ns),
                                                                                 a, a3, c, b))
    write_csv(os.path.join(out, "poisson_fits.csv"), fits)
    plot_poisson(rows, out)
    return L, fits


def plot_poisson(rows, out):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    for op, ls in [("approximate", "-"), ("exact", "--")]:
        for pc, col in [("sgs", "C0"), ("multigrid", "C3")]:
            sel = [r for r in rows if r["operator"] == op and r["preconditioner"] == pc]
            if not sel:
                continue
            ns = [int(r["n"]) for r in sel]
            for ax, key in [(axs[0], "its"), (axs[1], "s")]:
                ax.plot(ns, [float(r["cold1_" + key]) for r in sel], ls, color=col, marker="o",
                        label="%s, %s, cold (step 1)" % (op, pc))
                ax.plot(ns, [float(r["warm_" + key]) for r in sel], ls, color=col, marker="x", alpha=0.6,
                        label="%s, %s, warm (step M)" % (op, pc))
    from matplotlib.ticker import NullFormatter, ScalarFormatter
    allns = sorted({int(r["n"]) for r in rows})
    for ax, yl in [(axs[0], "CG iterations (tol 1e-8)"), (axs[1], "seconds per solve")]:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(allns)
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("n (cavity n^3)")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
    axs[1].legend(fontsize=7, loc="lower right", framealpha=0.8)
    fig.suptitle("Poisson: SGS-CG vs multigrid-CG (MueLu), 7-point (solid) and 27-point (dashed) operator")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "poisson_iterations.png"), dpi=110)
    plt.close(fig)


def step_tables(out):
    rows = read_csv(os.path.join(out, "step_split.csv"))
    L = ["### A whole step split by stage and by effect (1 rank)", "",
         "Seconds per step from runs of 1 and 1 + N steps (the difference: the first step's one-off work left "
         "out). Stages: `stress` and `forces` run inside `momentum` (once per Runge-Kutta substage), shown "
         "indented and not added again; `momentum` also holds the Poisson matrix refill and preconditioner "
         "set-up when the density changed (every step here). Effects: `navier_stokes` without the other "
         "effects' nested stress/forces tasks (summary.json counts those in both). 'other' = wall - stages "
         "(dt, blow-up checks, time series). 'Poisson solve' and 'halo' are parts of the stages above.", ""]
    for r in rows:
        g = lambda k: float(r.get(k) or 0)
        wall = g("wall")
        top = sum(g("stage:" + s) for s in TOP_STAGES)
        L += ["#### %s, %s cells%s, %s steps: %.3g s/step, %.3g cell-steps/s, %.1f Poisson its/step" % (
            r["scene"], r["cells"], ", `%s`" % r["variant"] if r.get("variant") else "", r["steps"], wall,
            cells_of(r["cells"]) / wall if wall else 0, g("poisson_its")), "",
              "| stage | s/step | share |  | effect | s/step | share |", "|---|---|---|---|---|---|---|"]
        srows = []
        for s in ["properties", "advection", "momentum", "stress", "forces", "projection", "corrections",
                  "diagnostics"]:
            v = g("stage:" + s)
            srows.append(("&nbsp;&nbsp;(in momentum) " + s if s in NESTED else s, v))
        srows.append(("other", wall - top))
        srows.append(("of which Poisson solve", g("poisson_s")))
        srows.append(("of which halo exchange", g("halo_s")))
        order = ["navier_stokes", "gravity", "obstacles", "level_set", "reinit", "elasticity"]
        effs = [k[7:] for k in r if k.startswith("effect:") and r[k] not in ("", None)]
        erows = []
        for e in sorted(effs, key=lambda e: order.index(e) if e in order else 99):
            v = g("effect:" + e)
            if e == "navier_stokes":  # momentum's time includes the nested stress/forces tasks
                v -= g("stage:stress") + g("stage:forces")
            erows.append((e, v))
        for i in range(max(len(srows), len(erows))):
            a = srows[i] if i < len(srows) else ("", None)
            b = erows[i] if i < len(erows) else ("", None)
            fa = ("%.3g" % a[1], "%.1f %%" % (100 * a[1] / wall)) if a[1] is not None else ("", "")
            fb = ("%.3g" % b[1], "%.1f %%" % (100 * b[1] / wall)) if b[1] is not None else ("", "")
            L.append("| %s | %s | %s |  | %s | %s | %s |" % (a[0], fa[0], fa[1], b[0], fb[0], fb[1]))
        L.append("")
    return L


def mpi_tables(out, cores):
    rows = best_rounds(read_csv(os.path.join(out, "mpi.csv")))
    L = ["### MPI strong scaling (the machine has %d cores: 4 ranks are oversubscribed)" % cores, "",
         "Seconds per step (runs of 1 and 1 + N steps, differenced; the best of the rounds per rank count); "
         "rank 0's split: halo = `Halo::exchange` (pack, MPI_Sendrecv, unpack, all fields, all stages), "
         "Poisson = the CG solves (Belos + preconditioner, Tpetra's own communication inside), "
         "kernels = the rest (every other kernel, reductions, matrix refill and preconditioner set-up).", "",
         "| scene | ranks | decomposition | s/step | speed-up | efficiency | halo s | Poisson s | kernels s | halo % | Poisson % | kernels % | Poisson its | halo MB/step (rank 0) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    base = {}
    for r in rows:
        w, ranks = float(r["wall"]), int(r["ranks"])
        if ranks == 1:
            base[r["scene"]] = w
        b = base.get(r["scene"], float("nan"))
        h, p = float(r["halo_s"]), float(r["poisson_s"])
        k = w - h - p
        L.append("| %s %s | %d | %s | %.3g | %.2f | %.0f %% | %.3g | %.3g | %.3g | %.0f %% | %.0f %% | %.0f %% | %.1f | %.2f |" % (
            r["scene"], r["cells"], ranks, r["decomposition"], w, b / w, 100 * b / w / ranks, h, p, k, 100 * h / w,
            100 * p / w, 100 * k / w, float(r["poisson_its"]), float(r["halo_bytes"]) / 1e6))
    return L


# ---------------------------------------------------------------- cost model
def local_cells(cells, dec):
    return [c // d for c, d in zip(cells, dec)]


def halo_bytes_model(F, ln, nbrs):
    """Bytes sent by one rank per step: per decomposed axis d and neighbour, F scalar fields,
    slabs GHOST thick over the full extent (ghosts included, ln + 2 GHOST + 1) of the other axes."""
    ext = [l + 2 * GHOST + 1 for l in ln]
    tot = 0
    for d in range(3):
        a, b = [x for x in range(3) if x != d]
        tot += 8 * F * GHOST * ext[a] * ext[b] * nbrs[d]
    return tot


def voigt_check(scene, cells):
    return subprocess.run([VOIGT, "check", SCENES[scene], "--set", "domain.cells=[%s]" % ",".join(map(str, cells))],
                          capture_output=True, text=True, check=True).stdout


def halo_fields(scene, cells):
    """F for a scene: the count above, + 2 when `voigt check` says the momentum is conservative."""
    F = HALO_FIELDS[HALO_KIND[scene]]
    if "conservative rho u" in voigt_check(scene, cells):
        F += CONSERVATIVE_FIELDS
    return F


def field_components(scene, cells):
    """Doubles and ints per array point, from the field list of `voigt check`."""
    nd = ni = 0
    for name, comps in re.findall(r"^\s+(\w+) \((?:cell|node), (\d+), \w+\)", voigt_check(scene, cells), re.M):
        if name == "fix_mask":  # IntField (src/effects/navier_stokes/setup.cpp)
            ni += int(comps)
        else:
            nd += int(comps)
    return nd, ni


def model_tables(out, fits):
    L = ["### Cost model for clusters, checked against the measurements", ""]
    # -- halo
    L += ["**Halo bytes per step per rank.** `Halo::exchange` sends, per decomposed axis and neighbour, a "
          "slab %d cells thick over the full extent (ghosts included) of the other two axes, for every field "
          "exchanged: B = 8 F %d sum_d k_d (m_a + 5)(m_b + 5) bytes per step, m the subdomain's cells per "
          "axis, k_d its neighbours along d (0-2), F the scalar fields exchanged per step, counted in the "
          "code: F = %d for single-phase Navier-Stokes (momentum 2 x u, projection u, dp, p, u) and F = %d "
          "for the paper's scenes (+ rho and the coefficients for the density change, level set 6, "
          "elasticity 24, reinit 7), + %d with the conservative momentum form (`advection.momentum: auto` "
          "picks it when the phases' densities differ: node density r0 and stage density r1). For a cube "
          "subdomain m^3 inside a 3-D decomposition (k = 2 on all axes): B ~ 96 F m^2 bytes, i.e. "
          "96 F / m bytes per cell and step (F = 57, m = 64: 86 bytes per cell; m = 32: 171)."
          % (GHOST, GHOST, HALO_FIELDS["cavity"], HALO_FIELDS["two_phase_elastic"], CONSERVATIVE_FIELDS), "",
          "| run | ranks | rank 0 subdomain | neighbours (x, y, z) | F | predicted MB/step | measured MB/step | ratio |",
          "|---|---|---|---|---|---|---|---|"]
    checks = []
    mpi = os.path.join(out, "mpi.csv")
    if os.path.exists(mpi):
        for r in best_rounds(read_csv(mpi)):
            if int(r["ranks"]) == 1:
                continue
            cells = [int(x) for x in r["cells"].split("x")]
            dec = [int(x) for x in r["decomposition"].split("x")]
            ln = local_cells(cells, dec)
            nbrs = [1 if d > 1 else 0 for d in dec]  # rank 0 sits in the low corner: one neighbour per split axis
            F = halo_fields(r["scene"], cells)
            pred = halo_bytes_model(F, ln, nbrs)
            meas = float(r["halo_bytes"])
            checks.append(meas / pred)
            L.append("| %s %s | %s | %s | %s | %d | %.3f | %.3f | %.3f |" % (
                r["scene"], r["cells"], r["ranks"], "x".join(map(str, ln)), ",".join(map(str, nbrs)), F, pred / 1e6,
                meas / 1e6, meas / pred))
    # -- Poisson iterations
    L += ["", "**Poisson iterations as the grid grows** (its = C n^alpha from the fits above, cold start, "
          "7-point operator; the 27-point one below). Check: the fit over all but the largest n predicts the "
          "largest.", "",
          "| operator | pc | alpha | n = 128 | n = 256 | n = 512 | n = 1024 | fit without largest n: predicted its at largest n | measured |",
          "|---|---|---|---|---|---|---|---|---|"]
    prow = read_csv(os.path.join(out, "poisson.csv")) if os.path.exists(os.path.join(out, "poisson.csv")) else []
    for f in fits:
        if f["start"] != "cold1":
            continue
        sel = [r for r in prow if r["operator"] == f["operator"] and r["preconditioner"] == f["preconditioner"]]
        ns = [int(r["n"]) for r in sel]
        its = [float(r["cold1_its"]) for r in sel]
        a2, c2 = fit(ns[:-1], its[:-1])
        L.append("| %s | %s | %.2f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |" % (
            f["operator"], f["preconditioner"], f["alpha"], *[f["C"] * n ** f["alpha"] for n in [128, 256, 512, 1024]],
            c2 * ns[-1] ** a2, its[-1]))
    # -- memory
    L += ["", "**Memory per cell.** Fields: every declared field is a full array with its ghost layers, "
          "(m_x + 5)(m_y + 5)(m_z + 5) points, 8 bytes per double component, 4 for the int `fix_mask`: "
          "bytes per owned cell = (8 D + 4 I) prod (m_d + 5) / prod m_d, with D and I counted from the field "
          "list of `voigt check` (what summary.json's `memory_bytes_per_rank` reports). The process holds "
          "more: the Poisson matrix (CRS, 12 bytes per non-zero + 8 per row), about 6 solver vectors "
          "(8 bytes per cell each), reinit's 3 scratch arrays (full arrays, when reinit is on), the "
          "multigrid hierarchy, Tpetra's graph and import buffers and the band lists (not modelled), the "
          "libraries' baseline (the RSS of an 8^3 cavity run), and a second copy of every field for the "
          "last good state (`checkpoint.last_good`, default on in `voigt run`). Predicted RSS = baseline + "
          "2 x fields + matrix + vectors + scratch; the rest of the measured RSS is the unmodelled part.", "",
          "| run | D + I | fields B/cell predicted | fields B/cell (summary.json) | predicted RSS MB | max RSS MB | (RSS - baseline) B/cell | unmodelled B/cell |",
          "|---|---|---|---|---|---|---|---|"]
    sp = os.path.join(out, "step_split.csv")
    if os.path.exists(sp):
        for r in read_csv(sp):
            cells = [int(x) for x in r["cells"].split("x")]
            nd, ni = field_components(r["scene"], cells)
            ncell = cells[0] * cells[1] * cells[2]
            pts = 1
            for c in cells:
                pts *= c + 2 * GHOST + 1
            pred = (8 * nd + 4 * ni) * pts / ncell
            meas = float(r["memory_bytes_per_rank"]) / ncell
            base = float(r.get("baseline_rss_kb") or 0) * 1024
            extra = 12 * float(r["matrix_nonzeros"]) + 8 * ncell + 6 * 8 * ncell + 3 * 8 * pts
            rss = float(r["rss_kb"]) * 1024
            predrss = base + 2 * float(r["memory_bytes_per_rank"]) + extra
            L.append("| %s %s%s | %d + %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |" % (
                r["scene"], r["cells"], " (%s)" % r["variant"] if r.get("variant") else "", nd, ni, pred, meas, predrss / 1e6, rss / 1e6, (rss - base) / ncell,
                (rss - predrss) / ncell))
    L.append("")
    return L, checks
