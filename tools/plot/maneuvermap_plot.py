#!/usr/bin/python3
"""Figures of maneuvermap outputs (docs/outputs.md, "Figures"), PNG and SVG, with matplotlib.

    maneuvermap_plot.py TARGET [--out DIR] [--paper-table1 FILE]

TARGET is one of
  - a run directory (`maneuvermap run`): map.png (the Maneuverability Map, paper Fig. 8),
    speed.png (speed profile), topdown.png (the run from above);
  - a sweep directory (`maneuvermap sweep`): min-dist.png (min distance per cell and policy),
    table1-comparison.png (ours beside the paper's Table 1, for a sweep over a_kmh and b_kmh),
    speed-profiles.png (every kept run, paper Fig. 7), and the run figures of each kept run when
    there are at most 8;
  - a snapshot CSV (`maneuvermap snapshot --out FILE.csv`, with FILE.json beside it):
    FILE-sets.png (the displacement sets at that moment, paper Fig. 3).

Every figure is written as NAME.png and NAME.svg into DIR (default: the run or sweep directory,
or the CSV's directory). Exit codes: 0 done, 2 nothing to plot in TARGET or bad input, 3
matplotlib or numpy cannot be imported. Run it with Debian's /usr/bin/python3 (python3-matplotlib).
"""

import argparse
import csv
import json
import math
import os
import sys

EXIT_BAD_INPUT = 2
EXIT_NO_MATPLOTLIB = 3

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors as mcolors
    from matplotlib.patches import Polygon, Circle
    from matplotlib.lines import Line2D
except ImportError as error:  # pragma: no cover - depends on the machine
    print(
        f"maneuvermap_plot: cannot import matplotlib/numpy ({error}); install python3-matplotlib and "
        f"python3-numpy (scripts/install-deps.sh) and run with /usr/bin/python3",
        file=sys.stderr,
    )
    sys.exit(EXIT_NO_MATPLOTLIB)

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_PAPER_TABLE1 = os.path.normpath(os.path.join(HERE, "..", "..", "data", "paper", "table1.csv"))

# Reproducible files: no dates in SVG/PNG metadata, fixed SVG ids.
matplotlib.rcParams.update(
    {
        "svg.hashsalt": "maneuvermap",
        "font.size": 10,
        "axes.titlesize": 11,
        "axes.labelsize": 10,
        "legend.fontsize": 9,
        "figure.dpi": 100,
        "savefig.dpi": 150,
        "axes.grid": True,
        "grid.alpha": 0.3,
    }
)

ADJ_COLOUR = "#d62728"
AGENT_COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"]
FAMILY_COLOURS = {"brake": "#1f77b4", "accelerate": "#2ca02c"}
MODE_COLOURS = {"nominal": "#e0e0e0", "avoid": "#fdd49e", "urgent": "#fc8d59", "near_crash": "#b30000"}


class BadInput(Exception):
    """Nothing to plot, or a file that is not what it should be (exit code 2)."""


# --- reading ----------------------------------------------------------------------------------


class csv_row(dict):
    """One row of a CSV file: its fields by column name, and where it came from (for messages)."""

    def __init__(self, fields, path, line):
        super().__init__(fields)
        self.path = path
        self.line = line

    def __missing__(self, column):
        raise BadInput(f"{self.path}:{self.line}: no column {column!r} (the header has {', '.join(map(str, self))})")


def read_csv(path):
    """The rows of a CSV file as `csv_row`s (header from the first line)."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None:
            raise BadInput(f"{path}: empty: expected a header line, as maneuvermap writes even without rows")
        rows = []
        for fields in reader:
            if None in fields:
                raise BadInput(f"{path}:{reader.line_num}: more fields than the header's {len(reader.fieldnames)}")
            rows.append(csv_row(fields, path, reader.line_num))
        return rows


def field_number(row, column):
    """The finite number in `column` of `row`, or BadInput naming the file, line, column and value."""
    text = row[column]
    try:
        result = float(text)
    except (TypeError, ValueError):
        raise BadInput(f"{row.path}:{row.line}: {column} = {text!r}: expected a number") from None
    if not math.isfinite(result):
        raise BadInput(f"{row.path}:{row.line}: {column} = {text!r}: expected a finite number")
    return result


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


# --- policies: one colour and line style each, the same on every figure ------------------------


def policy_key(policy):
    """(0, τ) for const:τ, (1, 0) for adj, (2, 0) for anything else: the legend order."""
    if policy.startswith("const:"):
        return (0, float(policy[6:]))
    if policy.startswith("const_"):
        return (0, float(policy[6:]))
    return (1, 0.0) if policy == "adj" else (2, 0.0)


def policy_label(policy):
    kind, tau = policy_key(policy)
    if kind == 0:
        return f"constant τ = {tau:g} s"
    return "ADJ" if policy == "adj" else policy


def policy_colour(policy):
    """Constant forecast times in blues, darker for longer τ (0.5 to 2 s); ADJ red."""
    kind, tau = policy_key(policy)
    if kind == 1:
        return ADJ_COLOUR
    if kind == 0:
        shade = 0.45 + 0.5 * min(max((tau - 0.25) / 1.75, 0.0), 1.0)
        return mcolors.to_hex(plt.get_cmap("Blues")(shade))
    return "#7f7f7f"


def policy_style(policy):
    kind, tau = policy_key(policy)
    if kind == 1:
        return "-"
    styles = {0.5: (0, (1, 1)), 1.0: "--", 1.5: (0, (5, 1, 1, 1)), 2.0: "-."}
    return styles.get(tau, ":")


# --- saving -----------------------------------------------------------------------------------


def save(fig, out_dir, name, written):
    os.makedirs(out_dir, exist_ok=True)
    for ext, meta in (("png", {"Software": None}), ("svg", {"Date": None})):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, metadata=meta, bbox_inches="tight")
        written.append(path)
    plt.close(fig)


# --- geometry ---------------------------------------------------------------------------------


def footprint_outline(footprint, x, y, heading):
    """The footprint's outline (N×2) placed at (x, y) with the heading."""
    c, s = math.cos(heading), math.sin(heading)
    if footprint.get("shape") == "rectangle":
        hl, hw = footprint["length_m"] / 2, footprint["width_m"] / 2
        local = np.array([[hl, hw], [-hl, hw], [-hl, -hw], [hl, -hw]])
    elif footprint.get("shape") == "disc":
        a = np.linspace(0, 2 * math.pi, 33)[:-1]
        r = footprint["radius_m"]
        local = np.stack([r * np.cos(a), r * np.sin(a)], axis=1)
    else:
        local = np.array(footprint["vertices_m"], dtype=float)
    rot = np.array([[c, -s], [s, c]])
    return local @ rot.T + np.array([x, y])


