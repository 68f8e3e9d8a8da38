//! Packaging of the FMU archives, one per model of the library:
//!
//! ```text
//! WoundOpening.fmu
//! ├── modelDescription.xml             (modelDescription/modelDescription.xml, as compiled in)
//! ├── binaries/linux64/WoundOpening.so (the cdylib built beside this executable)
//! └── documentation/index.html         (generated: model, variables, a plot)
//! PurseString.fmu
//! ├── modelDescription.xml             (modelDescription/PurseString/modelDescription.xml)
//! ├── binaries/linux64/PurseString.so  (the same cdylib: it picks the model by GUID)
//! └── documentation/index.html
//! ```

mod docs;

use std::io::Write;
use std::path::{Path, PathBuf};
use wound_opening::fmi::{MODELS, purse, wound};

type BoxError = Box<dyn std::error::Error>;

/// Directory of the running executable (`target/<profile>`), where cargo puts the cdylib.
fn profile_dir() -> Result<PathBuf, BoxError> {
    let exe = std::env::current_exe()?;
    Ok(exe.parent().ok_or("executable has no parent directory")?.to_path_buf())
}

fn shared_object(dir: &Path) -> Result<Vec<u8>, BoxError> {
    let name = format!("{}wound_opening{}", std::env::consts::DLL_PREFIX, std::env::consts::DLL_SUFFIX);
    let path = dir.join(&name);
    std::fs::read(&path).map_err(|e| format!("cannot read {} (built by cargo with the binary): {e}", path.display()).into())
}

fn platform_dir() -> Result<&'static str, BoxError> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => Ok("linux64"),
        ("linux", "x86") => Ok("linux32"),
        ("macos", _) => Ok("darwin64"),
        ("windows", "x86_64") => Ok("win64"),
        (os, arch) => Err(format!("no FMI 2.0 platform folder for {os}/{arch}").into()),
    }
}

/// Build every archive and return their paths.
pub fn build_fmus() -> Result<Vec<PathBuf>, BoxError> {
    let profile = profile_dir()?;
    let so = shared_object(&profile)?;
    let target = profile.parent().ok_or("profile directory has no parent")?;
    let out_dir = target.join("fmu");
    std::fs::create_dir_all(&out_dir)?;
    let mut paths = Vec::new();
    for (description, _) in &MODELS {
        let id = description.model_identifier;
        let docs = match id {
            wound::variables::MODEL_IDENTIFIER => docs::index_html()?,
            purse::variables::MODEL_IDENTIFIER => docs::purse_html(),
            other => return Err(format!("no documentation page for model {other}").into()),
        };
        let path = out_dir.join(format!("{id}.fmu"));
        write_fmu(&path, id, description.xml, &so, &docs)?;
        paths.push(path);
    }
    Ok(paths)
}

fn write_fmu(path: &Path, id: &str, xml: &str, so: &[u8], docs: &str) -> Result<(), BoxError> {
    let file = std::fs::File::create(path)?;
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    let so_name = format!("binaries/{}/{id}{}", platform_dir()?, std::env::consts::DLL_SUFFIX);
    let entries: [(&str, &[u8]); 3] =
        [("modelDescription.xml", xml.as_bytes()), (&so_name, so), ("documentation/index.html", docs.as_bytes())];
    for (name, bytes) in entries {
        zip.start_file(name, options)?;
        zip.write_all(bytes)?;
    }
    zip.finish()?;
    Ok(())
}
