//! `cargo fmu [all|package|scene|reference|exact-table]` (alias in `.cargo/config.toml`).

use std::path::PathBuf;
use std::process::ExitCode;

use packaging::fmu::{package, workspace_root, Profile, Reach, CONTACT, UNITS};
use packaging::{default_scene, exact_table, reference};

const USAGE: &str = "usage: cargo fmu [COMMAND]
  all        (default) package, then scene
  package    build the release libraries for every platform whose toolchain is present (linux64,
             win64), check each, and write target/fmu/wheel_rail_contact.fmu and
             target/fmu/wheelset.fmu
  scene      run the default scene (a creepage sweep) through target/fmu/wheel_rail_contact.fmu:
             prints a table, writes target/fmu/default_scene.csv and .svg
  reference  read CSV of FMU inputs and parameters (header: their names; optional step_size for
             creep relaxation) on stdin, write the core library's outputs as CSV on stdout
  exact-table [--counts A,N,B,AL,T] [--grid NXxNY] [--wide-grid NXxNY] [--extrapolate yes|no] [--out PATH]
             generate the exact_table model's table (default: the shipped settings, written to
             data/exact_table.bin; hours on two cores, docs/exact_table.md). Resumable: solved slices are kept
             in target/exact-table/";

fn out_dir() -> PathBuf {
    workspace_root().join("target").join("fmu")
}

fn fmu_path() -> PathBuf {
    out_dir().join(format!("{}.fmu", CONTACT.model_identifier))
}

fn run_package() -> Result<(), String> {
    for unit in &UNITS {
        let packaged = package(unit, Profile::Release, Reach::EveryToolchainPresent, &out_dir())?;
        for binary in &packaged.binaries {
            println!("{} {}: {}", unit.model_identifier, binary.platform.folder(), binary.summary);
        }
        for skipped in &packaged.skipped {
            println!("{} {}: skipped, {}", unit.model_identifier, skipped.platform.folder(), skipped.reason);
        }
        println!("wrote {}", packaged.fmu.display());
    }
    Ok(())
}

fn run_scene() -> Result<(), String> {
    eprintln!("cargo fmu: running the default scene through {} …", fmu_path().display());
    let (rows, files) = default_scene::run(&fmu_path(), &out_dir())?;
    println!("Default scene through {} (start values, swept creepage ξ):", fmu_path().display());
    print!("{}", default_scene::table(&rows));
    for file in files {
        println!("wrote {}", file.display());
    }
    Ok(())
}

fn run_exact_table() -> Result<(), String> {
    let mut args: Vec<String> = std::env::args().skip(2).collect();
    let out = match args.iter().position(|a| a == "--out") {
        Some(i) if i + 1 < args.len() => PathBuf::from(args.drain(i..i + 2).nth(1).expect("two drained")),
        Some(_) => return Err("--out needs a path".into()),
        None => workspace_root().join("data").join("exact_table.bin"),
    };
    let settings = exact_table::Settings::from_args(&args)?;
    exact_table::generate(&settings, &workspace_root().join("target").join("exact-table"), &out)
}

fn main() -> ExitCode {
    let command = std::env::args().nth(1).unwrap_or_else(|| "all".to_owned());
    let result = match command.as_str() {
        "all" => run_package().and_then(|()| run_scene()),
        "package" => run_package(),
        "scene" => run_scene(),
        "reference" => reference::outputs_csv(std::io::stdin().lock(), std::io::stdout().lock()),
        "exact-table" => run_exact_table(),
        _ => Err(USAGE.to_owned()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("cargo fmu {command}: {message}");
            ExitCode::FAILURE
        }
    }
}
