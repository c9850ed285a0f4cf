#!/usr/bin/env python3
"""The planning cost of a run per simulated second, from the cpu_us column of its decisions.csv.

A run made with `maneuvermap run SCENARIO --timing` records each plan's CPU time; this sums them per
whole simulated second and prints, as a Markdown table: the second, its plans, their CPU seconds, and
the mean and median microseconds per plan (docs/performance.md, "Many agents").
Run: python3 tools/many_agents/cost_per_second.py OUT_DIR/decisions.csv
"""
import csv
import math
import statistics
import sys


def fail(message):
    print(f"cost_per_second.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def main(path):
    per_second = {}
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None or "cpu_us" not in reader.fieldnames or "t" not in reader.fieldnames:
            fail(f"{path}: expected the columns t and cpu_us of a decisions.csv")
        for line, row in enumerate(reader, start=2):
            try:
                t, cpu = float(row["t"]), float(row["cpu_us"])
            except (TypeError, ValueError):
                fail(f"{path}:{line}: t and cpu_us must be numbers, got {row['t']!r}, {row['cpu_us']!r}")
            if not (math.isfinite(t) and math.isfinite(cpu)):
                fail(f"{path}:{line}: t and cpu_us must be finite, got {row['t']!r}, {row['cpu_us']!r}")
            per_second.setdefault(math.floor(t + 1e-9), []).append(cpu)
    if not per_second or all(c == 0.0 for cs in per_second.values() for c in cs):
        fail(f"{path}: no CPU times (run the scenario with --timing)")
    print("| simulated second | plans | planning CPU s | mean µs per plan | median µs per plan |")
    print("|---|---|---|---|---|")
    for second in sorted(per_second):
        cs = per_second[second]
        print(f"| {second} | {len(cs)} | {sum(cs) / 1e6:.2f} | {sum(cs) / len(cs):.0f} | {statistics.median(cs):.0f} |")
    total = sum(sum(cs) for cs in per_second.values())
    print(f"\n{total / 1e6:.1f} CPU seconds of planning in all")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        fail("expected one argument, the decisions.csv of a run made with --timing")
    try:
        main(sys.argv[1])
    except OSError as e:
        fail(f"{sys.argv[1]}: cannot read: {e.strerror}")
