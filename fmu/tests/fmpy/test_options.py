"""Every model and every scene option through FMU2Slave and simulate_fmu, against the core
library's outputs (`cargo fmu reference`, composed from the core independently of the FMU)."""

import math

import numpy as np
import pytest
from fmpy import simulate_fmu

from conftest import core_outputs, settable_start_values
from test_slave import expect_error, instantiated

OUTPUTS = ["force_longitudinal", "force_lateral", "adhesion_utilisation", "spin_moment",
           "current_friction_coefficient", "slip_velocity", "effective_creepage_longitudinal",
           "effective_creepage_lateral", "effective_spin_creepage", "contact_semi_axis_a", "contact_semi_axis_b",
           "max_pressure", "approach"]
ON = 1


def set_values(slave, model_description, values):
    types = {v.name: v.type for v in model_description.modelVariables}
    vr = {v.name: v.valueReference for v in model_description.modelVariables}
    reals = [(vr[n], float(x)) for n, x in values.items() if types[n] == "Real"]
    integers = [(vr[n], int(x)) for n, x in values.items() if types[n] != "Real"]
    if reals:
        slave.setReal([r for r, _ in reals], [x for _, x in reals])
    if integers:
        slave.setInteger([r for r, _ in integers], [x for _, x in integers])


def run(new_slave, model_description, parameters, rows, steps):
    """Parameters and rows[0] set in initialization mode; then for each further row its inputs,
    a DoStep of steps[k - 1]. Returns the FMU's outputs after initialization and after each step,
    and the rows the reference needs (every input and parameter, with step_size)."""
    vr = {v.name: v.valueReference for v in model_description.modelVariables}
    slave, _ = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    set_values(slave, model_description, parameters)
    slave.enterInitializationMode()
    set_values(slave, model_description, rows[0])
    slave.exitInitializationMode()
    read = lambda: dict(zip(OUTPUTS, slave.getReal([vr[name] for name in OUTPUTS])))
    results = [read()]
    time = 0.0
    for row, step in zip(rows[1:], steps):
        set_values(slave, model_description, row)
        slave.doStep(time, step)
        time += step
        results.append(read())
    start = settable_start_values(model_description)
    merged, reference_rows = {**start, **parameters}, []
    for row, step in zip(rows, [0.0] + list(steps)):
        merged = {**merged, **row}
        reference_rows.append({**merged, "step_size": step})
    return results, reference_rows


def assert_equal_to_core(results, reference_rows):
    expected = core_outputs(reference_rows)
    for k, (fmu, core) in enumerate(zip(results, expected)):
        for name in OUTPUTS:
            assert math.isclose(fmu[name], core[name], rel_tol=1e-12, abs_tol=0.0), (k, name, fmu[name], core[name])
    assert len(results) == len(expected)


CREEPAGE_ROWS = [
    {"creepage_longitudinal": 0.0, "creepage_lateral": 0.0, "spin_creepage": 0.0},
    {"creepage_longitudinal": 1e-3, "creepage_lateral": -5e-4, "spin_creepage": 0.3},
    {"creepage_longitudinal": 4e-3, "creepage_lateral": 1e-3, "spin_creepage": -0.5, "normal_force": 60e3},
    {"creepage_longitudinal": -2e-2, "creepage_lateral": 0.0, "spin_creepage": 1.0, "friction_coefficient": 0.2},
    {"creepage_longitudinal": 2e-4, "creepage_lateral": 3e-4, "spin_creepage": 0.1, "normal_force": -1.0},
]


@pytest.mark.parametrize("model, options", [
    (1, {}),
    (2, {}),
    (3, {}),
    (4, {}),
    (4, {"fastsim_strips": 9, "fastsim_elements": 13, "fastsim_traction_bound": 2, "fastsim_flexibility": 3}),
    (4, {"fastsim_strips": 6, "fastsim_elements": 30, "fastsim_flexibility": 2}),
    (5, {"exact_elements_longitudinal": 14, "exact_elements_lateral": 12}),
    (6, {}),
])
def test_every_model_equals_the_core(new_slave, model_description, model, options):
    results, rows = run(new_slave, model_description, {"creep_force_model": model, **options}, CREEPAGE_ROWS, [1e-3] * 4)
    assert_equal_to_core(results, rows)
    spin_moments = [r["spin_moment"] for r in results]
    if model in (1, 3):
        assert spin_moments == [0.0] * 5, "Polach and Shen-Hedrick-Elkins have no spin moment"
    else:
        assert spin_moments[1] != 0.0 and spin_moments[4] == 0.0, spin_moments
    assert results[4]["force_longitudinal"] == 0.0, "lift-off"


