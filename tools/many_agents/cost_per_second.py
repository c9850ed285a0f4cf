#!/usr/bin/env python3
"""The planning cost of a run per simulated second, from the cpu_us column of its decisions.csv.

A run made with `maneuvermap run SCENARIO --timing` records each plan's CPU time; this sums them per
whole simulated second and prints, as a Markdown table: the second, its plans, their CPU seconds, and
the mean and median microseconds per plan (docs/performance.md, "Many agents"). With --plot it also
draws them with matplotlib (PNG, and SVG beside it): the planning CPU seconds per simulated second
against the budget of a real-time factor (2 on two threads: 1 CPU-second per simulated second), and
the median and 90th percentile of the plans' CPU time against that budget per plan.
Run: python3 tools/many_agents/cost_per_second.py OUT_DIR/decisions.csv [--plot FIGURE.png]
"""
import argparse
import csv
import math
import statistics
import sys
from pathlib import Path


def fail(message):
    print(f"cost_per_second.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read(path):
    """{whole simulated second: [CPU µs of each plan in it]} of a decisions.csv."""
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
    return per_second


def quantile(values, q):
    """The q-quantile of `values` (nearest rank)."""
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, math.ceil(q * len(ordered)) - 1))]


def table(per_second):
    print("| simulated second | plans | planning CPU s | mean µs per plan | median µs per plan |")
    print("|---|---|---|---|---|")
    for second in sorted(per_second):
        cs = per_second[second]
        print(f"| {second} | {len(cs)} | {sum(cs) / 1e6:.2f} | {sum(cs) / len(cs):.0f} | {statistics.median(cs):.0f} |")
    total = sum(sum(cs) for cs in per_second.values())
    print(f"\n{total / 1e6:.1f} CPU seconds of planning in all")


def plot(per_second, out, factor, threads, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    seconds = sorted(per_second)
    budget = threads / factor  # CPU seconds per simulated second
    plans = statistics.median(len(per_second[s]) for s in seconds)
    fig, (total, each) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True, constrained_layout=True)
    total.bar(seconds, [sum(per_second[s]) / 1e6 for s in seconds], width=0.8, align="edge", color="tab:blue",
              label="planning CPU time")
    total.axhline(budget, color="tab:red", linestyle="--",
                  label=f"budget of a real-time factor {factor:g} on {threads} threads")
    total.set_ylabel("CPU s per simulated second")
    total.set_title(title)
    total.legend(loc="upper left")
    middle = [s + 0.5 for s in seconds]
    each.plot(middle, [statistics.median(per_second[s]) for s in seconds], marker="o", label="median plan")
    each.plot(middle, [quantile(per_second[s], 0.9) for s in seconds], marker="s", label="90th percentile")
    each.axhline(budget / plans * 1e6, color="tab:red", linestyle="--", label=f"budget per plan ({plans:g} a second)")
    each.set_yscale("log")
    each.set_ylabel("CPU µs per plan")
    each.set_xlabel("simulated time [s]")
    each.legend(loc="lower right")
    out = Path(out)
    fig.savefig(out, dpi=120)
    fig.savefig(out.with_suffix(".svg"))
    print(f"wrote {out} and {out.with_suffix('.svg')}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="The planning cost of a timed run per simulated second.")
    parser.add_argument("decisions", help="decisions.csv of a run made with maneuvermap run --timing")
    parser.add_argument("--plot", metavar="FIGURE.png", help="also draw the cost per simulated second")
    parser.add_argument("--factor", type=float, default=2.0, help="real-time factor of the budget line (default 2)")
    parser.add_argument("--threads", type=int, default=2, help="planning threads of the budget line (default 2)")
    parser.add_argument("--title", default="s6-busy-roundabout: 50 planning vehicles at 100 Hz",
                        help="title of the figure")
    args = parser.parse_args()
    if not (math.isfinite(args.factor) and args.factor > 0):
        fail(f"--factor: expected a number > 0, got {args.factor!r}")
    if args.threads < 1:
        fail(f"--threads: expected a whole number >= 1, got {args.threads}")
    try:
        per_second = read(args.decisions)
    except OSError as e:
        fail(f"{args.decisions}: cannot read: {e.strerror}")
    table(per_second)
    if args.plot:
        plot(per_second, args.plot, args.factor, args.threads, args.title)
