//! `include/wound_opening.h` is generated, never edited: this test regenerates it with the
//! cbindgen library pinned in Cargo.toml and `cbindgen.toml`, and fails on any difference.
//! With `UPDATE_HEADER=1` it rewrites the file instead.
//!
//! Only the files of the C boundary are read (the FMI shims and the direct API's shims
//! and status type), so the header holds exactly the exported functions and their types.

use std::path::Path;

const HEADER: &str = "include/wound_opening.h";
const SOURCES: [&str; 6] = [
    "src/fmi/fmi2/functions.rs",
    "src/fmi/fmi2/status.rs",
    "src/fmi/fmi2/exchange.rs",
    "src/capi/error.rs",
    "src/capi/solver_c.rs",
    "src/capi/series_c.rs",
];

fn generate() -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    let config = cbindgen::Config::from_file(Path::new(root).join("cbindgen.toml"))
        .expect("cbindgen.toml parses");
    let builder = SOURCES
        .iter()
        .fold(cbindgen::Builder::new(), |b, src| b.with_src(Path::new(root).join(src)));
    let bindings = builder.with_config(config).generate().expect("cbindgen generates the header");
    let mut out = Vec::new();
    bindings.write(&mut out);
    String::from_utf8(out).expect("the header is UTF-8")
}

#[test]
fn header_matches_the_sources() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(HEADER);
    let fresh = generate();
    if std::env::var_os("UPDATE_HEADER").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(path.parent().expect("include/")).expect("create include/");
        std::fs::write(&path, &fresh).expect("write the header");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    if checked_in != fresh {
        let first = checked_in.lines().zip(fresh.lines()).position(|(a, b)| a != b);
        let line = first.unwrap_or(checked_in.lines().count().min(fresh.lines().count()));
        panic!(
            "{HEADER} is out of date (first difference at line {}: checked in {:?}, generated {:?}); \
             regenerate with UPDATE_HEADER=1 cargo test --release --test header",
            line + 1,
            checked_in.lines().nth(line).unwrap_or("<end of file>"),
            fresh.lines().nth(line).unwrap_or("<end of file>"),
        );
    }
}

/// Every FMI 2.0 function (the 25 common ones, the 9 of co-simulation and the 10 of Model
/// Exchange) is declared in the header.
#[test]
fn header_declares_all_44_fmi_functions() {
    let fresh = generate();
    let names = [
        "fmi2GetTypesPlatform",
        "fmi2GetVersion",
        "fmi2SetDebugLogging",
        "fmi2Instantiate",
        "fmi2FreeInstance",
        "fmi2SetupExperiment",
        "fmi2EnterInitializationMode",
        "fmi2ExitInitializationMode",
        "fmi2Terminate",
        "fmi2Reset",
        "fmi2GetReal",
        "fmi2GetInteger",
        "fmi2GetBoolean",
        "fmi2GetString",
        "fmi2SetReal",
        "fmi2SetInteger",
        "fmi2SetBoolean",
        "fmi2SetString",
        "fmi2GetFMUstate",
        "fmi2SetFMUstate",
        "fmi2FreeFMUstate",
        "fmi2SerializedFMUstateSize",
        "fmi2SerializeFMUstate",
        "fmi2DeSerializeFMUstate",
        "fmi2GetDirectionalDerivative",
        "fmi2SetRealInputDerivatives",
        "fmi2GetRealOutputDerivatives",
        "fmi2DoStep",
        "fmi2CancelStep",
        "fmi2GetStatus",
        "fmi2GetRealStatus",
        "fmi2GetIntegerStatus",
        "fmi2GetBooleanStatus",
        "fmi2GetStringStatus",
        "fmi2EnterEventMode",
        "fmi2NewDiscreteStates",
        "fmi2EnterContinuousTimeMode",
        "fmi2CompletedIntegratorStep",
        "fmi2SetTime",
        "fmi2SetContinuousStates",
        "fmi2GetDerivatives",
        "fmi2GetEventIndicators",
        "fmi2GetContinuousStates",
        "fmi2GetNominalsOfContinuousStates",
    ];
    assert_eq!(names.len(), 44);
    for name in names {
        let declared = fresh.contains(&format!(" {name}(")) || fresh.contains(&format!("*{name}("));
        assert!(declared, "{name} is not declared in the generated header");
    }
}
