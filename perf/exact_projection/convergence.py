#!/usr/bin/python3
"""Did every projection of a run converge, and what did it leave? (issue 19)

    perf/exact_projection/convergence.py RUN_DIR [RUN_DIR ...]

One line per run from its timeseries.csv: steps, the last t, CG iterations a step (mean, max), the
largest relative residual (<= the tolerance on every step when every solve converged; a capped
solve shows as a larger one, and in summary.json `poisson.unconverged`), and max |div u| after the
projection over max |div u| before it (median and max over steps).
"""
import os
import statistics
import sys

from voigt_post import series


def line(d):
    c = series.timeseries(d)
    its, res = c["poisson_iterations"], c["poisson_residual"]
    ratio = [a / b for a, b in zip(c["max_divergence"], c["max_divergence_predicted"]) if b > 0]
    unconv = series.summary(d, {}).get("poisson", {}).get("unconverged", "?")
    return ("%s: %d steps to t = %.4g s, CG its mean %.1f max %d, residual max %.2e, unconverged %s, "
            "max div after/before median %.2e max %.2e" % (os.path.basename(os.path.normpath(d)), len(its), c["t"][-1],
                                                            statistics.mean(its), max(its), max(res), unconv,
                                                            statistics.median(ratio), max(ratio)))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for d in sys.argv[1:]:
        print(line(d))
