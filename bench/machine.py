# SPDX-License-Identifier: MIT
"""What the benchmark scripts print about the machine they ran on (imported by
bench/block_bench.py and bench/work_precision.py)."""
import os
import platform


def load_average():
    """The 1-minute load average, or NaN where the system does not say."""
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def cpu_model():
    """The CPU's model name from /proc/cpuinfo, else what platform knows."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"
