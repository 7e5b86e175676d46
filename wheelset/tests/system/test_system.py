"""The wheelset on track as an SSP (systems/wheelset_on_track/), run by the fixed-step master
scripts/ssp_master.py (fmpy's FMU2Slave): its files against the SSP 1.0 schemas and the parameter
file, the physics of the coupled FMUs against references that do not come from them (Klingel's
formula with the geometry's conicity; the linear stability analysis of linear_stability.py), and
bad input ending the run with a message naming the unit, the time and the variable.

Needs the packaged FMUs (`cargo fmu package`, run first by scripts/test-all; built if missing)."""

import io
import pathlib
import re
import sys
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.ssp.simulation import simulate_ssp
from fmpy.ssp.ssd import find_components, ns, read_ssd, read_ssv
from lxml import etree

import linear_stability as ls

ROOT = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "scripts"))

import ssp_master  # noqa: E402
import wheelset_system as ws  # noqa: E402


@pytest.fixture(scope="module")
def ssp(tmp_path_factory):
    return ws.system_ssp(tmp_path_factory.mktemp("ssp") / "wheelset_on_track.ssp")


def _values(ssp, resource):
    return {p.name: p.value for p in read_ssv(str(ssp), resource=resource).parameters}


def test_the_ssd_and_its_parameter_sets_are_valid_ssp_1_0(ssp):
    """fmpy's reader validates SystemStructure.ssd and every .ssv it binds against the SSP 1.0
    schemas it ships; the variants are checked here too. Every input of the three units that the
    run needs is connected: the wheelset's twelve loads and each wheel's six motions."""
    ssd = read_ssd(str(ssp))
    for variant in ("hunting_check", "klingel_check"):
        read_ssv(str(ssp), resource=f"resources/{variant}.ssv")
    assert [c.name for c in find_components(ssd.system)] == ["wheelset", "left_wheel", "right_wheel"]
    ends = {(c.endElement, c.endConnector) for c in ssd.system.connections}
    loads = [f"{side}_{kind}_{axis}" for side in ("left", "right") for kind in ("track_force", "track_moment")
             for axis in "xyz"]
    assert {("wheelset", n) for n in loads} <= ends
    for wheel in ("left_wheel", "right_wheel"):
        assert {(wheel, n) for n in ["wheelset_lateral_displacement", "wheelset_yaw_angle",
                                     "wheelset_lateral_velocity", "wheelset_yaw_rate", "rolling_speed",
                                     "wheel_angular_speed"]} <= ends
    assert len(ends) == len(ssd.system.connections) == 24


def _with_ssd(ssp, directory, edit):
    """A copy of the SSP whose SystemStructure.ssd is edit(text)."""
    copy = directory / "edited.ssp"
    with zipfile.ZipFile(ssp) as source, zipfile.ZipFile(copy, "w") as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "SystemStructure.ssd":
                data = edit(data.decode()).encode()
            target.writestr(item, data)
    return copy


def test_an_ssd_that_breaks_the_schema_or_names_a_missing_variable_is_refused(ssp, tmp_path):
    """The validation is real: an element SSP 1.0 does not have fails the schema; a connection to
    a variable the FMU lacks ends the run before it starts, naming it."""
    broken = _with_ssd(ssp, tmp_path, lambda text: text.replace("<ssd:Connections>", "<ssd:Connections><ssd:Wire/>"))
    with pytest.raises(Exception, match="Failed to validate SystemStructure.ssd"):
        ws.run(broken, stop_time=0.01)
    renamed = _with_ssd(ssp, tmp_path, lambda text: text.replace(
        'endConnector="left_track_force_y"', 'endConnector="left_track_force_lateral"'))
    with pytest.raises(ssp_master.SystemRunError, match="names wheelset.left_track_force_lateral, which the system lacks"):
        ws.run(renamed, stop_time=0.01)


