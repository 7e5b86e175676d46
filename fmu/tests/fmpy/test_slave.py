"""FMU2Slave: call order, invalid values, GUID, independence, Reset, step sizes, logging."""

import ctypes
import math

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (fmi2CallbackFunctions, fmi2Discard, fmi2Error, fmi2LastSuccessfulTime, fmi2OK,
                       fmi2String, fmi2Terminated, fmi2Boolean, fmi2Real)

from conftest import CONTACT_INPUTS, core_forces, start_values

OUTPUTS = ["force_longitudinal", "force_lateral", "adhesion_utilisation"]

# A logger that sees the FMU's raw call: (environment, instance, status, category, format, text).
# The FMU passes "%s" and the text as the one variadic argument, which arrives like a sixth
# named pointer argument on the platforms the FMU is built for.
RAW_LOGGER = ctypes.CFUNCTYPE(None, ctypes.c_void_p, fmi2String, ctypes.c_int, fmi2String, fmi2String, fmi2String)


class RecordingCallbacks:
    """Callbacks with a raw logger and a distinctive componentEnvironment."""

    ENVIRONMENT = 0x5EED

    def __init__(self):
        self.messages = []

        def log(environment, instance, status, category, format_, text):
            self.messages.append((environment, instance.decode(), status, category.decode(), format_.decode(), text.decode()))

        self.logger = RAW_LOGGER(log)  # kept alive as long as the instance
        self.structure = fmi2CallbackFunctions()
        ctypes.cast(ctypes.byref(self.structure), ctypes.POINTER(ctypes.c_void_p))[0] = ctypes.cast(self.logger, ctypes.c_void_p)
        self.structure.componentEnvironment = self.ENVIRONMENT

    def texts(self):
        return [m[5] for m in self.messages]


def instantiated(new_slave, name="instance", logging=False):
    slave, callbacks = new_slave(name), RecordingCallbacks()
    slave.instantiate(callbacks=callbacks.structure, loggingOn=logging)
    slave.recording = callbacks  # keep the callbacks alive with the slave
    return slave, callbacks


def stepping(new_slave, name="instance", logging=False, stop_time=None):
    slave, callbacks = instantiated(new_slave, name, logging)
    slave.setupExperiment(startTime=0.0, stopTime=stop_time)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    return slave, callbacks


def outputs(slave, vr):
    return slave.getReal([vr[name] for name in OUTPUTS])


def expect_error(call, *arguments, status=fmi2Error):
    with pytest.raises(FMICallException) as raised:
        call(*arguments)
    assert raised.value.status == status


def test_guid_mismatch_returns_null(model_description, unzip_directory):
    from fmpy.fmi2 import FMU2Slave
    slave = FMU2Slave(guid="{not-the-guid}", unzipDirectory=unzip_directory,
                      modelIdentifier=model_description.coSimulation.modelIdentifier, instanceName="wrong")
    callbacks = RecordingCallbacks()
    with pytest.raises(Exception, match="Failed to instantiate model"):
        slave.instantiate(callbacks=callbacks.structure)
    assert slave.component is None
    assert "fmuGUID {not-the-guid} does not match" in callbacks.texts()[0]
    slave.freeLibrary()


@pytest.mark.parametrize("state", ["instantiated", "initializationMode", "stepComplete", "terminated"])
def test_illegal_call_orders_give_fmi2error_and_a_message(new_slave, state, vr):
    slave, callbacks = instantiated(new_slave, logging=False)
    if state != "instantiated":
        slave.setupExperiment(startTime=0.0)
        slave.enterInitializationMode()
    if state in ("stepComplete", "terminated"):
        slave.exitInitializationMode()
    if state == "terminated":
        slave.terminate()
    allowed = {
        "setupExperiment": {"instantiated"},
        "enterInitializationMode": {"instantiated"},
        "exitInitializationMode": {"initializationMode"},
        "doStep": {"stepComplete"},
        "terminate": {"stepComplete"},
        "getReal": {"initializationMode", "stepComplete", "terminated"},
        "setReal": {"instantiated", "initializationMode", "stepComplete"},
    }
    calls = {
        "setupExperiment": lambda: slave.setupExperiment(startTime=0.0),
        "enterInitializationMode": slave.enterInitializationMode,
        "exitInitializationMode": slave.exitInitializationMode,
        "doStep": lambda: slave.doStep(0.0, 1e-3),
        "terminate": slave.terminate,
        "getReal": lambda: slave.getReal([vr["force_lateral"]]),
        "setReal": lambda: slave.setReal([vr["normal_force"]], [1e5]),
    }
    for name, call in calls.items():
        if state in allowed[name]:
            continue
        expect_error(call)
        assert callbacks.texts()[-1] == f"fmi2{name[0].upper()}{name[1:]}: illegal call in state {state}"
    expect_error(slave.fmi2CancelStep, slave.component)
    assert callbacks.texts()[-1] == f"fmi2CancelStep: illegal call in state {state}"


