#!/usr/bin/python3
"""Fills docs/reproduction.md from the sweep outputs and the paper's numbers.

    report.py --table1 DIR --roundabout DIR --paper data/paper/table1.csv \
              --template docs/reproduction.template.md --out docs/reproduction.md

DIR are output directories of `maneuvermap sweep` (runs.csv, and for the roundabout the kept run
directories with decisions.csv, map.csv and summary.json). Placeholders in the template look like
{{NAME}}; every one must be known, and every number in the tables comes from the inputs.
Standard library only.
"""

import argparse
import csv
import json
import math
import os
import re
import statistics
import sys

PAPER_POLICY = {"const_0.5": "const:0.5", "const_1.0": "const:1.0", "const_1.5": "const:1.5",
                "const_2.0": "const:2.0", "adj": "adj"}
POLICY_ORDER = ["const:0.5", "const:1.0", "const:1.5", "const:2.0", "adj"]
POLICY_LABEL = {"const:0.5": "τ = 0.5 s", "const:1.0": "τ = 1.0 s", "const:1.5": "τ = 1.5 s",
                "const:2.0": "τ = 2.0 s", "adj": "ADJ", "robust": "robust (ours)"}
# The sensitivity study and the roundabout add the robust policy, which the paper does not have.
EXTENDED_ORDER = POLICY_ORDER + ["robust"]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else None


def normalise_policy(text):
    """'const:1' / 'const:1.0' / 'const_1.0' → 'const:1.0'; 'adj' stays."""
    text = text.strip().replace("_", ":")
    if text.startswith("const:"):
        return "const:%.1f" % float(text.split(":", 1)[1])
    return text


def mean_sd(values):
    values = [v for v in values if v is not None]
    if not values:
        return None, None
    if len(values) == 1:
        return values[0], 0.0
    return statistics.fmean(values), statistics.stdev(values)


def fmt(value, digits=2):
    return "–" if value is None else f"{value:.{digits}f}"


def majority(values):
    counts = {}
    for v in values:
        counts[v] = counts.get(v, 0) + 1
    if not counts:
        return "–", counts
    best = max(counts.items(), key=lambda kv: (kv[1], kv[0]))
    return best[0], counts


# ---------------------------------------------------------------------------------------------
# Table 1

def table1_cells(runs):
    cells = {}
    for r in runs:
        if r.get("error"):
            continue
        key = (int(float(r["b_kmh"])), int(float(r["a_kmh"])), normalise_policy(r["policy"]))
        cells.setdefault(key, []).append(r)
    return cells