def test_the_parameter_sets_are_the_parameter_files(ssp):
    """The .ssv values against data/wheelset/passenger_coach.toml (wheelset, suspension, the two
    variants, the wheel load W/2 and the profiles) and the track the contact data were made on."""
    parameters = ls.load_parameters()
    wheelset = _values(ssp, "resources/passenger_coach.ssv")
    for table in ("wheelset", "primary_suspension"):
        for name, value in parameters[table].items():
            if name in wheelset:
                assert float(wheelset[name]) == value, name
    assert {n for n in parameters["primary_suspension"]} <= set(wheelset)
    for name in ("mass", "yaw_inertia", "spin_inertia"):
        assert float(wheelset[name]) == parameters["wheelset"][name]
    for variant in ("hunting_check", "klingel_check"):
        values = _values(ssp, f"resources/{variant}.ssv")
        assert {f"wheelset.{n}": v for n, v in parameters[variant].items()} == {n: float(v) for n, v in values.items()}
    contact = _values(ssp, "resources/contact_unit.ssv")
    data = ls.load_contact_data()
    assert float(contact["vertical_force"]) == pytest.approx(parameters["wheelset"]["axle_load"] / 2, rel=1e-12)
    # The profiles the units use: the .ssv's if it sets them, else the packaged FMU's start values.
    starts = {v.name: v.start for v in _model_description(ssp, "wheel_rail_contact.fmu").modelVariables}
    profiles = tuple(contact.get(name, starts[name]) for name in ("wheel_profile", "rail_profile"))
    assert profiles == (data["wheel_profile"], data["rail_profile"])
    assert float(contact["track_gauge"]) == data["track_gauge"]
    assert float(contact["wheel_nominal_radius"]) == data["nominal_radius"]
    assert float(wheelset["centred_rolling_radius"]) == pytest.approx(data["centred_radius"], abs=1e-10)


def _model_description(ssp, fmu):
    """The modelDescription of resources/`fmu` in the SSP."""
    with zipfile.ZipFile(ssp) as archive:
        return read_model_description(io.BytesIO(archive.read(f"resources/{fmu}")))


def _bound_parameters(ssp):
    """[(component, FMU, ssv:Parameter element)] of every ParameterBinding of the SSD in document
    order: the .ssv files it names and its inline sets (lxml elements, comments kept)."""
    with zipfile.ZipFile(ssp) as archive:
        ssd = etree.fromstring(archive.read("SystemStructure.ssd"))
        bound = []
        for component in ssd.iterfind("ssd:System/ssd:Elements/ssd:Component", namespaces=ns):
            fmu = component.get("source").removeprefix("resources/")
            for binding in component.iterfind("ssd:ParameterBindings/ssd:ParameterBinding", namespaces=ns):
                source = binding.get("source")
                root = etree.fromstring(archive.read(source)) if source else binding
                bound += [(component.get("name"), fmu, p) for p in root.iter(f"{{{ns['ssv']}}}Parameter")]
    return bound


def test_enumerations_are_integers_named_in_a_comment_and_strings_only_set_where_they_differ(ssp):
    """For masters that apply only ssv:Integer (OMSimulator drops ssv:Enumeration values) and do not
    deliver String values set before instantiation (OMSimulator again): every Enumeration variable
    that the SSD's bindings set is an ssv:Integer whose value is an item of the FMU's
    modelDescription.xml, with a comment beside it naming that item; a String parameter is set only
    where the value differs from the FMU's start value."""
    descriptions = {fmu: {v.name: v for v in _model_description(ssp, fmu).modelVariables}
                    for fmu in ("wheelset.fmu", "wheel_rail_contact.fmu")}
    enumerations = set()
    for component, fmu, parameter in _bound_parameters(ssp):
        variable = descriptions[fmu][parameter.get("name")]
        value = parameter.find("*")
        if variable.type == "Enumeration":
            items = {int(item.value): item.name for item in variable.declaredType.items}
            assert etree.QName(value).localname == "Integer", (component, variable.name)
            comments = [c.text.strip() for c in parameter.iter(etree.Comment)]
            assert comments == [items[int(value.get("value"))]], (component, variable.name, comments)
            enumerations.add((component, variable.name, comments[0]))
        assert etree.QName(value).localname != "Enumeration", (component, variable.name)
        if variable.type == "String":
            assert value.get("value") != variable.start, (component, variable.name)
    assert {("left_wheel", "wheel_side", "left"), ("right_wheel", "wheel_side", "right"),
            ("left_wheel", "contact_geometry", "profiles"), ("right_wheel", "creep_force_model", "kalker_linear"),
            ("right_wheel", "vertical_contact", "prescribed_force"), ("left_wheel", "contact_method", "hertz")} <= enumerations