def perimeter_points(outline, spacing=0.05):
    pts = []
    n = len(outline)
    for i in range(n):
        a, b = outline[i], outline[(i + 1) % n]
        k = max(1, int(math.ceil(np.linalg.norm(b - a) / spacing)))
        for j in range(k):
            pts.append(a + (b - a) * j / k)
    return np.array(pts)


def closest_points(outline_a, outline_b):
    """Nearest pair of points of two outlines (sampled every 5 cm)."""
    pa, pb = perimeter_points(outline_a), perimeter_points(outline_b)
    d = np.linalg.norm(pa[:, None, :] - pb[None, :, :], axis=2)
    i, j = np.unravel_index(np.argmin(d), d.shape)
    return pa[i], pb[j]


def convex_hull(points):
    """Monotone chain; points N×2 → hull vertices counter-clockwise."""
    pts = sorted(set(map(tuple, np.round(points, 6))))
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


# --- a run ------------------------------------------------------------------------------------


class Run:
    """A run directory: the five files of `maneuvermap run`."""

    def __init__(self, directory):
        self.dir = directory
        self.summary = read_json(os.path.join(directory, "summary.json"))
        self.scene = read_json(os.path.join(directory, "scene.json"))
        self._trajectories = None
        self._map = None
        self._decisions = None

    @property
    def policy(self):
        return self.summary.get("policy", "")

    def trajectories(self):
        """{agent: dict of numpy arrays t, x, y, heading, speed}."""
        if self._trajectories is None:
            by_agent = {}
            for row in read_csv(os.path.join(self.dir, "trajectories.csv")):
                by_agent.setdefault(row["agent"], []).append(
                    tuple(field_number(row, column) for column in ("t", "x", "y", "heading", "speed"))
                )
            self._trajectories = {
                name: dict(zip(("t", "x", "y", "heading", "speed"), np.array(rows).T)) for name, rows in by_agent.items()
            }
        return self._trajectories

    def map_rows(self):
        if self._map is None:
            self._map = read_csv(os.path.join(self.dir, "map.csv"))
        return self._map

    def decisions(self):
        if self._decisions is None:
            self._decisions = read_csv(os.path.join(self.dir, "decisions.csv"))
        return self._decisions

    def planning_agents(self):
        return [a["name"] for a in self.scene["agents"] if a["kind"] == "planning_vehicle"]

    def vehicle(self, name):
        for v in self.summary.get("vehicles", []):
            if v["agent"] == name:
                return v
        return None


def run_title(run):
    s = run.summary
    if s.get("format") == "maneuvermap-measurement/1":
        return f"{s['scenario']} (recorded, CommonRoad {s.get('commonroad_version', '')}) — policy {policy_label(run.policy)}"
    params = ", ".join(f"{k} = {v:g}" for k, v in s.get("parameters", {}).items() if k.endswith("_kmh"))
    text = f"{s['scenario']} — policy {policy_label(run.policy)}, seed {s['seed']}"
    return text + (f"\n{params}" if params else "")