@pytest.mark.parametrize("name, value", [
    ("creepage_longitudinal", math.nan), ("creepage_lateral", math.inf), ("spin_creepage", -math.inf),
    ("normal_force", math.nan), ("semi_axis_a", -1e-3), ("semi_axis_b", 0.0), ("friction_coefficient", -0.2),
    ("shear_modulus", 0.0), ("poisson_ratio", 0.7), ("measured_peak_adhesion", 0.25),
])
def test_invalid_values_give_fmi2error_naming_the_variable_and_the_instance_recovers(new_slave, vr, name, value):
    slave, callbacks = stepping(new_slave)
    before = outputs(slave, vr)
    if name.startswith("measured_"):
        slave.setInteger([vr["stiffness_source"]], [2])
    slave.setReal([vr[name]], [value])
    expect_error(slave.doStep, 0.0, 0.1)
    message = callbacks.texts()[-1]
    assert message.startswith(f"fmi2DoStep: {name} = "), message
    assert "is invalid" in message
    if causality_of(slave, name) == "input":
        # The outputs depend on it directly: read at the invalid value they are the same error.
        expect_error(slave.getReal, [vr["force_longitudinal"]])
        assert callbacks.texts()[-1].startswith(f"fmi2GetReal: {name} = "), callbacks.texts()[-1]
    else:
        # A parameter acts at the next step: the outputs are the last step's.
        assert outputs(slave, vr) == before
    good = 0.33 if name.startswith("measured_") else start_values_of(slave, name)
    slave.setReal([vr[name]], [good])
    if not name.startswith("measured_"):
        assert outputs(slave, vr) == before, "the failed step kept nothing"
    slave.doStep(0.0, 0.1)  # raises on any status worse than fmi2Warning


def causality_of(slave, name):
    from fmpy import read_model_description
    return next(v.causality for v in read_model_description(slave.unzipDirectory).modelVariables if v.name == name)


def start_values_of(slave, name):
    from fmpy import read_model_description
    return start_values(read_model_description(slave.unzipDirectory))[name]


def test_lift_off_gives_zero_forces_without_error(new_slave, vr):
    slave, _ = stepping(new_slave)
    slave.setReal([vr["normal_force"]], [-5.0])
    slave.doStep(0.0, 0.1)  # raises on any status worse than fmi2Warning
    assert outputs(slave, vr) == [0.0, 0.0, 0.0]


def test_two_instances_do_not_interfere(new_slave, vr, model_description):
    first, _ = stepping(new_slave, "first")
    second, _ = stepping(new_slave, "second")
    first.setReal([vr["creepage_lateral"], vr["normal_force"]], [1e-3, 80e3])
    second.setReal([vr["creepage_longitudinal"], vr["spin_creepage"]], [-3e-3, 0.8])
    first.doStep(0.0, 0.1)
    second.doStep(0.0, 0.25)
    defaults = start_values(model_description)
    expected = core_forces([
        {**defaults, "creepage_lateral": 1e-3, "normal_force": 80e3},
        {**defaults, "creepage_longitudinal": -3e-3, "spin_creepage": 0.8},
    ])
    assert tuple(outputs(first, vr)) == expected[0]
    assert tuple(outputs(second, vr)) == expected[1]
    assert expected[0] != expected[1]