def test_the_step_is_where_omsimulator_reads_it_and_the_master_takes_it_from_there(ssp):
    """The communication step sits in OMSimulator's annotation of the system, spelt with the
    prefixes OMSimulator matches literally (it reads the SSD without namespaces, only the first
    ssc:Annotation of ssd:Annotations, and only with description="oms-ma" as a fixed-step master);
    scripts/ssp_master.py reads the same number, and DefaultExperiment gives start and stop."""
    with zipfile.ZipFile(ssp) as archive:
        ssd = etree.fromstring(archive.read("SystemStructure.ssd"))
    system = ssd.find("ssd:System", namespaces=ns)
    annotations = [e for e in system if isinstance(e.tag, str)][-1]
    assert annotations.prefix == "ssd" and etree.QName(annotations).localname == "Annotations"
    first = annotations.find("*")
    assert (first.prefix, etree.QName(first).localname, first.get("type")) == ("ssc", "Annotation", "org.openmodelica")
    path = ["Annotations", "SimulationInformation", "FixedStepMaster"]
    element = first
    for name in path:
        element = element.find(f"{{{ssp_master.STEP_NAMESPACE}}}{name}")
        assert element is not None and element.prefix == "oms", name
    assert element.get("description") == "oms-ma"
    assert float(element.get("stepSize")) == 2e-4
    experiment = ssd.find("ssd:DefaultExperiment", namespaces=ns)
    assert (float(experiment.get("startTime")), float(experiment.get("stopTime"))) == (0.0, 1.0)
    assert ssp_master.default_experiment(ssp) == (0.0, 1.0, 2e-4)


def test_fmpys_own_ssp_simulation_cannot_run_this_system(ssp):
    """Why the master is our own (scripts/ssp_master.py): fmpy 0.3.32's simulate_ssp starts every
    connection at 0, so the wheelset's first step sees track_force_z = 0, lift-off, and fails."""
    with pytest.raises(Exception, match="fmi2DoStep failed"):
        simulate_ssp(str(ssp), stop_time=0.01, step_size=1e-3)