def plot_map(run, agent, out_dir, name, written):
    """Figure 1: the Maneuverability Map of one planning vehicle (paper Fig. 8)."""
    rows = [r for r in run.map_rows() if r["agent"] == agent]
    decisions = [d for d in run.decisions() if d["agent"] == agent]
    if not decisions:
        print(f"maneuvermap_plot: {run.dir}: {agent} never planned; no map", file=sys.stderr)
        return
    if not rows:
        print(f"maneuvermap_plot: {run.dir}: {agent} planned without a map column (planner map_column: false); "
              "no map", file=sys.stderr)
        return
    times = np.array(sorted({field_number(r, "t") for r in rows}))
    taus = np.array(sorted({field_number(r, "tau") for r in rows}))
    t_index = {t: i for i, t in enumerate(times)}
    tau_index = {t: i for i, t in enumerate(taus)}
    mi = {"brake": np.full((len(taus), len(times)), np.nan), "accelerate": np.full((len(taus), len(times)), np.nan)}
    excluded = np.zeros((len(taus), len(times)), dtype=bool)
    for r in rows:
        i, j = tau_index[field_number(r, "tau")], t_index[field_number(r, "t")]
        mi["brake"][i, j] = field_number(r, "mi_brake")
        mi["accelerate"][i, j] = field_number(r, "mi_accel")
        excluded[i, j] = r["excluded"] == "1"
    dt = float(np.median(np.diff(times))) if len(times) > 1 else run.summary.get("time_step_s", 0.01)
    dtau = float(np.median(np.diff(taus))) if len(taus) > 1 else 0.125
    t_edges = np.append(times - dt / 2, times[-1] + dt / 2)
    tau_edges = np.append(taus - dtau / 2, taus[-1] + dtau / 2)

    dt_times = np.array([field_number(d, "t") for d in decisions])
    tau_bar = np.array([field_number(d, "tau_bar") for d in decisions])
    ttc = np.array([field_number(d, "ttc") if d["ttc"] != "" else np.nan for d in decisions])
    families = [d["family"] for d in decisions]
    modes = [d["mode"] for d in decisions]
    # Under the robust policy: the steps at which ADJ decided, no maneuver being safe under every
    # forecast time (decisions.csv's robust column, docs/method.md §8).
    fallback = np.array([run.policy == "robust" and d.get("robust") == "0" for d in decisions], dtype=bool)
    # Switches of the selected family while avoiding (non-nominal modes only).
    switches = []
    last = None
    for t, fam, mode in zip(dt_times, families, modes):
        if mode == "nominal":
            continue
        if last is not None and fam != last:
            switches.append((t, fam))
        last = fam

    fig = plt.figure(figsize=(9, 6.4))
    grid = fig.add_gridspec(3, 2, height_ratios=[0.35, 3, 3], width_ratios=[40, 1], hspace=0.12, wspace=0.03)
    ax_mode = fig.add_subplot(grid[0, 0])
    axes = [fig.add_subplot(grid[1, 0], sharex=ax_mode), fig.add_subplot(grid[2, 0], sharex=ax_mode)]
    cax = fig.add_subplot(grid[1:, 1])

    # The decision strip: the planning mode (top half) and, while avoiding, the family (bottom half).
    for t, fam, mode in zip(dt_times, families, modes):
        ax_mode.axvspan(t - dt / 2, t + dt / 2, ymin=0.5, ymax=1, color=MODE_COLOURS.get(mode, "#cccccc"), lw=0)
    for t0, t1, fam in family_spans(dt_times, families, modes, dt):
        ax_mode.axvspan(t0, t1, ymin=0.0, ymax=0.5, color=FAMILY_COLOURS[fam], lw=0)
    ax_mode.set_ylim(0, 1)
    ax_mode.set_yticks([0.25, 0.75])
    ax_mode.set_yticklabels(["family", "mode"], fontsize=8)
    ax_mode.axhline(0.5, color="white", lw=0.8)
    ax_mode.grid(False)
    plt.setp(ax_mode.get_xticklabels(), visible=False)
    ax_mode.set_title(f"Maneuverability Map of {agent}: {run_title(run)}")

    cmap = plt.get_cmap("RdYlGn").copy()
    cmap.set_bad("#9e9e9e")
    for ax, fam, label in zip(axes, ("brake", "accelerate"), ("brake-and-steer  MI⁻(τ)", "accelerate-and-steer  MI⁺(τ)")):
        values = np.ma.masked_where(excluded | np.isnan(mi[fam]), mi[fam])
        ax.grid(False)
        mesh = ax.pcolormesh(t_edges, tau_edges, values, cmap=cmap, vmin=0, vmax=1, shading="flat", rasterized=True)
        ax.step(dt_times, tau_bar, where="mid", color="black", lw=1.6, label="τ̄ (selected forecast time)")
        ax.plot(dt_times, ttc, color="white", lw=1.0, ls="--", label="TTC")
        if fallback.any():
            ax.scatter(dt_times[fallback], tau_bar[fallback], marker="o", s=6, color="#7b3294", zorder=3, lw=0)
        for t, fam_to in switches:
            ax.axvline(t, color=FAMILY_COLOURS[fam_to], lw=1.4, ls=":")
        ax.set_ylim(tau_edges[0], tau_edges[-1])
        ax.set_ylabel("forecast time τ [s]")
        ax.text(0.01, 0.96, label, transform=ax.transAxes, va="top", ha="left", fontsize=10,
                bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "none", "pad": 2})
        ax.grid(False)
    plt.setp(axes[0].get_xticklabels(), visible=False)
    axes[1].set_xlabel("time t [s]")
    axes[1].set_xlim(t_edges[0], t_edges[-1])
    cax.grid(False)
    fig.colorbar(mesh, cax=cax, label="maneuverability index MI")

    handles = [
        Line2D([], [], color="black", lw=1.6, label="τ̄"),
        Line2D([], [], color="#555555", lw=1.0, ls="--", label="TTC"),
        Polygon([[0, 0]], closed=True, color="#9e9e9e", label="excluded (τ > TTC)"),
    ]
    if fallback.any():
        handles.append(Line2D([], [], color="#7b3294", marker="o", ms=4, ls="none", label="τ̄ where ADJ decided"))
    handles += [Line2D([], [], color=FAMILY_COLOURS[f], lw=1.4, ls=":", label=f"switch to {f}")
                for f in ("brake", "accelerate") if any(to == f for _, to in switches)]
    handles += [Polygon([[0, 0]], closed=True, color=c, label=f"mode {m}") for m, c in MODE_COLOURS.items() if m in modes]
    handles += [Polygon([[0, 0]], closed=True, color=FAMILY_COLOURS[f], label=f"family {f}")
                for f in ("brake", "accelerate") if any(fa == f and m != "nominal" for fa, m in zip(families, modes))]
    fig.legend(handles=handles, loc="lower center", ncol=5, frameon=False, bbox_to_anchor=(0.5, -0.06))
    save(fig, out_dir, name, written)


def family_spans(times, families, modes, dt):
    """Contiguous spans of non-nominal decisions of one family: (t0, t1, family)."""
    spans = []
    start = None
    for k, (t, fam, mode) in enumerate(zip(times, families, modes)):
        active = mode != "nominal"
        if active and (start is None or families[start] != fam):
            if start is not None:
                spans.append((times[start] - dt / 2, t - dt / 2, families[start]))
            start = k
        elif not active and start is not None:
            spans.append((times[start] - dt / 2, t - dt / 2, families[start]))
            start = None
    if start is not None:
        spans.append((times[start] - dt / 2, times[-1] + dt / 2, families[start]))
    return spans


