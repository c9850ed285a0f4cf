#!/usr/bin/env python3
"""A synthetic CommonRoad recording of any length, to measure how a replay's cost grows with it:
CARS cars on parallel lanes 4 m apart, driving east for the whole recording at 10 ± 3 m/s (a
sinusoid in time), recorded every 0.04 s (25 Hz, as in highD-like data). No lanelets, no planning
problem: replay it with --agent 1.

    /usr/bin/python3 tools/python/make_long_recording.py --seconds 120 --cars 11 > long.xml
    /usr/bin/time build/release/cli/maneuvermap replay long.xml --agent 1 --no-avoidance
"""
import argparse
import math
import sys

TIME_STEP = 0.04


def car(identifier: int, lane_y: float, steps: int) -> str:
    lines = [f'  <dynamicObstacle id="{identifier}">', "    <type>car</type>",
             "    <shape><rectangle><length>4.5</length><width>2.0</width></rectangle></shape>"]
    x = 0.0
    for k in range(steps):
        speed = 10.0 + 3.0 * math.sin(0.05 * k + identifier)
        tag = "initialState" if k == 0 else "state"
        lines.append(f"    <{tag}><position><point><x>{x:.4f}</x><y>{lane_y}</y></point></position>"
                     f"<orientation><exact>0.0</exact></orientation><time><exact>{k}</exact></time>"
                     f"<velocity><exact>{speed:.4f}</exact></velocity></{tag}>")
        if k == 0:
            lines.append("    <trajectory>")
        x += speed * TIME_STEP
    lines += ["    </trajectory>", "  </dynamicObstacle>"]
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=120.0, help="length of the recording (default 120 s)")
    parser.add_argument("--cars", type=int, default=11, help="number of cars (default 11)")
    args = parser.parse_args()
    if not args.seconds >= 2 * TIME_STEP or args.cars < 1:
        parser.error(f"--seconds {args.seconds} --cars {args.cars}: expected at least 0.08 s and 1 car")
    steps = int(round(args.seconds / TIME_STEP))
    print('<?xml version="1.0" encoding="UTF-8"?>')
    print(f'<commonRoad timeStepSize="{TIME_STEP}" commonRoadVersion="2020a" benchmarkID="ZAM_Long-1_1_T-1">')
    for i in range(args.cars):
        print(car(i + 1, 4.0 * i, steps))
    print("</commonRoad>")
    return 0


if __name__ == "__main__":
    sys.exit(main())
