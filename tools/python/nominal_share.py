"""How much of a run's planning goes to steps whose nominal maneuver is safe whatever the forecast.

    PYTHONPATH=build/release/python /usr/bin/python3 tools/python/nominal_share.py s6-busy-roundabout --every 20

Runs SCENARIO (decisions only, as a sweep does) and, every EVERY-th step, plans each planning vehicle
that planned at that step again on its input twice: as it did (its own policy, without the map
column; timed) and under the robust policy. When the robust plan is nominal, u_nom is safe under every
forecast time that TTC does not exclude, of every obstacle, so rule 1 of spec §8 applies it whatever
forecast time the indices select: a planner could decide such a step without the indices. Prints,
per kind of step (u_nom safe under every forecast time or not, and the mode of the plan as it was),
the plans, their mean time and their share of the sampled plans' time (docs/performance.md,
"Many agents").
"""
import argparse
import collections
import time

import maneuvermap as mm


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", help="a built-in scenario's name or a scenario file")
    parser.add_argument("--every", type=int, default=20, help="sample every N-th step (default 20)")
    parser.add_argument("--jobs", type=int, default=2, help="planning threads of the run (default 2)")
    args = parser.parse_args()
    if args.every < 1:
        parser.error(f"--every {args.every}: expected a whole number >= 1")
    simulation = mm.sim.simulation(mm.sim.load(args.scenario), jobs=args.jobs, map_columns=False)
    robust = mm.forecast_policy.parse("robust")
    plans: collections.Counter[str] = collections.Counter()
    seconds: collections.defaultdict[str, float] = collections.defaultdict(float)
    while not simulation.ended():
        simulation.step()
        if simulation.step_index % args.every != 0:
            continue
        for vehicle in range(simulation.planning_vehicle_count):
            if not simulation.planned_now(vehicle):
                continue
            scene = simulation.planning_input(vehicle)
            if scene is None:  # not present
                continue
            scene.config.map_column = False
            start = time.perf_counter()
            as_planned = mm.plan(scene)
            elapsed = time.perf_counter() - start
            scene.config.policy = robust
            under_all = mm.plan(scene)  # `robust`: decided from the maneuvers safe under every forecast time
            safe_under_all = under_all.robust and under_all.mode == mm.planning_mode.nominal
            kind = ("u_nom safe under every forecast time" if safe_under_all else "not") + ", " + as_planned.mode.name
            plans[kind] += 1
            seconds[kind] += elapsed
    total = sum(seconds.values())
    print(f"{args.scenario}: {sum(plans.values())} plans sampled (one step in {args.every}), {total:.2f} s of planning")
    print("| step | plans | mean ms per plan | share of the time |")
    print("|---|---|---|---|")
    for kind in sorted(plans):
        print(f"| {kind} | {plans[kind]} | {1e3 * seconds[kind] / plans[kind]:.3f} | "
              f"{100 * seconds[kind] / total if total > 0 else 0.0:.0f} % |")


if __name__ == "__main__":
    main()
