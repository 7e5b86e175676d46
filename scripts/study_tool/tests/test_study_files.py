"""Malformed study files are refused up front with an error naming the key; variable names are
checked against the FMU's modelDescription.xml."""

import tomllib

import pytest

from .conftest import ROOT, command, spec

GRID = '[grid]\ncreepage_longitudinal = [1e-3]\n'


def document(top="", grid="", tables=""):
    """A study file: top-level keys, the [grid] table (one valid axis plus `grid`), further tables."""
    return f"{top}\n{GRID}{grid}\n{tables}\n"


def every_model(interface):
    """The FMU's models, as its modelDescription.xml declares them (checked against the core's list
    of rungs by the adapter's tests)."""
    return ", ".join(interface["variables"]["creep_force_model"]["items"])


@pytest.mark.parametrize("text, message", [
    (document(top='chunksize = 5'), "chunksize: unknown key (did you mean chunk_size?)"),
    (document(top='models = ["polach", "exakt"]'),
     lambda interface: f"models[1]: 'exakt' is not a creep_force_model ({every_model(interface)})"),
    (document(top='models = []'), "models: must be a non-empty list"),
    (document(top='outputs = ["force_longitudinal", "force_lateal"]'), "outputs[1]: unknown output 'force_lateal' "
                                                         "(did you mean force_lateral?)"),
    (document(top='outputs = ["normal_force"]'), "outputs[0]: normal_force is an input, not an output"),
    (document(top='chunk_size = 0'), "chunk_size: must be an integer >= 1, not 0"),
    (document(top='step_size = -1.0'), "step_size: must be a number > 0, not -1.0"),
    (document(grid='friction_coeficient = [0.3]'), "grid.friction_coeficient: unknown key (did you mean friction_coefficient?)"),
    (document(tables='[fixed]\nforce_longitudinal = 1.0'), "fixed.force_longitudinal: force_longitudinal is an output, not an input or parameter"),
    (document(tables='[fixed]\ntraction_law = "polach2005_moist"'), "fixed.traction_law: 'polach2005_moist' is not a TractionLaw "
                                                   "(coulomb, polach2005_dry, polach2005_wet, polach2005_user)"),
    (document(tables='[fixed]\ncreep_force_model = "exact"'), "fixed.creep_force_model: set the model with the top-level key models"),
    (document(tables='[fixed]\nfastsim_strips = 2.5'), "fixed.fastsim_strips: must be an integer, not 2.5"),
    (document(tables='[fixed]\nnormal_force = "heavy"'), "fixed.normal_force: must be a number, not 'heavy'"),
    (document(tables='[fixed]\nwheel_profile = 1002'),
     "fixed.wheel_profile: must be a string (a file path or a built-in profile's name), not 1002"),
    (document(tables='[fixed]\ncreepage_longitudinal = 1e-3'), "grid.creepage_longitudinal: is also set in [fixed]"),
    (document(grid='friction_coefficient = { linspace = [0.1, 0.4] }'),
     "grid.friction_coefficient.linspace: must be [start, stop, n] with n a positive integer"),
    (document(grid='friction_coefficient = { geomspace = [0.0, 0.4, 5] }'),
     "grid.friction_coefficient.geomspace: start and stop must be non-zero and of one sign"),
    (document(grid='friction_coefficient = []'), "grid.friction_coefficient: is an empty list"),
    (document(tables='[random]\nsamples = 10\nfriction_coefficient = { distribution = "normal", mean = 0.3, std = 0.03 }'),
     "random.seed: missing: random draws need a seed and a number of samples"),
    (document(tables='[random]\nseed = 1\nsamples = 10\nfriction_coefficient = { distribution = "gauss", mean = 0.3 }'),
     "random.friction_coefficient.distribution: must be one of uniform, loguniform, normal, lognormal, choice, not 'gauss'"),
    (document(tables='[random]\nseed = 1\nsamples = 10\nfriction_coefficient = { distribution = "normal", mean = 0.3 }'),
     "random.friction_coefficient.std: missing (a normal distribution needs mean, std)"),
    (document(tables='[random]\nseed = 1\nsamples = 10\nfriction_coefficient = { distribution = "uniform", low = 0.4, high = 0.2 }'),
     "random.friction_coefficient.high: must be greater than low"),
    (document(tables='[random]\nseed = 1\nsamples = 0'), "random.samples: must be an integer >= 1, not 0"),
    (document(tables='[[cases]]\ntraction_law = "polach2005_dry"'), "cases[0].name: missing: every case needs a name"),
    (document(tables='[[cases]]\nname = "dry"\ntraction_lav = "polach2005_dry"'), "cases[0].traction_lav: unknown key (did you mean traction_law?)"),
    (document(tables='[plot]\nx = "creepage"'), "plot.x: unknown variable 'creepage'"),
    (document(top='outputs = ["force_longitudinal"]', tables='[plot]\ny = ["max_pressure"]'), "plot.y[0]: 'max_pressure' is not among the study's outputs"),
    (document(tables='[plot]\nerror_map = { x = "semi_axis_b", y = "creepage_longitudinal", output = "force_longitudinal" }'),
     "plot.error_map.x: 'semi_axis_b' is not a [grid] axis"),
])
def test_a_malformed_study_names_the_key(interface, text, message):
    if callable(message):
        message = message(interface)
    with pytest.raises(spec.StudyError) as raised:
        spec.parse(tomllib.loads(text), interface)
    assert str(raised.value).startswith(message), str(raised.value)


def test_the_valid_base_document_parses(interface):
    study = spec.parse(tomllib.loads(document()), interface)
    assert study["grid"] == {"creepage_longitudinal": [1e-3]} and study["models"] == ["polach"]


def test_the_command_reports_a_malformed_study_with_its_file_and_key(study_file):
    path = study_file('models = ["polach"]\n[grid]\nfriction_coeficient = [0.3]\n')
    result = command("run", path, "--serial", "--no-progress")
    assert result.returncode == 2
    assert result.stderr.strip() == (f"{path}: grid.friction_coeficient: unknown key (did you mean "
                                      "friction_coefficient?)")


def test_the_command_reports_invalid_toml(study_file):
    path = study_file('models = ["polach"\n')
    result = command("run", path, "--serial", "--no-progress")
    assert result.returncode == 2
    assert result.stderr.startswith(f"{path}: not valid TOML: ")


def test_the_examples_are_valid(interface):
    examples = sorted((ROOT / "examples" / "studies").glob("*.toml"))
    assert len(examples) == 3
    for path in examples:
        study = spec.load(path, interface)
        assert spec.scenes(study, interface)
