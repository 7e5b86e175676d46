"""Exact-theory scenes after the study tool's allocator set-up (runner.keep_freed_memory) reuse the
memory the scenes before them freed: next to no page faults, where glibc's defaults under Dask's
MALLOC_TRIM_THRESHOLD_ fault every scene's memory in afresh. Each measurement runs in a process of
its own, started with the environment a Dask worker gets."""

import json
import os
import subprocess
import sys

from .conftest import ROOT

# Two exact scenes on the FMU's default grid, run on one instance (fmi2Reset between them), then
# the page faults of two more: what a chunk costs per scene once the first scenes have run.
MEASURE = """
import json, pickle, resource, sys
sys.path.insert(0, {scripts!r})
from study_tool import runner, spec
from fmpy import read_model_description
if {keep}:
    runner.keep_freed_memory()
interface = spec.fmu_interface(read_model_description({fmu!r}))
directory = runner.unpack_fmu(open({fmu!r}, "rb").read())
scenes = [{{"creep_force_model": 5, "creepage_longitudinal": x}} for x in (1e-3, 2e-3, 3e-3, 4e-3)]
outputs = ["force_longitudinal"]
runner.run_chunk(directory, interface, scenes[:2], outputs, 0, 1e-3)
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
results = runner.run_chunk(directory, interface, scenes[2:], outputs, 0, 1e-3)
print(json.dumps([resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before, [r[0] for r in results]]))
"""


def page_faults(fmu_path, keep):
    code = MEASURE.format(scripts=str(ROOT / "scripts"), fmu=str(fmu_path), keep=keep)
    environment = {**os.environ, "MALLOC_TRIM_THRESHOLD_": "65536"}  # as distributed's nanny starts a worker
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=environment, check=True,
                          timeout=120)
    faults, statuses = json.loads(done.stdout.splitlines()[-1])
    assert statuses == ["ok", "ok"]
    return faults


def test_exact_scenes_reuse_freed_memory_after_keep_freed_memory(fmu_path, interface):
    assert interface["variables"]["creep_force_model"]["items"]["exact"] == 5
    without = page_faults(fmu_path, keep=False)
    with_ = page_faults(fmu_path, keep=True)
    # Measured: 11 797 faults for the two scenes without, 2 with.
    assert without > 5000, without
    assert with_ < 500, with_
