"""A fixed-step co-simulation master for an SSP (System Structure and Parameterization 1.0) of FMI 2.0
Co-Simulation FMUs, written with fmpy's FMU2Slave, as many users write one. The SSP is the single
description of the system: its components, their connections, their parameter values (.ssv files
and inline parameter sets) and the default experiment are read from it, nothing from elsewhere.

Why not fmpy's own SSP support (fmpy.ssp.simulation.simulate_ssp, fmpy 0.3.32)? It ignores the
SSD's ParameterBindings (only a parameter set passed as an argument is applied), cannot set String
or Enumeration-by-name parameters (set_value handles Real, Integer, Boolean), starts every
connection at 0.0 (a wheelset FMU fed track_force_z = 0 reports lift-off at t = 0) and steps the
components one after another with the connections applied afterwards, so a direct-feedthrough
unit's outputs lag a step. This master uses fmpy's SSD reader (fmpy.ssp.ssd.read_ssd, which
validates the SSD and its .ssv files against the SSP 1.0 schemas bundled with fmpy) and does the
rest itself:

- parameters: every ParameterBinding of each component in document order, then the extra
  parameter sets and values given to `simulate` (names `component.variable`), set after
  instantiation, before initialisation; Enumerations by their item names or values (ssv:Integer);
- coupling: explicit (Jacobi) with a fixed communication step h; at each communication point the
  components are visited in an order in which every unit with direct feedthrough (an output that
  depends on an input, by its modelDescription's ModelStructure) comes after the units that feed
  it: its inputs are set from their current outputs, then its outputs read; then every unit does
  its step from t to t + h with these inputs held. The same exchange is done once in
  initialisation mode;
- errors: an FMI call that fails (fmi2Error, fmi2Fatal) ends the run with SystemRunError naming
  the component, the time and the FMU's own log messages (which name the variable and its value),
  and so does an output that is not finite.

With `model_exchange=ModelExchange(...)` the same master runs the FMUs as FMI 2.0 Model Exchange
instead: one CVODE (fmpy's, BDF with Newton iterations on a dense difference-quotient Jacobian)
integrates every unit's continuous states, and each evaluation of its right-hand side sets the
states, does the exchange above (so the connections are solved inside the right-hand side, not
held over a step) and reads the derivatives; the communication step is then only the interval at
which the result is recorded.
"""

