"""Whole runs from Python threads: does `maneuvermap.sim.run` use both cores? (docs/python.md, "Cost")

    PYTHONPATH=build/release/python /usr/bin/python3 tools/python/time_runs_in_threads.py

Runs the left turn S3 with eight seeds one after the other, then in a pool of two threads, and
checks that both give the same runs; prints the wall times (median of three tries each).
"""
import concurrent.futures
import statistics
import time

import maneuvermap as mm

SEEDS = range(8)


def one_run(seed):
    record = mm.sim.run("s3-left-turn", seed=seed, map_columns=False)
    return record.x.tobytes(), record.metrics[0].crash


def wall_time(work):
    times, result = [], None
    for _ in range(3):
        start = time.perf_counter()
        result = work()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def main():
    sequential, first = wall_time(lambda: [one_run(seed) for seed in SEEDS])
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        threaded, second = wall_time(lambda: list(pool.map(one_run, SEEDS)))
    assert first == second, "the threads' runs differ from the sequential ones"
    print(f"{len(SEEDS)} runs of s3-left-turn: one after the other {sequential:.2f} s, "
          f"in two threads {threaded:.2f} s ({sequential / threaded:.2f}x), identical runs")


if __name__ == "__main__":
    main()
