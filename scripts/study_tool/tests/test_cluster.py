"""A study run against a real Dask cluster the test starts itself: `dask scheduler` and
`dask worker` processes on 127.0.0.1 with free ports, started from an empty directory without
PYTHONPATH (so they cannot import this project: the runner's code and the FMU's bytes come from
the client), and always stopped afterwards. Each worker runs two threads, so two chunks share a
process: each scene's message must still be its own."""

import os
import signal
import socket
import subprocess
import time

import pandas as pd
import pytest

from .conftest import ROOT, clean_environment, command, run_in_process

DASK = ROOT / ".venv" / "bin" / "dask"
STUDY = """
name = "cluster"
models = ["polach", "shen_hedrick_elkins", "exact"]
chunk_size = 5
[fixed]
exact_elements_longitudinal = 8
exact_elements_lateral = 8
[grid]
creepage_longitudinal = { geomspace = [1e-4, 1e-2, 6] }
friction_coefficient = [0.2, -0.15, 0.4, -0.25]
"""


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_for_port(port, process, timeout=30.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        assert process.poll() is None, "the scheduler exited"
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            time.sleep(0.1)
    raise TimeoutError(f"no scheduler on port {port} after {timeout} s")


def stop(process):
    """SIGTERM to the process's group (a worker's nanny and its worker), SIGKILL if it lingers."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(timeout=15)


@pytest.fixture
def cluster(tmp_path):
    """A scheduler and two single-threaded workers; yields the scheduler's address."""
    port = free_port()
    empty = tmp_path / "cluster"
    empty.mkdir()
    common = dict(cwd=empty, env=clean_environment(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                  start_new_session=True)
    processes = [subprocess.Popen([DASK, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--no-dashboard", "--no-show"], **common)]
    try:
        wait_for_port(port, processes[0])
        address = f"tcp://127.0.0.1:{port}"
        processes.append(subprocess.Popen([DASK, "worker", address, "--nworkers", "2", "--nthreads", "2",
                                           "--host", "127.0.0.1", "--no-dashboard", "--local-directory",
                                           str(empty)], **common))
        yield address
    finally:
        for process in reversed(processes):
            stop(process)


def test_run_on_a_cluster_started_by_address_equals_the_serial_run(cluster, study_file, fmu_path, tmp_path):
    path = study_file(STUDY)
    result = command("run", path, "--scheduler", cluster, "--out", tmp_path / "cluster-out", "--no-progress",
                     timeout=120)
    assert result.returncode == 0, result.stderr
    assert "72 scenes in 15 chunks of up to 5; 15 chunks computed, 0 reused" in result.stdout
    reference = run_in_process(path, fmu_path, tmp_path / "serial-out")
    frame = pd.read_parquet(tmp_path / "cluster-out" / "results.parquet")
    negative = frame["friction_coefficient"] < 0
    assert list(frame["status"]) == ["error" if n else "ok" for n in negative]
    for mu, message in zip(frame.loc[negative, "friction_coefficient"], frame.loc[negative, "message"]):
        assert message == f"[error] fmi2ExitInitializationMode: friction_coefficient = {mu} is invalid: must be finite and >= 0"
    pd.testing.assert_frame_equal(frame, reference.frame, check_exact=True)
    for plot in ("creep_curves.png", "creep_curves.svg"):
        assert (tmp_path / "cluster-out" / plot).stat().st_size > 0
