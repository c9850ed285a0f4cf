"""A small study of a scenario built in Python: a pedestrian steps out from behind a parked van.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/pedestrian_study.py out/pedestrian-study.png

Car A drives at 40 km/h past a van parked at the kerb; a pedestrian walks out from in front of the
van across A's lane. The scenario is written in Python (no scenario file: docs/python.md, "A
scenario built in Python") and run for a range of the pedestrian's start times, once with A
planning with Maneuverability Maps and once as the naive baseline that only follows its path
(avoidance off), the runs in parallel threads. Prints each run's outcome and the counts of crashes,
and draws A's smallest gap to any road user (0 at a crash) against the start time.
"""
import concurrent.futures
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import maneuvermap as mm  # noqa: E402

KMH = 1.0 / 3.6
START_TIMES = np.round(np.arange(1.5, 4.51, 0.25), 2)  # when the pedestrian sets off [s]


def scenario(pedestrian_start: float, avoidance: bool) -> mm.sim.scenario:
    car = mm.sim.planning_vehicle(
        name="A", path=mm.sim.path(mm.pose((-50.0, 0.0), 0.0)).straight(120.0),
        initial_speed=40 * KMH, desired_speed=40 * KMH, shape=mm.rectangle(4.5, 1.8), avoidance=avoidance,
        planner=mm.planner_config(safety_margin=0.3))
    # The van stands at the kerb, 2 to 4 m right of A's path; the pedestrian comes out in front of it.
    van = mm.sim.static_obstacle(name="van", vertices=[(8.0, -4.0), (13.5, -4.0), (13.5, -2.0), (8.0, -2.0)])
    walker = mm.sim.pedestrian(
        name="P", motion=mm.sim.scripted_motion(
            path=mm.sim.path(mm.pose((14.5, -3.5), math.pi / 2)).straight(10.0),
            start_time=pedestrian_start, before_start=mm.sim.before_start_behaviour.wait,
            speed=mm.sim.speed_profile.constant(1.4)))
    return mm.sim.scenario(name=f"pedestrian-at-{pedestrian_start:.2f}s", duration=8.0, planning_vehicles=[car],
                           pedestrians=[walker], static_obstacles=[van])


def main(out: str) -> None:
    cases = [(start, avoidance) for avoidance in (False, True) for start in START_TIMES]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        runs = list(pool.map(lambda case: mm.sim.run(scenario(*case), decision_only=True), cases))
    crashes = {False: 0, True: 0}
    gap: dict[bool, list[float]] = {False: [], True: []}
    for (start, avoidance), run in zip(cases, runs):
        m = run.metrics[0]
        crashes[avoidance] += int(m.crash)
        gap[avoidance].append(0.0 if m.crash or m.min_dist_m is None else m.min_dist_m)
        ending = f"crash at {m.crash_time_s:.2f} s with {m.crash_with}" if m.crash else f"no crash, {m.min_dist_m:.2f} m"
        print(f"pedestrian at {start:.2f} s, {'maps ' if avoidance else 'naive'}: {ending}, "
              f"slowest {m.min_speed_kmh:.1f} km/h")
    print(f"naive: {crashes[False]} crashes in {len(START_TIMES)} runs")
    print(f"maps: {crashes[True]} crashes in {len(START_TIMES)} runs")

    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    ax.plot(START_TIMES, gap[False], "o--", label="naive (follows its path)")
    ax.plot(START_TIMES, gap[True], "o-", label="with Maneuverability Maps")
    ax.axhline(0.3, color="grey", lw=0.8, ls=":", label="A's safety margin")
    ax.set_xlabel("pedestrian sets off at [s]")
    ax.set_ylabel("A's smallest gap to a road user [m] (0: crash)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "pedestrian-study.png")
