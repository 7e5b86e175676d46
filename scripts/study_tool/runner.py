"""The worker side of a study: runs one chunk of scenes on one FMU instance.

Self-contained on purpose (imports only the standard library, fmpy, pyarrow and distributed): the client
ships this module's code to the workers by value (cloudpickle), so a Dask worker needs the
packages installed but nothing of this project on its disk. The FMU itself reaches a worker as
bytes in a worker plugin, which unpacks it once per worker into a worker-local temporary directory.
"""

import ctypes
import io
import os
import pickle
import shutil
import tempfile
import time
import zipfile

# Modules, not names from them: shipped by value, this code refers to fmpy's ctypes types through
# their modules (cloudpickle sends a module by name; a ctypes type by value it cannot).
import fmpy
import fmpy.fmi1
import fmpy.fmi2
import pyarrow as pa
import pyarrow.parquet as pq
from distributed.diagnostics.plugin import WorkerPlugin

CPU_SECONDS = "wrc_study_cpu_seconds"
STATUS_LABELS = ["ok", "warning", "discard", "error", "fatal", "pending"]


def unpack_fmu(fmu_bytes, prefix="wrc-study-"):
    """Unpacks the FMU's bytes into a fresh temporary directory; returns its path."""
    directory = tempfile.mkdtemp(prefix=prefix)
    with zipfile.ZipFile(io.BytesIO(fmu_bytes)) as archive:
        archive.extractall(directory)
    return directory


# glibc's mallopt parameters (malloc.h): M_TRIM_THRESHOLD, M_MMAP_THRESHOLD.
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3


def keep_freed_memory():
    """Lets glibc's malloc keep memory the FMU frees for its next allocations, in this process.

    The exact theory allocates and frees about 22 MB per scene. With glibc's defaults the larger
    blocks come from mmap and go back to the kernel when freed, and Dask's workers are started
    with MALLOC_TRIM_THRESHOLD_=65536 (distributed's nanny.pre-spawn-environ), which also returns
    the heap's free top: every scene then faults its pages in afresh, 5 400 page faults per exact
    scene in-process and 6 000 on a worker, 16 % of its CPU time. Blocks up to 32 MiB from the
    heap and 64 MiB of free heap kept make that next to 0 (scripts/study_tool/tests/test_allocator.py).
    Without glibc (no mallopt) nothing changes."""
    mallopt = getattr(ctypes.CDLL(None), "mallopt", None)
    if mallopt is not None:
        mallopt(M_MMAP_THRESHOLD, 32 << 20)
        mallopt(M_TRIM_THRESHOLD, 64 << 20)


class FmuOnWorkers(WorkerPlugin):
    """Carries the FMU's bytes to every worker (also to workers that join later) and unpacks them
    there once; removes the directory when the worker closes or the plugin is replaced. Sets the
    worker's allocator up for the FMU (keep_freed_memory)."""

    def __init__(self, fmu_bytes):
        self.fmu_bytes = fmu_bytes
        self.directory = None

    def setup(self, worker):
        keep_freed_memory()
        self.directory = unpack_fmu(self.fmu_bytes)

    def teardown(self, worker):
        if self.directory is not None:
            shutil.rmtree(self.directory, ignore_errors=True)


def plugin_directory(plugin_name):
    """The directory the named FmuOnWorkers plugin unpacked on the worker running this task."""
    from distributed import get_worker

    return get_worker().plugins[plugin_name].directory


def raw_logger_type():
    """The FMU's logger as this FMU calls it: format "%s" and the message as the one variadic
    argument, which on the platforms the FMU is built for (linux64) arrives like a sixth named
    argument. fmpy's logger proxy (fmpy.logging) would format any printf call, but it keeps one
    Python callback for the whole process: instances in two worker threads would swap messages.
    (A function, not a module constant: this code travels by value, a ctypes type cannot.)"""
    return ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                            ctypes.c_char_p, ctypes.c_char_p)


