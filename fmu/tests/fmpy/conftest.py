"""Fixtures of the fmpy suite: the packaged FMU, fresh FMU2Slave instances, and the core
library's reference forces (computed by `cargo fmu reference`, never by the FMU itself)."""

import csv
import io
import os
import pathlib
import subprocess

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

ROOT = pathlib.Path(__file__).resolve().parents[3]
FMU = ROOT / "target" / "fmu" / "wheel_rail_contact.fmu"
CONTACT_INPUTS = [
    "creepage_longitudinal", "creepage_lateral", "spin_creepage", "normal_force", "semi_axis_a",
    "semi_axis_b", "friction_coefficient", "shear_modulus", "poisson_ratio",
]


def cargo(*arguments, stdin=None):
    result = subprocess.run(["cargo", *arguments], cwd=ROOT, input=stdin, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    return result.stdout


@pytest.fixture(scope="session")
def fmu_path():
    """The FMU `cargo fmu package` wrote (scripts/test-all builds it first; built here if missing)."""
    if not FMU.exists():
        cargo("fmu", "package")
    return str(FMU)


@pytest.fixture(scope="session")
def model_description(fmu_path):
    return read_model_description(fmu_path)


@pytest.fixture(scope="session")
def unzip_directory(fmu_path, tmp_path_factory):
    return extract(fmu_path, unzipdir=str(tmp_path_factory.mktemp("fmu")))


@pytest.fixture(scope="session")
def vr(model_description):
    """Value reference by variable name."""
    return {v.name: v.valueReference for v in model_description.modelVariables}


@pytest.fixture
def new_slave(model_description, unzip_directory):
    """Makes FMU2Slave objects (not yet instantiated); frees them after the test."""
    slaves = []

    def make(name="instance"):
        slave = FMU2Slave(
            guid=model_description.guid,
            unzipDirectory=unzip_directory,
            modelIdentifier=model_description.coSimulation.modelIdentifier,
            instanceName=name,
        )
        slaves.append(slave)
        return slave

    yield make
    for slave in slaves:
        if slave.component is not None:
            slave.freeInstance()


def start_values(model_description):
    return {v.name: float(v.start) for v in model_description.modelVariables if v.start is not None and v.type == "Real"}


def core_forces(rows):
    """The core library's (force_longitudinal, force_lateral, adhesion_utilisation) per row of
    the nine contact inputs (dicts keyed by variable name)."""
    text = io.StringIO()
    writer = csv.writer(text)
    writer.writerow(CONTACT_INPUTS)
    for row in rows:
        writer.writerow([repr(float(row[name])) for name in CONTACT_INPUTS])
    output = cargo("fmu", "reference", stdin=text.getvalue())
    return [tuple(float(x) for x in line.split(",")[:3]) for line in output.strip().splitlines()[1:]]


def settable_start_values(model_description):
    """Start value of every numeric input and parameter: float for Real, int for Integer and
    Enumeration (the String parameters, the profiles' names, are not numbers: the reference
    tool's rows cannot hold them)."""
    values = {}
    for v in model_description.modelVariables:
        if v.causality in ("input", "parameter") and v.type != "String":
            values[v.name] = float(v.start) if v.type == "Real" else int(v.start)
    return values


def core_outputs(rows):
    """The core library's outputs (dicts keyed by output name) for a sequence of rows, each a dict
    of input and parameter values plus an optional `step_size` (creep relaxation: 0 initialises
    the relaxed force, h > 0 advances it from the previous row's over a step h)."""
    columns = sorted({name for row in rows for name in row})
    text = io.StringIO()
    writer = csv.writer(text)
    writer.writerow(columns)
    for row in rows:
        writer.writerow([repr(float(row[name])) for name in columns])
    lines = cargo("fmu", "reference", stdin=text.getvalue()).strip().splitlines()
    names = lines[0].split(",")
    return [dict(zip(names, (float(x) for x in line.split(",")))) for line in lines[1:]]
