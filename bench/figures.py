# SPDX-License-Identifier: MIT
"""Fits and pictures shared by the benchmark scripts (imported by bench/work_precision.py
and bench/scaling.py)."""
import math
import os
import shutil
import subprocess


def power_law(xs, ys):
    """Least-squares fit of log(y) = log(c) + p log(x): returns (p, c); (nan, nan) with fewer
    than two distinct x."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    if n < 2:
        return float("nan"), float("nan")
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((x - mx) ** 2 for x in lx)
    if not sxx > 0:
        return float("nan"), float("nan")
    p = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx
    return p, math.exp(my - p * mx)


def fit_slope(xs, ys):
    """Least-squares slope of log(y) against log(x)."""
    return power_law(xs, ys)[0]


def gnuplot(script, variables, png, who):
    """Runs gnuplot on @p script with the `name=value` strings @p variables set first (png
    among them); prints what happened, prefixed with @p who. Without gnuplot it says how to
    install it and draws nothing."""
    if not shutil.which("gnuplot"):
        print("%s: no gnuplot (apt-get install -y --no-install-recommends gnuplot-nox); %s not "
              "drawn" % (who, png))
        return False
    os.makedirs(os.path.dirname(os.path.abspath(png)), exist_ok=True)
    done = subprocess.run(["gnuplot", "-e", "; ".join(variables), script],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        print("%s: gnuplot failed on %s:\n%s" % (who, png, done.stdout))
        return False
    print("wrote %s" % png)
    return True
