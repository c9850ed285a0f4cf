"""Parameter sweeps from Python: write_sweep runs a sweep as `maneuvermap sweep` does (docs/python.md)."""
import csv
import pickle
import subprocess

import numpy as np
import pytest

import maneuvermap as mm
from conftest import assert_same_attributes


def test_a_sweep_from_python_writes_the_files_of_the_command_line_and_gives_its_runs(cli, tmp_path):
    assert "table1" in mm.sim.builtin_sweeps()
    record = mm.sim.write_sweep("table1", tmp_path / "python", repetitions=1, jobs=2)
    # 5 speeds of A × 2 of B × 5 policies, one repetition each, in grid order.
    assert len(record) == 50 and record.failed == 0 and record.agent == "A"
    assert record.parameters == ["a_kmh", "b_kmh"]
    assert record.values.shape == (50, 2)
    assert record.values[0].tolist() == [25.0, 35.0] and record.values[-1].tolist() == [45.0, 30.0]
    assert record.policy[:5] == ["const:0.5", "const:1", "const:1.5", "const:2", "adj"]
    assert record.repetition.tolist() == [0] * 50 and record.seed.tolist() == [1] * 50
    # Its files are those of the command line, byte for byte (on one job there, two here).
    subprocess.run([cli, "sweep", "table1", "--repetitions", "1", "--jobs", "1", "--out", str(tmp_path / "cli")],
                   check=True, capture_output=True)
    for name in ("runs.csv", "table.csv", "table.md"):
        assert (tmp_path / "python" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert record.table == (tmp_path / "python" / "table.md").read_text()
    # Each run's metrics are its row of runs.csv.
    with open(tmp_path / "python" / "runs.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 50
    for row, metrics, policy in zip(rows, record.metrics, record.policy):
        assert row["policy"] == policy and int(row["crash"]) == int(metrics.crash)
        assert float(row["min_dist_m"]) == pytest.approx(metrics.min_dist_m, abs=5e-4)
    # S3 as the paper's Table 1: B turns too late for A in every cell, at speeds that differ by cell.
    assert all(m.crash for m in record.metrics) and len({round(m.speed_kmh, 1) for m in record.metrics}) > 10
    assert_same_attributes(record, pickle.loads(pickle.dumps(record)), "sweep_record")


def test_a_sweep_file_with_its_runs_kept_and_bad_arguments(source_dir, tmp_path):
    record = mm.sim.write_sweep(source_dir / "sweeps" / "roundabout.yaml", tmp_path / "s2", jobs=1)
    assert len(record) == 5 and record.parameters == [] and record.values.shape == (5, 0)
    assert record.policy == ["const:0.5", "const:1", "const:2", "adj", "robust"]
    assert (tmp_path / "s2" / "runs").is_dir() and str(tmp_path / "s2" / "runs.csv") in record.files
    crashed = np.array([m.crash for m in record.metrics])
    assert crashed.tolist() == [c == "1" for c in (r["crash"] for r in csv.DictReader(open(tmp_path / "s2" / "runs.csv")))]
    with pytest.raises(mm.sim.scenario_error, match="did you mean table1"):
        mm.sim.write_sweep("tabel1", tmp_path / "never")
    with pytest.raises(ValueError, match="repetitions = 0: expected from 1 to 20000 \\(50 cells"):
        mm.sim.write_sweep("table1", tmp_path / "never", repetitions=0)
    with pytest.raises(ValueError, match="repetitions = 20001: expected from 1 to 20000"):
        mm.sim.write_sweep("table1", tmp_path / "never", repetitions=20001)
    (tmp_path / "lone.yaml").write_text(
        "format: maneuvermap-scenario/1\nname: lone\nduration_s: 0.2\nagents:\n"
        "  - {name: A, kind: planning_vehicle, desired_speed_mps: 10,\n"
        "     path: {start: {position_m: [0, 0], heading_deg: 0}, segments: [{straight_m: 50}]}}\n")
    (tmp_path / "lone.sweep.yaml").write_text(
        "format: maneuvermap-sweep/1\nname: lone\nscenario: lone.yaml\nagent: A\nrepetitions: 2\n")
    lone = mm.sim.write_sweep(tmp_path / "lone.sweep.yaml", tmp_path / "lone")
    assert len(lone) == 2 and lone.seed.tolist() == [0, 1] and lone.metrics[0].min_speed_kmh == pytest.approx(36.0)
    with pytest.raises(mm.sim.scenario_error, match="no roads: and no roundabout:"):
        mm.sim.write_sweep(tmp_path / "lone.sweep.yaml", tmp_path / "never", on_roads=True)
    assert not (tmp_path / "never").exists()
