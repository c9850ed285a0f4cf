#!/usr/bin/env python3
"""Draws how the planner's cost grows (docs/performance.md) from maneuvermap_bench's JSON output.

    maneuvermap_bench --benchmark_out=bench.json --benchmark_out_format=json
    python3 tools/plot/performance_chart.py bench.json OUT.png

Three panels, median time per planning step with the slowest repetition's median as a bar:
against the number of interacting obstacles (plan/obstacles:N, each point labelled with the
obstacles the planner kept as relevant), the number of forecast times
(plan_forecast_grid/forecast_count:N) and the samples per family (plan_resolution/...).
Also writes OUT with the .svg suffix, and prints the plotted values as CSV.
"""
import json
import re
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}


def read(path):
    """{run_name: {aggregate: microseconds}} of the aggregate rows of a benchmark JSON file."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    rows = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") != "aggregate":
            continue
        name = re.sub(r"/repeats:\d+$", "", b["run_name"])
        row = rows.setdefault(name, {})
        row[b["aggregate_name"]] = b["real_time"] * TO_US[b["time_unit"]]
        if b["aggregate_name"] == "median" and "relevant" in b:
            row["relevant"] = int(b["relevant"])
    return rows


def series(rows, prefix, parse):
    points = []
    for name, values in rows.items():
        if name.startswith(prefix) and "median" in values:
            points.append((parse(name[len(prefix):]), values["median"], values.get("max", values["median"])))
    return sorted(points)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = read(sys.argv[1])
    out = Path(sys.argv[2])

    def args(text):
        return [int(v) for v in re.findall(r":(\d+)", text)]

    panels = [
        ("interacting obstacles", series(rows, "plan/", lambda s: args(s)[0])),
        ("forecast times (0 to 2 s)", series(rows, "plan_forecast_grid/", lambda s: args(s)[0])),
        ("samples per family (accelerations x curvatures)",
         series(rows, "plan_resolution/", lambda s: args(s)[0] * args(s)[1])),
    ]
    labels = {p[0] * p[1]: f"{p[0]}x{p[1]}" for p in
              [args(n[len("plan_resolution/"):]) for n in rows if n.startswith("plan_resolution/")]}
    figure, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    print("panel,x,median_us,max_us")
    for ax, (title, points) in zip(axes, panels):
        if not points:
            ax.set_title(f"{title}\n(no data)")
            continue
        x = [p[0] for p in points]
        median = [p[1] for p in points]
        worst = [p[2] for p in points]
        ax.plot(x, median, marker="o", label="median")
        ax.plot(x, worst, marker="v", linestyle="--", label="slowest repetition")
        for p in points:
            print(f"{title.split(' (')[0]},{p[0]},{p[1]:.3f},{p[2]:.3f}")
        ax.set_yscale("log")
        ax.set_xlabel(title)
        ax.set_ylabel("time per planning step [us]")
        ax.grid(True, which="both", alpha=0.3)
        if title.startswith("interacting"):
            # Issue 5's targets for the median, where it sets one.
            targets = [(n, t) for n, t in ((0, 5.0), (1, 100.0), (8, 1000.0)) if n in x]
            ax.plot([t[0] for t in targets], [t[1] for t in targets], linestyle="none", marker="x", color="black",
                    markersize=8, label="target (issue 5)")
            for name, values in rows.items():
                if name.startswith("plan/obstacles:") and "relevant" in values:
                    n = args(name)[0]
                    ax.annotate(f"{values['relevant']} relevant", (n, values["median"]), textcoords="offset points",
                                xytext=(6, 4) if n == 0 else (4, -14), fontsize=8)
        if "samples" in title:
            ax.set_xticks(x)
            ax.set_xticklabels([labels.get(v, str(v)) for v in x], rotation=30)
        else:
            ax.set_xticks(x)
        ax.legend(loc="lower right" if title.startswith("interacting") else "upper left", fontsize=8)
    figure.suptitle("maneuvermap: cost of one planning step (maneuvermap_bench, one core)")
    figure.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(out, dpi=120)
    figure.savefig(out.with_suffix(".svg"))


if __name__ == "__main__":
    main()
