"""The wheelset running on track as an SSP (systems/wheelset_on_track/: the wheelset FMU and a left
and a right contact unit), run by the fixed-step master scripts/ssp_master.py: assembling the
SSP with the packaged FMUs, the runs of the physics checks (wheelset/tests/system/test_system.py),
the measurements on them, and the command `scripts/run-wheelset` (CSV and plots under
target/wheelset/; `--measure` prints the Klingel and critical-speed figures of docs/wheelset.md).

Units SI throughout; y the wheelset's lateral displacement [m], ψ its yaw [rad] (track axes x
forward, y right, z down, as the contact unit's)."""

import argparse
import csv
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
import tomllib

import numpy as np
from lxml import etree

import ssp_master

ROOT = pathlib.Path(__file__).resolve().parents[1]
SYSTEM_SOURCE = ROOT / "systems" / "wheelset_on_track"
FMUS = {name: ROOT / "target" / "fmu" / name for name in ("wheelset.fmu", "wheel_rail_contact.fmu")}
OUTPUT = ROOT / "target" / "wheelset"
PARAMETERS = ROOT / "data" / "wheelset" / "passenger_coach.toml"
CONTACT_DATA = ROOT / "data" / "wheelset" / "contact_data.json"
DISPLACEMENT = "wheelset.wheelset_lateral_displacement"
YAW = "wheelset.wheelset_yaw_angle"

# The checks' runs (docs/wheelset.md, "The coupled system"). The communication steps are below the
# shortest time constant in the loop, the wheel spin's I_s V/(Σ f11 r²) ≈ 27 µs × V/(m/s): 0.27 ms
# at 10 m/s, 1.7 ms at 62 m/s. Halving them moves the Klingel wavelength by 0.3 mm (8.6790 m at
# 0.2 ms, 8.6793 at 0.1 ms) and the critical speed by 0.05 m/s (61.74 m/s at 0.25 ms, 61.79 at
# 0.125 ms).
KLINGEL_SPEED, KLINGEL_STEP, KLINGEL_START, KLINGEL_DURATION = 10.0, 2e-4, 3e-3, 2.0
HUNTING_STEP, HUNTING_DURATION = 2.5e-4, 1.0
# The describing function's amplitude of the reference critical speed (4.5 mm, where V_c(A) is
# stationary) and the window of peaks around it whose growth rate is measured: V_c(A) of the
# linear reference is 61.95 m/s at 4.0 mm and 62.78 at 5.0 mm (docs/wheelset.md, "Results").
# The runs start at the window's ends, so that a growing and a decaying oscillation cross it
# (starting higher, the wheelset with kalker_linear, unsaturated, climbs the flange at once).
HUNTING_WINDOW = (4.0e-3, 5.0e-3)
HUNTING_SPEEDS = (60.0, 62.0, 64.0)
# The finer set of `--measure` (docs/wheelset.md), for every creep force model.
MEASURE_SPEEDS = (60.0, 61.0, 62.0, 63.0, 64.0)


def build_fmus_if_missing():
    """The packaged FMUs (`cargo fmu package`, which scripts/test-all runs first)."""
    if not all(path.exists() for path in FMUS.values()):
        subprocess.run(["cargo", "fmu", "package"], cwd=ROOT, check=True)


def system_ssp(path=None):
    """The SSP assembled from systems/wheelset_on_track/ and the packaged FMUs (default
    target/wheelset/wheelset_on_track.ssp)."""
    build_fmus_if_missing()
    return ssp_master.assemble(SYSTEM_SOURCE, FMUS, path or OUTPUT / "wheelset_on_track.ssp")


