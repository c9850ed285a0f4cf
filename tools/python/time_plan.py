"""What a planning step costs when called from Python (docs/python.md, "Cost").

    PYTHONPATH=build/release/python /usr/bin/python3 tools/python/time_plan.py

Replays the left turn S3 to 4.80 s, the instant of the benchmark case `plan/obstacles:1`
(docs/performance.md), takes A's planning input there and times `maneuvermap.plan` on it, and a call
that only reads the input (`validation_error`): median and slowest of 5 repetitions of 400 calls.
Compare with `build/release/benchmarks/maneuvermap_bench --benchmark_filter='^plan/obstacles:1/'`.
"""
import statistics
import time

import maneuvermap as mm


def median_and_max_us(call, calls=400, repetitions=5):
    call()  # the first NumPy array imports NumPy
    means = []
    for _ in range(repetitions):
        start = time.perf_counter()
        for _ in range(calls):
            call()
        means.append((time.perf_counter() - start) / calls * 1e6)
    return statistics.median(means), max(means)


def main():
    simulation = mm.sim.simulation(mm.sim.load("s3-left-turn"))
    a = simulation.find("A")
    assert a is not None, "s3-left-turn has no agent A"
    while simulation.time < 4.80 - 1e-9:
        simulation.step()
    scene = simulation.planning_input(a)
    assert scene is not None, "A does not plan at 4.80 s"
    result = mm.plan(scene)
    print(f"S3 at {simulation.time:.2f} s: {result.work.relevant_obstacles} relevant obstacle, "
          f"{result.work.bound_checks} bound checks (the benchmark input has 18673)")
    for name, call in (("maneuvermap.plan", lambda: mm.plan(scene)),
                       ("maneuvermap.validation_error", lambda: mm.validation_error(scene)),
                       ("reading the map column", lambda: (result.mi_brake, result.mi_accelerate))):
        median, slowest = median_and_max_us(call)
        print(f"{name:30} median {median:8.1f} µs, slowest repetition {slowest:8.1f} µs")


if __name__ == "__main__":
    main()
