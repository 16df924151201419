//! The paper is credited to its authors, fully in the README and the core's
//! docs, briefly in `monge --help`; BOBYQA to Powell's 2009 report.

use std::fs;
use std::path::Path;

use predicates::prelude::*;

use crate::common;
use common::monge;

/// A file of the workspace, as text.
fn workspace_file(path: &str) -> String {
    fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path),
    )
    .unwrap()
}

#[test]
fn help_credits_tellier_et_al_2019() {
    monge().arg("--help").assert().success().stdout(
        predicate::str::contains("Tellier et al. 2019")
            .and(predicate::str::contains("Automation in Construction 106"))
            .and(predicate::str::contains("Mesnil").not()),
    );
}

#[test]
fn readme_and_core_docs_cite_the_paper_fully() {
    for path in ["README.md", "crates/monge-core/src/lib.rs"] {
        let text = workspace_file(path)
            .replace("\n//! ", " ")
            .replace('\n', " ");
        for part in [
            "Tellier",
            "Douthe",
            "Hauswirth",
            "Baverel",
            "Surfaces with planar curvature lines: discretization, generation and application",
            "Automation in Construction 106 (2019) 102880",
            "10.1016/j.autcon.2019.102880",
        ] {
            assert!(text.contains(part), "{path} does not cite `{part}`");
        }
        assert!(
            !text.contains("Léger"),
            "{path} still credits the wrong authors"
        );
    }
}

#[test]
fn bobyqa_is_powells_2009_report() {
    let text = workspace_file("crates/monge-core/src/tools/optimise.rs");
    assert!(text.contains("DAMTP 2009/NA06"));
    monge()
        .args(["fit", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("Powell 2009"));
}
