#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the VEM-DDA paper's four examples (examples/10-13) with DDA blocks and with VEM
blocks, and prints a Markdown table of steps, step cuts and wall time side by side (the
table in docs/benchmarks.md, "The VEM-DDA paper's examples"; issue 6).

    python3 bench/vem_dda_examples.py [path/to/nmm] [--repeat N]

Each case runs N times (default 3) and the fastest wall time is kept (the others are
disturbed by whatever else the machine does). The VEM variant of a case is its own
`case_vem.toml` when the example has one, else the case with the one word of its block
material changed (`model = "dda"` on the line whose comment offers "vem").
"""

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (example folder, DDA case, VEM case or None to derive it)
CASES = [
    ("10_rotating_triangle", "case.toml", "case_vem.toml"),
    ("11_block_on_ramp", "case_phi15.toml", None),
    ("11_block_on_ramp", "case_phi30.toml", None),
    ("11_block_on_ramp", "case_phi40.toml", None),
    ("11_block_on_ramp", "case_static_phi70.toml", "case_static_phi70_vem.toml"),
    ("12_tunnel_36_blocks", "case_phi30.toml", None),
    ("12_tunnel_36_blocks", "case_phi0.toml", None),
    ("13_block_wall_70", "case.toml", "case_vem.toml"),
]

# The paper's run times, where it gives them (section 5.4).
PAPER = {("13_block_wall_70", "case.toml"): "DDA 1.606 s, VEM-DDA 1.943 s"}


def vem_variant(folder, case):
    """A temporary VEM copy of examples/FOLDER/CASE next to it (its geometry is relative)."""
    path = os.path.join(ROOT, "examples", folder, case)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text, n = re.subn(r'^model = "dda"(?=[^\n]*"vem")', 'model = "vem"', text, count=1,
                      flags=re.M)
    if n != 1:
        sys.exit(f"{path}: no `model = \"dda\"` line offering \"vem\"")
    handle, name = tempfile.mkstemp(prefix=".bench_vem_", suffix=".toml",
                                    dir=os.path.dirname(path))
    with os.fdopen(handle, "w", encoding="utf-8") as f:
        f.write(text)
    return name


def run(nmm, case_file, repeat):
    best = None
    with tempfile.TemporaryDirectory() as out:
        for _ in range(repeat):
            done = subprocess.run([nmm, "run", case_file, "-o", out, "--quiet"],
                                  capture_output=True, text=True, check=False)
            with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
                summary = json.load(f)
            if done.returncode != 0:
                return f"failed: {summary['status'][:60]}"
            if best is None or summary["wall_seconds"] < best["wall_seconds"]:
                best = summary
    return f"{best['steps']} / {best['step_cuts']} / {best['wall_seconds']:.2f} s"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("nmm", nargs="?", default=os.path.join(ROOT, "build", "release", "nmm"))
    parser.add_argument("--repeat", type=int, default=3, help="runs per case (fastest kept)")
    args = parser.parse_args()
    print("| example | case | DDA: steps / cuts / wall | VEM: steps / cuts / wall | paper |")
    print("| --- | --- | --- | --- | --- |")
    for folder, case, vem_case in CASES:
        dda = run(args.nmm, os.path.join(ROOT, "examples", folder, case), args.repeat)
        if vem_case:
            vem = run(args.nmm, os.path.join(ROOT, "examples", folder, vem_case), args.repeat)
        else:
            variant = vem_variant(folder, case)
            try:
                vem = run(args.nmm, variant, args.repeat)
            finally:
                os.remove(variant)
        print(f"| {folder} | {case} | {dda} | {vem} | {PAPER.get((folder, case), '')} |",
              flush=True)


if __name__ == "__main__":
    main()