class Instance:
    """One FMU instance with its own logger, which keeps the messages of status warning and worse."""

    def __init__(self, directory, interface, name):
        self.messages = []

        def log(environment, instance_name, status, category, format_, text):
            if status == 0:
                return
            label = STATUS_LABELS[status] if 0 < status < len(STATUS_LABELS) else str(status)
            message = text if format_ == b"%s" else format_
            self.messages.append(f"[{label}] {(message or b'').decode('utf-8', 'replace')}")

        self.logger = raw_logger_type()(log)  # kept alive as long as the instance
        self.callbacks = fmpy.fmi2.fmi2CallbackFunctions()
        ctypes.cast(ctypes.byref(self.callbacks), ctypes.POINTER(ctypes.c_void_p))[0] = \
            ctypes.cast(self.logger, ctypes.c_void_p)
        self.callbacks.allocateMemory = fmpy.fmi2.fmi2CallbackAllocateMemoryTYPE(fmpy.calloc)
        self.callbacks.freeMemory = fmpy.fmi2.fmi2CallbackFreeMemoryTYPE(fmpy.free)
        self.slave = fmpy.fmi2.FMU2Slave(guid=interface["guid"], unzipDirectory=directory,
                                         modelIdentifier=interface["model_identifier"], instanceName=name)
        self.slave.instantiate(callbacks=self.callbacks, loggingOn=False)

    def free(self):
        self.slave.freeInstance()


def set_values(slave, interface, values):
    """Sets Real variables with setReal, Integer and Enumeration ones with setInteger, String ones
    with setString."""
    variables = interface["variables"]
    kind = lambda n: variables[n]["type"]
    reals = [(variables[n]["vr"], float(x)) for n, x in values.items() if kind(n) == "Real"]
    integers = [(variables[n]["vr"], int(x)) for n, x in values.items() if kind(n) not in ("Real", "String")]
    strings = [(variables[n]["vr"], str(x)) for n, x in values.items() if kind(n) == "String"]
    if strings:
        slave.setString([vr for vr, _ in strings], [x for _, x in strings])
    if reals:
        slave.setReal([vr for vr, _ in reals], [x for _, x in reals])
    if integers:
        slave.setInteger([vr for vr, _ in integers], [x for _, x in integers])


def run_scene(slave, interface, scene, outputs, steps, step_size):
    """One scene on an instance that is fresh or just reset: parameters set before
    initialisation, inputs in initialisation mode, then `steps` steps of `step_size`."""
    variables = interface["variables"]
    parameters = {n: x for n, x in scene.items() if variables[n]["causality"] == "parameter"}
    inputs = {n: x for n, x in scene.items() if variables[n]["causality"] == "input"}
    slave.setupExperiment(startTime=0.0)
    set_values(slave, interface, parameters)
    slave.enterInitializationMode()
    set_values(slave, interface, inputs)
    slave.exitInitializationMode()
    for k in range(steps):
        slave.doStep(currentCommunicationPoint=k * step_size, communicationStepSize=step_size)
    return slave.getReal([variables[n]["vr"] for n in outputs])


def run_chunk(fmu, interface, scenes, outputs, steps, step_size, name="chunk"):
    """Runs `scenes` (dicts of variable values) on one instance, fmi2Reset between scenes.

    `fmu` is the unpacked FMU's directory, or ("plugin", NAME) for the directory a FmuOnWorkers
    plugin unpacked on this worker. Returns per scene (status, message, output values): a scene
    the FMU refuses is "error" with the FMU's log messages and NaN outputs; the instance is then
    reset (or, if even that fails, replaced) and the chunk goes on."""
    directory = plugin_directory(fmu[1]) if isinstance(fmu, tuple) else fmu
    nan = float("nan")
    results = []
    instance = Instance(directory, interface, name)
    try:
        for k, scene in enumerate(scenes):
            if k > 0:
                try:
                    instance.slave.reset()
                except fmpy.fmi1.FMICallException:
                    instance.free()
                    instance = Instance(directory, interface, name)
            instance.messages.clear()
            try:
                values = run_scene(instance.slave, interface, scene, outputs, steps, step_size)
                results.append(("ok", "", values))
            except fmpy.fmi1.FMICallException as failure:
                message = "; ".join(instance.messages) or str(failure)
                results.append(("error", message, [nan] * len(outputs)))
    finally:
        instance.free()
    return results