def plot_speed(runs, agent_of, out_dir, name, title, written, label_of=None):
    """Figure 2: speed profiles of several runs on one chart (paper Fig. 7)."""
    fig, ax = plt.subplots(figsize=(8, 4.6))
    seen = set()
    ordered = sorted(runs, key=lambda r: (policy_key(r.policy), r.dir))
    for run in ordered:
        agent = agent_of(run)
        traj = run.trajectories().get(agent)
        if traj is None:
            continue
        label = label_of(run) if label_of else policy_label(run.policy)
        show = label not in seen
        seen.add(label)
        ax.plot(traj["t"], traj["speed"] * 3.6, color=policy_colour(run.policy), ls=policy_style(run.policy),
                lw=2.0 if run.policy == "adj" else 1.6, label=label if show else None)
        v = run.vehicle(agent)
        if v and v.get("crash") and v.get("crash_time_s") is not None:
            ax.plot([v["crash_time_s"]], [v["speed_kmh"]], marker="X", ms=9, color=policy_colour(run.policy),
                    mec="black", ls="none")
        i = int(np.argmin(traj["speed"]))
        ax.plot([traj["t"][i]], [traj["speed"][i] * 3.6], marker="o", ms=4, color=policy_colour(run.policy))
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(f"speed [km/h]")
    ax.set_title(title)
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], marker="o", ms=4, color="#555555", ls="none"))
    labels.append("lowest speed")
    if any((r.vehicle(agent_of(r)) or {}).get("crash") for r in runs):
        handles.append(Line2D([], [], marker="X", ms=8, color="#555555", mec="black", ls="none"))
        labels.append("crash")
    ax.legend(handles, labels, loc="best")
    save(fig, out_dir, name, written)


def plot_topdown(run, out_dir, name, written):
    """Figure 3: the run from above: roads, paths, trajectories, footprints, closest approach."""
    scene = run.scene
    trajs = run.trajectories()
    fig, ax = plt.subplots(figsize=(8, 7.5))
    road_colour, lane_colour = "#d9d9d9", "#bdbdbd"
    for lanelet in scene.get("lanelets", []):
        outline = np.array(lanelet["left_m"] + lanelet["right_m"][::-1], dtype=float)
        if len(outline) >= 3:
            ax.add_patch(Polygon(outline, closed=True, fc=road_colour, ec=lane_colour, lw=0.4, zorder=0))
    for road in scene.get("roads", []):
        line = np.array(road["centre_line_m"])
        ax.plot(line[:, 0], line[:, 1], color=road_colour, lw=1, solid_capstyle="butt", zorder=0)
        draw_band(ax, line, road["width_m"], road_colour)
    area = scene.get("drivable_area")
    if area:  # the road constraint's edges (spec §5), where a maneuver leaves the road
        for a, b in area["boundary_m"]:
            ax.plot([a[0], b[0]], [a[1], b[1]], color="#525252", lw=1.2, solid_capstyle="butt", zorder=1)
    ring = scene.get("roundabout")
    if ring:
        cx, cy = ring["center_m"]
        lane = 2 * max([a["lane_offset_m"] for a in ring["arms"]] + [1.75])
        ax.add_patch(Circle((cx, cy), ring["radius_m"] + lane / 2, color=road_colour, zorder=0, lw=0))
        ax.add_patch(Circle((cx, cy), ring["radius_m"] - lane / 2, color="#eef3e9", zorder=0, lw=0))
        for arm in ring["arms"]:
            for key in ("entry_lane_m", "exit_lane_m"):
                draw_band(ax, np.array(arm[key]), lane, road_colour)
    for k, agent in enumerate(scene["agents"]):
        if agent["kind"] == "static_obstacle":
            ax.add_patch(Polygon(agent["vertices_m"], closed=True, color="#636363", zorder=3))
            continue
        path = np.array(agent["path_m"])
        ax.plot(path[:, 0], path[:, 1], color=lane_colour, lw=0.8, ls="--", zorder=1)

    names = [a["name"] for a in scene["agents"] if a["kind"] != "static_obstacle"]
    colour = {n: AGENT_COLOURS[i % len(AGENT_COLOURS)] for i, n in enumerate(names)}
    footprints = {a["name"]: a.get("footprint") for a in scene["agents"]}
    end_time = run.summary.get("end_time_s", 0)
    interval = 0.5 if end_time <= 8 else 1.0
    xs, ys = [], []
    for n in names:
        tr = trajs.get(n)
        if tr is None:
            continue
        ax.plot(tr["x"], tr["y"], color=colour[n], lw=1.8, zorder=4, label=f"{n} ({kind_label(scene, n)})")
        xs += list(tr["x"])
        ys += list(tr["y"])
        marks = np.arange(math.ceil(tr["t"][0] / interval) * interval, tr["t"][-1] + 1e-9, interval)
        for j, t in enumerate(marks):
            i = int(np.argmin(np.abs(tr["t"] - t)))
            outline = footprint_outline(footprints[n], tr["x"][i], tr["y"][i], tr["heading"][i])
            ax.add_patch(Polygon(outline, closed=True, fill=False, ec=colour[n], lw=0.8, alpha=0.55, zorder=5))
            if j % 2 == 0:
                ax.annotate(f"{t:g}", (tr["x"][i], tr["y"][i]), fontsize=8, color=colour[n], ha="center", va="center",
                            zorder=6)

    title = f"{run_title(run)}\nfootprints every {interval:g} s (labels: time in s)"
    for v in run.summary.get("vehicles", []):
        a, b = v["agent"], v.get("closest_agent")
        t = v.get("min_dist_time_s")
        if not b or t is None or a not in trajs or b not in trajs:
            continue
        ta, tb = trajs[a], trajs[b]
        ia, ib = int(np.argmin(np.abs(ta["t"] - t))), int(np.argmin(np.abs(tb["t"] - t)))
        oa = footprint_outline(footprints[a], ta["x"][ia], ta["y"][ia], ta["heading"][ia])
        ob = footprint_outline(footprints[b], tb["x"][ib], tb["y"][ib], tb["heading"][ib])
        for o, n in ((oa, a), (ob, b)):
            ax.add_patch(Polygon(o, closed=True, fc=colour[n], ec="black", lw=1.2, alpha=0.8, zorder=7))
        pa, pb = closest_points(oa, ob)
        if v.get("crash"):
            ax.plot([pa[0]], [pa[1]], marker="X", ms=14, color="#b30000", mec="black", zorder=9, ls="none",
                    label=f"crash of {a} with {v.get('crash_with')} at t = {v.get('crash_time_s'):.2f} s")
        else:
            ax.plot([pa[0], pb[0]], [pa[1], pb[1]], color="black", lw=1.5, zorder=8, marker="o", ms=3,
                    label=f"closest approach {a}–{b}: {v['min_dist_m']:.2f} m at t = {t:.2f} s")
        title += f"\n{a}: min distance {v['min_dist_m']:.2f} m, speed there {v['speed_kmh']:.1f} km/h, bypass {v['bypass']}"
    if xs:
        pad = 6.0
        x0, x1, y0, y1 = min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad
        # Not thinner than 3:5, so that a straight road shows its surroundings.
        span = 0.6 * max(x1 - x0, y1 - y0)
        if x1 - x0 < span:
            x0, x1 = (x0 + x1 - span) / 2, (x0 + x1 + span) / 2
        if y1 - y0 < span:
            y0, y1 = (y0 + y1 - span) / 2, (y0 + y1 + span) / 2
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (east) [m]")
    ax.set_ylabel("y (north) [m]")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.08), fontsize=8, ncol=2, frameon=False)
    save(fig, out_dir, name, written)