# Model Exchange (docs/coupling-stability.md, "Model Exchange in OMSimulator"): the same system with
# OMSimulator's variable-step annotation (oms:VariableStepSolver, CVODE) in place of its fixed-step
# master, which makes OMSimulator instantiate both FMUs as Model Exchange in one strongly coupled
# system. OMSimulator passes the connections between the FMUs at the end of each CVODE call of at
# most maximumStepSize, not within its right-hand side (SystemSC.cpp, cvode_rhs and doStepCVODE),
# so the coupling's stability bounds maximumStepSize as it bounds a Co-Simulation step: 0.2 ms
# (the Co-Simulation SSP's step) stays within 0.5 % of the 10 µs reference at 20 and 80 m/s, 1 m/s
# needs 0.05 ms. The relative tolerance: CVODE's absolute one is it times each state's nominal.
MODEL_EXCHANGE_MAXIMUM_STEP = 2e-4
MODEL_EXCHANGE_RELATIVE_TOLERANCE = 1e-6


def model_exchange_ssp(path=None, maximum_step=MODEL_EXCHANGE_MAXIMUM_STEP, forward_speed=None):
    """The system as `system_ssp` assembles it, for Model Exchange in OMSimulator (default
    target/wheelset/wheelset_on_track_me.ssp): the fixed-step master's annotation replaced by
    CVODE's with `maximum_step` [s]; `forward_speed` [m/s], if given, replaces the wheelset's."""
    build_fmus_if_missing()
    oms = ssp_master.STEP_NAMESPACE
    with tempfile.TemporaryDirectory() as scratch:
        source = pathlib.Path(scratch) / "wheelset_on_track"
        shutil.copytree(SYSTEM_SOURCE, source)
        ssd = etree.parse(str(source / "SystemStructure.ssd"))
        (master,) = ssd.getroot().iter(f"{{{oms}}}FixedStepMaster")
        solver = etree.Element(f"{{{oms}}}VariableStepSolver", description="cvode",
                               relativeTolerance=repr(MODEL_EXCHANGE_RELATIVE_TOLERANCE), minimumStepSize="1e-12",
                               maximumStepSize=repr(maximum_step), initialStepSize="1e-07")
        master.getparent().replace(master, solver)
        ssd.write(str(source / "SystemStructure.ssd"), xml_declaration=True, encoding="UTF-8")
        if forward_speed is not None:
            coach = etree.parse(str(source / "resources" / "passenger_coach.ssv"))
            (value,) = coach.xpath("//ssv:Parameter[@name='forward_speed']/ssv:Real",
                                   namespaces={"ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues"})
            value.set("value", repr(float(forward_speed)))
            coach.write(str(source / "resources" / "passenger_coach.ssv"), xml_declaration=True, encoding="UTF-8")
        return ssp_master.assemble(source, FMUS, path or OUTPUT / "wheelset_on_track_me.ssp")


def run(ssp, variant=None, parameters=None, stop_time=None, step_size=None):
    """The system run by the master; `variant`: None, "hunting_check" or "klingel_check" (the
    parameter sets resources/<variant>.ssv of the SSP); `parameters`: {"component.variable": value}."""
    sets = [f"resources/{variant}.ssv"] if variant else []
    return ssp_master.simulate(ssp, parameter_sets=sets, parameters=parameters, stop_time=stop_time,
                               step_size=step_size)


def downward_zero_crossings(time, signal):
    """The times [s] where the signal crosses zero from above, linearly interpolated."""
    above = signal[:-1] > 0
    index = np.nonzero(above & (signal[1:] <= 0))[0]
    return time[index] + (time[index + 1] - time[index]) * signal[index] / (signal[index] - signal[index + 1])


def extrema(time, signal):
    """The local extrema (t, |value|) of a sampled signal, each refined by the parabola through
    it and its two neighbours."""
    middle = signal[1:-1]
    index = 1 + np.nonzero(((middle > signal[:-2]) & (middle >= signal[2:]))
                           | ((middle < signal[:-2]) & (middle <= signal[2:])))[0]
    before, at, after = signal[index - 1], signal[index], signal[index + 1]
    curvature = before - 2 * at + after
    shift = 0.5 * (before - after) / curvature
    step = time[1] - time[0]
    return time[index] + shift * step, np.abs(at - 0.25 * (before - after) * shift)


