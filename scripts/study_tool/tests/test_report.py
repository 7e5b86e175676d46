"""The end-of-study report: the error against the reference model is matched scene by scene, and
the plots are written beside the results."""

import numpy as np
import pandas as pd

from .conftest import report, run_in_process, spec

STUDY = """
name = "report"
models = ["exact", "polach", "fastsim"]
outputs = ["force_longitudinal", "force_lateral"]
chunk_size = 9
[fixed]
exact_elements_longitudinal = 8
exact_elements_lateral = 8
[grid]
semi_axis_a = [0.0036, 0.0072]
creepage_longitudinal = [1e-4, 1e-3, 1e-2]
friction_coefficient = [0.2, 0.4]
[plot]
x = "creepage_longitudinal"
family = ["friction_coefficient", "a_over_b"]
error_map = { x = "a_over_b", y = "creepage_longitudinal", output = "force_longitudinal" }
"""


def test_errors_against_exact_and_the_plots(study_file, fmu_path, tmp_path):
    out = tmp_path / "out"
    path = study_file(STUDY)
    outcome = run_in_process(path, fmu_path, out)
    summary, plots = report.report(outcome, spec.prepare(path, fmu_path), out)
    frame = pd.read_parquet(out / "results.parquet")
    # The same scene under each model: rows k, k + 12, k + 24 (models are the outer axis).
    exact, polach, fastsim = (frame[frame["creep_force_model"] == m].reset_index(drop=True)
                              for m in ("exact", "polach", "fastsim"))
    assert (exact["creepage_longitudinal"] == polach["creepage_longitudinal"]).all()
    limit = exact["friction_coefficient"] * exact["normal_force"]
    for name, model in (("polach", polach), ("fastsim", fastsim)):
        error = np.abs(model["force_longitudinal"] - exact["force_longitudinal"]) / limit
        assert error.max() > 0
        line = f"error of {name} against exact in force_longitudinal, |Δ|/(μQ): max {error.max():.3g}, " \
               f"mean {error.mean():.3g} over 12 scenes"
        assert line in summary, summary
    assert [p.name for p in plots] == ["creep_curves.png", "creep_curves.svg", "error_map.png", "error_map.svg"]
    assert all(p.stat().st_size > 1000 for p in plots)
    assert (out / "summary.txt").read_text() == summary + "\n"


MONTE_CARLO = """
name = "monte_carlo"
models = ["polach"]
outputs = ["force_longitudinal", "force_lateral"]
[fixed]
rolling_speed = 20.0
[grid]
creepage_longitudinal = { geomspace = [1e-4, 0.4, 15] }
[random]
seed = 3
samples = 5
[[cases]]
name = "dry"
traction_law = "polach2005_dry"
random.friction_coefficient = { distribution = "normal", mean = 0.55, std = 0.05 }
[plot]
x = "creepage_longitudinal"
y = ["adhesion_coefficient"]
"""


def test_monte_carlo_summary_gives_the_spread_of_each_samples_peak(study_file, fmu_path, tmp_path):
    path = study_file(MONTE_CARLO)
    outcome = run_in_process(path, fmu_path, tmp_path / "out")
    summary, _ = report.report(outcome, spec.prepare(path, fmu_path), tmp_path / "out")
    frame = outcome.frame
    adhesion = np.hypot(frame["force_longitudinal"], frame["force_lateral"]) / frame["normal_force"]
    peaks = adhesion.groupby(frame["sample"]).max()
    assert len(peaks) == 5
    # Polach 2005 dry: the peak lies below mu0 (friction falls with slip) and above half of it.
    mu0 = frame.groupby("sample")["friction_coefficient"].first()
    assert ((peaks < mu0) & (peaks > 0.5 * mu0)).all()
    q = peaks.quantile([0.05, 0.5, 0.95])
    line = "dry: polach".ljust(28) + " " + "adhesion_coefficient".ljust(28) + \
        f" {q[0.5]:.6g} [{q[0.05]:.6g}, {q[0.95]:.6g}] over 5 samples"
    assert "  " + line in summary, summary
