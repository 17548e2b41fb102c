#!/usr/bin/env python3
"""Floating-point operations per cell of each perf_kernels family, counted by callgrind.

perf/flops/run drives it; see perf/flops/README.md. Reads the callgrind dumps that
perf_kernels writes under valgrind (one per benchmark loop, named "<benchmark>
iterations=<n>", bench_kernels.cpp loop()), takes every instruction's execution count
(--dump-instr=yes: addresses relative to their object file, as objdump prints them),
decodes each executed instruction with objdump, and counts:
  flops  add, sub, mul, div, min, max, sqrt: 1 per lane; fused multiply-add: 2 per lane;
         lanes from the register (xmm 2 doubles, ymm 4, zmm 8; single precision twice)
  packed the share of those flops done by packed (SIMD) instructions: how vectorised it is
Combined with the native run's cell updates per second (perf_kernels --benchmark_format=json
at the same grid), it prints GFLOP/s and the fraction of the core's peak for the
instruction set the build uses.
"""
import argparse
import glob
import json
import re
import subprocess
import sys
from collections import defaultdict

ARITH = re.compile(r"^v?(add|sub|mul|div|min|max|sqrt)(p|s)([ds])$")
FMA = re.compile(r"^vf(n?m)(add|sub|addsub|subadd)(132|213|231)(p|s)([ds])$")


def lanes(operands, packed, prec):
    if not packed:
        return 1
    width = 512 if "zmm" in operands else 256 if "ymm" in operands else 128
    return width // (64 if prec == "d" else 32)


def classify(mnemonic, operands):
    """(flops, packed) of one instruction; (0, False) if it is not FP arithmetic."""
    m = ARITH.match(mnemonic)
    if m:
        packed = m.group(2) == "p"
        return lanes(operands, packed, m.group(3)), packed
    m = FMA.match(mnemonic)
    if m:
        packed = m.group(4) == "p"
        return 2 * lanes(operands, packed, m.group(5)), packed
    return 0, False


def parse_dump(path):
    """(name, iterations, {object: {address: Ir}}) of one callgrind dump (self costs only)."""
    name, iters = None, 1
    costs = defaultdict(lambda: defaultdict(int))
    ob = None
    skip_next = False
    with open(path) as f:
        for line in f:
            if line.startswith("desc: Trigger: Client Request: "):
                trig = line.split("Client Request: ", 1)[1].strip()
                m = re.match(r"(.*) iterations=(\d+)$", trig)
                if m:
                    name, iters = m.group(1), int(m.group(2))
            elif line.startswith("ob="):
                ob = line[3:].strip()
            elif line.startswith("calls="):
                skip_next = True  # the next cost line is the call's inclusive cost
            elif line.startswith("0x"):
                if skip_next:
                    skip_next = False
                    continue
                parts = line.split()
                costs[ob][int(parts[0], 16)] += int(parts[-1])
    return name, iters, costs


_disasm = {}


def disassemble(obj):
    """{address: (mnemonic, operands)} of an object file (objdump, cached)."""
    if obj not in _disasm:
        out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-M", "att", obj], capture_output=True,
                             text=True).stdout
        table = {}
        for line in out.splitlines():
            m = re.match(r"^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
            if m:
                table[int(m.group(1), 16)] = (m.group(2), m.group(3))
        _disasm[obj] = table
    return _disasm[obj]


def count(costs):
    r = {"ir": 0, "flops": 0, "packed_flops": 0, "fp_instr": 0, "unknown_ir": 0, "by_object": {}}
    for obj, addrs in costs.items():
        table = disassemble(obj) if obj and not obj.startswith("???") else {}
        fl = 0
        for a, ir in addrs.items():
            r["ir"] += ir
            ins = table.get(a)
            if ins is None:
                r["unknown_ir"] += ir
                continue
            f, packed = classify(*ins)
            if f:
                r["fp_instr"] += ir
                r["flops"] += f * ir
                fl += f * ir
                if packed:
                    r["packed_flops"] += f * ir
        r["by_object"][obj] = {"ir": sum(addrs.values()), "flops": fl}
    return r


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dumps", help="glob of callgrind dumps (e.g. 'dir/cg.out.*')")
    p.add_argument("--native", help="perf_kernels --benchmark_format=json output of the native run")
    p.add_argument("--ghz", type=float, required=True, help="core clock for the peak")
    p.add_argument("--flops-per-cycle", type=float, required=True, help="peak flops per cycle of the build's ISA")
    p.add_argument("--json", help="write the table as JSON here")
    a = p.parse_args()
    acc = defaultdict(lambda: {"iterations": 0, "ir": 0, "flops": 0, "packed_flops": 0, "fp_instr": 0,
                               "unknown_ir": 0})
    for path in sorted(glob.glob(a.dumps)):
        name, iters, costs = parse_dump(path)
        if name is None:
            continue
        c = count(costs)
        d = acc[name]
        d["iterations"] += iters
        for k in ("ir", "flops", "packed_flops", "fp_instr", "unknown_ir"):
            d[k] += c[k]
    native = {}
    if a.native:
        for b in json.load(open(a.native))["benchmarks"]:
            native[b["name"]] = b
    peak = a.ghz * a.flops_per_cycle
    rows = []
    print("| kernel family | flops / cell | packed share | instructions / cell | FP instr. share | cell updates/s "
          "| GFLOP/s | of peak (%.1f GFLOP/s) | of STREAM triad | bound by |" % peak)
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, d in acc.items():
        n = native.get(name, {})
        cells = n.get("cells")
        if not cells:
            print("%s: no native run with a 'cells' counter" % name, file=sys.stderr)
            continue
        per = cells * d["iterations"]
        fpc, ipc = d["flops"] / per, d["ir"] / per
        rate = n.get("items_per_second", 0)
        gf = fpc * rate / 1e9
        row = {"kernel": name, "flops_per_cell": fpc, "packed_share": d["packed_flops"] / max(d["flops"], 1),
               "instructions_per_cell": ipc, "fp_instruction_share": d["fp_instr"] / max(d["ir"], 1),
               "cell_updates_per_second": rate, "gflops": gf, "peak_fraction": gf / peak,
               "unknown_instruction_share": d["unknown_ir"] / max(d["ir"], 1),
               "triad_fraction": n.get("frac_triad", 0)}
        # What limits it, by the two yardsticks: >= 25 % of triad (memory), or
        # mostly packed arithmetic (compute, vectorised); else neither (gathers, latency).
        row["bound"] = ("memory" if row["triad_fraction"] >= 0.25 else
                        "compute, vectorised" if row["packed_share"] >= 0.5 else "scalar")
        rows.append(row)
        print("| %s | %.0f | %.2f | %.0f | %.2f | %.3g | %.2f | %.2f | %.2f | %s |" % (
            name, fpc, row["packed_share"], ipc, row["fp_instruction_share"], rate, gf, row["peak_fraction"],
            row["triad_fraction"], row["bound"]))
    if a.json:
        json.dump({"peak_gflops": peak, "ghz": a.ghz, "flops_per_cycle": a.flops_per_cycle, "rows": rows},
                  open(a.json, "w"), indent=1)


if __name__ == "__main__":
    main()