@pytest.mark.parametrize("law, mu0, user", [
    (2, 0.55, {}),
    (3, 0.30, {}),
    (4, 0.40, {"adhesion_reduction_factor": 0.8, "slip_reduction_factor": 0.3, "friction_limit_ratio": 0.5,
               "friction_decay_rate": 0.9}),
])
def test_polach_2005_equals_the_core_and_friction_falls_with_slip(new_slave, model_description, law, mu0, user):
    rows = [{"creepage_longitudinal": xi, "rolling_speed": speed, "friction_coefficient": mu0, "spin_creepage": 0.2}
            for xi, speed in [(1e-3, 30.0), (5e-3, 30.0), (2e-2, 30.0), (0.1, 30.0), (0.3, 30.0), (0.1, -5.0)]]
    results, reference = run(new_slave, model_description, {"traction_law": law, **user}, rows, [1e-3] * 5)
    assert_equal_to_core(results, reference)
    friction = [r["current_friction_coefficient"] for r in results]
    assert friction[0] < mu0 and all(a > b for a, b in zip(friction[:5], friction[1:5])), friction
    # Beyond the peak the force falls (Polach 2005's point): |F_x| at 30 % slip < at 10 %.
    assert abs(results[4]["force_longitudinal"]) < abs(results[3]["force_longitudinal"])
    # The slower wheel slips less at the same creepage: more friction.
    assert friction[5] > friction[3]


def test_polach_2005_requires_model_polach(new_slave, model_description):
    slave, callbacks = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    set_values(slave, model_description, {"traction_law": 2, "creep_force_model": 3})
    slave.enterInitializationMode()
    expect_error(slave.exitInitializationMode)
    assert callbacks.texts()[-1] == ("fmi2ExitInitializationMode: traction_law = 2 is invalid: Polach 2005 needs "
                                     "creep_force_model = 1 (polach), not creep_force_model = 3 (shen_hedrick_elkins)")


def test_hertz_contact_equals_the_core_and_ignores_the_semi_axis_inputs(new_slave, model_description):
    rows = [{"normal_force": q, "semi_axis_a": math.nan, "semi_axis_b": -1.0, "creepage_lateral": 5e-4,
             "spin_creepage": 0.4} for q in [100e3, 50e3, -1.0, 0.0, 150e3]]
    parameters = {"hertz_contact": ON, "wheel_profile_curvature": -0.5, "rail_profile_curvature": 1 / 0.3}
    results, reference = run(new_slave, model_description, parameters, rows, [1e-3] * 4)
    assert_equal_to_core(results, reference)
    assert [r["force_longitudinal"] for r in results[2:4]] == [0.0, 0.0], "lift-off"
    assert [r["contact_semi_axis_a"] for r in results[2:4]] == [0.0, 0.0]
    # a ∝ Q^(1/3) at fixed curvatures.
    ratio = results[4]["contact_semi_axis_a"] / results[0]["contact_semi_axis_a"]
    assert math.isclose(ratio, 1.5 ** (1 / 3), rel_tol=1e-12)


def test_creepages_from_kinematics_through_standstill(new_slave, model_description):
    rows = [{"rolling_speed": v, "wheel_angular_speed": (v + 0.01) / 0.46, "lateral_slip_velocity": 0.002,
             "spin_angular_velocity": 0.5, "creepage_longitudinal": math.nan}
            for v in [2.0, 0.5, 0.01, 0.0, -0.01, -0.5, -2.0]]
    results, reference = run(new_slave, model_description, {"creepages_from_kinematics": ON}, rows, [1e-3] * 6)
    assert_equal_to_core(results, reference)
    limit = 0.3 * 100e3
    assert all(math.hypot(r["force_longitudinal"], r["force_lateral"]) <= limit for r in results)
    assert results[3]["effective_spin_creepage"] == 0.0, "no spin creepage at standstill"
    # The spin's lateral part reverses with the direction of travel.
    assert results[0]["effective_spin_creepage"] == -results[6]["effective_spin_creepage"]