def kind_label(scene, name):
    for a in scene["agents"]:
        if a["name"] == name:
            if "type" in a:  # a recorded road user (maneuvermap measure)
                return ("measured " if a["kind"] == "planning_vehicle" else "") + a["type"]
            return {"planning_vehicle": "planning", "scripted_vehicle": "scripted", "pedestrian": "pedestrian"}.get(
                a["kind"], a["kind"])
    return ""


def draw_band(ax, line, width, colour):
    """A polyline drawn as a band `width` metres wide, in data units."""
    if len(line) < 2:
        return
    left, right = [], []
    for i in range(len(line)):
        a = line[max(i - 1, 0)]
        b = line[min(i + 1, len(line) - 1)]
        d = b - a
        n = np.array([-d[1], d[0]]) / (np.linalg.norm(d) or 1.0)
        left.append(line[i] + n * width / 2)
        right.append(line[i] - n * width / 2)
    ax.add_patch(Polygon(np.array(left + right[::-1]), closed=True, color=colour, lw=0, zorder=0))


def plot_run(directory, out_dir, written):
    run = Run(directory)
    agents = run.planning_agents()
    for agent in agents:
        suffix = "" if len(agents) == 1 else f"-{agent}"
        plot_map(run, agent, out_dir, f"map{suffix}", written)
    if agents:
        plot_speed([run], lambda r: agents[0], out_dir, "speed",
                   f"Speed of {agents[0]}: {run_title(run)}", written)
    plot_topdown(run, out_dir, "topdown", written)
    rooms = os.path.join(directory, "rooms.csv")
    if os.path.isfile(rooms):
        plot_rooms(run, read_csv(rooms), out_dir, "rooms", written)


def plot_rooms(run, rows, out_dir, name, written):
    """The room to maneuver of every measured road user over time (maneuvermap measure)."""
    by_agent = {}
    for r in rows:
        by_agent.setdefault(r["agent"], []).append((field_number(r, "t"), field_number(r, "room"), r["mode"] != "nominal"))
    fig, ax = plt.subplots(figsize=(9, 4.8))
    least = min(by_agent.items(), key=lambda item: min(room for _, room, _ in item[1]))[0] if by_agent else None
    for i, (agent, points) in enumerate(by_agent.items()):
        t, room, unsafe = (np.array(v) for v in zip(*points))
        colour = AGENT_COLOURS[i % len(AGENT_COLOURS)]
        emphasis = agent == least or len(by_agent) <= len(AGENT_COLOURS)
        ax.plot(t, room, color=colour if emphasis else "#9e9e9e", lw=1.8 if emphasis else 0.8,
                alpha=1.0 if emphasis else 0.6, label=agent if emphasis else None, zorder=3 if emphasis else 2)
        ax.plot(t[unsafe], room[unsafe], ls="none", marker="x", ms=4, color=colour if emphasis else "#9e9e9e",
                zorder=4)
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("room max(MI⁻, MI⁺) at τ̄")
    title = f"Room to maneuver of {len(by_agent)} recorded road user{'s' if len(by_agent) != 1 else ''}: {run_title(run)}"
    if len(by_agent) > len(AGENT_COLOURS):
        title += f"\nthe one with the least room coloured ({least}), the others grey"
    ax.set_title(title, fontsize=10)
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], ls="none", marker="x", ms=5, color="#555555"))
    labels.append("what it did was not safe (mode not nominal)")
    ax.legend(handles, labels, loc="lower left", fontsize=8, ncol=2)
    save(fig, out_dir, name, written)


# --- a sweep ----------------------------------------------------------------------------------


def cell_key(row, params):
    return tuple(field_number(row, p) for p in params)


def sweep_cells(rows, params):
    """{(params..., policy): [rows]} in file order."""
    cells = {}
    for r in rows:
        cells.setdefault(cell_key(r, params) + (r["policy"],), []).append(r)
    return cells


