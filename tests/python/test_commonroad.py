"""CommonRoad recordings from Python: read, measure, and the same room as the planner (docs/python.md)."""
import concurrent.futures
import multiprocessing
import pickle
import subprocess
import sys

import numpy as np
import pytest

import maneuvermap as mm
from conftest import assert_same_attributes

PEDESTRIAN_COLLISION = "data/commonroad/OSC_PedestrianCollision-1_1_T-1.xml"


def test_a_recording_reads_into_its_road_users_and_lanes(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    assert s.version in ("2018b", "2020a")
    assert s.time_step > 0
    assert s.lanelets and s.lanelets[0].left_bound.shape[1] == 2
    assert s.date == "2023-04-19"
    by_id = {lane.id: lane for lane in s.lanelets}
    links = [(lane.id, next_id) for lane in s.lanelets for next_id in lane.successors]
    assert links and all(lane in by_id[next_id].predecessors for lane, next_id in links if next_id in by_id)
    users = mm.commonroad.measurable_road_users(s)
    assert users
    first = s.obstacle(users[0])
    assert first.positions.shape == (len(first.states), 2)
    assert np.all(np.diff(first.steps) == 1)


def test_a_measurement_is_the_planner_on_the_recorded_inputs_bit_for_bit(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    agent = mm.commonroad.measurable_road_users(s)[0]
    measured = mm.commonroad.measure(s, agent)
    assert len(measured.steps) == len(s.obstacle(agent).states)
    assert measured.mi_brake.shape == (len(measured.steps), 17)
    assert np.all((0.0 <= measured.rooms) & (measured.rooms <= 1.0))
    for k in range(0, len(measured.steps), 17):
        step = measured.steps[k]
        scene, ids = mm.commonroad.planning_input(s, agent, step.step)
        assert ids == step.obstacle_ids
        result = mm.plan(scene)
        assert result.mi_brake.tobytes() == measured.mi_brake[k].tobytes()
        assert result.mi_accelerate.tobytes() == measured.mi_accelerate[k].tobytes()
        assert mm.commonroad.room(result) == measured.rooms[k]


def test_the_car_of_the_pedestrian_collision_runs_out_of_room(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    car = mm.commonroad.recorded_ego(s, s.planning_problems[0])
    assert car is not None
    measured = mm.commonroad.measure(s, car)
    assert measured.rooms[0] > 0.5
    assert measured.rooms.min() == 0.0


def test_a_measurement_pickles_with_every_attribute(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    car = mm.commonroad.recorded_ego(s, s.planning_problems[0])
    assert car is not None
    measured = mm.commonroad.measure(s, car)
    assert measured.agent != 0 and measured.steps[-1].step > 0 and measured.steps[-1].obstacle_ids
    assert_same_attributes(measured, pickle.loads(pickle.dumps(measured)), "measurement")


def measure_in_worker(s, agent):
    """What a worker process returns: the rooms of a measurement."""
    return mm.commonroad.measure(s, agent).rooms


def test_a_read_scenario_pickles_whole_and_measures_the_same_in_another_process(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    copy = pickle.loads(pickle.dumps(s))
    assert copy == s and copy != mm.commonroad.read_scenario(source_dir / "data/commonroad/USA_Lanker-1_1_T-1.xml")
    assert_same_attributes(s, copy, "scenario")
    car = mm.commonroad.recorded_ego(s, s.planning_problems[0])
    assert car is not None
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        rooms = pool.submit(measure_in_worker, s, car).result()
    assert rooms.tobytes() == mm.commonroad.measure(s, car).rooms.tobytes()


def test_bad_files_and_unknown_road_users_raise_value_errors_that_say_where(source_dir):
    with pytest.raises(mm.commonroad.read_error, match="bad.xml"):
        mm.commonroad.read_scenario_text("<commonRoad>", "bad.xml")
    with pytest.raises(ValueError, match="no-such-file.xml"):
        mm.commonroad.read_scenario(source_dir / "no-such-file.xml")
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    with pytest.raises(mm.commonroad.measure_error, match="424242"):
        mm.commonroad.measure(s, 424242)


def test_a_replay_drives_one_road_user_with_the_planner_and_replays_the_others(source_dir):
    s = mm.commonroad.read_scenario(source_dir / PEDESTRIAN_COLLISION)
    baseline = mm.sim.run(mm.commonroad.replay_scenario(s, 34, avoidance=False))
    planned = mm.sim.run(mm.commonroad.replay_scenario(s, 34, desired_speed=9.0))
    assert [a.name for a in planned.agents] == ["car-34", "pedestrian-35"]
    # The pedestrian is where it was recorded at every recorded step, in both runs.
    pedestrian = s.obstacle(35)
    for run in (baseline, planned):
        for state in pedestrian.states:
            k = int(round(state.step * s.time_step / 0.01))
            if k < len(run.times):
                assert run.present[k, 1]
                assert abs(run.x[k, 1] - state.position.x) < 1e-6 and abs(run.y[k, 1] - state.position.y) < 1e-6
    assert len(baseline.maps[0].times) == 0 and baseline.metrics[0].max_lateral_offset_m < 0.05
    assert len(planned.maps[0].times) > 0 and planned.metrics[0].max_lateral_offset_m > 0.5
    with pytest.raises(mm.commonroad.measure_error, match="a pedestrian"):
        mm.commonroad.replay_scenario(s, 35)


def test_the_long_recording_generator_writes_a_recording_that_replays(source_dir):
    # tools/python/make_long_recording.py makes the recordings of docs/simulator.md's replay-cost table.
    text = subprocess.run([sys.executable, str(source_dir / "tools/python/make_long_recording.py"), "--seconds", "2",
                           "--cars", "3"], check=True, capture_output=True, text=True).stdout
    s = mm.commonroad.read_scenario_text(text, "long.xml")
    assert s.time_step == 0.04
    assert mm.commonroad.measurable_road_users(s) == [1, 2, 3]
    assert all(len(s.obstacle(i).states) == 50 for i in (1, 2, 3))
    run = mm.sim.run(mm.commonroad.replay_scenario(s, 1, avoidance=False))
    assert not any(m.crash for m in run.metrics)
    # Replayed car 2's speed changes by its accel over each step (docs/outputs.md).
    present = run.present[:-1, 1] & run.present[1:, 1]
    change = run.speed[1:, 1] - run.speed[:-1, 1]
    assert np.allclose(change[present], (run.acceleration[:-1, 1] * 0.01)[present], atol=1e-9)


def test_a_reactive_replay_holds_up_the_car_behind_the_driven_one(source_dir):
    s = mm.commonroad.read_scenario(source_dir / "data/commonroad/USA_Lanker-1_1_T-1.xml")
    plain = mm.sim.run(mm.commonroad.replay_scenario(s, 1214), map_columns=False)
    reactive = mm.sim.run(mm.commonroad.replay_scenario(s, 1214, reactive=True), map_columns=False)
    names = [a.name for a in plain.agents]
    behind = names.index("car-1216")
    # Car 1216, 14 m behind the driven car, falls behind its recording.
    both = plain.present[:, behind] & reactive.present[:, behind]
    lag = np.hypot(plain.x[both, behind] - reactive.x[both, behind], plain.y[both, behind] - reactive.y[both, behind])
    assert lag.max() > 1.0
    assert reactive.metrics[0].crash == plain.metrics[0].crash


def test_on_its_lanelets_a_road_user_has_at_most_the_room_it_has_off_them(source_dir):
    s = mm.commonroad.read_scenario(source_dir / "data/commonroad/USA_Lanker-1_1_T-1.xml")
    open_ground = mm.commonroad.measure(s, 1214)
    on_road = mm.commonroad.measure(s, 1214, on_lanelets=True)
    assert np.all(on_road.rooms <= open_ground.rooms + 1e-4)
    assert np.any(on_road.rooms < open_ground.rooms - 0.01)
    assert any(step.result.on_drivable_area for step in on_road.steps)
    replay = mm.commonroad.replay_scenario(s, 1214, on_lanelets=True)
    assert replay.drivable_area is not None and len(replay.drivable_area.polygons) == len(s.lanelets)