import dataclasses
import math
import pathlib
import shutil
import tempfile
import zipfile
from ctypes import byref, c_double

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException, calloc, free
from fmpy.fmi2 import (FMU2Model, FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.logging import addLoggerProxy
from fmpy.ssp.ssd import find_components, ns, read_ssd, read_ssv
from fmpy.sundials import CVodeSolver
from lxml import etree

# Where the SSD carries the communication step (SSP 1.0 has no element for it): OMSimulator's
# annotation of the system, ssd:System/ssd:Annotations/ssc:Annotation type="org.openmodelica" ->
# oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster stepSize="…" (as OMSimulator writes
# and reads it: src/OMSimulatorLib/SystemWC.cpp, ssd/Tags.cpp), so that one number serves both masters.
STEP_ANNOTATION = "org.openmodelica"
STEP_NAMESPACE = "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd"
LOG_STATUS = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PENDING"]


class SystemRunError(Exception):
    """A run that cannot go on: the unit, the time [s] and what it reported; `result`, the run up
    to the last communication point before it (as `simulate` returns it; None before the first)."""

    def __init__(self, component, time, message, result=None):
        super().__init__(f"{component} at t = {time:.6g} s: {message}")
        self.component, self.time, self.message, self.result = component, time, message, result


def assemble(source_directory, fmus, ssp_path):
    """Writes the SSP zip `ssp_path`: SystemStructure.ssd and resources/*.ssv of `source_directory`,
    and the FMUs `fmus` ({name in resources/: path}) that its components name as their source."""
    source_directory, ssp_path = pathlib.Path(source_directory), pathlib.Path(ssp_path)
    ssp_path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(ssp_path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.write(source_directory / "SystemStructure.ssd", "SystemStructure.ssd")
        for parameters in sorted((source_directory / "resources").glob("*.ssv")):
            archive.write(parameters, f"resources/{parameters.name}")
        for name, path in fmus.items():
            archive.write(path, f"resources/{name}")
    return ssp_path


def default_experiment(ssp_path):
    """(start time, stop time, communication step) [s]: the SSD's DefaultExperiment and the step of
    its system's fixed-step-master annotation (STEP_ANNOTATION; None without one)."""
    with zipfile.ZipFile(ssp_path) as archive, archive.open("SystemStructure.ssd") as file:
        root = etree.parse(file).getroot()
    experiment = root.find("ssd:DefaultExperiment", namespaces=ns)
    step = None
    oms = {"oms": STEP_NAMESPACE}
    for annotation in root.findall("ssd:System/ssd:Annotations/ssc:Annotation", namespaces=ns):
        if annotation.get("type") == STEP_ANNOTATION:
            master = annotation.find("oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster", namespaces=oms)
            if master is not None:
                step = float(master.get("stepSize"))
    start = float(experiment.get("startTime", 0.0)) if experiment is not None else 0.0
    stop = float(experiment.get("stopTime")) if experiment is not None and experiment.get("stopTime") else None
    return start, stop, step


@dataclasses.dataclass
class ModelExchange:
    """How `simulate` integrates Model Exchange FMUs: CVODE's relative tolerance (its absolute
    tolerance is it times each state's nominal) and largest step [s]."""
    relative_tolerance: float = 1e-6
    maximum_step: float = math.inf


class _Unit:
    """One component: its FMU2Slave (FMU2Model for Model Exchange), its variables by name and the
    log messages it sent."""

    def __init__(self, component, ssp_directory, work_directory, model_exchange=False):
        self.name = component.name
        path = str(pathlib.Path(ssp_directory) / component.source)
        self.description = read_model_description(path)
        self.variables = {v.name: v for v in self.description.modelVariables}
        self.messages = _MESSAGES.setdefault(self.name, [])
        unzipped = extract(path, unzipdir=str(pathlib.Path(work_directory) / self.name))
        interface, kind = (self.description.modelExchange, FMU2Model) if model_exchange \
            else (self.description.coSimulation, FMU2Slave)
        if interface is None:
            raise SystemRunError(self.name, math.nan, "its FMU lacks the interface asked for")
        self.fmu = kind(guid=self.description.guid, unzipDirectory=unzipped,
                        modelIdentifier=interface.modelIdentifier, instanceName=self.name)
        self.states = len(self.description.derivatives)
        self.has_feedthrough = any(
            output.dependencies is None or any(d.causality == "input" for d in output.dependencies)
            for output in self.description.outputs)

    def variable(self, name):
        if name not in self.variables:
            raise ValueError(f"{self.name} has no variable {name!r}")
        return self.variables[name]

    def set(self, name, value):
        """Sets variable `name` to `value` (a string or number as in an .ssv; Enumerations by item
        name or value)."""
        variable = self.variable(name)
        reference = [variable.valueReference]
        if variable.type == "Real":
            self.fmu.setReal(reference, [float(value)])
        elif variable.type == "Integer":
            self.fmu.setInteger(reference, [int(value)])
        elif variable.type == "Enumeration":
            items = {item.name: int(item.value) for item in variable.declaredType.items}
            if str(value) in items:
                value = items[str(value)]
            elif not str(value).lstrip("-").isdigit():
                raise ValueError(f"{name} = {value!r} is not one of its items {sorted(items)}")
            self.fmu.setInteger(reference, [int(value)])
        elif variable.type == "Boolean":
            self.fmu.setBoolean(reference, [str(value).lower() in ("true", "1")])
        else:
            self.fmu.setString(reference, [str(value)])

    def report(self):
        """The log messages received since the last report, one per line."""
        text = "; ".join(f"[{status}] {message}" for status, message in self.messages)
        self.messages.clear()
        return text or "no message logged"


# The log messages of the running units by instance name, [(status, message)].
_MESSAGES = {}


def _log(component, instance_name, status, category, message):
    """The FMUs' logger: a message of a unit of a running `simulate` is kept for its report; any
    other (an FMU that fmpy runs elsewhere in the process) printed as fmpy's own logger does."""
    label = LOG_STATUS[status] if status < len(LOG_STATUS) else str(status)
    text = message.decode("utf-8", "replace")
    name = instance_name.decode("utf-8", "replace")
    if name in _MESSAGES:
        _MESSAGES[name].append((label, text))
    else:
        print(f"[{label}] {text}")


# One set of callbacks for the process, alive as long as the module: fmpy's logger proxy (which
# formats the printf-style arguments) keeps a single, process-wide pointer to the last logger it
# was given, so a logger that went away would crash later FMU calls, also fmpy's own.
_CALLBACKS = fmi2CallbackFunctions()
_CALLBACKS.logger = fmi2CallbackLoggerTYPE(_log)
_CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
_CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
addLoggerProxy(byref(_CALLBACKS))


def _visiting_order(units, connections):
    """The units ordered so that each unit with direct feedthrough comes after every unit feeding
    it (Kahn's topological sort); an algebraic loop cannot be solved by this explicit master."""
    feeding = {u.name: {start for start, _, end, _ in connections if end == u.name} if u.has_feedthrough else set()
               for u in units}
    ordered = []
    while len(ordered) < len(units):
        ready = [u for u in units if u not in ordered and feeding[u.name] <= {o.name for o in ordered}]
        if not ready:
            raise SystemRunError("system", math.nan, "its direct-feedthrough units form an algebraic loop")
        ordered.append(ready[0])
    return ordered


def _parameter_values(components, ssp_path, parameter_sets, parameters):
    """[(component, variable, value)] in the order they are applied: each component's
    ParameterBindings in document order (.ssv files and inline sets), then the further .ssv files
    `parameter_sets` of the SSP, then `parameters` (both named `component.variable`)."""
    values = []
    for component in components:
        for binding in component.parameterBindings:
            if binding.parameterMapping or binding.prefix:
                raise SystemRunError(component.name, math.nan, "parameter mappings and prefixes are not supported")
            for parameter_set in binding.parameterValues:
                values += [(component.name, p.name, p.value) for p in parameter_set.parameters]
    named = [(p.name, p.value) for path in parameter_sets for p in read_ssv(str(ssp_path), resource=path).parameters]
    for full_name, value in named + list((parameters or {}).items()):
        component, _, name = full_name.partition(".")
        values.append((component, name, value))
    return values


def _model_exchange(units, call, exchange, start, settings, clock):
    """After Model Exchange's initialization: the event iteration (one fmi2NewDiscreteStates per
    unit while it asks for another), continuous-time mode, and one CVODE over every unit's states
    whose right-hand side sets the states, exchanges the connections (`exchange`) and reads the
    derivatives (`clock[0]`: the time CVODE evaluates at, for messages). Returns advance(t,
    t_next): the integration from t to t_next, each unit told of the accepted point. A failure inside CVODE's callbacks (which cannot raise through C) ends the
    integration and is raised after it."""
    for unit in units:
        while call(unit, "newDiscreteStates")[0]:
            pass
        call(unit, "enterContinuousTimeMode")
    stateful = [u for u in units if u.states]
    total = sum(u.states for u in stateful)
    buffers = {u.name: (c_double * u.states)() for u in stateful}
    failures = []

    def each(pointer, transfer):
        """`transfer(unit, its slice of the CVODE vector at pointer)` per unit with states."""
        vector, at = np.ctypeslib.as_array(pointer, (total,)), 0
        for unit in stateful:
            transfer(unit, vector[at:at + unit.states])
            at += unit.states

    def guarded(callback):
        def run(*arguments):
            if failures:
                return
            try:
                callback(*arguments)
            except SystemRunError as failure:
                failures.append(failure)
        return run

    def read(function):
        def transfer(unit, part):
            call(unit, function, buffers[unit.name], unit.states)
            part[:] = buffers[unit.name]
        return guarded(lambda pointer, _n: each(pointer, transfer))

    def write(unit, part):
        buffers[unit.name][:] = part
        call(unit, "setContinuousStates", buffers[unit.name], unit.states)

    def set_states(pointer, _n):
        each(pointer, write)
        exchange()

    def set_time(time):
        clock[0] = time
        for unit in units:
            call(unit, "setTime", time)

    class NoInputs:
        @staticmethod
        def apply(_time):
            pass

    solver = CVodeSolver(nx=total, nz=0, get_x=read("getContinuousStates"), set_x=guarded(set_states),
                         get_dx=read("getDerivatives"), get_z=lambda _z, _n: None,
                         get_nominals=read("getNominalsOfContinuousStates"), set_time=guarded(set_time),
                         input=NoInputs(), startTime=start, maxStep=settings.maximum_step,
                         relativeTolerance=settings.relative_tolerance, maxNumSteps=1_000_000)

    def advance(time, next_time):
        try:
            solver.step(time, next_time)
        except RuntimeError as failure:
            if not failures:
                raise SystemRunError("system", time, f"CVODE: {failure}") from failure
        if failures:
            raise failures[0]
        for unit in units:
            call(unit, "completedIntegratorStep")

    return advance


def simulate(ssp_path, parameter_sets=(), parameters=None, stop_time=None, step_size=None, model_exchange=None):
    """Runs the SSP `ssp_path` from its DefaultExperiment's start to `stop_time` (default: its
    stopTime) with communication step `step_size` [s] (default: the step of its system's
    oms:FixedStepMaster annotation, STEP_ANNOTATION); with `model_exchange` (a ModelExchange) as
    Model Exchange, integrated by CVODE, `step_size` the interval of the result's rows.

    `parameter_sets`: paths inside the SSP of further .ssv files (names `component.variable`),
    applied after the SSD's bindings; `parameters`: {"component.variable": value} applied last.
    Returns a structured numpy array: `time` [s] and every connected output as
    `component.connector`, at every communication point. Raises SystemRunError."""
    start, default_stop, default_step = default_experiment(ssp_path)
    stop_time = default_stop if stop_time is None else stop_time
    step_size = default_step if step_size is None else step_size
    if stop_time is None or step_size is None or not step_size > 0:
        raise SystemRunError("system", start, f"needs a stop time and a step > 0 (got {stop_time}, {step_size})")
    ssd = read_ssd(str(ssp_path))
    system = ssd.system
    connections = [(c.startElement, c.startConnector, c.endElement, c.endConnector) for c in system.connections]
    if any(None in connection for connection in connections):
        raise SystemRunError("system", start, "connections to the system's own connectors are not supported")
    work_directory = pathlib.Path(tempfile.mkdtemp(prefix="ssp_master_"))
    units = []
    try:
        ssp_directory = extract(str(ssp_path), unzipdir=str(work_directory / "ssp"))
        components = find_components(system)
        units = [_Unit(c, ssp_directory, work_directory, model_exchange is not None) for c in components]
        by_name = {u.name: u for u in units}
        for unit in units:
            unit.fmu.instantiate(callbacks=_CALLBACKS)
            unit.fmu.setupExperiment(startTime=start, stopTime=stop_time)
        # The time messages name: the communication point, or CVODE's time inside its callbacks.
        clock = [start]
        values = {}

        def call(unit, function, *arguments):
            """An FMI call of `unit`; its failure a SystemRunError with the unit's log messages
            and the values its connected inputs had."""
            try:
                return getattr(unit.fmu, function)(*arguments)
            except FMICallException as failure:
                given = ", ".join(f"{end_connector} = {values[(start_name, start_connector)]:.6g}"
                                  for start_name, start_connector, end, end_connector in connections
                                  if end == unit.name and (start_name, start_connector) in values)
                raise SystemRunError(unit.name, clock[0], f"{function} failed: {unit.report()}"
                                     + (f" (its inputs: {given})" if given else "")) from failure

        overrides = _parameter_values(components, ssp_path, parameter_sets, parameters)
        for component, name, value in overrides:
            if component not in by_name:
                raise SystemRunError(component, start, f"is not a component of the system (parameter {name})")
            unit = by_name[component]
            try:
                unit.set(name, value)
            except (FMICallException, ValueError) as failure:
                raise SystemRunError(component, start, f"parameter {name} = {value}: {failure}; {unit.report()}") \
                    from failure

        for start_name, start_connector, end, end_connector in connections:
            for name, connector in ((start_name, start_connector), (end, end_connector)):
                if name not in by_name or connector not in by_name[name].variables:
                    raise SystemRunError(name, start, f"a connection names {name}.{connector}, which the system lacks")
                if by_name[name].variable(connector).type != "Real":
                    raise SystemRunError(name, start, f"connector {connector}: only Real connections are supported")
        order = _visiting_order(units, connections)
        inputs = {u.name: [(by_name[u.name].variable(end_connector).valueReference, (start_name, start_connector))
                           for start_name, start_connector, end, end_connector in connections if end == u.name]
                  for u in units}
        outputs = {u.name: sorted({start_connector for start_name, start_connector, _, _ in connections
                                   if start_name == u.name}) for u in units}
        output_references = {u.name: [u.variable(n).valueReference for n in outputs[u.name]] for u in units}
        columns = [(u.name, n) for u in units for n in outputs[u.name]]

        def set_inputs(unit):
            if inputs[unit.name]:
                call(unit, "setReal", [r for r, _ in inputs[unit.name]], [values[s] for _, s in inputs[unit.name]])

        def exchange():
            """Each unit in visiting order: a unit with direct feedthrough gets its inputs from the
            current outputs, then every unit's outputs are read; the units without feedthrough
            get their inputs last."""
            for unit in order:
                if unit.has_feedthrough:
                    set_inputs(unit)
                if outputs[unit.name]:
                    read = call(unit, "getReal", output_references[unit.name])
                    for name, value in zip(outputs[unit.name], read):
                        if not math.isfinite(value):
                            raise SystemRunError(unit.name, clock[0], f"output {name} = {value}: {unit.report()}")
                        values[(unit.name, name)] = value
            for unit in order:
                if not unit.has_feedthrough:
                    set_inputs(unit)

        for unit in units:
            call(unit, "enterInitializationMode")
        exchange()
        for unit in units:
            call(unit, "exitInitializationMode")
        if model_exchange is not None:
            advance = _model_exchange(units, call, exchange, start, model_exchange, clock)
        steps = round((stop_time - start) / step_size)
        dtype = [("time", np.float64)] + [(f"{c}.{n}", np.float64) for c, n in columns]
        rows = []
        try:
            for k in range(steps + 1):
                time = clock[0] = start + k * step_size
                exchange()
                rows.append(tuple([time] + [values[c] for c in columns]))
                if k == steps:
                    break
                if model_exchange is not None:
                    advance(time, start + (k + 1) * step_size)
                    continue
                for unit in units:
                    call(unit, "doStep", time, step_size)
        except SystemRunError as error:
            error.result = np.array(rows, dtype=dtype)
            raise
        for unit in units:
            call(unit, "terminate")
        return np.array(rows, dtype=dtype)
    finally:
        for unit in units:
            if unit.fmu.component is not None:
                unit.fmu.freeInstance()
            _MESSAGES.pop(unit.name, None)
        shutil.rmtree(work_directory, ignore_errors=True)