def table1_comparison(runs, paper):
    cells = table1_cells(runs)
    lines = ["| B km/h | A km/h | policy | crashes (ours, of runs) | paper crash | min dist m (ours mean ± sd) | paper dist | TTC at min s (ours) | paper TTC | speed km/h (ours) | paper speed | bypass (ours: majority, counts) | paper bypass |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in paper:
        key = (int(p["b_kmh"]), int(p["a_kmh"]), PAPER_POLICY[p["policy"]])
        ours = cells.get(key, [])
        crashes = sum(int(r["crash"]) for r in ours)
        dist_mean, dist_sd = mean_sd([number(r["min_dist_m"]) for r in ours])
        ttc_mean, _ = mean_sd([number(r["ttc_at_min_s"]) for r in ours])
        speed_mean, _ = mean_sd([number(r["speed_kmh"]) for r in ours])
        side, counts = majority([r["bypass"] for r in ours])
        count_text = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
        lines.append(f"| {key[0]} | {key[1]} | {POLICY_LABEL[key[2]]} | {crashes}/{len(ours)} | {p['crash']} | "
                     f"{fmt(dist_mean)} ± {fmt(dist_sd)} | {p['min_dist_m']} | {fmt(ttc_mean)} | {p['ttc_at_min_s'] or '–'} | "
                     f"{fmt(speed_mean, 1)} | {p['speed_kmh']} | {side} ({count_text}) | {p['bypass']} |")
    return "\n".join(lines)


def table1_summary(runs, paper):
    """Per policy: crashes and mean min distance over all cells, ours and the paper's."""
    cells = table1_cells(runs)
    lines = ["| policy | crashed runs (ours) | crashed cells (paper) | mean min dist of runs without crash, m (ours) | mean min dist of cells without crash, m (paper) | left / right / none bypasses (ours) | left / right (paper) |",
             "|---|---|---|---|---|---|---|"]
    for policy in POLICY_ORDER:
        ours = [r for (b, a, pol), rs in cells.items() if pol == policy for r in rs]
        theirs = [p for p in paper if PAPER_POLICY[p["policy"]] == policy]
        crashed = sum(int(r["crash"]) for r in ours)
        free = [number(r["min_dist_m"]) for r in ours if int(r["crash"]) == 0]
        their_free = [float(p["min_dist_m"]) for p in theirs if p["crash"] == "0"]
        sides = {s: sum(1 for r in ours if r["bypass"] == s) for s in ("left", "right", "none")}
        their_sides = {s: sum(1 for p in theirs if p["bypass"] == s) for s in ("left", "right")}
        lines.append(f"| {POLICY_LABEL[policy]} | {crashed}/{len(ours)} | {sum(p['crash'] == '1' for p in theirs)}/{len(theirs)} | "
                     f"{fmt(statistics.fmean(free) if free else None)} | {fmt(statistics.fmean(their_free) if their_free else None)} | "
                     f"{sides['left']} / {sides['right']} / {sides['none']} | {their_sides['left']} / {their_sides['right']} |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# Roundabout

def find_runs(directory):
    """Run directories below `directory` (those holding a summary.json), by policy."""
    found = {}
    for root, _dirs, files in os.walk(directory):
        if "summary.json" in files and "decisions.csv" in files:
            with open(os.path.join(root, "summary.json")) as f:
                summary = json.load(f)
            found[normalise_policy(str(summary.get("policy", "")))] = (root, summary)
    return found


def planning_metrics(summary, agent="A"):
    for v in summary.get("vehicles", summary.get("planning_vehicles", [])):
        if v.get("agent", v.get("name")) == agent:
            return v
    vehicles = summary.get("vehicles", summary.get("planning_vehicles", []))
    return vehicles[0] if vehicles else {}


def intervals(times, flags, step):
    """Maximal runs of consecutive times where flags is true, as (start, end)."""
    out = []
    start = None
    last = None
    for t, on in zip(times, flags):
        if on and start is None:
            start = t
        if not on and start is not None:
            out.append((start, last))
            start = None
        last = t
    if start is not None:
        out.append((start, last))
    return [(a, b) for a, b in out if b - a >= step / 2 or a == b]


def roundabout_timeline(run_dir, agent="A"):
    decisions = [r for r in read_csv(os.path.join(run_dir, "decisions.csv")) if r["agent"] == agent]
    times = [float(r["t"]) for r in decisions]
    step = times[1] - times[0] if len(times) > 1 else 0.01
    avoiding = [r["mode"] != "nominal" for r in decisions]
    brake = [r["mode"] != "nominal" and r["family"] == "brake" for r in decisions]
    accel = [r["mode"] != "nominal" and r["family"] == "accelerate" for r in decisions]
    # τ̄ limited by TTC: some forecast time is excluded and τ̄ is the largest one still allowed.
    excluded = {}
    for r in read_csv(os.path.join(run_dir, "map.csv")):
        if r["agent"] != agent:
            continue
        t = round(float(r["t"]), 6)
        allowed, any_excluded = excluded.get(t, (0.0, False))
        if int(r["excluded"]):
            any_excluded = True
        else:
            allowed = max(allowed, float(r["tau"]))
        excluded[t] = (allowed, any_excluded)
    capped = []
    for r, t in zip(decisions, times):
        allowed, any_excluded = excluded.get(round(t, 6), (None, False))
        capped.append(any_excluded and allowed is not None and abs(float(r["tau_bar"]) - allowed) < 1e-9)
    last_threat = max((t for r, t in zip(decisions, times) if r["ttc"] != ""), default=None)
    return {
        "reacting": intervals(times, avoiding, step),
        "brake": intervals(times, brake, step),
        "accelerate": intervals(times, accel, step),
        "capped": intervals(times, capped, step),
        "last_threat": last_threat,
    }


def describe_intervals(spans, limit=6):
    if not spans:
        return "never"
    text = ", ".join(f"{a:.2f}–{b:.2f} s" for a, b in spans[:limit])
    if len(spans) > limit:
        text += f" and {len(spans) - limit} more"
    return text


def roundabout_speeds(runs_by_policy):
    paper = {"const:0.5": "≈ 26", "const:1.0": "32–33", "const:2.0": "32–33", "adj": "≈ 36", "robust": "–"}
    lines = ["| policy | lowest speed km/h (ours) | paper | final speed km/h (ours) | min gap m (ours) |",
             "|---|---|---|---|---|"]
    for policy in ["const:0.5", "const:1.0", "const:2.0", "adj", "robust"]:
        if policy not in runs_by_policy:
            lines.append(f"| {POLICY_LABEL[policy]} | (no run) | {paper[policy]} | | |")
            continue
        run_dir, summary = runs_by_policy[policy]
        m = planning_metrics(summary)
        trajectory = [r for r in read_csv(os.path.join(run_dir, "trajectories.csv")) if r["agent"] == "A"]
        final = float(trajectory[-1]["speed"]) * 3.6 if trajectory else None
        lines.append(f"| {POLICY_LABEL[policy]} | {fmt(m.get('min_speed_kmh'), 1)} | {paper[policy]} | {fmt(final, 1)} | "
                     f"{fmt(m.get('min_dist_m'))} |")
    return "\n".join(lines)


def roundabout_timeline_table(runs_by_policy):
    lines = ["| event (ADJ) | ours | paper (Fig. 8a and text) |", "|---|---|---|"]
    if "adj" not in runs_by_policy:
        return "(no ADJ run)"
    t = roundabout_timeline(runs_by_policy["adj"][0])
    first = t["reacting"][0][0] if t["reacting"] else None
    lines.append(f"| A starts reacting to B | {fmt(first)} s | ≈ 1.0–1.1 s |")
    lines.append(f"| avoiding with brake-and-steer | {describe_intervals(t['brake'])} | 1.1–1.5 s |")
    lines.append(f"| avoiding with accelerate-and-steer | {describe_intervals(t['accelerate'])} | from ≈ 1.5 s |")
    lines.append(f"| τ̄ limited by TTC | {describe_intervals(t['capped'])} | ≈ 1.8–2.6 s |")
    lines.append(f"| last step with a finite TTC (vehicles separating) | {fmt(t['last_threat'])} s | ≈ 2.9 s |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# S3: the sensitivity study and the timeline of single runs

def variants_table(directories):
    """Crashes and distances per policy for each S3 variant sweep (B turning from farther left)."""
    lines = ["| B turns from | B's turn visible for | A km/h | " + " | ".join(POLICY_LABEL[p] for p in EXTENDED_ORDER) + " |",
             "|---|---|---|" + "---|" * len(EXTENDED_ORDER)]
    for directory in directories:
        with open(os.path.join(directory, "sweep.json")) as f:
            sweep = json.load(f)
        description = sweep.get("description", "")
        match = re.search(r"from ([0-9.]+) m left of A's lane: ([0-9.]+) m of visible turn", description)
        offset, visible = (match.group(1), float(match.group(2))) if match else ("?", None)
        runs = [r for r in read_csv(os.path.join(directory, "runs.csv")) if not r.get("error")]
        for a in sorted({int(float(r["a_kmh"])) for r in runs}):
            cells = []
            for policy in EXTENDED_ORDER:
                rs = [r for r in runs if int(float(r["a_kmh"])) == a and normalise_policy(r["policy"]) == policy]
                crashed = sum(int(r["crash"]) for r in rs)
                free = [number(r["min_dist_m"]) for r in rs if int(r["crash"]) == 0]
                text = f"{crashed}/{len(rs)} crashed"
                if free:
                    text += f", gap {statistics.fmean(free):.2f} m"
                cells.append(text)
            visible_text = f"{visible:.1f} m, {visible / (35 / 3.6):.2f} s" if visible else "?"
            lines.append(f"| {offset} m left of A's lane | {visible_text} | {a} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def s3_timeline(run_dirs):
    """For example runs: when B appears and starts turning; A's reactions before the turn (to noise in
    B's first observations) and from the turn on: first finite TTC, first avoiding step, first τ̄ > 0;
    the crash or the gap."""
    lines = ["| run | B appears | A avoids before B turns (steps) | B starts turning | from then: first finite TTC for A "
             "| A first avoids (mode not nominal) | A's first τ̄ > 0 while avoiding | crash |",
             "|---|---|---|---|---|---|---|---|"]
    for label, run_dir in run_dirs:
        trajectory = read_csv(os.path.join(run_dir, "trajectories.csv"))
        appears = next((float(r["t"]) for r in trajectory if r["agent"] == "B"), None)
        turning = [float(r["t"]) for r in trajectory if r["agent"] == "B" and abs(float(r["curvature"])) > 1e-6]
        turn = turning[0] if turning else None
        decisions = [r for r in read_csv(os.path.join(run_dir, "decisions.csv")) if r["agent"] == "A"]
        before = sum(1 for r in decisions if r["mode"] != "nominal" and (turn is None or float(r["t"]) < turn))
        after = [r for r in decisions if turn is not None and float(r["t"]) >= turn]
        first_ttc = next((float(r["t"]) for r in after if r["ttc"] != ""), None)
        first_avoid = next((float(r["t"]) for r in after if r["mode"] != "nominal"), None)
        first_long = next((float(r["t"]) for r in after if r["mode"] != "nominal" and float(r["tau_bar"]) > 0), None)
        with open(os.path.join(run_dir, "summary.json")) as f:
            m = planning_metrics(json.load(f))
        crash = f"{m['crash_time_s']:.2f} s at {m['speed_kmh']:.1f} km/h" if m.get("crash") else f"none (gap {m['min_dist_m']:.2f} m)"
        lines.append(f"| {label} | {fmt(appears)} s | {before} | {fmt(turn)} s | {fmt(first_ttc)} s | {fmt(first_avoid)} s | "
                     f"{fmt(first_long) + ' s' if first_long is not None else 'never'} | {crash} |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--table1", required=True)
    parser.add_argument("--roundabout", required=True)
    parser.add_argument("--paper", required=True)
    parser.add_argument("--template", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--variants", nargs="*", default=[], help="sweep directories of the S3 variants")
    parser.add_argument("--s3-runs", nargs="*", default=[], help="LABEL=RUN_DIR example runs of S3")
    args = parser.parse_args()

    runs = read_csv(os.path.join(args.table1, "runs.csv"))
    paper = read_csv(args.paper)
    roundabout = find_runs(args.roundabout)
    values = {
        "TABLE1_COMPARISON": table1_comparison(runs, paper),
        "TABLE1_SUMMARY": table1_summary(runs, paper),
        "ROUNDABOUT_SPEEDS": roundabout_speeds(roundabout),
        "ROUNDABOUT_TIMELINE": roundabout_timeline_table(roundabout),
        "TABLE1_RUNS": str(len(runs)),
        "TABLE1_FAILED": str(sum(1 for r in runs if r.get("error"))),
        "S3_VARIANTS": variants_table(args.variants),
        "S3_TIMELINE": s3_timeline([tuple(item.split("=", 1)) for item in args.s3_runs]),
    }
    with open(args.template) as f:
        text = f.read()
    unknown = sorted(set(re.findall(r"\{\{([A-Z0-9_]+)\}\}", text)) - set(values))
    if unknown:
        sys.exit(f"report.py: unknown placeholders in {args.template}: {', '.join(unknown)}")
    for key, value in values.items():
        text = text.replace("{{" + key + "}}", value)
    with open(args.out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
