"""What serious co-simulation masters use: FMU state (get/set/free, serialisation, also across
processes), directional derivatives against central finite differences, and the capability
flags that announce them."""

import json
import subprocess
import sys
import pathlib

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Error

import master_scene
from test_slave import RecordingCallbacks, expect_error, instantiated, stepping

HERE = pathlib.Path(__file__).resolve().parent


def test_all_three_master_capabilities_are_declared(model_description):
    co_simulation = model_description.coSimulation
    assert co_simulation.canGetAndSetFMUstate
    assert co_simulation.canSerializeFMUstate
    assert co_simulation.providesDirectionalDerivative


def test_get_state_run_100_steps_set_state_run_again_is_bit_identical(new_slave, vr):
    slave, _ = stepping(new_slave)
    master_scene.run(slave, vr, 0, 200)
    state = slave.getFMUstate()
    first = master_scene.run(slave, vr, 200, 100)
    slave.setFMUstate(state)
    second = master_scene.run(slave, vr, 200, 100)
    slave.freeFMUstate(state)
    assert first == second
    assert len(set(map(tuple, first))) > 90, "the outputs change along the run"


FRESH_PROCESS = """
import json, sys
sys.path.insert(0, sys.argv[1])
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Slave
import master_scene

unzip_directory, blob_path = sys.argv[2], sys.argv[3]
description = read_model_description(unzip_directory)
vr = {v.name: v.valueReference for v in description.modelVariables}
slave = FMU2Slave(guid=description.guid, unzipDirectory=unzip_directory,
                  modelIdentifier=description.coSimulation.modelIdentifier, instanceName="fresh process")
slave.instantiate()
with open(blob_path, "rb") as blob:
    state = slave.deSerializeFMUstate(blob.read())
slave.setFMUstate(state)
slave.freeFMUstate(state)
print(json.dumps(master_scene.run(slave, vr, 200, 100)))
slave.terminate()
slave.freeInstance()
"""


