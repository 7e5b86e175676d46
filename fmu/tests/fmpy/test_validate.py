from fmpy.validation import validate_fmu


def test_fmpy_validate_finds_no_problems(fmu_path):
    assert validate_fmu(fmu_path) == []


def test_all_34_functions_are_exported(fmu_path, new_slave):
    # FMU2Slave binds every common and Co-Simulation function at load (requireFunctions=True).
    slave = new_slave()
    for name in ["fmi2GetTypesPlatform", "fmi2DoStep", "fmi2CancelStep", "fmi2GetStringStatus",
                 "fmi2DeSerializeFMUstate", "fmi2GetDirectionalDerivative"]:
        assert callable(getattr(slave, name))
    assert slave.getVersion() == "2.0"
    assert slave.getTypesPlatform() == "default"
