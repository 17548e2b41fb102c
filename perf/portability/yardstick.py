#!/usr/bin/env python3
"""The device's memory-bandwidth ceiling measured outside Kokkos (issue 25): STREAM copy and
triad through PyTorch on the GPU, timed with CUDA events (best of N after warm-up), bytes as
STREAM counts them (copy 2 x 8 B, triad 3 x 8 B per element). device-check runs it on the
device machine, whose python3 holds PyTorch, so that the kernels' rates can be read against
what the card delivers as well as against Kokkos's own STREAM.

    python3 perf/portability/yardstick.py [MB per array, default 1000] [repeats, default 200]
"""
import json
import sys

try:
    import torch
except ImportError:
    print(json.dumps({"error": "no torch"}))
    sys.exit(0)
if not torch.cuda.is_available():
    print(json.dumps({"error": "no CUDA device"}))
    sys.exit(0)

mb = float(sys.argv[1]) if len(sys.argv) > 1 else 1000.0
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 200
n = int(mb * 1e6 / 8)
a = torch.rand(n, dtype=torch.float64, device="cuda")
b = torch.rand(n, dtype=torch.float64, device="cuda")
c = torch.rand(n, dtype=torch.float64, device="cuda")


def best(f):
    for _ in range(10):  # warm-up: clocks ramp, allocator settles
        f()
    torch.cuda.synchronize()
    ts = []
    for _ in range(reps):
        e0, e1 = torch.cuda.Event(enable_timing=True), torch.cuda.Event(enable_timing=True)
        e0.record()
        f()
        e1.record()
        e1.synchronize()
        ts.append(e0.elapsed_time(e1) / 1e3)
    return min(ts)


t_copy = best(lambda: c.copy_(a))
t_triad = best(lambda: torch.add(b, c, alpha=3.0, out=a))
print(json.dumps({
    "device": torch.cuda.get_device_name(0), "torch": torch.__version__, "mb_per_array": mb,
    "repeats": reps, "copy_GBs": 16 * n / t_copy / 1e9, "triad_GBs": 24 * n / t_triad / 1e9,
}))
