# SPDX-License-Identifier: MIT
"""One run of nmm for the benchmark scripts (imported by bench/block_bench.py and
bench/stress.py)."""
import csv
import json
import os
import shutil
import subprocess
import sys
import time


def run_nmm(nmm, case, out, who, threads=None, extra=()):
    """Runs `nmm run CASE -o OUT --quiet [EXTRA...]` into a fresh @p out.

    Returns (summary.json as a dict, the rows of history.csv with float values, wall
    seconds). Exits naming @p who (the calling script) and the command when nmm wrote no
    summary.json."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    command = [nmm] + (["--threads", str(threads)] if threads else [])
    command += ["run", case, "-o", out, "--quiet"] + list(extra)
    start = time.monotonic()
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    elapsed = time.monotonic() - start
    summary_file = os.path.join(out, "summary.json")
    if not os.path.exists(summary_file):
        sys.exit("%s: %s wrote no summary.json:\n%s" % (who, " ".join(command), done.stdout))
    with open(summary_file) as f:
        summary = json.load(f)
    rows = []
    history = os.path.join(out, "history.csv")
    if os.path.exists(history):
        with open(history) as f:
            rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    return summary, rows, elapsed
