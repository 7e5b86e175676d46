"""The Python example (examples/python/lateral_sweep.py), run as a user runs it, on the suite's FMU:
it exits 0 and writes a CSV and a PNG whose values are those of a wheel on its rail. The expected
facts come from the model description, the README's conventions, statics and CONTACT's published
Manchester A-2.2 solution, never from the example's own numbers."""

import csv
import math
import pathlib
import subprocess
import sys

import pytest

from conftest import ROOT

EXAMPLE = ROOT / "examples" / "python" / "lateral_sweep.py"
DATA = ROOT / "core" / "tests" / "data"
POINTS, HALF_RANGE = 81, 8e-3  # the sweep the example documents: y_ws from -8 to +8 mm
TREAD_ANGLE = 0.05  # rad: a tread contact's angle is the few hundredths of the tread's and rail's slopes
FLANGE_ANGLE = 0.3  # rad: well past any tread slope, on the flange root or face


@pytest.fixture(scope="module")
def run(fmu_path, tmp_path_factory):
    """The example's process (its result) and output folder, run once for this module."""
    out = tmp_path_factory.mktemp("lateral_sweep")
    result = subprocess.run([sys.executable, str(EXAMPLE), "--fmu", fmu_path, "--out", str(out)],
                            cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, (result.stdout, result.stderr)
    return result, out


@pytest.fixture(scope="module")
def rows(run):
    with open(run[1] / "lateral_sweep.csv", newline="") as file:
        return [{name: float(value) for name, value in row.items()} for row in csv.DictReader(file)]


def item_name(variable):
    """The name of an Enumeration variable's start item."""
    return next(item.name for item in variable.declaredType.items if int(item.value) == int(variable.start))


@pytest.fixture(scope="module")
def variables(model_description):
    return {v.name: v for v in model_description.modelVariables}


@pytest.fixture(scope="module")
def wheel_load(variables):
    """The vertical load the FMU carries by default: vertical_force, with vertical_contact's default."""
    assert item_name(variables["vertical_contact"]) == "prescribed_force"
    return float(variables["vertical_force"].start)


@pytest.fixture(scope="module")
def flange_side(variables):
    """+1 if the wheel's flange meets its rail as the wheelset moves to +y, -1 otherwise. y points to
    the right (README); a wheel's flange is on the track's inside, so moving the wheelset towards a
    wheel's side brings that wheel's flange to its rail's gauge face."""
    return {"right": 1, "left": -1}[item_name(variables["wheel_side"])]


def centred(rows):
    return min(rows, key=lambda row: abs(row["wheelset_lateral_displacement"]))


def test_the_example_writes_the_sweep_prints_its_table_and_plots_it(run, rows):
    result, out = run
    positions = [row["wheelset_lateral_displacement"] for row in rows]
    assert len(rows) == POINTS
    assert positions[0] == pytest.approx(-HALF_RANGE) and positions[-1] == pytest.approx(HALF_RANGE)
    assert all(b > a for a, b in zip(positions, positions[1:]))
    assert centred(rows)["wheelset_lateral_displacement"] == pytest.approx(0.0, abs=1e-12)
    # The printed table: every 10th point, y_ws in mm first.
    table = [line.split() for line in result.stdout.splitlines() if line.split() and line.split()[0][-1].isdigit()]
    assert [float(line[0]) for line in table] == pytest.approx([y * 1e3 for y in positions[::10]], abs=0.05)
    png = out / "lateral_sweep.png"
    assert str(png) in result.stdout and str(out / "lateral_sweep.csv") in result.stdout
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


def test_every_position_carries_the_wheel_load(rows, wheel_load):
    # z points down and the force acts on the wheel: track_force_z = -vertical_force (README).
    for row in rows:
        assert row["track_force_z"] == pytest.approx(-wheel_load, rel=1e-6), row
        assert row["contact_patch_count"] >= 1, row


def test_the_centred_wheelset_runs_on_the_tread_where_contact_puts_it(rows, wheel_load, variables):
    row = centred(rows)
    assert row["contact_patch_count"] == 1, row
    assert abs(row["patch1_contact_angle"]) < TREAD_ANGLE, row
    # On the rail head's crown, far from the gauge corner (the flange's contact, ~40 mm out).
    assert abs(row["patch1_rail_lateral_position"]) < 10e-3, row
    # The tread's small slope tilts the normal force by a few percent at most, and without yaw or
    # lateral velocity only the small spin creepage adds a lateral creep force.
    assert abs(row["track_force_y"]) < 0.05 * wheel_load, row
    # CONTACT's case no. 1 is the same geometry (y_ws = 0, no yaw or roll; its speed does not
    # move the contact): the README's tolerances, 0.01 rad, and the flat gap's 1.4 mm (within 2 mm).
    assert item_name(variables["wheel_side"]) == "right"
    with open(DATA / "manchester_a22_inputs.csv") as file:
        inputs = next(r for r in csv.DictReader(line for line in file if not line.startswith("#"))
                      if (r["wheel"], r["case"]) == ("right", "1"))
    assert float(inputs["y_ws_mm"]) == float(inputs["yaw_ws_rad"]) == float(inputs["roll_ws_rad"]) == 0.0
    with open(DATA / "mbench_a22_contact_ref_out.csv") as file:
        contact = next(r for r in csv.DictReader(line for line in file if not line.startswith("#"))
                       if (r["wheel"], r["case"]) == ("right", "1"))
    assert row["patch1_contact_angle"] == pytest.approx(float(contact["deltcp_tr"]), abs=0.01)
    assert row["patch1_rail_lateral_position"] == pytest.approx(float(contact["ycp_r"]) * 1e-3, abs=2e-3)


def test_away_from_the_flange_the_wheel_stays_on_its_tread(rows, flange_side):
    for row in rows:
        if row["wheelset_lateral_displacement"] * flange_side < 0:
            assert row["contact_patch_count"] == 1, row
            assert abs(row["patch1_contact_angle"]) < TREAD_ANGLE, row


def test_towards_the_flange_the_contact_angle_and_the_lateral_force_grow(rows, wheel_load, flange_side):
    towards = sorted((row for row in rows if row["wheelset_lateral_displacement"] * flange_side >= 0),
                     key=lambda row: abs(row["wheelset_lateral_displacement"]))
    angles = [abs(row["patch1_contact_angle"]) for row in towards]
    lateral = [abs(row["track_force_y"]) for row in towards]
    # Rising, allowing small wobbles (a tread patch ordered first while the flange also touches),
    # up to the flange's steepest contact: beyond it the contact climbs towards the flange's tip,
    # where the flank flattens, and angle and lateral force fall again (CONTACT's solution
    # on the right wheel: the angle from 1.16 rad at y_ws = 6.5 mm to 0.95 at 8 mm, F_y from 12.5
    # to 8.5 kN), so there only the angle is checked to stay on the flange.
    steepest = max(range(len(towards)), key=lambda k: angles[k])
    for k in range(1, steepest + 1):
        assert angles[k] > max(angles[:k]) - 0.02, (towards[k], max(angles[:k]))
        assert lateral[k] > max(lateral[:k]) - 0.05 * wheel_load, (towards[k], max(lateral[:k]))
    for k in range(steepest + 1, len(towards)):
        assert angles[k] > FLANGE_ANGLE, towards[k]
    end = towards[-1]
    assert angles[-1] > FLANGE_ANGLE, end
    # The rail pushes the wheel back towards the track centre... but within a few tenths of a
    # millimetre of it, where the lateral force is the small difference between the normal force's
    # tilt and the spin's creep force (some 300 N each; CONTACT's case 1 at y_ws = 0: 36 N
    # of 10 kN), and its sign lies within the contact methods' accuracy (the non-Hertzian patch:
    # up to 29 N outward at y_ws = 0.1-0.24 mm, where it slides 3 mm across the flat gap).
    for row in towards[1:]:
        assert row["track_force_y"] * flange_side < 0 or abs(row["track_force_y"]) < 0.005 * wheel_load, row
    # ...and on the flange's slope the normal force alone must hold the wheel load, so its lateral
    # part, Q tan(delta), far exceeds the centred wheelset's lateral force.
    assert lateral[-1] > 0.5 * wheel_load * math.tan(angles[-1]), end
    assert lateral[-1] > 10 * lateral[0], (end, towards[0])