def test_reset_returns_to_the_start_values(new_slave, vr, model_description):
    slave, _ = stepping(new_slave)
    initial = outputs(slave, vr)
    slave.setReal([vr["normal_force"], vr["shear_modulus"]], [50e3, 70e9])
    slave.doStep(0.0, 0.5)
    assert outputs(slave, vr) != initial
    slave.reset()
    slave.setupExperiment(startTime=2.0)
    slave.enterInitializationMode()
    defaults = start_values(model_description)
    assert slave.getReal([vr[n] for n in CONTACT_INPUTS]) == [defaults[n] for n in CONTACT_INPUTS]
    slave.exitInitializationMode()
    assert outputs(slave, vr) == initial
    slave.doStep(2.0, 0.5)  # raises on any status worse than fmi2Warning


def test_variable_step_sizes_and_the_step_status(new_slave, vr):
    slave, callbacks = stepping(new_slave, stop_time=1.0)
    time = 0.0
    for step in [1e-6, 0.25, 1e-3, 0.123456789, 0.5]:
        slave.doStep(time, step)  # raises on any status worse than fmi2Warning
        time += step
        value = fmi2Real()
        slave.fmi2GetRealStatus(slave.component, fmi2LastSuccessfulTime, ctypes.byref(value))
        assert value.value == time
    flag = fmi2Boolean(7)
    slave.fmi2GetBooleanStatus(slave.component, fmi2Terminated, ctypes.byref(flag))
    assert flag.value == 0
    expect_error(slave.doStep, time, 0.5)  # beyond stopTime
    expect_error(slave.doStep, time + 0.1, 0.01)  # not the instance's time
    expect_error(slave.doStep, time, 0.0)
    expect_error(slave.doStep, time, -0.1)
    assert callbacks.texts()[-1] == "fmi2DoStep: communicationStepSize = -0.1 is invalid: must be finite and > 0"
    status = ctypes.c_int(-1)
    expect_error(slave.fmi2GetStatus, slave.component, 0, ctypes.byref(status), status=fmi2Discard)


def test_get_in_initialization_mode_reflects_the_inputs_just_set(new_slave, vr, model_description):
    slave, _ = instantiated(new_slave)
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.setReal([vr["creepage_longitudinal"]], [2e-3])
    expected = core_forces([{**start_values(model_description), "creepage_longitudinal": 2e-3}])[0]
    assert tuple(outputs(slave, vr)) == expected


def test_the_log_callback_receives_the_messages_with_environment_and_format(new_slave, vr):
    slave, callbacks = stepping(new_slave, name="logged wheel", logging=True)
    slave.doStep(0.0, 0.1)
    environment, instance, status, category, format_, text = callbacks.messages[-1]
    assert (environment, instance, status, category, format_) == (RecordingCallbacks.ENVIRONMENT, "logged wheel", fmi2OK, "logCalls", "%s")
    assert text == "fmi2DoStep: currentCommunicationPoint = 0, communicationStepSize = 0.1"
    # Only errors: the trace of a good step is filtered out, the error of a bad one is not.
    slave.setDebugLogging(True, ["logStatusError"])
    count = len(callbacks.messages)
    slave.doStep(0.1, 0.1)
    assert len(callbacks.messages) == count
    expect_error(slave.doStep, 0.0, 0.1)
    assert callbacks.messages[-1][2:4] == (fmi2Error, "logStatusError")
    # Debug logging off: errors still reach the logger, traces do not.
    slave.setDebugLogging(False, [])
    slave.doStep(0.2, 0.1)
    expect_error(slave.doStep, 0.0, 0.1)
    assert callbacks.texts()[-1] == "fmi2DoStep: currentCommunicationPoint = 0 is not the instance's time 0.30000000000000004"
    assert all(m[3] != "logCalls" for m in callbacks.messages[count:])


def test_fmpys_own_logger_formats_the_messages(new_slave, capsys):
    slave = new_slave("fmpy logger")
    slave.instantiate(loggingOn=True)  # fmpy's default callbacks with its native variadic proxy
    slave.setupExperiment(startTime=0.0)
    expect_error(slave.doStep, 0.0, 0.1)
    assert "fmi2DoStep: illegal call in state instantiated" in capsys.readouterr().out
