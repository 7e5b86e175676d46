"""Fixtures of the study-tool suite (scripts/study): the packaged FMU, its interface, study files
written into the test's directory, and the command line run as a user runs it."""

import os
import pathlib
import subprocess
import sys

import pytest
from fmpy import read_model_description

ROOT = pathlib.Path(__file__).resolve().parents[3]
FMU = ROOT / "target" / "fmu" / "wheel_rail_contact.fmu"
sys.path.insert(0, str(ROOT / "scripts"))

from study_tool import execute, report, spec  # noqa: E402


@pytest.fixture(scope="session")
def fmu_path():
    """The FMU `cargo fmu package` wrote (scripts/test-all builds it first; built here if missing)."""
    if not FMU.exists():
        subprocess.run(["cargo", "fmu", "package"], cwd=ROOT, check=True, capture_output=True)
    return FMU


@pytest.fixture(scope="session")
def interface(fmu_path):
    return spec.fmu_interface(read_model_description(str(fmu_path)))


@pytest.fixture
def study_file(tmp_path):
    def write(text, name="study.toml"):
        path = tmp_path / name
        path.write_text(text)
        return path
    return write


def run_in_process(path, fmu_path, out, **options):
    """The study run without Dask, in this process (the reference the parallel runs must equal)."""
    return execute.run(spec.prepare(path, fmu_path), out, serial=True, progress=False, **options)


def command(*arguments, timeout=120, **kwargs):
    """scripts/study with the arguments, as a user runs it; returns the CompletedProcess."""
    return subprocess.run([str(ROOT / "scripts" / "study"), *map(str, arguments)], cwd=ROOT, capture_output=True,
                          text=True, timeout=timeout, **kwargs)


def clean_environment():
    """The environment without PYTHONPATH: Dask workers started with it cannot import this project."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
