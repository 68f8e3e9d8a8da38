//! The platform binaries of the archives: the library of the host (built by cargo beside
//! this executable) and, when their Rust targets are installed (scripts/cross.sh), the
//! cross-built libraries of the other shipped platforms, each in its FMI folder:
//!
//! ```text
//! target triple                 FMI 2.0 folder   FMI 3.0 folder   file
//! x86_64-unknown-linux-gnu      linux64          x86_64-linux     WoundOpening.so
//! aarch64-unknown-linux-gnu     aarch64-linux    aarch64-linux    WoundOpening.so
//! x86_64-pc-windows-gnu         win64            x86_64-windows   WoundOpening.dll
//! x86_64-apple-darwin           darwin64 (*)     x86_64-darwin    WoundOpening.dylib
//! aarch64-apple-darwin          darwin64 (*)     aarch64-darwin   WoundOpening.dylib
//! ```
//!
//! (*) FMI 2.0 has one macOS folder, loaded on Intel and Apple Silicon alike: its library
//! is universal, the two darwin libraries in one file (universal.rs).
//!
//! FMI 2.0 names six folders (win32, win64, linux32, linux64, darwin32, darwin64) and none
//! for aarch64: its archives use the FMI 3.0 tuple `aarch64-linux`, as the Reference FMUs
//! do. The linkers are those of .cargo/config.toml: zig for Linux (glibc 2.17), MinGW-w64
//! for Windows, rust-lld with libSystem's stubs (target/macos-stubs) for macOS.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::universal;

type BoxError = Box<dyn std::error::Error>;

/// The platforms built besides the host when their targets are installed: the Windows and
/// aarch64 Linux binaries (run under Wine and qemu by scripts/cross_tests.sh) and the two
/// macOS ones (their Mach-O headers checked by tests/python/test_desk_binaries.py).
pub const CROSS_TARGETS: [&str; 4] = [
    "x86_64-pc-windows-gnu",
    "aarch64-unknown-linux-gnu",
    "x86_64-apple-darwin",
    "aarch64-apple-darwin",
];

/// One platform binary: its FMI 2.0 and FMI 3.0 folders (None: not in that version's
/// archives), the suffix of the library in the archive, and the library's bytes.
pub struct Binary {
    pub fmi2: Option<&'static str>,
    pub fmi3: Option<&'static str>,
    pub suffix: &'static str,
    pub bytes: Vec<u8>,
}

/// The oldest macOS a darwin library loads on, written into its LC_BUILD_VERSION: rustc's
/// own minimum for the target (10.12 on Intel; 11.0, the first for Apple Silicon, on arm64),
/// since the build leaves `MACOSX_DEPLOYMENT_TARGET` unset, so that one cargo invocation
/// builds both.
pub fn minimum_macos(triple: &str) -> Option<&'static str> {
    match triple {
        "x86_64-apple-darwin" => Some("10.12"),
        "aarch64-apple-darwin" => Some("11.0"),
        _ => None,
    }
}

/// FMI folders and library name of a target triple: (FMI 2.0 folder, FMI 3.0 folder,
/// prefix and suffix of the file cargo writes).
pub fn folders(triple: &str) -> Option<(&'static str, &'static str, &'static str, &'static str)> {
    Some(match triple {
        "x86_64-unknown-linux-gnu" => ("linux64", "x86_64-linux", "lib", ".so"),
        "aarch64-unknown-linux-gnu" => ("aarch64-linux", "aarch64-linux", "lib", ".so"),
        "x86_64-pc-windows-gnu" | "x86_64-pc-windows-msvc" => {
            ("win64", "x86_64-windows", "", ".dll")
        }
        "x86_64-apple-darwin" => ("darwin64", "x86_64-darwin", "lib", ".dylib"),
        "aarch64-apple-darwin" => ("darwin64", "aarch64-darwin", "lib", ".dylib"),
        _ => return None,
    })
}

/// The target triple this executable was built for (from its OS and architecture).
pub fn host_triple() -> Result<&'static str, BoxError> {
    host_triple_of(std::env::consts::OS, std::env::consts::ARCH)
}

fn host_triple_of(os: &str, arch: &str) -> Result<&'static str, BoxError> {
    match (os, arch) {
        ("linux", "x86_64") => Ok("x86_64-unknown-linux-gnu"),
        ("linux", "aarch64") => Ok("aarch64-unknown-linux-gnu"),
        ("windows", "x86_64") => Ok(if cfg!(target_env = "msvc") {
            "x86_64-pc-windows-msvc"
        } else {
            "x86_64-pc-windows-gnu"
        }),
        ("macos", "x86_64") => Ok("x86_64-apple-darwin"),
        ("macos", "aarch64") => Ok("aarch64-apple-darwin"),
        (os, arch) => Err(format!("no FMI platform folder for {os}/{arch}").into()),
    }
}

