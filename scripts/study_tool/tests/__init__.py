"""The parameter-study tool's suite (a package, so its conftest does not collide with fmu/tests/fmpy's)."""