def plot_min_dist(sweep, rows, out_dir, written):
    """Minimum distance per cell and policy (mean ± sd over the repetitions), crashes marked."""
    params = list(sweep["parameters"].keys())
    cells = sweep_cells(rows, params)
    combos = []
    for key in cells:
        if key[:-1] not in combos:
            combos.append(key[:-1])
    policies = sorted({k[-1] for k in cells}, key=policy_key)
    fig, ax = plt.subplots(figsize=(min(16.0, max(6.0, 1.5 + 0.18 * len(combos) * len(policies))), 4.6))
    width = 0.8 / len(policies)
    for p_i, policy in enumerate(policies):
        for c_i, combo in enumerate(combos):
            group = [r for r in cells.get(combo + (policy,), []) if r["error"] == ""]
            if not group:
                continue
            d = np.array([field_number(r, "min_dist_m") for r in group if r["min_dist_m"] != ""])
            crashes = sum(r["crash"] == "1" for r in group)
            x = c_i + (p_i - (len(policies) - 1) / 2) * width
            mean = d.mean() if len(d) else 0.0
            sd = d.std(ddof=1) if len(d) > 1 else 0.0
            ax.bar(x, mean, width * 0.9, color=policy_colour(policy), yerr=sd if sd > 0 else None, capsize=2,
                   label=policy_label(policy) if c_i == 0 else None, edgecolor="black", lw=0.4)
            if crashes:
                ax.plot([x], [0], marker="x", color="#b30000", ms=8, mew=2, ls="none")
                ax.annotate(f"{crashes}/{len(group)}", (x, 0), xytext=(0, -14), textcoords="offset points",
                            ha="center", fontsize=7, color="#b30000")
    varying = [i for i, p in enumerate(params) if len(sweep["parameters"][p]) > 1]
    fixed = [f"{p} = {sweep['parameters'][p][0]:g}" for i, p in enumerate(params) if i not in varying]
    ax.set_xticks(range(len(combos)))
    ax.set_xticklabels(["\n".join(f"{params[i]} = {combo[i]:g}" for i in varying) or sweep["scenario"]
                        for combo in combos], fontsize=8 if len(combos) > 6 else 9)
    if fixed:
        ax.text(0.0, 1.01, "fixed: " + ", ".join(fixed), transform=ax.transAxes, fontsize=8, va="bottom")
    ax.set_ylabel("minimum distance [m]")
    ax.set_title(f"Sweep {sweep['sweep']}: minimum distance of {sweep['agent']} "
                 + ("\n" if fixed else "")
                 + (f"(mean ± sd over {sweep['repetitions']} repetitions)" if sweep["repetitions"] > 1 else "(one run per cell)"))
    handles, labels = ax.get_legend_handles_labels()
    if any(r["crash"] == "1" for r in rows):
        handles.append(Line2D([], [], marker="x", color="#b30000", mew=2, ls="none"))
        labels.append("crash (runs crashed / runs)")
    ax.legend(handles, labels, loc="best")
    ax.margins(y=0.15)
    save(fig, out_dir, "min-dist", written)


def paper_policy(policy):
    """Our policy name as the paper's table1.csv writes it: const:0.5 → const_0.5, const:1 → const_1.0."""
    kind, tau = policy_key(policy)
    return f"const_{tau:.1f}" if kind == 0 else policy


def plot_table1(sweep, rows, paper_rows, out_dir, written):
    """Figure 5: Table 1 as a chart, ours (mean ± sd, crashes) beside the paper's, per B speed."""
    cells = sweep_cells(rows, ["a_kmh", "b_kmh"])
    paper = {(field_number(r, "a_kmh"), field_number(r, "b_kmh"), r["policy"]): r for r in paper_rows}
    a_values = sorted({k[0] for k in cells})
    b_values = sorted({k[1] for k in cells}, reverse=True)
    policies = sorted({k[2] for k in cells}, key=policy_key)
    fig, axes = plt.subplots(len(b_values), 1, figsize=(10, 3.4 * len(b_values) + 0.8), sharex=True, squeeze=False)
    width = 0.8 / len(policies)
    top = 0.0
    for ax, b in zip(axes[:, 0], b_values):
        for p_i, policy in enumerate(policies):
            for a_i, a in enumerate(a_values):
                x = a_i + (p_i - (len(policies) - 1) / 2) * width
                group = [r for r in cells.get((a, b, policy), []) if r["error"] == ""]
                if group:
                    d = np.array([field_number(r, "min_dist_m") for r in group if r["min_dist_m"] != ""])
                    crashes = sum(r["crash"] == "1" for r in group)
                    mean = d.mean() if len(d) else 0.0
                    sd = d.std(ddof=1) if len(d) > 1 else 0.0
                    top = max(top, mean + sd)
                    ax.bar(x, mean, width * 0.85, color=policy_colour(policy), yerr=sd if sd > 0 else None,
                           capsize=2, edgecolor="black", lw=0.4)
                    if crashes:
                        ax.plot([x], [-0.09], marker="x", color="#b30000", ms=7, mew=2, ls="none")
                        if crashes < len(group):
                            ax.annotate(f"{crashes}", (x, -0.09), xytext=(5, -3), textcoords="offset points",
                                        fontsize=7, color="#b30000")
                    sides = [r["bypass"] for r in group]
                    side = max(("left", "right", "none"), key=sides.count)
                    ax.annotate(side[0].upper(), (x, -0.26), ha="center", va="center", fontsize=7,
                                color="black", fontweight="bold")
                ref = paper.get((a, b, paper_policy(policy)))
                if ref is not None:
                    value = float(ref["min_dist_m"] or 0)
                    top = max(top, value)
                    if ref["crash"] == "1":
                        ax.plot([x], [-0.09], marker="o", mfc="none", mec="black", ms=9, ls="none")
                    else:
                        ax.plot([x], [value], marker="D", mfc="white", mec="black", ms=5, ls="none", zorder=5)
                    ax.annotate(ref["bypass"][0].upper(), (x, -0.38), ha="center", va="center", fontsize=7,
                                color="black")
        ax.axhline(0, color="black", lw=0.6)
        ax.set_ylabel("minimum distance [m]")
        ax.set_title(f"B at {b:g} km/h", loc="left")
    for ax in axes[:, 0]:
        ax.set_ylim(-0.45, max(0.5, top) * 1.15)
        ax.text(-0.52, -0.26, "ours", fontsize=7, ha="right", va="center")
        ax.text(-0.52, -0.38, "paper", fontsize=7, ha="right", va="center")
    axes[-1, 0].set_xticks(range(len(a_values)))
    axes[-1, 0].set_xticklabels([f"A at {a:g} km/h" for a in a_values])
    axes[-1, 0].set_xlim(-0.6, len(a_values) - 0.4)
    handles = [Polygon([[0, 0]], closed=True, color=policy_colour(p), label=policy_label(p)) for p in policies]
    handles += [
        Line2D([], [], marker="D", mfc="white", mec="black", ms=5, ls="none", label="paper's value"),
        Line2D([], [], marker="x", color="#b30000", mew=2, ls="none", label="ours crashed (count if not all)"),
        Line2D([], [], marker="o", mfc="none", mec="black", ms=9, ls="none", label="paper crashed"),
    ]
    fig.legend(handles=handles, loc="lower center", ncol=4, frameon=False, bbox_to_anchor=(0.5, -0.07))
    n = sweep["repetitions"]
    fig.suptitle(f"Table 1 ({sweep['scenario']}): minimum distance of A per cell and policy — ours: mean ± sd over {n} "
                 f"repetition{'s' if n != 1 else ''}; letters: bypass side (L/R, ours majority)", fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "table1-comparison", written)