def test_creep_relaxation_equals_the_core_and_never_overshoots(new_slave, model_description):
    rows = [{"creepage_longitudinal": 1e-3, "rolling_speed": 5.0}] + \
           [{"creepage_longitudinal": 4e-3, "rolling_speed": 5.0}] * 6 + [{"creepage_longitudinal": 4e-3, "rolling_speed": 0.0}]
    steps = [1e-4, 5e-4, 2e-3, 1e-2, 3e-3, 1.0, 0.5]
    results, reference = run(new_slave, model_description, {"creep_relaxation": ON}, rows, steps)
    assert_equal_to_core(results, reference)
    forces = [r["force_longitudinal"] for r in results]
    steady = core_outputs([{**reference[-1], "step_size": 0.0}])[0]["force_longitudinal"]
    assert forces[0] > forces[1] > forces[2] > forces[3] > forces[4] >= forces[5] >= steady, (forces, steady)
    assert forces[6] == forces[7], "frozen at standstill"


def test_all_options_together_equal_the_core(new_slave, model_description):
    parameters = {"traction_law": 2, "hertz_contact": ON, "creepages_from_kinematics": ON, "creep_relaxation": ON,
                  "relaxation_length": 0.02, "regularisation_speed": 0.05}
    rows = [{"rolling_speed": v, "wheel_angular_speed": w / 0.46, "friction_coefficient": 0.55, "normal_force": q}
            for v, w, q in [(10.0, 10.0, 100e3), (10.0, 10.5, 100e3), (5.0, 6.0, 90e3), (0.0, 0.2, 90e3),
                            (-1.0, -1.1, 0.0), (3.0, 3.1, 100e3)]]
    results, reference = run(new_slave, model_description, parameters, rows, [2e-3, 1e-3, 5e-3, 1e-2, 0.1])
    assert_equal_to_core(results, reference)


def test_reset_clears_the_relaxed_force(new_slave, model_description):
    """fmi2Reset returns every variable to its start value, and the instance to its state after
    instantiation. The relaxed force itself is re-initialised at ExitInitializationMode, so what a
    leaking reset shows is the first run: it moves inputs and the relaxation length away from their
    start values and leaves the force mid-transient; the second run sets only creep_relaxation and
    must equal the core from the start values, which differs from the core from the first run's."""
    vr = {v.name: v.valueReference for v in model_description.modelVariables}
    slave, _ = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    set_values(slave, model_description, {"creep_relaxation": ON, "relaxation_length": 0.05})
    slave.enterInitializationMode()
    first_run = {"creepage_longitudinal": 5e-3, "normal_force": 60e3, "rolling_speed": 3.0}
    set_values(slave, model_description, first_run)
    slave.exitInitializationMode()
    slave.setReal([vr["creepage_longitudinal"]], [2e-3])
    slave.doStep(0.0, 1e-4)
    slave.reset()

    slave.setupExperiment(startTime=0.0)
    set_values(slave, model_description, {"creep_relaxation": ON})
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    initial = slave.getReal([vr["force_longitudinal"]])[0]
    slave.setReal([vr["creepage_longitudinal"]], [3e-3])
    slave.doStep(0.0, 1e-4)
    relaxed = slave.getReal([vr["force_longitudinal"]])[0]

    start = settable_start_values(model_description)
    run = lambda values: core_outputs([{**values, "creep_relaxation": ON, "step_size": 0.0},
                                       {**values, "creep_relaxation": ON, "creepage_longitudinal": 3e-3,
                                        "step_size": 1e-4}])
    expected = run(start)
    assert initial == expected[0]["force_longitudinal"]
    assert math.isclose(relaxed, expected[1]["force_longitudinal"], rel_tol=1e-12, abs_tol=0.0)
    leaked = run({**start, "relaxation_length": 0.05, **first_run})
    for k in range(2):
        assert not math.isclose(leaked[k]["force_longitudinal"], expected[k]["force_longitudinal"], rel_tol=1e-3)