def equivalent_conicity(amplitude):
    """tan γ_e(A) of the library's geometry (data/wheelset/contact_data.json, every 0.25 mm),
    linearly interpolated."""
    with open(CONTACT_DATA) as file:
        table = np.array(json.load(file)["conicity"])
    return float(np.interp(amplitude, table[:, 0], table[:, 1]))


def parameters_file():
    """data/wheelset/passenger_coach.toml as {table: {name: value}} (SI units)."""
    with open(PARAMETERS, "rb") as file:
        return {table: {name: entry["value"] for name, entry in entries.items()}
                for table, entries in tomllib.load(file).items()}


def klingel_run(ssp):
    """The free wheelset at KLINGEL_SPEED, started KLINGEL_START off centre (the SSD's
    kalker_linear)."""
    return run(ssp, "klingel_check", {
        "wheelset.forward_speed": KLINGEL_SPEED, "wheelset.initial_lateral_displacement": KLINGEL_START},
        stop_time=KLINGEL_DURATION, step_size=KLINGEL_STEP)


def klingel_measurement(result, speed=KLINGEL_SPEED):
    """The simulated kinematic oscillation's wavelength [m] (speed × the mean period between the
    first and the last downward zero crossing of y) and amplitude [m] (mean |y| of the extrema
    between them), and Klingel's wavelength λ = 2π √(r0 s / tan γ_e) (Klingel 1883; Wickens 2003,
    ch. 2) with r0 and s of data/wheelset/passenger_coach.toml and tan γ_e at that amplitude."""
    time, y = result["time"], result[DISPLACEMENT]
    crossings = downward_zero_crossings(time, y)
    if len(crossings) < 2:
        raise ValueError(f"fewer than two downward zero crossings of y in {time[-1]} s")
    wavelength = speed * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    peak_times, peaks = extrema(time, y)
    amplitude = float(np.mean(peaks[(peak_times > crossings[0]) & (peak_times < crossings[-1])]))
    wheelset = parameters_file()["wheelset"]
    klingel = 2 * math.pi * math.sqrt(wheelset["nominal_rolling_radius"] * wheelset["half_contact_distance"]
                                      / equivalent_conicity(amplitude))
    return wavelength, amplitude, klingel


def hunting_runs(ssp, speed, creep_force_model="kalker_linear", step_size=HUNTING_STEP):
    """The hunting_check wheelset at `speed`, started at each end of HUNTING_WINDOW; a run that
    grows to the flange and derails counts up to its last communication point."""
    runs = []
    for start in HUNTING_WINDOW:
        try:
            runs.append(run(ssp, "hunting_check", {
                "wheelset.forward_speed": speed, "wheelset.initial_lateral_displacement": start,
                "left_wheel.creep_force_model": creep_force_model,
                "right_wheel.creep_force_model": creep_force_model},
                stop_time=HUNTING_DURATION, step_size=step_size))
        except ssp_master.SystemRunError as error:
            runs.append(error.result)
    return runs


def growth_rate(results, window=HUNTING_WINDOW):
    """The oscillation's growth rate σ [1/s] at amplitudes within `window` [m]: the least-squares
    slope of ln |y| over the extrema of y within it (after the first one: the start's transient),
    averaged over the runs that have at least three; None if none has."""
    slopes = []
    for result in results:
        times, peaks = extrema(result["time"], result[DISPLACEMENT])
        inside = (peaks >= window[0]) & (peaks <= window[1])
        inside[:1] = False  # a run without extrema has none to skip
        if np.count_nonzero(inside) >= 3:
            slopes.append(np.polyfit(times[inside], np.log(peaks[inside]), 1)[0])
    return float(np.mean(slopes)) if slopes else None


def critical_speed(rates):
    """The speed where the growth rate crosses zero [m/s], linearly interpolated between the two
    measured speeds that bracket it ({speed: σ}); None if none do."""
    speeds = sorted(v for v, rate in rates.items() if rate is not None)
    for low, high in zip(speeds, speeds[1:]):
        if rates[low] < 0 <= rates[high]:
            return low + (high - low) * (-rates[low]) / (rates[high] - rates[low])
    return None


