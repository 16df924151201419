//! The fuzz targets' seed corpora (`fuzz/corpus/TARGET/`), replayed through the
//! targets' own properties (`fuzz/src/lib.rs`, compiled here as a module):
//! every seed, and every input a campaign ever added to a corpus, gives a typed
//! error or a finite result in every build of the normal suite. Fuzzing itself
//! (`fuzz/run.sh`) needs its instrumented build and is run apart.

use std::path::{Path, PathBuf};

#[path = "../../../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod properties;

use monge_io::{DesignFormat, MeshFormat};

/// A fuzz target's name (`fuzz/fuzz_targets/NAME.rs`) and the property it checks.
type Target = (&'static str, fn(&[u8]));

/// Every fuzz target.
const TARGETS: [Target; 7] = [
    ("design_json", |d| properties::design(d, DesignFormat::Json)),
    ("design_toml", |d| properties::design(d, DesignFormat::Toml)),
    ("mesh_obj", |d| properties::mesh(d, MeshFormat::Obj)),
    ("mesh_ply", |d| properties::mesh(d, MeshFormat::Ply)),
    ("mesh_json", |d| properties::mesh(d, MeshFormat::Json)),
    ("iges", properties::iges),
    ("points", properties::points),
];

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz")
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn every_target_has_a_property_here() {
    let mut targets: Vec<String> = names_in(&fuzz_dir().join("fuzz_targets"))
        .into_iter()
        .filter_map(|f| f.strip_suffix(".rs").map(str::to_owned))
        .collect();
    targets.sort();
    let mut here: Vec<&str> = TARGETS.iter().map(|(n, _)| *n).collect();
    here.sort();
    assert_eq!(targets, here);
    assert_eq!(
        names_in(&fuzz_dir().join("corpus")),
        here,
        "one corpus per target"
    );
}

#[test]
fn every_seed_keeps_the_targets_property() {
    let mut replayed = 0;
    for (name, property) in TARGETS {
        let dir = fuzz_dir().join("corpus").join(name);
        for file in names_in(&dir) {
            let path = dir.join(&file);
            let data = std::fs::read(&path).unwrap();
            let run = std::panic::catch_unwind(|| property(&data));
            assert!(run.is_ok(), "{name}: {} broke the property", path.display());
            replayed += 1;
        }
    }
    assert!(replayed >= TARGETS.len(), "{replayed} seeds");
}