def every_item_of(model_description, invalid, type_name):
    """The message for an invalid enumeration value: every item of the FMU's type, as declared."""
    simple_type = next(t for t in model_description.typeDefinitions if t.name == type_name)
    items = ", ".join(f"{int(item.value)} ({item.name})" for item in simple_type.items)
    return f"{invalid} is invalid: must be one of {items}"


@pytest.mark.parametrize("parameters, message", [
    ({"creep_force_model": 4, "fastsim_strips": 0}, "fastsim_strips = 0 is invalid: must be an integer in 1..=10000"),
    ({"creep_force_model": 5, "exact_elements_lateral": -2}, "exact_elements_lateral = -2 is invalid: must lie in [1, 400]"),
    ({"creep_force_model": 7}, lambda model_description: every_item_of(model_description, "creep_force_model = 7", "Model")),
    ({"traction_law": 4, "adhesion_reduction_factor": 0.0},
     "adhesion_reduction_factor = 0 is invalid: k_A must lie in (0, 1]"),
    ({"creepages_from_kinematics": ON, "regularisation_speed": -1.0},
     "regularisation_speed = -1 is invalid: must be finite and > 0"),
    ({"hertz_contact": ON, "wheel_profile_curvature": math.nan},
     "wheel_profile_curvature = NaN is invalid: must be finite"),
    ({"creep_relaxation": ON, "relaxation_length": -1.0},
     "relaxation_length = -1 is invalid: must be finite and >= 0 (0: derived from the contact)"),
    ({"creep_relaxation": 3}, "creep_relaxation = 3 is invalid: must be one of 0 (off), 1 (on)"),
])
def test_invalid_option_parameters_give_fmi2error_at_initialization(new_slave, model_description, parameters, message):
    slave, callbacks = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    set_values(slave, model_description, parameters)
    slave.enterInitializationMode()
    expect_error(slave.exitInitializationMode)
    if callable(message):
        message = message(model_description)
    assert callbacks.texts()[-1] == f"fmi2ExitInitializationMode: {message}"
    # The master corrects the value and carries on.
    start = settable_start_values(model_description)
    set_values(slave, model_description, {name: start[name] for name in parameters})
    slave.exitInitializationMode()


def test_structural_parameters_are_fixed_after_initialization(new_slave, model_description):
    vr = {v.name: v.valueReference for v in model_description.modelVariables}
    slave, callbacks = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    expect_error(slave.setInteger, [vr["creep_force_model"]], [2])
    assert callbacks.texts()[-1] == "fmi2SetInteger: creep_force_model is a fixed parameter and cannot be set after initialization"
    slave.setReal([vr["relaxation_length"]], [0.01])  # tunable


def test_simulate_fmu_with_kinematics_and_relaxation(fmu_path, model_description):
    """simulate_fmu with start values switching options on and an input table braking the wheel."""
    inputs = ["rolling_speed", "wheel_angular_speed"]
    table = np.array([(0.0, 10.0, 10.0 / 0.46), (0.5, 10.0, 9.7 / 0.46), (1.0, 8.0, 8.0 / 0.46)],
                     dtype=[("time", np.float64)] + [(name, np.float64) for name in inputs])
    options = {"creepages_from_kinematics": ON, "creep_relaxation": ON, "traction_law": 2}
    result = simulate_fmu(fmu_path, stop_time=1.0, output_interval=0.05, input=table, output=inputs + OUTPUTS,
                          start_values={**options, "friction_coefficient": 0.55})
    assert len(result) >= 21
    start = {**settable_start_values(model_description), **options, "friction_coefficient": 0.55}
    # Each recorded row holds the inputs its step used (see test_simulate.py); the first is the
    # initialization.
    rows = [{**start, "rolling_speed": r["rolling_speed"], "wheel_angular_speed": r["wheel_angular_speed"],
             "step_size": 0.0 if k == 0 else r["time"] - result["time"][k - 1]} for k, r in enumerate(result)]
    expected = core_outputs(rows)
    for row, core in zip(result, expected):
        for name in OUTPUTS:
            assert math.isclose(row[name], core[name], rel_tol=1e-12, abs_tol=0.0), (row["time"], name)
    # A braking wheel (ωr < V: ξ > 0) gets F_x < 0, built up over the relaxation length.
    forces = result["force_longitudinal"]
    assert forces.min() < -3e4 and forces[2] > forces.min(), forces
