#!/usr/bin/env python3
"""The fast planner against the reference (spec §11) on recorded steps of CommonRoad files, on the
files' lanelets (spec §5's road constraint): draws random (file, road user, step) triples whose
planning input starts on the lanelets, plans each with mm.plan and mm.plan_reference, and prints
the largest |ΔMI| over the forecast times and both families per step, then its distribution.
Where the reference's exhaustive forecast-time search over the neighbours would be too large, both
plan under a constant policy: the map columns compared do not depend on the policy.

    PYTHONPATH=build/release/python /usr/bin/python3 tools/python/lanelet_accuracy.py \
        ../shared/data/commonroad/*.xml [--steps 150] [--seed 5]
"""
import argparse
import random
import sys

import numpy as np

import maneuvermap as mm


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("files", nargs="+", help="CommonRoad XML files")
    parser.add_argument("--steps", type=int, default=150, help="recorded steps to compare (default 150)")
    parser.add_argument("--seed", type=int, default=5, help="seed of the draw (default 5)")
    args = parser.parse_args()
    if args.steps < 1:
        parser.error(f"--steps {args.steps}: expected at least 1")

    scenarios = [(path, mm.commonroad.read_scenario(path)) for path in sorted(args.files)]
    candidates = []
    for index, (_, scenario) in enumerate(scenarios):
        for agent in mm.commonroad.measurable_road_users(scenario):
            for step in scenario.obstacle(agent).steps:
                candidates.append((index, agent, int(step)))
    rng = random.Random(args.seed)
    rng.shuffle(candidates)

    errors = []
    print("file,agent,step,relevant,largest_abs_delta_mi,forecast_time_s,family")
    for index, agent, step in candidates:
        if len(errors) == args.steps:
            break
        path, scenario = scenarios[index]
        try:
            scene, _ = mm.commonroad.planning_input(scenario, agent, step, on_lanelets=True)
        except ValueError:
            continue  # a step the recording cannot be planned at (no history yet, standing still)
        fast = mm.plan(scene)
        if fast.status != mm.plan_status.ok or not fast.on_drivable_area:
            continue
        try:
            reference = mm.plan_reference(scene)
        except ValueError:
            # The reference's exhaustive forecast-time search over many turning neighbours is too
            # large: compare the map columns, which do not depend on the policy, under a constant one.
            scene.config.policy = mm.forecast_policy.parse("const:1.0")
            fast = mm.plan(scene)
            reference = mm.plan_reference(scene)
        brake = np.abs(fast.mi_brake - reference.mi_brake)
        accelerate = np.abs(fast.mi_accelerate - reference.mi_accelerate)
        family = "brake" if brake.max() >= accelerate.max() else "accelerate"
        worst = brake if family == "brake" else accelerate
        k = int(worst.argmax())
        errors.append(float(worst[k]))
        relevant = sum(1 for o in fast.obstacles if o.relevant)
        print(f"{path},{agent},{step},{relevant},{worst[k]:.4f},{fast.forecast_times[k]:.3f},{family}", flush=True)

    values = np.array(errors)
    print(f"# {len(values)} steps (seed {args.seed}): largest |dMI| max {values.max():.4f}, "
          f"p95 {np.percentile(values, 95):.4f}, median {np.median(values):.4f}, "
          f"over 0.02: {int((values > 0.02).sum())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
