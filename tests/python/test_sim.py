"""The simulator from Python: a run gives what `maneuvermap run` writes, as arrays (docs/python.md)."""
import concurrent.futures
import copy
import csv
import json
import math
import multiprocessing
import pathlib
import pickle
import re
import subprocess

import numpy as np
import pytest

import maneuvermap as mm
from conftest import assert_same_attributes


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_a_run_gives_the_trajectories_and_the_map_that_maneuvermap_run_writes(cli, tmp_path):
    subprocess.run([cli, "run", "s3-left-turn", "--out", str(tmp_path)], check=True, capture_output=True)
    record = mm.sim.run("s3-left-turn")
    names = [a.name for a in record.agents]
    rows = read_csv(tmp_path / "trajectories.csv")
    present = record.present
    assert len(rows) == int(present.sum())
    k_of_time = {f"{t:.6f}": k for k, t in enumerate(record.times)}
    for row in rows:
        k, n = k_of_time[row["t"]], names.index(row["agent"])
        assert present[k, n]
        for column, array in (("x", record.x), ("y", record.y), ("heading", record.heading),
                              ("speed", record.speed), ("accel", record.acceleration),
                              ("curvature", record.curvature)):
            assert float(row[column]) == pytest.approx(array[k, n], abs=6e-7), (row, column)
    map_rows = read_csv(tmp_path / "map.csv")
    a = record.map("A")
    assert len(map_rows) == a.mi_brake.size
    for index, row in enumerate(map_rows):
        step, i = divmod(index, len(a.forecast_times))
        assert float(row["t"]) == pytest.approx(a.times[step], abs=6e-7)
        assert float(row["tau"]) == pytest.approx(a.forecast_times[i], abs=6e-7)
        assert float(row["mi_brake"]) == pytest.approx(a.mi_brake[step, i], abs=6e-7)
        assert float(row["mi_accel"]) == pytest.approx(a.mi_accelerate[step, i], abs=6e-7)
        assert (row["excluded"] == "1") == a.excluded[step, i]


