"""scripts/study run STUDY.toml [--scheduler ADDRESS] [--workers N] [--out DIR] [--serial]
scripts/study bench [--models polach exact] [--workers N] [--repeat K]"""

import argparse
import pathlib
import sys

from . import spec  # the rest (Dask, pandas, matplotlib) is imported once the study is valid

ROOT = pathlib.Path(__file__).resolve().parents[2]
FMU = ROOT / "target" / "fmu" / "wheel_rail_contact.fmu"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="scripts/study", description="Parameter studies of the wheel-rail contact FMU on Dask.")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="run a study file (resumes one interrupted earlier)")
    run.add_argument("study", type=pathlib.Path, help="the study file (TOML; see examples/studies/)")
    run.add_argument("--scheduler", help="address of an existing Dask scheduler, e.g. tcp://host:8786 "
                                         "(default: a LocalCluster on this machine)")
    run.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core)")
    run.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    run.add_argument("--out", type=pathlib.Path, help="results directory (default: target/studies/NAME, NAME the study's name)")
    run.add_argument("--fmu", type=pathlib.Path, default=FMU, help=f"the FMU (default: {FMU.relative_to(ROOT)})")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    bench = commands.add_parser("bench", help="scenes per second per model, in-process and on LocalClusters of 1 and N "
                                              "workers, and N workers' efficiency")
    bench.add_argument("--models", nargs="+", default=["polach", "exact"])
    bench.add_argument("--workers", type=int, default=2, help="N, the larger LocalCluster's workers (default: 2)")
    bench.add_argument("--repeat", type=int, default=1, help="K, the repetitions of the 1- and N-worker pair with "
                                                             "its controls (default: 1); with more, the median efficiency")
    bench.add_argument("--fmu", type=pathlib.Path, default=FMU)
    arguments = parser.parse_args(argv)
    if arguments.command == "bench":
        from . import bench as benchmark

        if arguments.workers < 2 or arguments.repeat < 1:
            parser.error("bench takes --workers >= 2 and --repeat >= 1")
        results = benchmark.bench(arguments.fmu, arguments.models, arguments.workers, arguments.repeat)
        print(benchmark.table(results, arguments.workers))
        return 0
    if arguments.workers is not None and (arguments.workers < 1 or arguments.scheduler or arguments.serial):
        parser.error("--workers takes a number >= 1 and goes with neither --scheduler nor --serial")
    if arguments.scheduler and arguments.serial:
        parser.error("--scheduler and --serial exclude each other")
    if not arguments.fmu.exists():
        parser.error(f"no FMU at {arguments.fmu}: build it with `cargo fmu package`")
    try:
        prepared = spec.prepare(arguments.study, arguments.fmu)
    except spec.StudyError as error:
        print(f"{arguments.study}: {error}", file=sys.stderr)
        return 2
    from . import execute, report

    out = arguments.out or ROOT / "target" / "studies" / prepared.study["name"]
    try:
        outcome = execute.run(prepared, out, scheduler=arguments.scheduler,
                              workers=arguments.workers, serial=arguments.serial, progress=not arguments.no_progress)
    except KeyboardInterrupt:
        print(f"interrupted: the chunks finished so far are kept in {out / execute.PARTS}; "
              "run the same command again to resume", file=sys.stderr)
        return 130
    text, plots = report.report(outcome, prepared, out)
    print(text)
    print(f"results: {outcome.results}")
    for path in plots:
        print(f"plot: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