def test_a_state_serialised_here_continues_bit_identically_in_a_fresh_process(new_slave, vr, unzip_directory, tmp_path):
    slave, _ = stepping(new_slave)
    master_scene.run(slave, vr, 0, 200)
    state = slave.getFMUstate()
    blob = slave.serializeFMUstate(state)
    slave.freeFMUstate(state)
    assert blob[:8] == b"WRCstate"
    expected = master_scene.run(slave, vr, 200, 100)
    (tmp_path / "state.bin").write_bytes(blob)
    result = subprocess.run([sys.executable, "-c", FRESH_PROCESS, str(HERE), unzip_directory, str(tmp_path / "state.bin")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout) == expected


def test_corrupted_truncated_and_foreign_blobs_give_fmi2error_and_change_nothing(new_slave, vr):
    slave, callbacks = stepping(new_slave)
    master_scene.run(slave, vr, 0, 50)
    state = slave.getFMUstate()
    blob = slave.serializeFMUstate(state)
    before = slave.getReal([vr[n] for n in master_scene.OUTPUTS])
    flipped = bytearray(blob)
    flipped[len(blob) // 2] ^= 0x01
    own_version = int.from_bytes(blob[8:10], "little")
    cases = [
        (blob[:-1], "truncated"),
        (blob[:9], "truncated"),
        (bytes(flipped), "corrupted: the CRC-32 checksum does not match"),
        (b"PK\x03\x04" + blob[4:], "not a serialized state of this FMU"),
        (blob + b"\x00", "trailing bytes"),
        (blob[:8] + (own_version + 1).to_bytes(2, "little") + blob[10:],
         f"format version {own_version + 1}; this FMU reads version {own_version}"),
        (blob[:10] + bytes([blob[10] ^ 1]) + blob[11:], "variable-layout tag 0x"),
    ]
    for bad, reason in cases:
        expect_error(slave.deSerializeFMUstate, bad)
        assert callbacks.texts()[-1].startswith("fmi2DeSerializeFMUstate: serializedState rejected: ")
        assert reason in callbacks.texts()[-1], callbacks.texts()[-1]
    assert slave.getReal([vr[n] for n in master_scene.OUTPUTS]) == before
    after_rejections = master_scene.run(slave, vr, 50, 20)
    slave.setFMUstate(state)
    assert master_scene.run(slave, vr, 50, 20) == after_rejections
    slave.freeFMUstate(state)


# Points across a/b, both sides of the spin switch of Polach's eq. (21) (aΦ = −2η), near
# saturation, and with the measured curve's stiffness; none on a kink (a row of Kalker's table,
# Φ = 0, the switch itself), where only one-sided derivatives exist.
POINTS = {
    "round": dict(creepage_longitudinal=1e-3, creepage_lateral=-0.6e-3, spin_creepage=0.3),
    "long ellipse a/b = 3": dict(semi_axis_a=9e-3, semi_axis_b=3e-3, creepage_lateral=0.4e-3, spin_creepage=-0.2),
    "wide ellipse a/b = 1/3": dict(semi_axis_a=3e-3, semi_axis_b=9e-3, creepage_lateral=0.4e-3, spin_creepage=-0.2),
    "below the spin switch": dict(creepage_lateral=-0.6e-3, spin_creepage=0.1),
    "spin only": dict(creepage_longitudinal=0.2e-3, spin_creepage=-0.8),
    "near saturation": dict(creepage_longitudinal=12e-3, creepage_lateral=-6e-3, spin_creepage=0.5),
    "measured curve": dict(stiffness_source=2, creepage_longitudinal=2e-3, creepage_lateral=1e-3, spin_creepage=0.2),
}


# Sizes of inputs that are zero at a point, for the finite-difference step.
TYPICAL = dict(creepage_longitudinal=1e-3, creepage_lateral=1e-3, spin_creepage=0.1, normal_force=1e5,
               semi_axis_a=5e-3, semi_axis_b=5e-3, friction_coefficient=0.3)


def at_point(new_slave, vr, point):
    slave, callbacks = stepping(new_slave)
    values = {n: v for n, v in point.items() if n != "stiffness_source"}
    if "stiffness_source" in point:
        slave.setInteger([vr["stiffness_source"]], [point["stiffness_source"]])
    slave.setReal([vr[n] for n in values], list(values.values()))
    return slave, callbacks


def outputs_at(slave, vr, time, changes):
    """The outputs after a step with `changes` to the inputs (then undone)."""
    names = list(changes)
    previous = slave.getReal([vr[n] for n in names])
    slave.setReal([vr[n] for n in names], [changes[n] for n in names])
    slave.doStep(time, master_scene.STEP)
    result = slave.getReal([vr[n] for n in master_scene.OUTPUTS])
    slave.setReal([vr[n] for n in names], previous)
    return result


@pytest.mark.parametrize("label", POINTS)
def test_directional_derivatives_match_central_finite_differences(new_slave, vr, label):
    slave, _ = at_point(new_slave, vr, POINTS[label])
    unknowns = [vr[n] for n in master_scene.OUTPUTS]
    base = dict(zip(master_scene.INPUTS, slave.getReal([vr[n] for n in master_scene.INPUTS])))
    time = 0.0
    value = outputs_at(slave, vr, time, {})
    time += master_scene.STEP
    if label == "near saturation":
        assert value[2] > 0.9, value
    # Each input alone, then all together along one direction.
    directions = [{n: 1.0} for n in master_scene.INPUTS]
    directions.append({"creepage_longitudinal": 0.3, "creepage_lateral": -0.2, "spin_creepage": 40.0,
                       "normal_force": -2e6, "semi_axis_a": 0.5, "semi_axis_b": -0.3, "friction_coefficient": 10.0})
    for direction in directions:
        derivative = slave.getDirectionalDerivative(unknowns, [vr[n] for n in direction], list(direction.values()))
        # Central difference with a step moving each input by ~1e-5 of its size.
        t = 1e-5 * min((abs(base[n]) or TYPICAL[n]) / abs(d) for n, d in direction.items())
        plus = outputs_at(slave, vr, time, {n: base[n] + t * d for n, d in direction.items()})
        minus = outputs_at(slave, vr, time + master_scene.STEP, {n: base[n] - t * d for n, d in direction.items()})
        time += 2 * master_scene.STEP
        difference = [(p - m) / (2 * t) for p, m in zip(plus, minus)]
        for name, exact, approximate, output in zip(master_scene.OUTPUTS, derivative, difference, value):
            # Relative 1e-6 on each output's own scale: the change over a unit step of the
            # direction (scaled to the inputs' size) compared with the output itself.
            scale = max(abs(exact), abs(output) / (t / 1e-5))
            assert abs(exact - approximate) <= 1e-6 * scale, (label, direction, name, exact, approximate)


def test_parameters_as_knowns_and_inputs_as_unknowns_are_errors_naming_them(new_slave, vr):
    slave, callbacks = at_point(new_slave, vr, POINTS["round"])
    expect_error(slave.getDirectionalDerivative, [vr["force_lateral"]], [vr["poisson_ratio"]], [1.0])
    assert callbacks.texts()[-1] == ("fmi2GetDirectionalDerivative: poisson_ratio (value reference 101) cannot be a "
                                     "known: derivatives are taken with respect to the continuous Real inputs and the "
                                     "continuous states only")
    expect_error(slave.getDirectionalDerivative, [vr["normal_force"]], [vr["semi_axis_a"]], [1.0])
    assert "normal_force (value reference 3) cannot be an unknown: not an output" in callbacks.texts()[-1]


# Issue 16: the state tests above run with creep relaxation off, where the outputs depend on the
# inputs alone. With relaxation on and the state taken mid-transient, a state that lost its relaxed
# force, or a set-state that kept the instance's own, gives a different continuation.

def test_a_state_taken_mid_transient_restores_the_relaxed_force(new_slave, vr):
    slave, _ = instantiated(new_slave)
    time = master_scene.relaxing_mid_transient(slave, vr)
    state = slave.getFMUstate()
    first = master_scene.hold(slave, vr, time, 10)
    slave.setFMUstate(state)
    second = master_scene.hold(slave, vr, time, 10)
    slave.freeFMUstate(state)
    assert first == second
    forces = [float.fromhex(row[0]) for row in first]
    assert abs(forces[1] - forces[0]) > 1e-2 * abs(forces[0]), "the transient is under way"
    # Held long enough the force settles at the steady state: a different run from the restored one.
    settled = float.fromhex(master_scene.hold(slave, vr, time + 10 * master_scene.STEP, 2000)[-1][0])
    assert abs(settled - forces[0]) > 0.05 * abs(settled), (settled, forces)


FRESH_PROCESS_HOLDING = FRESH_PROCESS.replace("master_scene.run(slave, vr, 200, 100)",
                                              "master_scene.hold(slave, vr, float(sys.argv[4]), 10)")


def test_a_mid_transient_state_continues_bit_identically_in_a_fresh_process(new_slave, vr, unzip_directory, tmp_path):
    slave, _ = instantiated(new_slave)
    time = master_scene.relaxing_mid_transient(slave, vr)
    state = slave.getFMUstate()
    blob = slave.serializeFMUstate(state)
    slave.freeFMUstate(state)
    expected = master_scene.hold(slave, vr, time, 10)
    (tmp_path / "state.bin").write_bytes(blob)
    result = subprocess.run([sys.executable, "-c", FRESH_PROCESS_HOLDING, str(HERE), unzip_directory,
                             str(tmp_path / "state.bin"), repr(time)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout) == expected
