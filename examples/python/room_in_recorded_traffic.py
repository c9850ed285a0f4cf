"""How much room to maneuver the road users of a CommonRoad recording had, from Python.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/room_in_recorded_traffic.py \\
        data/commonroad/ZAM_Intersection-1_1_T-1.xml

Measures every road user that can be measured (docs/commonroad.md) and prints, for each, its least
room and when, and how many of its steps left it no room at all; the room is max(MI−, MI+) under the
selected forecast times (spec §7).
"""
import sys

import numpy as np

import maneuvermap as mm


def main(file):
    recording = mm.commonroad.read_scenario(file)
    print(f"{recording.benchmark_id}: {len(recording.obstacles)} obstacles, time step {recording.time_step} s")
    print(f"{'road user':>10} {'type':>10} {'steps':>6} {'least room':>11} {'at t [s]':>9} {'no room':>8}")
    for agent in mm.commonroad.measurable_road_users(recording):
        measured = mm.commonroad.measure(recording, agent)
        rooms = measured.rooms
        k = int(np.argmin(rooms))
        print(f"{agent:>10} {recording.obstacle(agent).type:>10} {len(rooms):>6} {rooms[k]:>11.3f} "
              f"{measured.times[k]:>9.2f} {int(np.sum(rooms == 0.0)):>8}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: room_in_recorded_traffic.py FILE.xml")
    try:
        main(sys.argv[1])
    except ValueError as error:  # read_error, measure_error: they name the file, line and field
        print(f"room_in_recorded_traffic.py: error: {error}", file=sys.stderr)
        sys.exit(2)