/// Every binary for the archives: the host's library from `profile` (`target/release`),
/// then each installed cross target's, built by cargo into `target/<triple>/release`.
/// A cross target whose Rust standard library is not installed is left out, with a note
/// on stderr naming the script that installs it.
///
/// The darwin libraries go into the FMI 3.0 folders alone; FMI 2.0's `darwin64` gets the
/// universal file of all of them.
pub fn binaries(profile: &Path) -> Result<Vec<Binary>, BoxError> {
    let host = host_triple()?;
    let mut out = vec![read_binary(host, profile)?];
    let target_dir = profile.parent().ok_or("profile directory has no parent")?;
    let sdk = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/macos-stubs");
    let stubs = sdk.join("usr/lib/libSystem.tbd");
    let mut triples = Vec::new();
    for triple in CROSS_TARGETS.into_iter().filter(|t| *t != host) {
        if !target_installed(triple) {
            eprintln!(
                "note: Rust target {triple} not installed: no {triple} binary (bash scripts/cross.sh installs it)"
            );
        } else if minimum_macos(triple).is_some() && !stubs.is_file() {
            eprintln!(
                "note: no {}: no {triple} binary (bash scripts/cross.sh writes it)",
                stubs.display()
            );
        } else {
            triples.push(triple);
        }
    }
    if !triples.is_empty() {
        cross_build(&triples, target_dir, &sdk)?;
    }
    for triple in triples {
        out.push(read_binary(triple, &target_dir.join(triple).join("release"))?);
    }
    let (darwin, mut out): (Vec<Binary>, Vec<Binary>) =
        out.into_iter().partition(|b| b.fmi2 == Some("darwin64"));
    if !darwin.is_empty() {
        let slices: Vec<&[u8]> = darwin.iter().map(|b| b.bytes.as_slice()).collect();
        let fat =
            if slices.len() == 1 { slices[0].to_vec() } else { universal::universal(&slices)? };
        out.push(Binary {
            fmi2: Some("darwin64"),
            fmi3: None,
            suffix: darwin[0].suffix,
            bytes: fat,
        });
        out.extend(darwin.into_iter().map(|b| Binary { fmi2: None, ..b }));
    }
    Ok(out)
}

fn read_binary(triple: &str, dir: &Path) -> Result<Binary, BoxError> {
    let (fmi2, fmi3, prefix, suffix) =
        folders(triple).ok_or_else(|| format!("no FMI platform folder for {triple}"))?;
    let path: PathBuf = dir.join(format!("{prefix}wound_opening{suffix}"));
    let bytes = std::fs::read(&path)
        .map_err(|e| format!("cannot read {} (built by cargo): {e}", path.display()))?;
    Ok(Binary { fmi2: Some(fmi2), fmi3: Some(fmi3), suffix, bytes })
}

/// Whether rustc has the standard library of `triple` (`rustup target add` installs it).
fn target_installed(triple: &str) -> bool {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let libdir =
        Command::new(rustc).args(["--print", "target-libdir", "--target", triple]).output();
    match libdir {
        Ok(out) if out.status.success() => {
            let dir = PathBuf::from(String::from_utf8_lossy(&out.stdout).trim());
            std::fs::read_dir(dir).is_ok_and(|entries| {
                entries.flatten().any(|e| e.file_name().to_string_lossy().starts_with("libstd-"))
            })
        }
        _ => false,
    }
}

/// `cargo build --release --lib --no-default-features --target <triple>...`, with the
/// linkers of .cargo/config.toml: the library alone, without the packaging's dependencies.
/// One invocation for every target: cargo then compiles them side by side, one target's
/// single-threaded stages (a crate's front end, a link) beside another's. `sdk` (the
/// libSystem stubs) is the macOS SDK root for rustc (SDKROOT).
fn cross_build(triples: &[&str], target_dir: &Path, sdk: &Path) -> Result<(), BoxError> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .args(["build", "--release", "--quiet", "--lib", "--no-default-features", "--target-dir"])
        .arg(target_dir);
    for triple in triples {
        command.args(["--target", triple]);
    }
    let status = command
        .env_remove("MACOSX_DEPLOYMENT_TARGET")
        .env("SDKROOT", sdk)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .status()?;
    if !status.success() {
        return Err(format!(
            "cargo build --release --lib --target {} failed (the linkers: bash scripts/cross.sh)",
            triples.join(" --target ")
        )
        .into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_of_every_host() {
        let cases = [
            ("linux", "x86_64", "linux64", "x86_64-linux", ".so"),
            ("linux", "aarch64", "aarch64-linux", "aarch64-linux", ".so"),
            ("windows", "x86_64", "win64", "x86_64-windows", ".dll"),
            ("macos", "x86_64", "darwin64", "x86_64-darwin", ".dylib"),
            ("macos", "aarch64", "darwin64", "aarch64-darwin", ".dylib"),
        ];
        for (os, arch, fmi2, fmi3, suffix) in cases {
            let triple = host_triple_of(os, arch).unwrap();
            let (f2, f3, _, s) = folders(triple).unwrap();
            assert_eq!((f2, f3, s), (fmi2, fmi3, suffix), "{os}/{arch} ({triple})");
        }
        assert!(host_triple_of("freebsd", "x86_64").is_err());
        for triple in CROSS_TARGETS {
            assert!(folders(triple).is_some(), "{triple}");
        }
    }
}
