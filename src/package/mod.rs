//! Packaging of the FMU archives, one per model of the library:
//!
//! ```text
//! WoundOpening.fmu
//! ├── modelDescription.xml             (generated from the model's table: fmi::fmi2::xml)
//! ├── binaries/linux64/WoundOpening.so (the cdylib built beside this executable)
//! ├── binaries/win64/WoundOpening.dll, binaries/aarch64-linux/WoundOpening.so,
//! │   binaries/darwin64/WoundOpening.dylib (x86_64 + arm64)
//! │                                    (cross-built when their targets are installed: platforms.rs)
//! ├── documentation/index.html         (generated: model, variables, plots of the results)
//! └── extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml, WoundOpening_out.csv
//! WoundOpening-me.fmu                  (FMI 2.0 Model Exchange; WoundOpening.fmu is co-simulation)
//! WoundOpening-fmi3.fmu                (FMI 3.0: both interfaces, binaries/x86_64-linux/WoundOpening.so,
//!                                       x86_64-windows/WoundOpening.dll, aarch64-linux/WoundOpening.so,
//!                                       x86_64-darwin/ and aarch64-darwin/WoundOpening.dylib)
//! PurseString.fmu, PurseString-fmi3.fmu (the same cdylib: it picks the model by GUID)
//!
//! Nothing here names a model: every archive comes from the table of models (models::MODELS).
//! ```

mod cases;
mod docs;
mod platforms;
mod reference;
mod ssp;
mod universal;

use std::io::Write;
use std::path::{Path, PathBuf};
use wound_opening::fmi::fmi2::xml::Interfaces;
use wound_opening::fmi::{fmi2, fmi3};
use wound_opening::models::MODELS;

type BoxError = Box<dyn std::error::Error>;

/// Directory of the running executable (`target/<profile>`), where cargo puts the cdylib.
fn profile_dir() -> Result<PathBuf, BoxError> {
    let exe = std::env::current_exe()?;
    Ok(exe.parent().ok_or("executable has no parent directory")?.to_path_buf())
}

/// Build every archive and return their paths: per model, `<id>.fmu` (FMI 2.0) and
/// `<id>-fmi3.fmu` (FMI 3.0), each with co-simulation and Model Exchange; a model with
/// continuous states gets two FMI 2.0 archives instead, `<id>.fmu` (co-simulation) and
/// `<id>-me.fmu` (Model Exchange), so that a co-simulation importer does not parse the
/// hundreds of state and derivative variables (FMI 2.0 has no arrays) on every load.
pub fn build_fmus() -> Result<Vec<PathBuf>, BoxError> {
    let profile = profile_dir()?;
    let binaries = platforms::binaries(&profile)?;
    let target = profile.parent().ok_or("profile directory has no parent")?;
    let out_dir = target.join("fmu");
    std::fs::create_dir_all(&out_dir)?;
    let mut paths = Vec::new();
    for (description, fresh) in &MODELS {
        let id = description.model_identifier;
        let results = reference::simulate(description, *fresh)?;
        let csv_name = format!("{id}_out.csv");
        let paper = cases::simulate(description, *fresh)?;
        let (case_files, case_related) = cases::entries(&paper);
        let case_page = cases::section_html(&paper)?;
        let fmi3 = (
            "-fmi3",
            "FMI 3.0: co-simulation and Model Exchange, from one library",
            Fmi::Three,
            fmi3::xml::fmi3(description),
        );
        let versions = if description.states.is_some() {
            vec![
                (
                    "",
                    "FMI 2.0: co-simulation",
                    Fmi::Two,
                    fmi2::xml::fmi2_with(description, Interfaces::CoSimulation),
                ),
                (
                    "-me",
                    "FMI 2.0: Model Exchange",
                    Fmi::Two,
                    fmi2::xml::fmi2_with(description, Interfaces::ModelExchange),
                ),
                fmi3,
            ]
        } else {
            vec![
                (
                    "",
                    "FMI 2.0: co-simulation and Model Exchange, from one library",
                    Fmi::Two,
                    fmi2::xml::fmi2(description),
                ),
                fmi3,
            ]
        };
        for (suffix, interfaces, version, model_description) in versions {
            let file = format!("{id}{suffix}.fmu");
            let docs = docs::index_html(description, interfaces, &file, &results, &case_page)?;
            let path = out_dir.join(&file);
            let mut entries: Vec<(String, Vec<u8>)> =
                vec![("modelDescription.xml".into(), model_description.into_bytes())];
            entries.extend(binary_entries(&binaries, version, id));
            entries.extend([
                ("documentation/index.html".into(), docs.into_bytes()),
                (
                    format!("{}/fmi-ls-manifest.xml", reference::FOLDER),
                    reference::manifest(description, &csv_name, &case_related).into_bytes(),
                ),
                (format!("{}/{csv_name}", reference::FOLDER), results.csv().into_bytes()),
            ]);
            entries.extend(case_files.iter().cloned());
            write_zip(&path, &entries)?;
            paths.push(path);
        }
    }
    paths.push(ssp::write_ssp(&out_dir)?);
    Ok(paths)
}

#[derive(Clone, Copy)]
enum Fmi {
    Two,
    Three,
}

/// The archive entries `binaries/<folder>/<id><suffix>` of every platform binary, in the
/// folders of FMI version `version`.
fn binary_entries(
    binaries: &[platforms::Binary],
    version: Fmi,
    id: &str,
) -> Vec<(String, Vec<u8>)> {
    binaries
        .iter()
        .filter_map(|b| {
            let folder = match version {
                Fmi::Two => b.fmi2,
                Fmi::Three => b.fmi3,
            }?;
            Some((format!("binaries/{folder}/{id}{}", b.suffix), b.bytes.clone()))
        })
        .collect()
}

/// Writes the archive next to `path` and renames it into place, so that a master loading
/// `path` meanwhile (a test, a wheel build copying it) reads the old archive or the new one,
/// never a partial file. The partial file is this process's own: two writers at once (the
/// test command's cross tests and its wheel build each run `fmu`) never rename each other's.
fn write_zip(path: &Path, entries: &[(String, Vec<u8>)]) -> Result<(), BoxError> {
    let name =
        path.file_name().and_then(|n| n.to_str()).ok_or("archive path without a file name")?;
    let partial = path.with_file_name(format!("{name}.partial-{}", std::process::id()));
    write_zip_to(&partial, entries)?;
    std::fs::rename(&partial, path)?;
    Ok(())
}

fn write_zip_to(path: &Path, entries: &[(String, Vec<u8>)]) -> Result<(), BoxError> {
    let file = std::fs::File::create(path)?;
    let mut zip = zip::ZipWriter::new(file);
    // The shared library is stored, not deflated: importers such as fmpy extract the
    // archive on every load, and inflating 1.5 MB costs them more than the whole
    // co-simulation run (see docs/benchmarks.md, "Loading the FMU").
    let deflated = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, bytes) in entries {
        zip.start_file(
            name.as_str(),
            if name.starts_with("binaries/") { stored } else { deflated },
        )?;
        zip.write_all(bytes)?;
    }
    zip.finish()?;
    Ok(())
}