def measured_critical_speed(ssp, creep_force_model="kalker_linear", speeds=HUNTING_SPEEDS):
    """({speed: σ}, the critical speed) of the coupled runs."""
    rates = {speed: growth_rate(hunting_runs(ssp, speed, creep_force_model)) for speed in speeds}
    return rates, critical_speed(rates)


def write_csv(result, path):
    names = result.dtype.names
    np.savetxt(path, np.column_stack([result[n] for n in names]), delimiter=",", header=",".join(names),
               comments="", fmt="%.9g")


def plot(result, path_stem, title):
    """y(t), ψ(t) and both wheels' lateral forces and yaw moments (track axes), as PNG and SVG."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    time = result["time"]
    figure, axes = plt.subplots(4, 1, sharex=True, figsize=(7.5, 8.5))
    axes[0].plot(time, result[DISPLACEMENT] * 1e3, color="black")
    axes[0].set_ylabel("y [mm]")
    axes[1].plot(time, result[YAW] * 1e3, color="black")
    axes[1].set_ylabel("ψ [mrad]")
    for side, color in (("left", "tab:blue"), ("right", "tab:red")):
        axes[2].plot(time, result[f"{side}_wheel.track_force_y"] / 1e3, color=color, label=f"{side} wheel")
        axes[3].plot(time, result[f"{side}_wheel.track_moment_z"] / 1e3, color=color, label=f"{side} wheel")
    axes[2].set_ylabel("lateral force\ntrack_force_y [kN]")
    axes[3].set_ylabel("yaw moment\ntrack_moment_z [kN m]")
    axes[3].set_xlabel("t [s]")
    axes[2].legend(loc="upper right", fontsize="small")
    for axis in axes:
        axis.grid(True, linewidth=0.3)
    axes[0].set_title("\n".join(textwrap.fill(line, 90) for line in title.split("\n")), fontsize="small")
    figure.tight_layout()
    for suffix in (".png", ".svg"):
        figure.savefig(path_stem.with_suffix(suffix), dpi=72)
    plt.close(figure)


def measure():
    """The Klingel and critical-speed figures of docs/wheelset.md, for each creep force model."""
    ssp = system_ssp()
    wavelength, amplitude, klingel = klingel_measurement(klingel_run(ssp))
    print(f"Klingel ({KLINGEL_SPEED} m/s, kalker_linear, step {KLINGEL_STEP * 1e3} ms): wavelength "
          f"{wavelength:.4f} m at amplitude {amplitude * 1e3:.3f} mm (tan γ_e {equivalent_conicity(amplitude):.4f}); "
          f"Klingel's {klingel:.4f} m; {100 * (wavelength / klingel - 1):+.2f} %")
    for model in ("kalker_linear", "polach", "exact_table"):
        rates, speed = measured_critical_speed(ssp, model, MEASURE_SPEEDS)
        print(f"critical speed, {model}: " + ", ".join(
            f"σ({v:g} m/s) = {'-' if r is None else f'{r:+.3f}'} 1/s" for v, r in rates.items())
              + f" -> {'not bracketed' if speed is None else f'{speed:.2f} m/s'}")


# Where ../shared/tools/omsimulator builds OMSimulator's CLI.
OMSIMULATOR_BUILT_HERE = pathlib.Path("/work/oms/OMSimulator/install/bin/OMSimulator")
# OMSimulator names a result column model.system.component.variable; both are the SSD's name.
OMSIMULATOR_PREFIX = "wheelset_on_track.wheelset_on_track."


def omsimulator():
    """The OMSimulator CLI: $OMSIMULATOR, `OMSimulator` on PATH or OMSIMULATOR_BUILT_HERE; None
    without one."""
    return (os.environ.get("OMSIMULATOR") or shutil.which("OMSimulator")
            or (str(OMSIMULATOR_BUILT_HERE) if OMSIMULATOR_BUILT_HERE.exists() else None))


def omsimulator_problems(output):
    """The lines of OMSimulator's output that are warnings or errors."""
    return [line for line in output.splitlines() if re.match(r"\s*(warning|error)\b", line, re.IGNORECASE)]


