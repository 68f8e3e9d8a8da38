//! Command line of the project.
//!
//! `cargo run --release -- fmu` writes `target/fmu/WoundOpening.fmu` and
//! `target/fmu/PurseString.fmu`.

mod package;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("fmu") => package::build_fmus(),
        _ => {
            eprintln!(
                "usage: wound_opening fmu    # writes <target>/fmu/WoundOpening.fmu and PurseString.fmu"
            );
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(paths) => {
            paths.iter().for_each(|p| println!("wrote {}", p.display()));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
