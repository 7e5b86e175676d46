"""A scene for the co-simulation-master tests, importable by a fresh Python process: inputs per
step and a runner that returns the outputs' exact bit patterns (float.hex)."""

import math

INPUTS = ["creepage_longitudinal", "creepage_lateral", "spin_creepage", "normal_force", "semi_axis_a",
          "semi_axis_b", "friction_coefficient"]
OUTPUTS = ["force_longitudinal", "force_lateral", "adhesion_utilisation"]
STEP = 1e-3


def inputs(k):
    """Inputs of step k: creepage ramp through saturation and sign change, spin, load and
    ellipse variation, a friction drop."""
    return [4e-3 * math.sin(0.05 * k), -2e-3 * math.cos(0.031 * k), 0.6 * math.sin(0.017 * k),
            60e3 + 40e3 * math.cos(0.011 * k), 6e-3 + 2e-3 * math.sin(0.007 * k),
            4.5e-3 + 1.5e-3 * math.cos(0.013 * k), 0.35 if k % 200 < 150 else 0.15]


def run(slave, vr, first, count):
    """Steps first .. first + count from time first * STEP; the outputs after each, as hex."""
    rows = []
    for k in range(first, first + count):
        slave.setReal([vr[n] for n in INPUTS], inputs(k))
        slave.doStep(k * STEP, STEP)
        rows.append([x.hex() for x in slave.getReal([vr[n] for n in OUTPUTS])])
    return rows


def relaxing_mid_transient(slave, vr):
    """Creep relaxation on (L = 0.02 m, V = 5 m/s: tau = 4 ms), initialised at the steady state
    of xi = 1e-3, then a creepage step to xi = 4e-3 and one step of 1 ms: the relaxed force, the
    FMU's only internal state, is mid-transient. Returns the time reached."""
    slave.setInteger([vr["creep_relaxation"]], [1])
    slave.setReal([vr["relaxation_length"], vr["rolling_speed"]], [0.02, 5.0])
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    slave.setReal([vr["creepage_longitudinal"]], [4e-3])
    slave.doStep(0.0, STEP)
    return STEP


def hold(slave, vr, time, count):
    """count steps of STEP from time with the inputs left as they are; the outputs as hex."""
    rows = []
    for k in range(count):
        slave.doStep(time + k * STEP, STEP)
        rows.append([x.hex() for x in slave.getReal([vr[n] for n in OUTPUTS])])
    return rows
