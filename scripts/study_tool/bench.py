"""`scripts/study bench`: scenes per second of a default grid per model, in-process and on
LocalClusters of 1 and 2 workers (or --workers ...), and the speedup over 1 worker. Not a test:
figures for the notes. The time runs from the first chunk submitted (cluster up, FMU on the
workers) to the last part written, so it includes Dask's scheduling and the client writing Parquet."""

import multiprocessing
import pathlib
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
# Creepage points and chunk size per model: enough scenes for a few seconds on one worker.
SIZES = {"polach": (2000, 1000), "exact": (20, 20)}


def burn(_):
    """A fixed amount of pure-Python CPU work; returns nothing of interest."""
    total = 0
    for i in range(5_000_000):
        total += i
    return total


def machine_speedup():
    """What 2 processes gain over 1 on pure CPU work right now: the ceiling for any 2-worker
    speedup on this (shared) machine at the time of the run."""
    started = time.perf_counter()
    burn(0)
    one = time.perf_counter() - started
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        pool.map(burn, [0, 1])  # warm both processes up
        started = time.perf_counter()
        pool.map(burn, [0, 1])
        two = time.perf_counter() - started
    return 2 * one / two


def study_text(model, points, chunk_size):
    return (f'name = "bench_{model}"\nmodels = ["{model}"]\nchunk_size = {chunk_size}\n'
            f'outputs = ["force_longitudinal", "force_lateral", "spin_moment"]\n' + GRID.format(points=points))


def bench(fmu, models, workers, serial=True):
    rows = []
    with tempfile.TemporaryDirectory(prefix="wrc-study-bench-") as directory:
        directory = pathlib.Path(directory)
        for model in models:
            points, chunk_size = SIZES.get(model, SIZES["exact"])
            path = directory / f"{model}.toml"
            path.write_text(study_text(model, points, chunk_size))
            prepared = spec.prepare(path, fmu)
            runs = ([("in-process", {"serial": True})] if serial else []) + \
                   [(f"{n} worker{'s' if n > 1 else ''}", {"workers": n}) for n in workers]
            for label, options in runs:
                if label == f"{max(workers)} workers":
                    rows.append((model, "control", 0, 0.0, machine_speedup(), 0.0, 0.0))
                out = directory / f"{model}-{label.replace(' ', '-')}"
                outcome = execute.run(prepared, out, progress=False, **options)
                assert (outcome.frame["status"] == "ok").all()
                rows.append((model, label, outcome.scenes_computed, outcome.seconds,
                             outcome.scenes_computed / outcome.seconds, outcome.cpu_seconds, outcome.client_cpu_seconds))
    return rows


def table(rows, workers):
    lines = [f"{'model':<8} {'run':<12} {'scenes':>7} {'seconds':>8} {'scenes/s':>9} {'speedup':>8} {'CPU ms/scene: workers':>22} {'client':>7}"]
    for model, label, scenes, seconds, rate, cpu, client in rows:
        if label == "control":
            lines.append(f"{model:<8} {'(2 processes of pure CPU work: ' + format(rate, '.2f') + 'x, the machine now)':<48}")
            continue
        one = next((r for m, l, _, _, r, _, _ in rows if m == model and l == f"{min(workers)} worker"), None)
        speedup = f"{rate / one:.2f}x" if one and label.endswith("workers") else ""
        lines.append(f"{model:<8} {label:<12} {scenes:>7} {seconds:>8.2f} {rate:>9.1f} {speedup:>8} {1e3 * cpu / scenes:>22.3f} {1e3 * client / scenes:>7.3f}")
    return "\n".join(lines)
