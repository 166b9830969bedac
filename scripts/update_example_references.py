#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes tests/regression/data/example_references.json: what each bundled example gives
when run for its first few steps (`nmm run CASE --steps N`), for the regression test
`ExampleReference.*` (tests/regression/example_references_test.cpp), which runs the same
and compares.

Run it after a change that is meant to change results, from the repository root:

    python3 scripts/update_example_references.py [path/to/nmm]

and say in the commit which examples moved and why. The list of cases is here (EXAMPLES):
a case that does not complete its steps is refused, so that no failure is stored as the
reference. Examples 05 and 06 are left out: one step of their fine meshes takes 6-12 s, and
their right answers are checked by the slow tests against closed forms. Example 02 is for
`nmm mesh`: its one static step with contact completes only after all ten cuts
(max_step_cuts), too close to the edge to store.
"""

import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "regression", "data", "example_references.json")

# (case file under examples/, steps): about a second of run each at most.
EXAMPLES = [
    ("01_cantilever/case.toml", 1),
    ("03_block_on_incline/case.toml", 50),
    ("04_dam_on_jointed_foundation/case.toml", 12),
    ("07_gravity_column/case.toml", 1),
    ("08_multi_block_slope/case.toml", 50),
    ("09_block_arch/case.toml", 30),
    ("10_rotating_triangle/case.toml", 5),
    ("10_rotating_triangle/case_vem.toml", 5),
    ("11_block_on_ramp/case_phi30.toml", 10),
    ("11_block_on_ramp/case_static_phi70.toml", 10),
    ("12_tunnel_36_blocks/case_phi30.toml", 10),
    ("12_tunnel_36_blocks/case_phi0.toml", 10),
    ("13_block_wall_70/case.toml", 20),
    ("13_block_wall_70/case_vem.toml", 20),
    ("14_single_joint_in_triangle/case.toml", 50),
    ("15_circular_sliding/case.toml", 20),
    ("16_jointed_double_cantilever/case.toml", 5),
]


def blas_environment():
    """OpenBLAS's Haswell kernels on any CPU with AVX2, as the test uses
    (tests/regression/example_references_test.cpp says why)."""
    env = dict(os.environ)
    with open("/proc/cpuinfo", encoding="utf-8") as f:
        if " avx2" in f.read():
            env["OPENBLAS_CORETYPE"] = "Haswell"
    return env


def run(nmm, case, steps, out):
    path = os.path.join(ROOT, "examples", case)
    done = subprocess.run([nmm, "run", path, "--steps", str(steps), "-o", out, "--quiet"],
                          capture_output=True, text=True, check=False, env=blas_environment())
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    if done.returncode != 0 or summary["status"] != "completed" or summary["steps"] != steps:
        sys.exit(f"{case}: did not complete {steps} steps (exit {done.returncode}): "
                 f"{summary['status']}")
    return {
        "case": case,
        "steps": steps,
        "time": summary["time"],
        "step_cuts": summary["step_cuts"],
        "max_penetration": summary.get("max_penetration", 0.0),
        "monitors": summary["monitors"],
    }


def main():
    nmm = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "release", "nmm")
    references = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, (case, steps) in enumerate(EXAMPLES):
            references.append(run(nmm, case, steps, os.path.join(tmp, str(k))))
            print(f"{case}: {steps} steps, {references[-1]['step_cuts']} cuts")
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w", encoding="utf-8") as f:
        json.dump({"generated_by": "scripts/update_example_references.py",
                   "examples": references}, f, indent=1)
        f.write("\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
