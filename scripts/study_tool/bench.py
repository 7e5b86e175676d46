"""`scripts/study bench`: scenes per second of a default grid per model, in-process and on
LocalClusters of 1 and N workers (default 2), N workers' speed-up over 1, and its efficiency: that
speed-up divided by what N processes gain over 1 on this machine in the same run. Not a test:
figures for the notes. The time of a study run goes from the first chunk submitted (cluster up,
FMU on the workers) to the last part written, so it includes Dask's scheduling and the Parquet
writes.

Why the efficiency: the machine may be shared (other builds, other studies), and what N processes
gain on it changes from minute to minute; a speed-up alone mixes Dask's losses with that load. The
control runs pure-Python CPU work (no I/O, no allocation; it fits in each core's cache) in a pool of
N processes: one of them alone, then all N at once, right before and right after the 1- and
N-worker runs; the machine's gain is N × (time alone) ÷ (time of N at once), the mean of the two
measurements, which are both printed so that a load change during the pair shows. With --repeat K
the pair and its controls run K times (the load comes in bursts) and the median efficiency is
printed too."""

import multiprocessing
import os
import pathlib
import shutil
import statistics
import tempfile
import time

from . import execute, spec

# The default grid: a/b from 0.5 to 2, ξ over the whole creep curve, with and without η and φ.
GRID = """
[grid]
semi_axis_a = [0.0027, 0.0041, 0.0054, 0.0081, 0.0108]
friction_coefficient = [0.2, 0.4]
creepage_lateral = [0.0, 0.001]
spin_creepage = [0.0, 0.5]
creepage_longitudinal = {{ geomspace = [1e-5, 0.1, {points}] }}
[fixed]
semi_axis_b = 0.0054
"""
# Creepage points and chunk size per model: 200 000 Polach scenes and 800 exact ones, seconds on
# one worker, in chunks of 0.2 to 0.5 s. Far shorter tasks pay Dask's per-task cost (a few ms in
# the client, its scheduler and the worker) on every few ms of scenes: Polach's chunks of 1000
# scenes (21 ms) cost the client 9 µs per scene against the worker's 21; chunks of 10 000, 4 µs
# against 18. Far longer ones leave a worker idle at the end while the other finishes its last.
SIZES = {"polach": (5000, 10000), "exact": (20, 10)}
# Iterations of the control's work per process: about a second on one idle core.
BURN = 20_000_000


def burn(iterations):
    """A fixed amount of pure-Python CPU work; returns nothing of interest."""
    total = 0
    for i in range(iterations):
        total += i
    return total


def machine_gain(processes, iterations=BURN):
    """What `processes` processes gain over one on pure CPU work right now: the ceiling for any
    speed-up of as many workers on this (shared) machine at the time of the run."""
    with multiprocessing.get_context("spawn").Pool(processes) as pool:
        pool.map(burn, [iterations // 10] * processes)  # every process started and warm
        started = time.perf_counter()
        pool.apply(burn, (iterations,))
        alone = time.perf_counter() - started
        started = time.perf_counter()
        pool.map(burn, [iterations] * processes, chunksize=1)
        together = time.perf_counter() - started
    return processes * alone / together


def study_text(model, points, chunk_size):
    return (f'name = "bench_{model}"\nmodels = ["{model}"]\nchunk_size = {chunk_size}\n'
            f'outputs = ["force_longitudinal", "force_lateral", "spin_moment"]\n' + GRID.format(points=points))


def bench(fmu, models, workers, repeat=1):
    """Per model: the in-process run, then `repeat` times the machine's gain, the 1-worker and
    `workers`-worker runs and the machine's gain again. Returns per model the in-process outcome,
    and per repetition a dict of the two runs' outcomes, the two gains and the load averages."""
    results = {}
    with tempfile.TemporaryDirectory(prefix="wrc-study-bench-") as directory:
        directory = pathlib.Path(directory)
        for model in models:
            points, chunk_size = SIZES.get(model, SIZES["exact"])
            path = directory / f"{model}.toml"
            path.write_text(study_text(model, points, chunk_size))
            prepared = spec.prepare(path, fmu)

            def run(label, **options):
                out = directory / f"{model}-{label}"
                outcome = execute.run(prepared, out, progress=False, **options)
                assert (outcome.frame["status"] == "ok").all()
                shutil.rmtree(out)  # a repetition computes every chunk again
                return outcome

            pairs = []
            in_process = run("in-process", serial=True)
            for _ in range(repeat):
                pair = {"load": os.getloadavg()[0], "gain before": machine_gain(workers)}
                pair["1 worker"] = run("1-worker", workers=1)
                pair["N workers"] = run(f"{workers}-workers", workers=workers)
                pair["gain after"] = machine_gain(workers)
                pair["load after"] = os.getloadavg()[0]
                pairs.append(pair)
            results[model] = (in_process, pairs)
    return results


def efficiency(pair):
    """(speed-up of N workers over 1, the machine's gain (mean), efficiency = their ratio)."""
    rate = lambda outcome: outcome.scenes_computed / outcome.seconds
    speedup = rate(pair["N workers"]) / rate(pair["1 worker"])
    gain = (pair["gain before"] + pair["gain after"]) / 2
    return speedup, gain, speedup / gain


def table(results, workers):
    lines = [f"{'model':<8} {'run':<12} {'scenes':>7} {'seconds':>8} {'scenes/s':>9} {'CPU ms/scene: workers':>22} {'client':>7}"]
    row = lambda model, name, outcome: (
        f"{model:<8} {name:<12} {outcome.scenes_computed:>7} {outcome.seconds:>8.2f} "
        f"{outcome.scenes_computed / outcome.seconds:>9.1f} {1e3 * outcome.cpu_seconds / outcome.scenes_computed:>22.3f} "
        f"{1e3 * outcome.client_cpu_seconds / outcome.scenes_computed:>7.3f}")
    for model, (in_process, pairs) in results.items():
        lines.append(row(model, "in-process", in_process))
        for pair in pairs:
            lines.append(row(model, "1 worker", pair["1 worker"]))
            lines.append(row(model, f"{workers} workers", pair["N workers"]))
            speedup, gain, ratio = efficiency(pair)
            lines.append(f"{model:<8} {workers} workers over 1: {speedup:.2f}x; {workers} processes of pure CPU work over 1 "
                         f"(the machine now): {pair['gain before']:.2f}x before, {pair['gain after']:.2f}x after, "
                         f"mean {gain:.2f}x; efficiency {ratio:.2f} (load average {pair['load']:.2f} at the start, "
                         f"{pair['load after']:.2f} at the end)")
        if len(pairs) > 1:
            lines.append(f"{model:<8} efficiency, median of {len(pairs)}: "
                         f"{statistics.median(efficiency(pair)[2] for pair in pairs):.2f}")
    return "\n".join(lines)
