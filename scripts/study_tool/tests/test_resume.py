"""A study killed half-way (SIGKILL to the command and its Dask workers) resumes: the chunks
written before the kill are reused untouched, only the rest is computed, and the result equals
an uninterrupted run."""

import os
import signal
import subprocess
import time

import pandas as pd

from .conftest import ROOT, command, run_in_process

# 24 chunks of 4 exact-theory scenes (20 x 20 elements, a few ms each): long enough to kill the
# run after some chunks and before the last.
STUDY = """
name = "resume"
models = ["exact"]
chunk_size = 4
[grid]
creepage_longitudinal = { geomspace = [1e-4, 2e-2, 12] }
semi_axis_a = [0.0036, 0.0054, 0.0072, 0.0108]
friction_coefficient = [0.25, 0.35]
"""
CHUNKS = 24


def parts(out):
    directory = out / "parts"
    return {p.name: p.stat().st_mtime_ns for p in directory.glob("*.parquet")} if directory.exists() else {}


def test_a_killed_run_resumes_without_recomputing_finished_chunks(study_file, fmu_path, tmp_path):
    path = study_file(STUDY)
    out = tmp_path / "out"
    # The killed workers cannot remove the FMU they unpacked: keep it in the test's directory.
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    process = subprocess.Popen([str(ROOT / "scripts" / "study"), "run", str(path), "--workers", "1", "--out",
                                str(out), "--no-progress"], cwd=ROOT, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True,
                               env={**os.environ, "TMPDIR": str(temporary)})
    try:
        deadline = time.monotonic() + 90
        while len(parts(out)) < 3:
            assert process.poll() is None, "the run ended before it could be killed"
            assert time.monotonic() < deadline, "no chunk written in 90 s"
            time.sleep(0.01)
    finally:
        os.killpg(process.pid, signal.SIGKILL)  # the command and its LocalCluster's processes
        process.wait(timeout=30)
    before = parts(out)
    assert 3 <= len(before) < CHUNKS, len(before)
    assert not (out / "results.parquet").exists()

    result = command("run", path, "--serial", "--out", out, "--no-progress")
    assert result.returncode == 0, result.stderr
    assert f"{CHUNKS} chunks of up to 4; {CHUNKS - len(before)} chunks computed, {len(before)} reused" in result.stdout
    after = parts(out)
    assert len(after) == CHUNKS
    assert {name: after[name] for name in before} == before, "a finished chunk was written again"

    uninterrupted = run_in_process(path, fmu_path, tmp_path / "uninterrupted")
    resumed = pd.read_parquet(out / "results.parquet")
    assert (resumed["status"] == "ok").all() and len(resumed) == 96
    pd.testing.assert_frame_equal(resumed, uninterrupted.frame, check_exact=True)


def test_a_finished_study_is_not_recomputed(study_file, fmu_path, tmp_path):
    path = study_file(STUDY.replace("[0.25, 0.35]", "[0.3]").replace(", 0.0108", ""))
    first = run_in_process(path, fmu_path, tmp_path / "out")
    second = run_in_process(path, fmu_path, tmp_path / "out")
    assert (first.computed, first.reused) == (9, 0)
    assert (second.computed, second.reused) == (0, 9)
    pd.testing.assert_frame_equal(first.frame, second.frame, check_exact=True)
    # Other plots, name or reference model: the same scenes, the chunks are reused.
    replotted = study_file(STUDY.replace('name = "resume"', 'name = "renamed"\nreference_model = "polach"')
                           .replace("[0.25, 0.35]", "[0.3]").replace(", 0.0108", "")
                           + '[plot]\nx = "semi_axis_a"\nfamily = "creepage_longitudinal"\n', name="replotted.toml")
    fourth = run_in_process(replotted, fmu_path, tmp_path / "out")
    assert (fourth.computed, fourth.reused) == (0, 9)
    # Another study in the same directory has another key: nothing of the first is reused.
    other = study_file(STUDY.replace("[0.25, 0.35]", "[0.2]").replace(", 0.0108", ""), name="other.toml")
    third = run_in_process(other, fmu_path, tmp_path / "out")
    assert (third.computed, third.reused) == (9, 0)
    assert (third.frame["friction_coefficient"] == 0.2).all()
