"""The first solve in a process against the warm one, for each punch path.

Each case runs in a fresh Python process (its imports done before the
timing): its first solve on the paper's layer (V* 0.2, kw 1, nu 0.2,
P/(mu h) 0.002), which finds the critical speed, builds the kernel table and
any rule the path needs (the asymmetric table: 801 points of a parabola
shifted by 0.2 h), then the median of --repeat solves at other loads
(everything cached), and the median of --repeat solves at new speeds
V* = 0.21, 0.22, ... (a speed sweep's points: new end exponents, kernel
tables and rules). Prints first, warm, new-speed and their ratios, and the
machine's load average; never asserts a time.

    .venv/bin/python benchmarks/bench_first_call.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

CASES = {
    "cylinder": "dict(radius=100.0)",
    "cylinder, damping 0.5": "dict(radius=100.0, damping=0.5)",
    "cylinder, friction 0.3": "dict(radius=100.0, friction=0.3)",
    "flat 0.5, friction 0.3": "dict(profile=mp.Flat(0.5), friction=0.3)",
    "rounded flat 0.3/100": "dict(profile=mp.RoundedFlat(0.3, 100.0))",
    "rounded flat, friction 0.3": (
        "dict(profile=mp.RoundedFlat(0.3, 100.0), friction=0.3)"
    ),
    "rounded flat, damping 0.5": (
        "dict(profile=mp.RoundedFlat(0.3, 100.0), damping=0.5)"
    ),
    "asymmetric table": "dict(profile=TABLE)",
    "asymmetric table, friction 0.3": "dict(profile=TABLE, friction=0.3)",
}

_CHILD = """
import json, statistics, sys, time
import movingpunch as mp
_xs = [-1.5 + 4.0 * i / 800 for i in range(801)]  # the parabola x^2/200 shifted by 0.2
TABLE = mp.Profile(tuple(_xs), tuple((x - 0.2) ** 2 / 200.0 for x in _xs))
kw = eval(sys.argv[1], {"mp": mp, "TABLE": TABLE})
repeat = int(sys.argv[2])
base = {"vstar": 0.2, "kw": 1.0, "nu": 0.2}
t0 = time.perf_counter()
mp.solve(**base, load=0.002, **kw)
first = time.perf_counter() - t0
warm = []
for k in range(repeat):
    t0 = time.perf_counter()
    mp.solve(**base, load=0.002 * (1 + 1e-3 * (k + 1)), **kw)
    warm.append(time.perf_counter() - t0)
speed = []  # a speed sweep's point: new end exponents, kernel and rules
for k in range(repeat):
    t0 = time.perf_counter()
    mp.solve(**{**base, "vstar": 0.2 + 0.01 * (k + 1)}, load=0.002, **kw)
    speed.append(time.perf_counter() - t0)
print(json.dumps({"first": first, "warm": statistics.median(warm),
                  "speed": statistics.median(speed)}))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    print(
        f"{'path':30} {'first ms':>9} {'warm ms':>9} {'first/warm':>10} "
        f"{'new V* ms':>10} {'/warm':>6}"
    )
    for name, expr in CASES.items():
        out = subprocess.run(
            [sys.executable, "-c", _CHILD, expr, str(args.repeat)],
            check=True,
            capture_output=True,
            text=True,
        )
        r = json.loads(out.stdout.splitlines()[-1])
        first, warm, speed = 1e3 * r["first"], 1e3 * r["warm"], 1e3 * r["speed"]
        print(
            f"{name:30} {first:9.2f} {warm:9.2f} {first / warm:10.1f} "
            f"{speed:10.2f} {speed / warm:6.1f}"
        )
    print(f"load average: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