def enumeration_names(interface):
    return {name: {value: item for item, value in v["items"].items()}
            for name, v in interface["variables"].items() if v["items"] is not None}


def chunk_table(fmu, interface, first_scene, pickled_chunk, outputs, steps, step_size):
    """Runs a chunk of (labels, values) scenes, pickled (Dask would otherwise walk every value of
    every scene looking for futures: seconds per study); returns its rows as an Arrow table (built
    here, on the worker): scene number, case, sample, every input
    and parameter (start values for those the study does not set; enumerations by item name), the
    outputs, status and message."""
    chunk = pickle.loads(pickled_chunk)
    cpu = time.process_time()
    results = run_chunk(fmu, interface, [values for _, values in chunk], outputs, steps, step_size,
                        name=f"scene{first_scene}")
    cpu = time.process_time() - cpu
    names = [n for n, v in interface["variables"].items() if v["causality"] in ("input", "parameter")]
    enums = enumeration_names(interface)
    variables = interface["variables"]
    columns = {"scene": [first_scene + k for k in range(len(chunk))],
               "case": [labels["case"] for labels, _ in chunk],
               "sample": [labels["sample"] for labels, _ in chunk]}
    for name in names:
        start = variables[name]["start"]
        values = [values.get(name, start) for _, values in chunk]
        columns[name] = [enums[name][x] for x in values] if name in enums else values
    for k, name in enumerate(outputs):
        columns[name] = [values[k] for _, _, values in results]
    columns["status"] = [status for status, _, _ in results]
    columns["message"] = [message for _, message, _ in results]
    types = {"scene": pa.int64(), "case": pa.string(), "sample": pa.int64(), "status": pa.string(),
             "message": pa.string()}
    for name in names:
        column_type = {"Real": pa.float64(), "String": pa.string()}.get(variables[name]["type"], pa.int64())
        types[name] = pa.string() if name in enums else column_type
    for name in outputs:
        types[name] = pa.float64()
    table = pa.table({name: pa.array(values, type=types[name]) for name, values in columns.items()})
    # The worker's CPU time for the chunk rides along as metadata, not as a column: the results
    # stay the same from run to run, and the benchmark can tell CPU cost from waiting for a core.
    return table.replace_schema_metadata({CPU_SECONDS: repr(cpu)})


def write_atomically(table, path):
    """Writes the table to a temporary file beside `path` and renames it: a part file is either
    complete or absent, whenever the process is killed."""
    path = str(path)
    temporary = os.path.join(os.path.dirname(path), f".{os.path.basename(path)}.{os.getpid()}.tmp")
    pq.write_table(table, temporary)
    os.replace(temporary, path)


def chunk_part(fmu, interface, first_scene, pickled_chunk, outputs, steps, step_size, path):
    """chunk_table, written as the Parquet part `path` where it ran; returns the CPU seconds of
    running the scenes. For workers that share the client's disk (a LocalCluster): receiving the
    tables and writing them in the client is one process's work that the workers' cores share;
    on Polach's chunks of 1000 scenes it took the client 11–14 µs per scene, 7–9 µs without it,
    against the worker's 21 µs of running the scenes."""
    table = chunk_table(fmu, interface, first_scene, pickled_chunk, outputs, steps, step_size)
    write_atomically(table.replace_schema_metadata(None), path)
    return float(table.schema.metadata[CPU_SECONDS.encode()])
