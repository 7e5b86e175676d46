"""The wheelset FMU and two contact units (left and right wheel, S1002 on UIC60 1:40 under half the
axle load each) coupled by a fixed-step master loop written with fmpy's FMU2Slave, as many users
write one: explicit (Jacobi) coupling, each FMU stepped with the others' outputs of the last
communication point. A short run of the free wheelset (no suspension, the Klingel variant of
data/wheelset/passenger_coach.toml) started 3 mm off centre: the kinematic oscillation, bounded.

Not yet the Klingel wavelength or critical-speed checks of issue 28 (docs/wheelset.md)."""

import math
import pathlib
import subprocess

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

ROOT = pathlib.Path(__file__).resolve().parents[2]
FMUS = ROOT / "target" / "fmu"
PROFILES, RIGHT, LEFT, PRESCRIBED_FORCE, KALKER_LINEAR = 2, 1, 0, 1, 2
# Half the axle load of data/wheelset/passenger_coach.toml.
WHEEL_LOAD = 109092.1 / 2
# The Manchester benchmark's track, as the contact data were made with (docs/wheelset.md).
TRACK = {"track_gauge": 1.435, "gauge_measuring_height": 0.014, "flange_back_distance": 1.360,
         "flange_back_position": -0.070, "wheel_nominal_radius": 0.46}
# What the wheelset gives each contact unit, by the same names.
COUPLED_OUTPUTS = ["wheelset_lateral_displacement", "wheelset_yaw_angle", "wheelset_lateral_velocity",
                   "wheelset_yaw_rate", "rolling_speed", "wheel_angular_speed"]
CONTACT_OUTPUTS = ["track_force_x", "track_force_y", "track_force_z",
                   "track_moment_x", "track_moment_y", "track_moment_z"]


def slave(name, tmp_path_factory, instance_name):
    """An instantiated FMU2Slave of target/fmu/<name>.fmu (`cargo fmu package` builds them;
    scripts/test-all runs it first) and its value references by name."""
    path = FMUS / f"{name}.fmu"
    if not path.exists():
        subprocess.run(["cargo", "fmu", "package"], cwd=ROOT, check=True)
    description = read_model_description(str(path))
    unzipped = extract(str(path), unzipdir=str(tmp_path_factory.mktemp(instance_name)))
    fmu = FMU2Slave(guid=description.guid, unzipDirectory=unzipped,
                    modelIdentifier=description.coSimulation.modelIdentifier, instanceName=instance_name)
    fmu.instantiate()
    return fmu, {v.name: v.valueReference for v in description.modelVariables}


def run(tmp_path_factory, speed, step, duration, initial_displacement):
    """The coupled run: y(t), ψ(t) and the right wheel's lateral force at each communication point."""
    wheelset, wvr = slave("wheelset", tmp_path_factory, "wheelset")
    wheels = {side: slave("wheel_rail_contact", tmp_path_factory, f"{side} wheel") for side in ("left", "right")}
    wheelset.setupExperiment(startTime=0.0)
    wheelset.enterInitializationMode()
    free = {"longitudinal_stiffness": 0.0, "lateral_stiffness": 0.0, "longitudinal_damping": 0.0,
            "lateral_damping": 0.0, "forward_speed": speed, "initial_lateral_displacement": initial_displacement}
    wheelset.setReal([wvr[n] for n in free], list(free.values()))
    wheelset.exitInitializationMode()
    state = wheelset.getReal([wvr[n] for n in COUPLED_OUTPUTS])
    for side, (fmu, vr) in wheels.items():
        fmu.setupExperiment(startTime=0.0)
        fmu.setInteger([vr["contact_geometry"], vr["wheel_side"], vr["vertical_contact"], vr["creep_force_model"]],
                       [PROFILES, LEFT if side == "left" else RIGHT, PRESCRIBED_FORCE, KALKER_LINEAR])
        fmu.setString([vr["wheel_profile"], vr["rail_profile"]], ["MBench_S1002", "MBench_UIC60"])
        fmu.setReal([vr[n] for n in TRACK], list(TRACK.values()))
        fmu.enterInitializationMode()
        fmu.setReal([vr["vertical_force"]] + [vr[n] for n in COUPLED_OUTPUTS], [WHEEL_LOAD] + state)
        fmu.exitInitializationMode()
    history = []
    for k in range(round(duration / step)):
        time = k * step
        loads = {side: fmu.getReal([vr[n] for n in CONTACT_OUTPUTS]) for side, (fmu, vr) in wheels.items()}
        names = [f"{side}_{n}" for side in ("left", "right") for n in CONTACT_OUTPUTS]
        wheelset.setReal([wvr[n] for n in names], loads["left"] + loads["right"])
        for fmu, vr in wheels.values():
            fmu.setReal([vr[n] for n in COUPLED_OUTPUTS], state)
        wheelset.doStep(currentCommunicationPoint=time, communicationStepSize=step)
        for fmu, _ in wheels.values():
            fmu.doStep(currentCommunicationPoint=time, communicationStepSize=step)
        state = wheelset.getReal([wvr[n] for n in COUPLED_OUTPUTS])
        history.append((time + step, state[0], state[1], loads["right"][1]))
    for fmu in [wheelset] + [fmu for fmu, _ in wheels.values()]:
        fmu.terminate()
        fmu.freeInstance()
    return history


def test_the_free_wheelset_oscillates_kinematically_and_stays_bounded(tmp_path_factory):
    speed, step, start = 10.0, 2e-4, 3e-3
    history = run(tmp_path_factory, speed, step, duration=1.2, initial_displacement=start)
    displacements = [y for _, y, _, _ in history]
    # Bounded: never beyond the start amplitude by more than a fifth (the free wheelset's
    # kinematic mode is nearly undamped, docs/wheelset.md), never near the flange (6.6 mm).
    assert max(abs(y) for y in displacements) < 1.2 * start
    # It oscillates: y crosses zero, and the yaw turns the wheelset back towards the centre
    # (ψ < 0 while y > 0 in the first quarter: heading towards −y).
    crossings = [t for (t, y0, _, _), (_, y1, _, _) in zip(history, history[1:]) if y0 > 0 >= y1]
    assert crossings, "no zero crossing within 1.2 s"
    assert min(psi for _, _, psi, _ in history[: len(history) // 8]) < 0
    # The first crossing near a quarter of Klingel's period, λ = 2π √(r0 s / γ_e) at 3 mm
    # (8.68 m, docs/wheelset.md) at 10 m/s: 0.217 s. Loosely (±25 %): the wavelength check of
    # issue 28, with the amplitude measured, is still to come.
    quarter = 2 * math.pi * math.sqrt(0.46 * 0.75 / 0.1804) / speed / 4
    assert crossings[0] == pytest.approx(quarter, rel=0.25)