def read_omsimulator_result(path):
    """OMSimulator's CSV result at `path` as {component.variable (and time): array}, None if absent."""
    path = pathlib.Path(path)
    if not path.exists():
        return None
    with open(path) as file:
        header = [name.strip() for name in next(csv.reader(file))]
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name.removeprefix(OMSIMULATOR_PREFIX): data[:, i] for i, name in enumerate(header)}


def run_model_exchange(executable, speed, maximum_step, directory, stop_time=0.5):
    """OMSimulator's run of `model_exchange_ssp` at `speed` [m/s] and `maximum_step` [s] in
    `directory`: (its warnings and errors, with a nonzero exit status among them; the result as
    `read_omsimulator_result` gives it; the wall time [s]; its whole output)."""
    directory = pathlib.Path(directory)
    ssp = model_exchange_ssp(directory / "me.ssp", maximum_step, forward_speed=speed)
    started = time.perf_counter()
    completed = subprocess.run([executable, "--resultFile=result.csv", f"--stopTime={stop_time}", str(ssp)],
                               cwd=directory, capture_output=True, text=True, timeout=3600)
    wall = time.perf_counter() - started
    output = completed.stdout + completed.stderr
    problems = omsimulator_problems(output)
    if completed.returncode != 0:
        problems.append(f"exit status {completed.returncode}")
    return problems, read_omsimulator_result(directory / "result.csv"), wall, output


def distance(result, reference, start=3e-3, stop_time=0.5):
    """docs/coupling-stability.md's distance: max over t = 10, 20, …, 500 ms of |y − y_ref| / y0."""
    times = np.arange(1, round(stop_time / 0.01) + 1) * 0.01
    y = np.interp(times, result["time"], result[DISPLACEMENT])
    return float(np.max(np.abs(y - np.interp(times, reference["time"], reference[DISPLACEMENT]))) / start)


def measure_model_exchange(speeds=(1.0, 20.0, 80.0), steps=(5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3)):
    """The table of docs/coupling-stability.md, "Model Exchange in OMSimulator": per speed and
    maximumStepSize, the distance from the 10 µs reference (the project's master, Co-Simulation)
    and OMSimulator's wall time per simulated second: of the 0.5 s run less a run of 0.1 ms (the
    start, reading the SSP and instantiating, ≈ 0.7 s, which is printed)."""
    executable = omsimulator()
    if executable is None:
        raise SystemExit("OMSimulator not found: set OMSIMULATOR or put OMSimulator on PATH")
    ssp = system_ssp()
    with tempfile.TemporaryDirectory() as directory:
        overhead = min(run_model_exchange(executable, 20.0, 1e-4, directory, stop_time=1e-4)[2] for _ in range(3))
    print(f"OMSimulator's start, SSP and instantiation (a run of 0.1 ms): {overhead:.2f} s")
    print("| speed [m/s] | maximumStepSize [ms] | distance | wall time per simulated second [s] | OMSimulator |")
    print("|---|---|---|---|---|")
    for speed in speeds:
        reference = run(ssp, parameters={"wheelset.forward_speed": speed}, stop_time=0.5, step_size=1e-5)
        for step in steps:
            with tempfile.TemporaryDirectory() as directory:
                problems, result, wall, _ = run_model_exchange(executable, speed, step, directory)
            complete = result is not None and result["time"][-1] >= 0.5 - 1e-9
            gap = f"{distance(result, reference):.2e}" if complete else "–"
            verdict = "clean" if not problems else f"{len(problems)} errors/warnings"
            per_second = f"{max(wall - overhead, 0.0) / 0.5:.2f}" if complete else "–"
            print(f"| {speed:g} | {step * 1e3:g} | {gap} | {per_second} | {verdict} |", flush=True)
    measure_model_exchange_in_the_right_hand_side(speeds)


