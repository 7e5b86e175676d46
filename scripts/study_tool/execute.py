"""Running a study: scenes in chunks on Dask (a LocalCluster, or any cluster by address) or
in-process, each finished chunk written at once as its own Parquet part (resumable), then the
parts gathered into results.parquet."""

import dataclasses
import hashlib
import json
import logging
import os
import pathlib
import pickle
import shutil
import time

import cloudpickle
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
from tqdm import tqdm

from . import runner

# Workers get the runner's code by value: nothing of this project is needed on their disks.
cloudpickle.register_pickle_by_value(runner)


class ByValue:
    """A function that travels by value inside a Dask task. Dask pickles a task graph with the
    standard pickle, which names a module-level function by reference (the scheduler and workers
    would have to import this package); this wrapper pickles as `cloudpickle.loads(code)`, so the
    receiving side rebuilds the function from its code and needs only the pinned packages."""

    def __init__(self, function):
        self.function = function
        self.code = cloudpickle.dumps(function)

    def __call__(self, *arguments, **keywords):
        return self.function(*arguments, **keywords)

    def __reduce__(self):
        return cloudpickle.loads, (self.code,)


RESULTS = "results.parquet"
PARTS = "parts"


@dataclasses.dataclass
class Outcome:
    results: pathlib.Path
    frame: pd.DataFrame
    chunks: int
    computed: int
    reused: int
    scenes_computed: int
    seconds: float  # wall time of the computed chunks, from the first submission to the last part written
    cpu_seconds: float  # the workers' CPU time for the computed chunks (running the scenes, building the tables)
    client_cpu_seconds: float  # this process's CPU time meanwhile (client, LocalCluster's scheduler, writing parts)


def part_path(out, key, index):
    return out / PARTS / f"{key}-{index:06d}.parquet"


def start_dask(scheduler, workers):
    """A client of the cluster at `scheduler`, or of a new LocalCluster of `workers` single-threaded
    worker processes (default: one per core). Returns (client, cluster or None)."""
    from distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler, timeout="30s"), None
    cluster = LocalCluster(n_workers=workers or os.cpu_count(), threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    return Client(cluster), cluster


def run(prepared, out, scheduler=None, workers=None, serial=False, progress=True):
    """Runs every chunk not already written under `out`, then gathers results.parquet. The time
    reported runs from the first chunk's submission (the cluster up, the FMU on the workers) to the
    last chunk's part written; so does the CPU time of this process reported."""
    out = pathlib.Path(out).resolve()  # a LocalCluster's workers write the parts, from their own directory
    (out / PARTS).mkdir(parents=True, exist_ok=True)
    for stale in (out / PARTS).glob(".*.tmp"):  # left by a run killed while writing a part
        stale.unlink()
    (out / "study.json").write_text(json.dumps({"key": prepared.key, **prepared.study}, indent=2) + "\n")
    chunks = prepared.chunks
    size = prepared.study["chunk_size"]
    pending = [i for i in range(len(chunks)) if not part_path(out, prepared.key, i).exists()]
    reused = len(chunks) - len(pending)
    bar = tqdm(total=len(prepared.scenes), initial=len(prepared.scenes) - sum(len(chunks[i]) for i in pending),
               unit="scene", desc=prepared.study["name"], disable=not progress, dynamic_ncols=True)
    settings = (prepared.study["outputs"], prepared.study["steps"], prepared.study["step_size"])

    cpu_seconds = []
    # The clocks when the last part was written: the run's end, before a LocalCluster's shut-down
    # (about a second, as long for 2 workers as for 1), which is not the study's work.
    ended = {}

    def finished(index, cpu):
        cpu_seconds.append(cpu)
        bar.update(len(chunks[index]))
        ended.update(wall=time.perf_counter(), cpu=time.process_time())

    started, client_cpu = time.perf_counter(), time.process_time()
    try:
        if pending and serial:
            runner.keep_freed_memory()
            directory = runner.unpack_fmu(prepared.fmu_bytes)
            started, client_cpu = time.perf_counter(), time.process_time()
            try:
                for index in pending:
                    finished(index, runner.chunk_part(directory, prepared.interface, index * size, pickle.dumps(chunks[index]),
                                                      *settings, part_path(out, prepared.key, index)))
            finally:
                shutil.rmtree(directory, ignore_errors=True)
        elif pending:
            started, client_cpu = run_on_dask(prepared, out, pending, settings, scheduler, workers, finished)
    finally:
        bar.close()
    seconds = ended.get("wall", started) - started
    client_cpu = ended.get("cpu", client_cpu) - client_cpu - (sum(cpu_seconds) if serial else 0.0)

    frame = gather(out, prepared.key, len(chunks))
    return Outcome(out / RESULTS, frame, len(chunks), len(pending), reused, sum(len(chunks[i]) for i in pending), seconds,
                   sum(cpu_seconds), client_cpu)


def run_on_dask(prepared, out, pending, settings, scheduler, workers, finished):
    """Submits the pending chunks, hands each one's CPU seconds to `finished` as it completes;
    returns the wall and CPU clocks' readings when the first chunk was submitted. A LocalCluster's
    workers write their parts themselves (runner.chunk_part); a cluster's by address may not see
    `out`, so their tables come back and this process writes them."""
    from distributed import as_completed

    client, cluster = start_dask(scheduler, workers)
    plugin = f"wrc-study-fmu-{hashlib.sha256(prepared.fmu_bytes).hexdigest()[:16]}"
    try:
        client.wait_for_workers(1, timeout=60)
        client.register_plugin(runner.FmuOnWorkers(prepared.fmu_bytes), name=plugin)
        started, client_cpu = time.perf_counter(), time.process_time()
        futures = {}
        chunk_table, chunk_part = ByValue(runner.chunk_table), ByValue(runner.chunk_part)
        # Sent to the workers once, not with every chunk (a list, as scatter splits a dict by keys).
        interface, = client.scatter([prepared.interface], broadcast=True)
        size, chunks = prepared.study["chunk_size"], prepared.chunks
        for index in pending:
            arguments = (("plugin", plugin), interface, index * size, pickle.dumps(chunks[index]), *settings)
            key = f"wrc-study-{prepared.key}-{index}"
            if cluster is None:
                future = client.submit(chunk_table, *arguments, key=key, pure=False)
            else:
                future = client.submit(chunk_part, *arguments, str(part_path(out, prepared.key, index)), key=key, pure=False)
            futures[future] = index
        for future in as_completed(futures):
            index, result = futures.pop(future), future.result()
            if cluster is None:
                runner.write_atomically(result.replace_schema_metadata(None), part_path(out, prepared.key, index))
                finished(index, float(result.schema.metadata[runner.CPU_SECONDS.encode()]))
            else:
                finished(index, result)
        return started, client_cpu
    finally:
        if cluster is None:
            try:
                client.unregister_worker_plugin(plugin)
            except Exception:  # the cluster may already be gone; its workers clean up on close
                pass
        client.close()
        if cluster is not None:
            cluster.close()


def gather(out, key, count):
    """Every part of the study, in scene order, as one table written atomically to results.parquet."""
    tables = [pq.read_table(part_path(out, key, i)) for i in range(count)]
    table = pa.concat_tables(tables)
    runner.write_atomically(table, out / RESULTS)
    return table.to_pandas()