def plot_sweep(directory, out_dir, paper_table1, written):
    sweep = read_json(os.path.join(directory, "sweep.json"))
    rows = read_csv(os.path.join(directory, "runs.csv"))
    if not rows:
        raise BadInput(f"{directory}/runs.csv has no runs")
    plot_min_dist(sweep, rows, out_dir, written)
    params = list(sweep["parameters"].keys())
    # Table 1's layout: A's and B's speeds swept (any other parameter held at one value).
    table1_shaped = {"a_kmh", "b_kmh"} <= set(params) and all(
        len(v) == 1 for p, v in sweep["parameters"].items() if p not in ("a_kmh", "b_kmh"))
    if table1_shaped and paper_table1 and os.path.isfile(paper_table1):
        plot_table1(sweep, rows, read_csv(paper_table1), out_dir, written)
    kept = [os.path.join(directory, d) for d in sweep.get("run_dirs", [])
            if os.path.isfile(os.path.join(directory, d, "summary.json"))]
    if kept:
        runs = [Run(d) for d in kept]
        agent = sweep["agent"]
        varying = [p for p in params if len(sweep["parameters"][p]) > 1]

        def label(r):
            text = policy_label(r.policy)
            if varying:
                text += ", " + ", ".join(f"{p} = {r.summary['parameters'][p]:g}" for p in varying)
            if sweep["repetitions"] > 1:
                text += f", seed {r.summary['seed']}"
            return text

        plot_speed(runs, lambda r: agent, out_dir, "speed-profiles",
                   f"Sweep {sweep['sweep']} ({sweep['scenario']}): speed of {agent}", written,
                   label_of=label if len(runs) <= 12 else None)
        if len(kept) <= 8:
            for d in kept:
                target = d if os.path.abspath(out_dir) == os.path.abspath(directory) else \
                    os.path.join(out_dir, os.path.relpath(d, directory))
                plot_run(d, target, written)
        else:
            print(f"maneuvermap_plot: {len(kept)} kept runs: not drawing each one "
                  f"(maneuvermap plot {directory}/runs/NAME draws one)", file=sys.stderr)


# --- a snapshot -------------------------------------------------------------------------------


