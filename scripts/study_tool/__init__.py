"""Parameter studies of the wheel-rail contact FMU on Dask: `scripts/study run STUDY.toml`."""
