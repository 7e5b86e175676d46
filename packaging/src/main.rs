//! `cargo fmu [all|package|scene|reference]` (alias in `.cargo/config.toml`).

use std::path::PathBuf;
use std::process::ExitCode;

use packaging::fmu::{package, workspace_root, Profile};
use packaging::{default_scene, reference};

const USAGE: &str = "usage: cargo fmu [COMMAND]
  all        (default) package, then scene
  package    build the release library and write target/fmu/wheel_rail_contact.fmu
  scene      run the default scene (a creepage sweep) through target/fmu/wheel_rail_contact.fmu:
             prints a table, writes target/fmu/default_scene.csv and .svg
  reference  read CSV of FMU inputs and parameters (header: their names; optional step_size for
             creep relaxation) on stdin, write the core library's outputs as CSV on stdout";

fn out_dir() -> PathBuf {
    workspace_root().join("target").join("fmu")
}

fn fmu_path() -> PathBuf {
    out_dir().join(format!("{}.fmu", wheel_rail_contact_fmu::model_description::MODEL_IDENTIFIER))
}

fn run_package() -> Result<(), String> {
    let path = package(Profile::Release, &out_dir())?;
    println!("wrote {}", path.display());
    Ok(())
}

fn run_scene() -> Result<(), String> {
    let (rows, files) = default_scene::run(&fmu_path(), &out_dir())?;
    println!("Default scene through {} (start values, swept creepage ξ):", fmu_path().display());
    print!("{}", default_scene::table(&rows));
    for file in files {
        println!("wrote {}", file.display());
    }
    Ok(())
}

fn main() -> ExitCode {
    let command = std::env::args().nth(1).unwrap_or_else(|| "all".to_owned());
    let result = match command.as_str() {
        "all" => run_package().and_then(|()| run_scene()),
        "package" => run_package(),
        "scene" => run_scene(),
        "reference" => reference::outputs_csv(std::io::stdin().lock(), std::io::stdout().lock()),
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