def plot_snapshot(csv_path, out_dir, written):
    """Figure 4: the displacement sets at one moment (paper Fig. 3)."""
    rows = read_csv(csv_path)
    if not rows or "end_x" not in rows[0]:
        raise BadInput(f"{csv_path}: not a snapshot CSV of maneuvermap")
    json_path = os.path.splitext(csv_path)[0] + ".json"
    info = read_json(json_path) if os.path.isfile(json_path) else None
    taus = sorted({field_number(r, "tau") for r in rows})
    tau = taus[0] if len(taus) == 1 else 1.0
    if info is not None:
        tau = min(taus, key=lambda t: abs(t - info["tau_bar_s"]))
    else:
        tau = min(taus, key=lambda t: abs(t - tau))
        print(f"maneuvermap_plot: no {json_path}: drawing τ = {tau:g} s without the nominal and chosen maneuvers",
              file=sys.stderr)
    at = [r for r in rows if abs(field_number(r, "tau") - tau) < 1e-6]
    pts = np.array([[field_number(r, "end_x"), field_number(r, "end_y")] for r in at])
    fam = np.array([r["family"] for r in at])
    # The decision's sets where the CSV has them (each obstacle at its own τ, or the robust sets),
    # else the column of τ̄.
    decision = "selected" in at[0]
    safe = np.array([r["selected" if decision else "safe"] == "1" for r in at])

    fig, (ax, ax_scene) = plt.subplots(1, 2, figsize=(12, 5.6), gridspec_kw={"width_ratios": [1.1, 1]})
    hull = convex_hull(pts)
    if len(hull) >= 3:
        ax.add_patch(Polygon(hull, closed=True, fc="#f0f0f0", ec="#969696", lw=1, zorder=0,
                             label="available set AS (both families)"))
    for family, marker in (("brake", "o"), ("accelerate", "s")):
        mask = (fam == family) & safe
        ax.scatter(pts[mask, 0], pts[mask, 1], s=9, marker=marker, color=FAMILY_COLOURS[family], zorder=2,
                   label=f"safe set, {family}-and-steer ({mask.sum()})")
    unsafe = ~safe
    ax.scatter(pts[unsafe, 0], pts[unsafe, 1], s=9, marker="x", color="#d62728", lw=0.8, zorder=2,
               label=f"collision set ({unsafe.sum()})")
    title = f"Displacement sets at τ = {tau:g} s"
    if info is not None:
        ego = info["ego"]
        ex, ey = ego["position_m"]
        nom, cho = info["nominal"], info["chosen"]
        ax.plot(*nom["end_m"], marker="*", ms=15, color="white", mec="black", ls="none", zorder=4,
                label=f"nominal: a = {nom['accel_mps2']:.2f} m/s², κ = {nom['curvature_per_m']:.3f} 1/m")
        ax.plot(*cho["end_m"], marker="D", ms=9, color="#ffd92f", mec="black", ls="none", zorder=5,
                label=f"chosen: a = {cho['accel_mps2']:.2f} m/s², κ = {cho['curvature_per_m']:.3f} 1/m")
        ax.add_patch(Polygon(footprint_outline(ego["footprint"], ex, ey, ego["heading_rad"]), closed=True,
                             fc="#bdbdbd", ec="black", lw=0.8, zorder=1))
        ttc = info.get("ttc_s")
        selected = decision and "mi_brake_selected" in info
        mi_brake = info["mi_brake_selected"] if selected else info["mi_brake_at_tau_bar"]
        mi_accel = info["mi_accel_selected"] if selected else info["mi_accel_at_tau_bar"]
        sets = ("safe under every τ ≤ τ̄" if info.get("robust") else "the decision's sets") if selected else f"τ = {tau:g} s"
        fig.suptitle(f"{info['scenario']}, {info['agent']} at t = {info['time_s']:.2f} s, "
                     f"policy {policy_label(info['policy'])}", fontsize=11)
        title = (f"{sets}: τ̄ = {info['tau_bar_s']:g} s, {info['family']}, {info['mode']}, "
                 f"TTC {'∞' if ttc is None else f'{ttc:.2f} s'}, MI⁻ = {mi_brake:.2f}, MI⁺ = {mi_accel:.2f}")
    ax.set_aspect("equal")
    ax.set_xlabel("x (east) [m]")
    ax.set_ylabel("y (north) [m]")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=2, frameon=False)

    # The scene at the same moment: the ego, its displacements, the obstacles and their forecasts.
    ax_scene.add_patch(Polygon(hull, closed=True, fc="#f0f0f0", ec="#969696", lw=1, zorder=0)) if len(hull) >= 3 else None
    ax_scene.scatter(pts[safe, 0], pts[safe, 1], s=3, color="#636363", zorder=1)
    ax_scene.scatter(pts[unsafe, 0], pts[unsafe, 1], s=3, color="#d62728", zorder=1)
    xs, ys = list(pts[:, 0]), list(pts[:, 1])
    if info is not None:
        ego = info["ego"]
        ax_scene.add_patch(Polygon(footprint_outline(ego["footprint"], *ego["position_m"], ego["heading_rad"]),
                                   closed=True, fc=AGENT_COLOURS[0], ec="black", lw=0.8, zorder=3,
                                   label=f"{info['agent']} (planning)"))
        xs.append(ego["position_m"][0])
        ys.append(ego["position_m"][1])
        for k, ob in enumerate(info["obstacles"]):
            c = AGENT_COLOURS[(k + 1) % len(AGENT_COLOURS)]
            x, y = ob["position_m"]
            ax_scene.add_patch(Polygon(footprint_outline(ob["footprint"], x, y, ob["heading_rad"]), closed=True,
                                       fc=c, ec="black", lw=0.8, zorder=3, label=f"{ob['name']} (observed)"))
            f = np.array(ob["forecast_m"])
            ax_scene.plot(f[:, 0], f[:, 1], color=c, ls="--", lw=1.2, zorder=2,
                          label=f"{ob['name']} forecast, τ = {ob['tau_s']:g} s, over {info['collision_window_s']:g} s")
            xs += [x] + list(f[:, 0])
            ys += [y] + list(f[:, 1])
    pad = 3.0
    ax_scene.set_xlim(min(xs) - pad, max(xs) + pad)
    ax_scene.set_ylim(min(ys) - pad, max(ys) + pad)
    ax_scene.set_aspect("equal")
    ax_scene.set_xlabel("x (east) [m]")
    ax_scene.set_ylabel("y (north) [m]")
    ax_scene.set_title("The scene: displacements (grey safe, red colliding)\nand forecasts", fontsize=10)
    if info is not None:
        ax_scene.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=8, ncol=1, frameon=False)
    stem = os.path.splitext(os.path.basename(csv_path))[0]
    save(fig, out_dir, f"{stem}-sets", written)


# --- main -------------------------------------------------------------------------------------


def main(argv):
    parser = argparse.ArgumentParser(description="Figures of maneuvermap run, sweep and snapshot outputs.")
    parser.add_argument("target", help="a run directory, a sweep directory or a snapshot CSV")
    parser.add_argument("--out", help="where to write the figures (default: next to the target)")
    parser.add_argument("--paper-table1", default=DEFAULT_PAPER_TABLE1,
                        help="the paper's Table 1 as CSV (default: data/paper/table1.csv of the source tree)")
    args = parser.parse_args(argv)
    target = args.target
    written = []
    try:
        if os.path.isdir(target):
            out_dir = args.out or target
            if os.path.isfile(os.path.join(target, "sweep.json")) and os.path.isfile(os.path.join(target, "runs.csv")):
                plot_sweep(target, out_dir, args.paper_table1, written)
            elif os.path.isfile(os.path.join(target, "summary.json")) and os.path.isfile(os.path.join(target, "scene.json")):
                plot_run(target, out_dir, written)
            else:
                raise BadInput(f"{target}: neither a run directory (summary.json, scene.json, ...) "
                               f"nor a sweep directory (sweep.json, runs.csv)")
        elif os.path.isfile(target) and target.endswith(".csv"):
            plot_snapshot(target, args.out or os.path.dirname(target) or ".", written)
        else:
            raise BadInput(f"{target}: not a run directory, a sweep directory or a snapshot CSV")
    except BadInput as error:
        print(f"maneuvermap_plot: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except (OSError, json.JSONDecodeError) as error:
        print(f"maneuvermap_plot: {target}: cannot read it: {type(error).__name__}: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except (KeyError, TypeError, ValueError, IndexError) as error:
        # A field of the JSON files, or a value, that is not what maneuvermap writes.
        print(f"maneuvermap_plot: {target}: not what maneuvermap writes ({type(error).__name__}: {error})",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
