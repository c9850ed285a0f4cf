"""Replays every road user of the bundled CommonRoad files, without and with the planner
(docs/commonroad.md, "What the bundled files show").

    PYTHONPATH=build/release/python /usr/bin/python3 tools/python/replay_all.py [--policy POLICY] [--reactive] [FILE.xml ...]

For each road user that can be driven: a replay without avoidance (the path follower alone, the
baseline) and one with the planner (default options, ADJ, or POLICY as on the command line:
`robust`, `const:1.0`); prints the crashes of each, with the
time and the closest distance, and the road users that cannot be driven, with the reason. With
--reactive the other vehicles keep their distance to the road user ahead on their recorded paths
(`replay --reactive`).
"""
import argparse
import pathlib
import time

import maneuvermap as mm

BUNDLED = ["OSC_PedestrianCollision-1_1_T-1", "ZAM_Intersection-1_1_T-1", "ZAM_Tutorial-1_2_T-1",
           "USA_Lanker-1_1_T-1"]


def describe(metrics):
    if metrics.crash:
        return f"crash at {metrics.crash_time_s:.2f} s with {metrics.crash_with}"
    return f"no crash, closest {metrics.min_dist_m:.4f} m" if metrics.min_dist_m is not None else "no crash"


def main(files, policy, reactive):
    for file in files:
        recording = mm.commonroad.read_scenario(file)
        start = time.perf_counter()
        driven, refused = 0, []
        crashes: dict[bool, list[int]] = {False: [], True: []}
        for agent in mm.commonroad.measurable_road_users(recording):
            try:
                runs = {avoid: mm.sim.run(mm.commonroad.replay_scenario(recording, agent, avoidance=avoid, policy=policy,
                                                                     reactive=reactive),
                                          map_columns=False).metrics[0] for avoid in (False, True)}
            except ValueError as error:
                refused.append(f"{agent}: {error}")
                continue
            driven += 1
            for avoid, metrics in runs.items():
                if metrics.crash:
                    crashes[avoid].append(agent)
            if runs[False].crash or runs[True].crash:
                print(f"  {pathlib.Path(file).stem} road user {agent}: without the planner {describe(runs[False])}; "
                      f"with it {describe(runs[True])}, slowest {runs[True].min_speed_kmh:.1f} km/h, "
                      f"{runs[True].max_lateral_offset_m:.2f} m aside")
        print(f"{pathlib.Path(file).stem}: {driven} road users driven, crashes without the planner "
              f"{crashes[False] or 'none'}, with it {crashes[True] or 'none'} ({time.perf_counter() - start:.1f} s)")
        for line in refused:
            print(f"  not driven: {line}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--policy", default="adj", help="forecast policy of the planner: adj, const:SECONDS or robust")
    parser.add_argument("files", nargs="*", help="CommonRoad files (default: the bundled ones)")
    parser.add_argument("--reactive", action="store_true",
                        help="the other vehicles keep their distance to the road user ahead (car following)")
    args = parser.parse_args()
    main(args.files or [f"data/commonroad/{name}.xml" for name in BUNDLED], mm.forecast_policy.parse(args.policy),
         args.reactive)