def test_the_passenger_coach_runs_from_the_ssps_defaults(ssp):
    """The SSD's default experiment (1 s, step 0.2 ms): the cited suspension holds the wheelset,
    started 3 mm off centre at 20 m/s, and its oscillation dies out; each wheel carries W/2."""
    result = ws.run(ssp)
    assert result["time"][-1] == pytest.approx(1.0)
    y = result[ws.DISPLACEMENT]
    assert abs(y[0]) == pytest.approx(3e-3)
    assert np.max(np.abs(y[len(y) // 2:])) < 1e-5
    for side in ("left", "right"):
        assert result[f"{side}_wheel.track_force_z"][-1] == pytest.approx(-109092.1 / 2, rel=1e-6)


def test_klingels_kinematic_oscillation(ssp):
    """The free wheelset (no suspension) at 10 m/s through the coupled FMUs (kalker_linear): its
    wavelength within 5 % of Klingel's λ = 2π √(r0 s / tan γ_e) (Klingel 1883; Wickens 2003,
    ch. 2), with r0, s of the parameter file and tan γ_e the geometry module's equivalent conicity
    (data/wheelset/contact_data.json) at the simulated amplitude. Bounded: no extremum beyond the
    start (the kinematic mode decays slightly, docs/wheelset.md)."""
    result = ws.klingel_run(ssp)
    wavelength, amplitude, klingel = ws.klingel_measurement(result)
    assert 1e-3 < amplitude <= ws.KLINGEL_START
    assert np.max(np.abs(result[ws.DISPLACEMENT])) <= 1.001 * ws.KLINGEL_START
    assert wavelength == pytest.approx(klingel, rel=0.05)


def test_critical_speed_against_the_linear_stability_analysis(ssp):
    """The hunting_check wheelset through the coupled FMUs (kalker_linear): the growth rate of its
    oscillation at amplitudes 4–5 mm at 60, 62 and 64 m/s, interpolated to zero, within 5 % of the
    critical speed of the linear model (linear_stability.py, spin free, describing functions at
    A = 4.5 mm: 62.80 m/s). The rates must bracket zero: decaying at 60 m/s, growing at 64."""
    parameters = ls.load_parameters()
    reference = ls.critical_speed(ls.variant(parameters, "hunting_check"),
                                  ls.ContactModel(ls.load_contact_data()).linearised(4.5e-3))
    rates, speed = ws.measured_critical_speed(ssp)
    assert None not in rates.values(), rates
    assert rates[60.0] < 0 < rates[64.0]
    assert speed == pytest.approx(reference, rel=0.05)


def test_a_parameter_out_of_range_names_the_unit_the_time_and_the_variable(ssp):
    with pytest.raises(ssp_master.SystemRunError) as error:
        ws.run(ssp, parameters={"wheelset.mass": -1813.0}, stop_time=0.01)
    assert error.value.component == "wheelset" and error.value.time == 0.0
    assert "mass = -1813 is invalid" in str(error.value)
    with pytest.raises(ssp_master.SystemRunError, match=r"right_wheel at t = 0 s: .*track_gauge = -1"):
        ws.run(ssp, parameters={"right_wheel.track_gauge": -1.0}, stop_time=0.01)


def test_a_wheelset_that_climbs_the_flange_derails_with_a_message(ssp):
    """Above its critical speed the hunting_check wheelset's oscillation grows to the flange
    (contact from 6.6 mm); with kalker_linear (creep forces unbounded by friction) it climbs it.
    With the derailment bound at 7 mm the wheelset unit ends the run naming the time and
    wheelset_lateral_displacement, and the run up to it is kept."""
    hunting = {"wheelset.forward_speed": 68.0, "wheelset.initial_lateral_displacement": 4e-3}
    with pytest.raises(ssp_master.SystemRunError) as error:
        ws.run(ssp, "hunting_check", dict(hunting, **{"wheelset.derailment_displacement": 7e-3}), stop_time=1.0)
    failure = error.value
    assert failure.component == "wheelset" and 0.1 < failure.time < 1.0
    reported = re.search(r"the wheelset derails at t = ([0-9.]+) s: wheelset_lateral_displacement = 0\.007\d* m "
                         r"is beyond derailment_displacement = 0\.007 m", failure.message)
    assert reported, failure.message
    # The wheelset names the end of the step that took it beyond the bound (SSD step 0.2 ms).
    assert float(reported.group(1)) == pytest.approx(failure.time + 2e-4, abs=1e-9)
    assert failure.result["time"][-1] == pytest.approx(failure.time)
    assert np.max(np.abs(failure.result[ws.DISPLACEMENT])) > 6.6e-3


def test_a_wheel_whose_creep_forces_lift_it_ends_the_run_naming_its_inputs(ssp):
    """The same run with the default bound (10 mm): a contact unit stops it first, at the flange
    (y ≈ 7.4 mm), its vertical balance with the creep forces failing; the master adds the values
    of the unit's inputs to its message, so the wheelset's state shows."""
    with pytest.raises(ssp_master.SystemRunError) as error:
        ws.run(ssp, "hunting_check", {"wheelset.forward_speed": 68.0,
                                      "wheelset.initial_lateral_displacement": 4e-3}, stop_time=1.0)
    failure = error.value
    assert failure.component in ("left_wheel", "right_wheel") and 0.1 < failure.time < 1.0
    assert "flange climb (derailment): vertical_force = 54546.05 N is not carried" in failure.message
    assert "wheelset_lateral_displacement = 0.007" in failure.message


def test_an_unloaded_wheel_is_lift_off(ssp):
    """A contact unit given no vertical force carries none: the wheelset stops at t = 0 naming
    the wheel's track_force_z."""
    with pytest.raises(ssp_master.SystemRunError,
                       match=r"wheelset at t = 0 s: .*lifts off the rail at t = 0 s: left_track_force_z = 0 N"):
        ws.run(ssp, parameters={"left_wheel.vertical_force": 0.0}, stop_time=0.01)


def test_the_run_command_writes_the_csv_and_plots(tmp_path, monkeypatch):
    """`scripts/run-wheelset` (scripts/wheelset_system.py): a short run's CSV and figures."""
    monkeypatch.setattr(ws, "OUTPUT", tmp_path)
    assert ws.main(["--stop-time", "0.05", "--name", "short"]) == 0
    header = (tmp_path / "short.csv").read_text().splitlines()[0].split(",")
    assert header[0] == "time" and ws.DISPLACEMENT in header and "left_wheel.track_force_y" in header
    assert (tmp_path / "short.png").stat().st_size > 0 and (tmp_path / "short.svg").stat().st_size > 0
    assert ws.main(["--set", "left_wheel.vertical_force=0", "--stop-time", "0.01", "--name", "bad"]) == 1


def test_growth_rate_of_runs_without_enough_extrema_is_none():
    """A run that never turns (a drift) or turns once has no growth rate to fit: None, not an
    IndexError; with three extrema after the first the slope of ln |y| is the decay rate."""
    time = np.linspace(0.0, 1.0, 1001)
    drift = {"time": time, ws.DISPLACEMENT: 1e-3 * time}
    assert ws.growth_rate([drift]) is None
    assert ws.growth_rate([]) is None
    sigma = -0.7
    decaying = {"time": time, ws.DISPLACEMENT: 2e-3 * np.exp(sigma * time) * np.cos(2 * np.pi * 5 * time)}
    assert ws.growth_rate([decaying], window=(1e-4, 1e-2)) == pytest.approx(sigma, rel=0.02)


# Model Exchange with the connections solved inside the integrator's right-hand side
# (scripts/ssp_master.py, model_exchange): one CVODE (fmpy's) over the wheelset's five states,
# the contact units evaluated at every right-hand side, no step bound by the coupling. Measured
# 2026-11-29 with maximum step 0.1 s, rows every 10 ms: distances 2.4e-6, 4.1e-5, 8.5e-5 of y0
# from the 10 µs Co-Simulation reference at 1, 20, 80 m/s (docs/coupling-stability.md), where a
# Co-Simulation master with the forces held over a step needs 0.05 ms at 1 m/s. With polach and
# exact_table at 20 m/s: 7.2e-5 and 6.0e-5 of y0.
@pytest.mark.parametrize("speed, model", [(1.0, "kalker_linear"), (20.0, "kalker_linear"), (80.0, "kalker_linear"),
                                          (20.0, "polach"), (20.0, "exact_table")])
def test_model_exchange_with_cvode_follows_the_reference_at_any_step(ssp, speed, model):
    parameters = {"wheelset.forward_speed": speed, "left_wheel.creep_force_model": model,
                  "right_wheel.creep_force_model": model}
    reference = ws.run(ssp, parameters=parameters, stop_time=0.5, step_size=1e-5)
    result = ssp_master.simulate(ssp, parameters=parameters, stop_time=0.5, step_size=1e-2,
                                 model_exchange=ssp_master.ModelExchange(relative_tolerance=1e-6, maximum_step=0.1))
    assert len(result) == 51 and result["time"][-1] == pytest.approx(0.5)
    assert ws.distance(result, reference) < 1e-3
    spin = result["wheelset.wheel_angular_speed"] * 0.45990634083 / speed - 1.0
    assert np.max(np.abs(spin)) < 1e-3, "the wheels keep rolling"


def test_a_derailment_in_model_exchange_is_reported_with_the_unit_time_and_message(ssp):
    """Thrown at 1 m/s towards a derailment bound of 4 mm from 3 mm: the wheelset's
    fmi2CompletedIntegratorStep at the first accepted point beyond it ends the run, named."""
    with pytest.raises(ssp_master.SystemRunError) as failure:
        ssp_master.simulate(ssp, parameters={"wheelset.initial_lateral_velocity": 1.0,
                                             "wheelset.derailment_displacement": 4e-3},
                            stop_time=0.05, step_size=1e-2, model_exchange=ssp_master.ModelExchange())
    error = failure.value
    assert error.component == "wheelset" and 0 < error.time < 0.05, error
    assert "completedIntegratorStep failed" in error.message and "derails" in error.message, error
    assert error.result is not None and len(error.result) >= 1
