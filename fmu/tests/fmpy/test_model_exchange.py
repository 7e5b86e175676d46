"""Both packaged FMUs as FMI 2.0 Model Exchange in fmpy, the same binaries as Co-Simulation: the
contact unit algebraic in its inputs (its outputs at any time are the core library's at that time's
inputs), its relaxed forces continuous states that fmpy's CVode integrates as the relaxation law's
closed form, the wheelset's states integrated by fmpy's CVode (its free lateral oscillation
against the closed form)."""

import math

import numpy as np
from fmpy import read_model_description, simulate_fmu

from conftest import CONTACT_INPUTS, ROOT, core_forces, start_values
from test_simulate import INPUTS, OUTPUTS, input_table

WHEELSET = ROOT / "target" / "fmu" / "wheelset.fmu"


def test_both_fmus_declare_model_exchange_beside_co_simulation(fmu_path):
    # The contact unit's event indicators: the switching functions of a wheel's patches (5 contacts: onset;
    # 4 pairs: join and deepest); the wheelset has no jumps.
    for path, states, indicators in ((fmu_path, 2, 13), (WHEELSET, 5, 0)):
        description = read_model_description(str(path))
        assert description.modelExchange is not None and description.coSimulation is not None, path
        assert description.modelExchange.modelIdentifier == description.coSimulation.modelIdentifier
        assert len(description.derivatives) == states, path
        assert description.numberOfEventIndicators == indicators, path


def test_the_contact_unit_in_model_exchange_gives_the_core_librarys_forces_at_each_time(fmu_path, model_description):
    table = input_table()
    result = simulate_fmu(fmu_path, fmi_type="ModelExchange", stop_time=1.0, output_interval=0.05, input=table,
                          output=INPUTS + OUTPUTS)
    assert len(result) >= 21 and result["time"][-1] == 1.0
    # Model Exchange has no step: each row holds the inputs at its time and the outputs computed from them.
    defaults = start_values(model_description)
    rows = [{name: (row[name] if name in INPUTS else defaults[name]) for name in CONTACT_INPUTS} for row in result]
    for row, reference in zip(result, core_forces(rows)):
        for name, value in zip(OUTPUTS, reference):
            assert math.isclose(row[name], value, rel_tol=1e-12, abs_tol=0.0), (row["time"], name, row[name], value)
    assert result["adhesion_utilisation"].max() > 0.9


def test_the_relaxed_forces_integrated_by_cvode_follow_the_relaxation_laws_closed_form(fmu_path, model_description):
    """Creep relaxation over L = 10 mm at V = 20 m/s (tau = 0.5 ms): initialised at the steady
    force of xi = 1e-3, then xi steps to 3e-3 at t1 = 2 ms (a time event of fmpy's input), and the
    forces follow F_ss2 + (F_ss1 - F_ss2) exp(-V (t - t1)/L), with the steady forces from the
    core library."""
    t1 = 2e-3
    table = np.array([(0.0, 1e-3), (t1, 1e-3), (t1, 3e-3), (0.01, 3e-3)],
                     dtype=[("time", np.float64), ("creepage_longitudinal", np.float64)])
    result = simulate_fmu(fmu_path, fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-10,
                          stop_time=0.01, output_interval=1e-4, input=table,
                          start_values={"creep_relaxation": 1, "relaxation_length": 0.01},
                          output=["force_longitudinal", "relaxed_force_longitudinal"])
    defaults = start_values(model_description)
    steady = [core_forces([{**defaults, "creepage_longitudinal": xi}])[0][0] for xi in (1e-3, 3e-3)]
    t = result["time"]
    expected = np.where(t < t1, steady[0], steady[1] + (steady[0] - steady[1]) * np.exp(-20.0 * (t - t1) / 0.01))
    change = abs(steady[1] - steady[0])
    assert change > 1e4
    assert np.max(np.abs(result["force_longitudinal"] - expected)) < 1e-5 * change
    assert np.all(result["relaxed_force_longitudinal"] == result["force_longitudinal"])


def test_the_wheelset_integrated_by_cvode_oscillates_as_the_closed_form():
    """y'' = -(2 k_y/m) y - (2 c_y/m) y' from y(0) = 2 mm (the start values: m = 1813 kg,
    k_y = 3.884 MN/m, c_y = 2 kN s/m per axlebox), no lateral force."""
    result = simulate_fmu(str(WHEELSET), fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-9,
                          stop_time=0.2, output_interval=1e-3, start_values={"initial_lateral_displacement": 2e-3},
                          output=["wheelset_lateral_displacement", "wheel_angular_speed"])
    k, c = 2 * 3.884e6 / 1813.0, 2 * 2.0e3 / 1813.0
    omega = math.sqrt(k - c * c / 4)
    t = result["time"]
    expected = 2e-3 * np.exp(-c / 2 * t) * (np.cos(omega * t) + c / 2 / omega * np.sin(omega * t))
    assert np.max(np.abs(result["wheelset_lateral_displacement"] - expected)) < 1e-5 * 2e-3
    assert np.all(result["wheel_angular_speed"] == 20.0 / 0.45990634083)
