"""simulate_fmu with an input table: a creepage ramp, a load step and a friction drop."""

import math

import numpy as np
from fmpy import simulate_fmu

from conftest import CONTACT_INPUTS, core_forces, start_values

INPUTS = ["creepage_longitudinal", "creepage_lateral", "spin_creepage", "normal_force", "semi_axis_a", "semi_axis_b",
          "friction_coefficient"]
OUTPUTS = ["force_longitudinal", "force_lateral", "adhesion_utilisation"]


def input_table():
    # time, ξ ramp 0 → 0.6 %, η = 0.05 %, φ = 0.2 /m, load step 100 → 60 kN at t = 0.4 (with its smaller
    # Hertzian ellipse, a, b ∝ Q^(1/3)), friction drop 0.3 → 0.15 at t = 0.7.
    a, b = 7.2e-3, 5.4e-3
    shrink = 0.6 ** (1 / 3)
    rows = [
        (0.0, 0.0, 5e-4, 0.2, 100e3, a, b, 0.3),
        (0.4, 2.4e-3, 5e-4, 0.2, 100e3, a, b, 0.3),
        (0.4, 2.4e-3, 5e-4, 0.2, 60e3, a * shrink, b * shrink, 0.3),
        (0.7, 4.2e-3, 5e-4, 0.2, 60e3, a * shrink, b * shrink, 0.3),
        (0.7, 4.2e-3, 5e-4, 0.2, 60e3, a * shrink, b * shrink, 0.15),
        (1.0, 6e-3, 5e-4, 0.2, 60e3, a * shrink, b * shrink, 0.15),
    ]
    return np.array(rows, dtype=[("time", np.float64)] + [(name, np.float64) for name in INPUTS])


def test_outputs_equal_the_core_library_for_the_inputs_set_before_each_step(fmu_path, model_description):
    table = input_table()
    result = simulate_fmu(fmu_path, stop_time=1.0, output_interval=0.05, input=table, output=INPUTS + OUTPUTS)
    # fmpy sets the inputs at the start of each step and records after it, so every recorded row
    # holds the inputs the step used (the table at the previous communication point) and the
    # outputs computed from them.
    times = result["time"]
    assert len(times) >= 21 and times[-1] == 1.0
    previous_times = np.concatenate([[0.0], times[:-1]])
    for name in ["creepage_longitudinal"]:
        expected = np.interp(previous_times, table["time"], table[name])
        assert np.allclose(result[name], expected, rtol=0, atol=1e-15)
    # The load step and friction drop happen at the table's events, not one step late.
    assert np.allclose(result["normal_force"][times > 0.4 + 1e-9], 60e3, rtol=1e-12, atol=0)
    assert np.allclose(result["normal_force"][times <= 0.4 + 1e-9], 100e3, rtol=1e-12, atol=0)
    assert np.allclose(result["friction_coefficient"][times > 0.7 + 1e-9], 0.15, rtol=1e-12, atol=0)

    defaults = start_values(model_description)
    rows = [{name: (row[name] if name in INPUTS else defaults[name]) for name in CONTACT_INPUTS} for row in result]
    expected = core_forces(rows)
    for row, reference in zip(result, expected):
        for name, value in zip(OUTPUTS, reference):
            assert math.isclose(row[name], value, rel_tol=1e-12, abs_tol=0.0), (row["time"], name, row[name], value)
    # The scene exercises saturation: utilisation rises towards 1 along the ramp.
    assert result["adhesion_utilisation"].max() > 0.9