def measure_model_exchange_in_the_right_hand_side(speeds, maximum_step=0.1):
    """The second table of docs/coupling-stability.md, "Model Exchange in OMSimulator": the
    project's master (scripts/ssp_master.py) with the FMUs as Model Exchange, the connections
    solved inside fmpy's CVODE's right-hand side, rows every 10 ms: distance from the 10 µs
    reference and wall time per simulated second (the 0.5 s run less a 10 ms run)."""
    ssp = system_ssp()
    settings = ssp_master.ModelExchange(MODEL_EXCHANGE_RELATIVE_TOLERANCE, maximum_step)
    print("\n| speed [m/s] | maximum step [ms] | distance | wall time per simulated second [s] |")
    print("|---|---|---|---|")
    for speed in speeds:
        reference = run(ssp, parameters={"wheelset.forward_speed": speed}, stop_time=0.5, step_size=1e-5)
        walls = []
        for stop in (0.01, 0.5):
            started = time.perf_counter()
            result = ssp_master.simulate(ssp, parameters={"wheelset.forward_speed": speed}, stop_time=stop,
                                         step_size=1e-2, model_exchange=settings)
            walls.append(time.perf_counter() - started)
        per_second = max(walls[1] - walls[0], 0.0) / 0.49
        print(f"| {speed:g} | {maximum_step * 1e3:g} | {distance(result, reference):.2e} | {per_second:.2f} |", flush=True)


def main(arguments=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--variant", choices=["hunting_check", "klingel_check"],
                        help="a parameter set of data/wheelset/passenger_coach.toml applied over the SSD's")
    parser.add_argument("--set", action="append", default=[], metavar="COMPONENT.VARIABLE=VALUE",
                        help="a parameter value, e.g. wheelset.forward_speed=70 or left_wheel.creep_force_model=polach")
    parser.add_argument("--creep-force-model", choices=["kalker_linear", "polach", "exact_table"],
                        help="both contact units' creep_force_model (the SSD's: kalker_linear)")
    parser.add_argument("--stop-time", type=float, help="[s], default the SSD's")
    parser.add_argument("--step", type=float, help="communication step [s], default the SSD's")
    parser.add_argument("--name", default="wheelset_on_track", help="stem of the CSV and plot files")
    parser.add_argument("--measure", action="store_true",
                        help="print the Klingel and critical-speed figures of docs/wheelset.md instead")
    parser.add_argument("--measure-model-exchange", action="store_true",
                        help="print the Model Exchange table of docs/coupling-stability.md (needs OMSimulator)")
    parser.add_argument("--model-exchange-ssp", action="store_true",
                        help="write target/wheelset/wheelset_on_track_me.ssp, the system for Model Exchange with "
                             "CVODE in OMSimulator, and print how to run it")
    options = parser.parse_args(arguments)
    if options.measure:
        measure()
        return 0
    if options.model_exchange_ssp:
        ssp = model_exchange_ssp()
        print(f"wrote {ssp}: run it with OMSimulator --resultFile=result.csv {ssp}")
        return 0
    if options.measure_model_exchange:
        measure_model_exchange()
        return 0
    values = {}
    if options.creep_force_model:
        values = {f"{side}_wheel.creep_force_model": options.creep_force_model for side in ("left", "right")}
    for assignment in options.set:
        name, _, value = assignment.partition("=")
        values[name] = value
    ssp = system_ssp()
    failure = None
    try:
        result = run(ssp, options.variant, values, options.stop_time, options.step)
    except ssp_master.SystemRunError as error:
        failure, result = error, error.result
        print(f"run-wheelset: the run ended: {error}", file=sys.stderr)
        if result is None or len(result) == 0:
            return 1
    csv, stem = OUTPUT / f"{options.name}.csv", OUTPUT / options.name
    write_csv(result, csv)
    settings = ", ".join([options.variant or "passenger coach"] + [f"{n}={v}" for n, v in values.items()])
    ended = f"\nended by {failure}".split(" (its inputs")[0] if failure else ""
    plot(result, stem, f"wheelset on track ({settings}){ended}")
    print(f"{ssp}: {len(result)} communication points; wrote {csv}, {stem}.png, {stem}.svg")
    return 1 if failure else 0


if __name__ == "__main__":
    sys.exit(main())
