"""Scenes the FMU refuses (negative μ, a NaN semi-axis) are recorded with the FMU's message while
every other scene completes — with the values it has in a study without the bad ones."""

import math

import pandas as pd

from .conftest import execute, run_in_process, spec

STUDY = """
name = "bad"
models = ["polach", "fastsim"]
chunk_size = 5
[grid]
friction_coefficient = [0.3, -0.1, 0.2]
semi_axis_a = [0.0072, nan]
creepage_longitudinal = [1e-3, 4e-3]
"""
GOOD = STUDY.replace("[0.3, -0.1, 0.2]", "[0.3, 0.2]").replace("[0.0072, nan]", "[0.0072]")


def test_bad_scenes_are_recorded_and_the_others_complete(study_file, fmu_path, tmp_path):
    outcome = run_in_process(study_file(STUDY), fmu_path, tmp_path / "out")
    frame = outcome.frame
    assert len(frame) == 24
    negative = frame["friction_coefficient"] < 0
    not_a_number = frame["semi_axis_a"].isna()
    bad = negative | not_a_number
    assert list(frame["status"]) == ["error" if b else "ok" for b in bad]
    assert all(m.startswith("[error] fmi2ExitInitializationMode: ") for m in frame.loc[bad, "message"])
    assert all("friction_coefficient = -0.1 is invalid" in m or "semi_axis_a = NaN is invalid" in m
               for m in frame.loc[bad, "message"])
    assert all("semi_axis_a = NaN is invalid" in m for m in frame.loc[not_a_number & ~negative, "message"])
    assert all("friction_coefficient = -0.1 is invalid" in m for m in frame.loc[negative & ~not_a_number, "message"])
    assert frame.loc[bad, "force_longitudinal"].isna().all()
    assert (frame.loc[~bad, "message"] == "").all()

    good = run_in_process(study_file(GOOD, name="good.toml"), fmu_path, tmp_path / "good").frame
    columns = [c for c in frame.columns if c not in ("scene",)]
    pd.testing.assert_frame_equal(frame.loc[~bad, columns].reset_index(drop=True), good[columns], check_exact=True)


def test_bad_scenes_on_dask_are_recorded_the_same(study_file, fmu_path, tmp_path):
    path = study_file(STUDY)
    serial = run_in_process(path, fmu_path, tmp_path / "serial")
    parallel = execute.run(spec.prepare(path, fmu_path), tmp_path / "dask", workers=2, progress=False)
    pd.testing.assert_frame_equal(parallel.frame, serial.frame, check_exact=True)
    assert (parallel.frame["status"] == "error").sum() == 16
    assert math.isnan(parallel.frame.loc[2, "force_longitudinal"]) and parallel.frame.loc[2, "status"] == "error"