def test_a_robust_run_marks_the_steps_its_robust_sets_decided_as_decisions_csv_does(cli, source_dir, tmp_path):
    # S3 with 2.3 s of B's turn visible: the robust policy avoids, falling back to ADJ at a few steps.
    file = source_dir / "sweeps" / "s3-variants" / "s3-left-turn-offset-14m.yaml"
    subprocess.run([cli, "run", str(file), "--set", "a_kmh=40", "--set", "b_kmh=35", "--policy", "robust",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    record = mm.sim.run(file, set={"a_kmh": 40.0, "b_kmh": 35.0}, policy=mm.forecast_policy.parse("robust"))
    assert not record.metrics[0].crash
    a = record.map("A")
    assert a.robust.dtype == bool and a.robust.any() and not a.robust.all()
    rows = read_csv(tmp_path / "decisions.csv")
    assert [row["robust"] == "1" for row in rows] == a.robust.tolist()
    # Where the robust sets decided, τ̄ is the largest forecast time not excluded.
    largest = np.array([a.forecast_times[~row].max() for row in a.excluded])
    np.testing.assert_array_equal(a.forecast_time[a.robust], largest[a.robust])


def test_the_same_scenario_and_seed_give_identical_arrays_on_one_and_two_threads():
    first = mm.sim.run("s1-crossing", seed=5, jobs=1)
    second = mm.sim.run("s1-crossing", seed=5, jobs=2)
    for name in ("times", "x", "y", "heading", "speed", "acceleration", "curvature", "status"):
        assert getattr(first, name).tobytes() == getattr(second, name).tobytes(), name
    assert first.maps[0].mi_brake.tobytes() == second.maps[0].mi_brake.tobytes()


def test_parameter_overrides_and_the_policy_reach_the_run():
    loaded = mm.sim.load("s3-left-turn", set={"a_kmh": 20.0}, policy=mm.forecast_policy.parse("const:0.5"))
    assert {p.name: p.value for p in loaded.parameters}["a_kmh"] == 20.0
    a = loaded.scenario.planning_vehicles[0]
    assert a.initial_speed == pytest.approx(20.0 / 3.6)
    assert a.planner.policy.kind == mm.forecast_policy_kind.constant
    record = mm.sim.run(loaded)
    chosen = record.map(a.name).forecast_time
    # The constant policy's τ, capped at the TTC where that is shorter (spec §7).
    assert set(np.unique(chosen)) <= set(np.arange(5) * 0.125)
    assert (chosen == 0.5).any()


def test_a_change_of_a_planning_vehicle_through_the_loaded_scenario_changes_the_run():
    loaded = mm.sim.load("s3-left-turn")
    loaded.scenario.planning_vehicles[0].avoidance = False
    record = mm.sim.run(loaded)
    assert len(record.maps[0].times) == 0
    assert record.metrics[0].planning_steps == 0


def test_the_planning_input_of_a_vehicle_plans_in_python_as_the_vehicle_planned():
    simulation = mm.sim.simulation(mm.sim.load("s3-left-turn"))
    a = simulation.find("A")
    assert a is not None
    compared = 0
    while not simulation.ended() and compared < 3:
        simulation.step()
        if simulation.planned_now(a) and simulation.step_index % 100 == 0:
            scene = simulation.planning_input(a)
            last = simulation.last_plan(a)
            assert scene is not None and last is not None
            mine = mm.plan(scene)
            theirs = last.result
            assert mine.command == theirs.command
            assert mine.mi_brake.tobytes() == theirs.mi_brake.tobytes()
            assert mine.mi_accelerate.tobytes() == theirs.mi_accelerate.tobytes()
            compared += 1
    assert compared == 3
    assert simulation.state(a).present()
    with pytest.raises(IndexError, match="state: agent [0-9]+ does not exist: expected an id from 0 to"):
        simulation.state(simulation.agent_count)


def test_a_planner_in_the_loop_from_python_drives_the_vehicle_as_its_own_planner_does():
    own = mm.sim.run("s1-crossing")
    sim = mm.sim.simulation(mm.sim.load("s1-crossing"))
    a = sim.find("A")
    assert a is not None
    xs = []
    while not sim.ended():
        scene = sim.planning_input(a)
        if scene is not None and sim.state(a).status == mm.sim.agent_status.active:
            sim.override_command(a, mm.plan(scene).command)  # what A itself decided, bit for bit
        xs.append(sim.state(a).pose.x)
        sim.step()
    xs.append(sim.state(a).pose.x)
    assert np.array_equal(np.array(xs), own.x[:, 0])
    # A controller that holds the speed and the lane drives A into B.
    sim = mm.sim.simulation(mm.sim.load("s1-crossing"))
    while not sim.ended():
        if sim.state(a).status == mm.sim.agent_status.active:
            sim.override_command(a, mm.maneuver(0.0, 0.0))
        sim.step()
    assert [(c.first, c.second) for c in sim.crashes()] == [(a, sim.find("B"))]
    with pytest.raises(ValueError, match=re.escape('planning vehicle "A" is crashed: only an active vehicle')):
        sim.override_command(a, mm.maneuver(0.0, 0.0))
    with pytest.raises(IndexError, match="override_command: planning vehicle 1 does not exist"):
        sim.override_command(1, mm.maneuver(0.0, 0.0))


def test_a_scenario_error_names_the_line_the_column_and_the_field():
    text = "format: maneuvermap-scenario/1\nnme: typo\n"
    with pytest.raises(mm.sim.scenario_error) as caught:
        mm.sim.load_text(text, "typo.yaml")
    assert (caught.value.source, caught.value.line, caught.value.field) == ("typo.yaml", 2, "nme")
    assert "did you mean name?" in str(caught.value)
    assert isinstance(caught.value, ValueError)
    with pytest.raises(mm.sim.scenario_error, match="a_kmhh"):
        mm.sim.load("s3-left-turn", set={"a_kmhh": 1.0})
    with pytest.raises(mm.sim.scenario_error, match="missing.yaml"):
        mm.sim.load("missing.yaml")


def test_every_builtin_scenario_loads():
    names = mm.sim.builtin_scenarios()
    assert "s2-roundabout" in names
    for name in names:
        assert mm.sim.load(name).scenario.validation_error() is None


def test_a_run_without_map_columns_makes_the_same_decisions_and_keeps_no_indices():
    with_maps = mm.sim.run("s3-left-turn")
    without = mm.sim.run("s3-left-turn", map_columns=False)
    assert without.x.tobytes() == with_maps.x.tobytes()
    a, b = with_maps.maps[0], without.maps[0]
    assert b.forecast_time.tobytes() == a.forecast_time.tobytes()
    assert b.mode.tobytes() == a.mode.tobytes()
    assert b.mi_brake.shape == b.mi_accelerate.shape == (len(b.times), 0)
    assert b.excluded.shape == a.excluded.shape


def test_a_run_that_decides_only_the_commands_drives_the_same_and_marks_the_steps_without_indices():
    without = mm.sim.run("s3-left-turn", map_columns=False)
    lean = mm.sim.run("s3-left-turn", decision_only=True)
    assert lean.x.tobytes() == without.x.tobytes() and lean.speed.tobytes() == without.speed.tobytes()
    a, b = without.maps[0], lean.maps[0]
    assert b.mode.tobytes() == a.mode.tobytes()
    assert b.time_to_collision.tobytes() == a.time_to_collision.tobytes()
    assert a.indices_computed.all()
    assert b.mi_brake.shape == (len(b.times), 0), "deciding only the commands computes no map column"
    skipped = ~b.indices_computed
    assert 0 < skipped.sum() < len(b.times)
    assert (b.mode[skipped] == int(mm.planning_mode.nominal)).all()
    assert np.array_equal(b.forecast_time[~skipped], a.forecast_time[~skipped])
    assert lean.metrics[0].time_in_brake_s == without.metrics[0].time_in_brake_s


def s1_crossing_built_in_python():
    """scenarios/s1-crossing.yaml at its defaults, written out in Python."""
    kmh = 1.0 / 3.6  # the scenario files' factor
    a_speed, b_speed = 40.0 * kmh, 36.0 * kmh
    a = mm.sim.planning_vehicle(
        name="A",
        path=mm.sim.path(mm.pose((-60.0, 0.0), 0.0)).straight(160.0),
        initial_speed=a_speed,
        desired_speed=a_speed,
        shape=mm.rectangle(4.5, 1.8),
        planner=mm.planner_config(
            policy=mm.forecast_policy.parse("adj"), safety_margin=0.3, displacement_horizon=1.0))
    # The file's `meet`: B starts so that both reach the conflict point (0, 0) at once.
    b_start = 60.0 / a_speed - 36.0 / b_speed
    b = mm.sim.scripted_vehicle(
        name="B",
        motion=mm.sim.scripted_motion(
            path=mm.sim.path(mm.pose((0.0, 36.0), math.radians(-90.0))).straight(136.0),
            start_time=b_start,
            speed=mm.sim.speed_profile.constant(b_speed)),
        shape=mm.rectangle(4.5, 1.8))
    return mm.sim.scenario(name="s1-crossing", duration=8.0, time_step=0.01, planning_vehicles=[a],
                           scripted_vehicles=[b])


def test_a_scenario_built_in_python_equals_its_file_and_runs_as_it_does():
    built = s1_crossing_built_in_python()
    loaded = mm.sim.load("s1-crossing").scenario
    assert built.planning_vehicles == loaded.planning_vehicles
    assert built.scripted_vehicles == loaded.scripted_vehicles
    assert built.pedestrians == loaded.pedestrians == []
    ours = mm.sim.run(built)
    theirs = mm.sim.run("s1-crossing")
    for name in ("times", "x", "y", "heading", "speed", "acceleration", "curvature", "status"):
        assert getattr(ours, name).tobytes() == getattr(theirs, name).tobytes(), name
    assert ours.map("A").mi_brake.tobytes() == theirs.map("A").mi_brake.tobytes()
    # B a little faster (and so later, to meet A at the crossing) is the file's b_kmh = 40.
    b = built.scripted_vehicles[0]
    b.motion.speed = mm.sim.speed_profile.constant(40.0 / 3.6)
    b.motion.start_time = 60.0 / (40.0 / 3.6) - 36.0 / (40.0 / 3.6)
    assert built.scripted_vehicles == mm.sim.load("s1-crossing", set={"b_kmh": 40.0}).scenario.scripted_vehicles
    faster = mm.sim.run(built)
    assert faster.x.tobytes() == mm.sim.run("s1-crossing", set={"b_kmh": 40.0}).x.tobytes()
    assert faster.x.tobytes() != ours.x.tobytes()


def test_a_scenario_built_in_python_writes_the_files_of_maneuvermap_run_which_it_plots(cli, tmp_path):
    ours, theirs = tmp_path / "python", tmp_path / "cli"
    built = s1_crossing_built_in_python()
    written = mm.sim.write_run(built, ours, jobs=2)
    assert [pathlib.Path(f).name for f in written] == [
        "trajectories.csv", "map.csv", "decisions.csv", "summary.json", "scene.json"]
    subprocess.run([cli, "run", "s1-crossing", "--out", str(theirs)], check=True, capture_output=True)
    for name in ("trajectories.csv", "map.csv", "decisions.csv"):
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name
    # The summary differs only where the file says more: its parameters, description and `meet`.
    summary, file_summary = (json.loads((d / "summary.json").read_text()) for d in (ours, theirs))
    assert summary["parameters"] == {} and file_summary["parameters"]["a_kmh"] == 40.0
    for key in set(summary) | set(file_summary):
        if key not in ("parameters", "description", "meetings"):
            assert summary[key] == file_summary[key], key
    subprocess.run([cli, "plot", str(ours)], check=True, capture_output=True)
    assert (ours / "topdown.png").stat().st_size > 0 and (ours / "map.png").stat().st_size > 0
    with pytest.raises(ValueError, match="apply when loading: pass a name or a file to write_run"):
        mm.sim.write_run(built, ours, seed=3)
    built.scripted_vehicles[0].shape = mm.rectangle(0.0, 1.8)
    with pytest.raises(ValueError, match='scripted_vehicles\\[0\\] "B": shape.length = 0'):
        mm.sim.write_run(built, tmp_path / "never")
    assert not (tmp_path / "never").exists()


def test_a_pedestrian_and_a_static_obstacle_added_in_python_take_part_in_the_run():
    scenario = s1_crossing_built_in_python()
    # A pedestrian walks toward A's road after the crossing and stops at its kerb for good; a cone
    # stands in A's lane beyond it.
    kerb = mm.sim.path(mm.pose((25.0, -8.0), math.pi / 2)).straight(16.0)
    scenario.pedestrians.append(mm.sim.pedestrian(
        name="P",
        motion=mm.sim.scripted_motion(path=kerb, speed=mm.sim.speed_profile.constant(1.4),
                                      stop=mm.sim.stop_rule(arc_length=5.5))))
    scenario.static_obstacles = [
        mm.sim.static_obstacle(name="cone", vertices=[(20.0, -0.5), (21.0, -0.5), (21.0, 0.5), (20.0, 0.5)])]
    assert scenario.validation_error() is None
    record = mm.sim.run(scenario)
    assert [agent.name for agent in record.agents] == ["A", "B", "P", "cone"]
    # The pedestrian stands at its stop from when it gets there: 5.5 m along, at (25, -2.5).
    assert record.y[:, 2].max() == pytest.approx(-2.5)
    assert (record.x[-1, 2], record.y[-1, 2], record.speed[-1, 2]) == pytest.approx((25.0, -2.5, 0.0))
    # The cone stands at the mean of its vertices, and A steers round it (without it, B is A's
    # closest road user).
    assert record.present[:, 3].all()
    assert (record.x[:, 3] == 20.5).all() and (record.y[:, 3] == 0.0).all()
    assert mm.sim.run("s1-crossing").metrics[0].closest_agent == "B"
    assert record.metrics[0].closest_agent == "cone"
    assert not record.metrics[0].crash and len(record.crashes) == 0
    closest = record.metrics[0].min_dist_m
    assert closest is not None and closest > 0.3


def test_a_drivable_area_given_to_a_scenario_built_in_python_keeps_its_vehicle_on_the_road(source_dir):
    on_road = mm.sim.load(source_dir / "examples" / "scenarios" / "s1-crossing-road.yaml").scenario
    assert on_road.drivable_area is not None
    built = s1_crossing_built_in_python()
    built.name = on_road.name
    built.planning_vehicles = on_road.planning_vehicles
    built.drivable_area = on_road.drivable_area
    assert mm.sim.run(built).y.tobytes() == mm.sim.run(on_road).y.tobytes()
    built.drivable_area = None
    assert built.drivable_area is None
    assert mm.sim.run(built).y.tobytes() != mm.sim.run(on_road).y.tobytes()


def test_copies_of_a_loaded_scenario_are_variants_that_leave_the_original_and_run_in_threads_as_alone():
    base = mm.sim.load("s1-crossing")
    original = base.scenario.scripted_vehicles[0].motion.start_time
    variants = []
    for delay in (0.0, 0.5, 1.0):
        variant = copy.deepcopy(base)
        variant.scenario.scripted_vehicles[0].motion.start_time += delay
        variants.append(variant)
    assert base.scenario.scripted_vehicles[0].motion.start_time == original
    assert copy.copy(base.scenario.planning_vehicles[0]) == base.scenario.planning_vehicles[0]
    alone = [mm.sim.run(v).x.tobytes() for v in variants]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        together = [r.x.tobytes() for r in pool.map(mm.sim.run, variants)]
    assert together == alone
    assert alone[0] == mm.sim.run("s1-crossing").x.tobytes()
    assert len(set(alone)) == 3  # B later, A's run another


def test_paths_built_in_python_and_a_bad_agent_give_clear_errors():
    corner = mm.sim.path.polyline([(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)])
    assert corner.length == 20.0
    assert corner.points(spacing=5.0).tolist() == [[0, 0], [5, 0], [10, 0], [10, 5], [10, 10]]
    half_circle = mm.sim.path.circular_arc((0.0, 0.0), 10.0, 0.0, math.pi)
    assert half_circle.length == pytest.approx(10.0 * math.pi)
    end = half_circle.end_pose
    assert (end.x, end.y, end.heading) == pytest.approx((-10.0, 0.0, -math.pi / 2))
    turn = mm.sim.path(mm.pose((0.0, 0.0), 0.0)).straight(5.0).turn(10.0, math.pi / 2)
    assert turn.at(5.0 + 10.0 * math.pi / 4).curvature == pytest.approx(0.1)
    assert (turn.end_pose.x, turn.end_pose.y, turn.end_pose.heading) == pytest.approx((15.0, 10.0, math.pi / 2))
    with pytest.raises(ValueError, match="straight length = -1"):
        mm.sim.path(mm.pose((0.0, 0.0), 0.0)).straight(-1.0)
    with pytest.raises(ValueError, match="empty"):
        mm.sim.path().at(0.0)
    with pytest.raises(TypeError, match="scripted_vehicle has no field 'nmae'; its fields are: name, motion"):
        mm.sim.scripted_vehicle(nmae="B")
    scenario = s1_crossing_built_in_python()
    scenario.scripted_vehicles[0].motion.speed = mm.sim.speed_profile.constant(-1.0)
    message = 'scripted_vehicles[0] "B": motion.speed.knots[0].speed = -1: expected a finite number ≥ 0 [m/s]'
    assert scenario.validation_error() == message
    with pytest.raises(ValueError, match=re.escape(message)):
        mm.sim.run(scenario)
    with pytest.raises(ValueError, match=re.escape(message)):
        mm.sim.simulation(scenario)


def test_the_scene_geometry_comes_with_the_loaded_scenario():
    roundabout = mm.sim.load("s2-roundabout")
    ring = roundabout.roundabout
    assert ring is not None and ring.radius > 0
    a = roundabout.scenario.planning_vehicles[0]
    path = a.path_points(spacing=1.0)
    assert path.shape[1] == 2 and len(path) > 10
    steps = np.hypot(*np.diff(path, axis=0).T)
    assert steps.max() <= 1.0 + 1e-9
    # The path reaches the ring: some point lies on the circulating lane's centre line.
    distance_to_centre = np.hypot(path[:, 0] - ring.center.x, path[:, 1] - ring.center.y)
    assert np.min(np.abs(distance_to_centre - ring.radius)) < 0.5
    # A run starts where the path says.
    record = mm.sim.run(roundabout)
    first = np.argmax(record.present[:, 0])
    start = np.array([record.x[first, 0], record.y[first, 0]])
    assert np.min(np.hypot(*(path - start).T)) < 1.0
    assert mm.sim.load("s3-left-turn").roundabout is None
    with pytest.raises(ValueError, match="spacing = 0.0"):
        a.path_points(spacing=0.0)


def test_run_takes_a_name_a_path_a_loaded_scenario_or_a_scenario_and_refuses_anything_else(source_dir):
    by_name = mm.sim.run("s1-crossing")
    by_path = mm.sim.run(source_dir / "scenarios" / "s1-crossing.yaml")
    assert mm.sim.load(source_dir / "scenarios" / "s1-crossing.yaml").source.endswith("s1-crossing.yaml")
    loaded = mm.sim.load("s1-crossing")
    by_loaded = mm.sim.run(loaded)
    by_scenario = mm.sim.run(loaded.scenario)
    for other in (by_path, by_loaded, by_scenario):
        assert other.x.tobytes() == by_name.x.tobytes()
    with pytest.raises(TypeError, match="expected a built-in name"):
        mm.sim.run(42)  # type: ignore[arg-type]  # the wrong type on purpose: its message
    with pytest.raises(ValueError, match="apply when loading"):
        mm.sim.run(loaded, seed=3)
    with pytest.raises(ValueError, match="jobs = 0: expected from 1 to 256 threads"):
        mm.sim.run(loaded, jobs=0)


def test_on_roads_plans_on_the_roads_and_the_roundabout_s_lanes_as_the_command_line_does(source_dir):
    plain = mm.sim.load("s2-roundabout")
    on_roads = mm.sim.load("s2-roundabout", on_roads=True)
    assert plain.scenario.drivable_area is None
    area = on_roads.scenario.drivable_area
    assert area is not None and len(area.boundary) > 100
    example = mm.sim.load(source_dir / "examples" / "scenarios" / "s2-roundabout-road.yaml")
    by_flag = mm.sim.run("s2-roundabout", on_roads=True)
    assert by_flag.x.tobytes() == mm.sim.run(example).x.tobytes()
    assert by_flag.x.tobytes() != mm.sim.run(plain).x.tobytes()
    with pytest.raises(ValueError, match="--on-roads: the scenario gives its own drivable_area"):
        mm.sim.load(source_dir / "examples" / "scenarios" / "s2-roundabout-road.yaml", on_roads=True)
    with pytest.raises(ValueError, match="apply when loading"):
        mm.sim.run(plain, on_roads=True)


def run_in_worker(name):
    """What a worker process of a Monte-Carlo study returns: the whole run record."""
    return mm.sim.run(name)


def test_a_run_record_pickles_with_every_attribute_and_comes_back_whole_from_another_process():
    record = mm.sim.run("s3-left-turn")  # A crashes into B under ADJ at the scenario's defaults
    assert record.crashes and record.metrics[0].crash and record.metrics[0].crash_time_s is not None
    assert len(record.maps[0].times) > 0 and record.maps[0].excluded.any()
    assert_same_attributes(record, pickle.loads(pickle.dumps(record)), "run_record")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert_same_attributes(record, pool.submit(run_in_worker, "s3-left-turn").result(), "run_record from a worker")


def test_a_simulations_states_and_last_plan_pickle_with_every_attribute():
    sim = mm.sim.simulation(mm.sim.load("s3-left-turn").scenario)
    while True:
        last = sim.last_plan(0)
        if sim.planned_now(0) and last is not None and last.result.mode != mm.planning_mode.nominal:
            break
        sim.step()
    for value in (sim.info(0), sim.state(0), last):
        assert_same_attributes(value, pickle.loads(pickle.dumps(value)), type(value).__name__)
    assert sim.state(0).speed > 0.0 and last.time > 0.0


def run_scenario_in_worker(scenario):
    """A worker process of a study that sends scenarios, not names: its run's positions."""
    return mm.sim.run(scenario).x.tobytes()


def test_a_scenario_built_in_python_is_written_as_a_file_that_loads_and_runs_as_it(cli, tmp_path):
    built = s1_crossing_built_in_python()
    built.pedestrians.append(mm.sim.pedestrian(
        name="P", radius=0.3,
        motion=mm.sim.scripted_motion(
            path=mm.sim.path(mm.pose((20.0, -8.0), math.pi / 2)).curve(6.0, 0.05).line_to((21.0, 2.0)),
            speed=mm.sim.speed_profile(knots=[mm.sim.speed_knot(0.0, 1.2), mm.sim.speed_knot(2.0, 0.4)]),
            stop=mm.sim.stop_rule(arc_length=7.0))))
    built.planning_vehicles[0].planner.map_column = False
    text = mm.sim.scenario_text(built)
    assert text.startswith("# A scenario as the simulator runs it") and 'name: "s1-crossing"' in text
    assert "curve: {length_m: 6, curvature_per_m: 0.05}" in text and "map_column: false" in text
    assert mm.sim.load_text(text).scenario == built
    file = tmp_path / "built.yaml"
    mm.sim.write_scenario(built, file)
    assert file.read_text() == text and mm.sim.load(str(file)).scenario == built
    # The command line runs the file as Python runs the scenario.
    subprocess.run([cli, "run", str(file), "--out", str(tmp_path / "cli")], check=True, capture_output=True)
    mm.sim.write_run(built, tmp_path / "python")
    for name in ("trajectories.csv", "map.csv", "decisions.csv", "scene.json"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "python" / name).read_bytes(), name
    # A scenario pickles as its file, so a process pool can take scenarios built in Python.
    assert pickle.loads(pickle.dumps(built)) == built
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert pool.submit(run_scenario_in_worker, built).result() == mm.sim.run(built).x.tobytes()
    # A loaded scenario keeps the roundabout and roads it draws.
    loaded = mm.sim.load("s2-roundabout", on_roads=True)
    again = mm.sim.load_text(mm.sim.scenario_text(loaded))
    assert again.scenario == loaded.scenario and again.roundabout is not None and again.parameters == []


def test_a_scenario_no_file_can_state_is_refused_and_agent_lists_compare_and_search_by_value():
    built = s1_crossing_built_in_python()
    built.scripted_vehicles[0].shape = mm.rectangle(4.5, 0.01)  # the simulator takes it, a file does not
    with pytest.raises(ValueError, match="footprint.width_m = 0.01: expected a size from 0.05 to 1000"):
        mm.sim.scenario_text(built)
    with pytest.raises(ValueError, match="footprint.width_m = 0.01"):
        pickle.dumps(built)
    built = s1_crossing_built_in_python()
    b = copy.deepcopy(built.scripted_vehicles[0])
    assert b in built.scripted_vehicles and built.scripted_vehicles.count(b) == 1
    built.scripted_vehicles.remove(b)
    assert len(built.scripted_vehicles) == 0 and built != s1_crossing_built_in_python()
    assert built.scripted_vehicles == [] and built.scripted_vehicles != 3


def agent_in_worker(agent):
    """A worker process that receives one agent and sends it back."""
    return agent


def test_agents_and_paths_pickle_by_their_values_bit_for_bit(source_dir):
    path = mm.sim.path(mm.pose((1.0, 2.0), 0.3)).straight(20.0).turn(15.0, math.pi / 2).line_to((0.0, 50.0))
    path.curve(3.0, -0.1)
    for p in (path, mm.sim.path(), mm.sim.path(mm.pose((4.0, 5.0), 1.0)), mm.sim.path.polyline([(0, 0), (3, 4), (3, 9)]),
              mm.sim.path.circular_arc((0.0, 0.0), 25.0, -0.5, 7.0)):
        again = pickle.loads(pickle.dumps(p))
        assert again == p and again.end_pose == p.end_pose and again.length == p.length
    built = s1_crossing_built_in_python()
    built.scripted_vehicles[0].shape = mm.rectangle(4.5, 0.01)  # no file states it, yet the agent pickles
    agents = [*built.planning_vehicles, *built.scripted_vehicles, *mm.sim.load("s7-crosswalk-crowd").scenario.pedestrians,
              *mm.sim.load(source_dir / "examples" / "scenarios" / "s1-crossing-kerbs.yaml").scenario.static_obstacles]
    assert {type(a).__name__ for a in agents} == {"planning_vehicle", "scripted_vehicle", "pedestrian", "static_obstacle"}
    for agent in agents:
        assert pickle.loads(pickle.dumps(agent)) == agent, agent.name
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert list(pool.map(agent_in_worker, agents)) == agents


def test_files_that_cannot_be_written_raise_os_errors_with_the_path(tmp_path):
    (tmp_path / "a-file").write_text("")
    blocked = tmp_path / "a-file" / "below"  # under a file: not a directory
    with pytest.raises(NotADirectoryError) as scenario_error:
        mm.sim.write_scenario(mm.sim.load("s1-crossing").scenario, blocked / "s1.yaml")
    assert scenario_error.value.filename == str(blocked / "s1.yaml")
    assert "cannot write the scenario file" in str(scenario_error.value)
    with pytest.raises(OSError) as run_error:
        mm.sim.write_run("s1-crossing", blocked)
    assert str(blocked) in str(run_error.value)
    with pytest.raises(OSError):
        mm.sim.write_sweep("table1", blocked, repetitions=1)


def test_a_run_written_as_a_commonroad_recording_is_measured_as_one(tmp_path):
    xml = tmp_path / "s4.xml"
    files = mm.sim.write_run("s4-pedestrian", tmp_path / "run", commonroad=xml)
    assert files[-1] == str(xml)
    recording = mm.commonroad.read_scenario(xml)
    assert recording.time_step == 0.1 and [o.type for o in recording.obstacles] == ["car", "pedestrian"]
    assert mm.commonroad.scenario_xml(recording) == xml.read_text()
    # The car (A) measured at every recorded step of the 8 s run, with room to spare throughout.
    measured = mm.commonroad.measure(recording, recording.obstacles[0].id)
    assert len(measured.times) == len(recording.obstacles[0].states) == 81
    assert 0.0 < measured.rooms.min() < 1.0
    with pytest.raises(ValueError, match="expected a whole multiple of the run's time step"):
        mm.sim.write_run("s4-pedestrian", tmp_path / "never", commonroad=xml, commonroad_step=0.025)
