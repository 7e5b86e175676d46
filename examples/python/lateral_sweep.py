"""Lateral sweep of a wheel on its rail: the FMU driven from Python with fmpy.

After `cargo fmu` has built target/fmu/wheel_rail_contact.fmu, from the repository root:

    .venv/bin/python examples/python/lateral_sweep.py [--fmu FILE] [--out DIR]

The FMU takes its contact from profiles (contact_geometry = profiles): the built-in S1002 wheel on
the UIC60 1:40 rail (the Manchester benchmark's), right wheel, default wheel load (vertical_force),
model (Polach) and contact method (non_hertzian: one patch per contact region, as CONTACT finds
it), pure rolling at 20 m/s. The wheelset is moved across the track, y_ws from -8 to
+8 mm (positive to the right), one co-simulation step per position: a quasi-static sweep without yaw
or lateral velocity. It shows the contact on the tread around the centre and the right wheel running
onto its flange towards +y, where the contact angle and the rail's push on the wheel towards the
track centre (track_force_y < 0) grow, up to the flange's steepest point (beyond it, the contact
climbing towards the flange's tip, both fall a little). It writes lateral_sweep.csv (the FMU's variable names, SI
units) and lateral_sweep.png to --out and prints every 10th point. An FMI call that does not
return fmi2OK stops it with exit code 1.
"""

import argparse
import csv
import pathlib
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402

Y_WS = "wheelset_lateral_displacement"
OUTPUTS = ["track_force_x", "track_force_y", "track_force_z", "contact_patch_count",
           "patch1_contact_angle", "patch1_rail_lateral_position"]
ROLLING_SPEED = 20.0  # m/s
STEP = 1e-3  # s, one co-simulation step per position
failed_calls = []


class FmiCallFailed(Exception):
    pass


def require_ok(call):
    """fmpy's hook after every FMI call ("fmi2DoStep(...) -> OK"). fmpy raises on fmi2Error and
    fmi2Fatal only; stop on a warning or discard too, and on fmi2Instantiate's NULL."""
    if call.rpartition(" -> ")[2] in ("WARNING", "DISCARD", "ERROR", "FATAL", "PENDING", "0x0"):
        failed_calls.append(call)
        raise FmiCallFailed(call)


def sweep(fmu_path, positions, unzip_directory):
    """Rows [y_ws, *OUTPUTS] for each lateral displacement y_ws [m] in positions."""
    description = read_model_description(fmu_path)
    variable = {v.name: v for v in description.modelVariables}
    vr = {name: v.valueReference for name, v in variable.items()}
    # An Enumeration is set by its item's value, declared in modelDescription.xml.
    profiles = next(int(item.value) for item in variable["contact_geometry"].declaredType.items
                    if item.name == "profiles")
    nominal_radius = float(variable["wheel_nominal_radius"].start)  # r0 [m]
    fmu = FMU2Slave(guid=description.guid, unzipDirectory=extract(fmu_path, unzipdir=unzip_directory),
                    modelIdentifier=description.coSimulation.modelIdentifier,
                    instanceName="lateral_sweep", fmiCallLogger=require_ok)
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.setInteger([vr["contact_geometry"]], [profiles])
        fmu.setString([vr["wheel_profile"], vr["rail_profile"]], ["MBench_S1002", "MBench_UIC60"])
        fmu.enterInitializationMode()
        # Pure rolling, omega = V / r0 (the start values roll purely at V = 20 m/s on r0 = 0.46 m;
        # a rolling speed of one's own needs its angular speed with it).
        fmu.setReal([vr["rolling_speed"], vr["wheel_angular_speed"], vr[Y_WS]],
                    [ROLLING_SPEED, ROLLING_SPEED / nominal_radius, positions[0]])
        fmu.exitInitializationMode()
        rows = []
        for k, y_ws in enumerate(positions):
            fmu.setReal([vr[Y_WS]], [y_ws])
            fmu.doStep(currentCommunicationPoint=k * STEP, communicationStepSize=STEP)
            rows.append([y_ws, *fmu.getReal([vr[name] for name in OUTPUTS])])
        return rows
    finally:
        if not failed_calls:  # after a failed call fmi2Terminate may be illegal: only free
            fmu.terminate()
        fmu.freeInstance()


def plot(rows, path):
    columns = np.array(rows).T  # y_ws, then OUTPUTS
    y_mm, fy, fz, angle = columns[0] * 1e3, columns[2], columns[3], columns[5]
    figure, (forces, angles) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    forces.plot(y_mm, fy, label="lateral, track_force_y")
    forces.plot(y_mm, fz, label="vertical, track_force_z (z down)")
    forces.set(ylabel="force on the wheel [N]", title="S1002 on UIC60 1:40, right wheel, pure rolling")
    forces.legend()
    angles.plot(y_mm, angle, color="C2")
    angles.set(ylabel="patch 1 contact angle [rad]", xlabel="wheelset lateral displacement y_ws [mm]")
    forces.grid(True)
    angles.grid(True)
    figure.tight_layout()
    figure.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fmu", type=pathlib.Path, default=pathlib.Path("target/fmu/wheel_rail_contact.fmu"))
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("target/fmu"))
    args = parser.parse_args()
    if not args.fmu.is_file():
        sys.exit(f"error: {args.fmu} not found: build it with `cargo fmu`, or pass --fmu FILE")
    try:
        with tempfile.TemporaryDirectory() as unzip_directory:
            rows = sweep(str(args.fmu), np.linspace(-8e-3, 8e-3, 81), unzip_directory)
    except FmiCallFailed:
        sys.exit(f"error: an FMI call did not return fmi2OK: {failed_calls[0]}")

    args.out.mkdir(parents=True, exist_ok=True)
    csv_path, png_path = args.out / "lateral_sweep.csv", args.out / "lateral_sweep.png"
    with open(csv_path, "w", newline="") as file:
        csv.writer(file).writerows([[Y_WS, *OUTPUTS], *rows])
    plot(rows, png_path)
    print(f"{'y_ws [mm]':>9} {'Fx [N]':>9} {'Fy [N]':>9} {'Fz [N]':>9} patches {'angle [rad]':>11} {'y_rail [mm]':>11}")
    for y_ws, fx, fy, fz, count, angle, y_rail in rows[::10]:
        print(f"{y_ws * 1e3:9.1f} {fx:9.1f} {fy:9.1f} {fz:9.1f} {count:7.0f} {angle:11.4f} {y_rail * 1e3:11.2f}")
    print(f"wrote {csv_path} and {png_path}")


if __name__ == "__main__":
    main()
