//! The documents a newcomer reads (README.md, docs/*.md, ARCHITECTURE.md) say
//! what is true:
//!
//! - every line of their ```sh blocks runs as typed, with this build of
//!   `monge`, in a fresh folder holding `examples/` (a line that cannot run here
//!   says so in a `# not run by the docs test: …` comment; a slow one,
//!   `# slow: run by scripts/docs-numbers.py`, is one of that script's commands);
//! - every measured number sits between markers that scripts/docs-numbers.py
//!   rewrites, and the cheap ones equal what the command prints now;
//! - the crates and monge-core's folders depend on each other one way, as
//!   ARCHITECTURE.md says.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use tempfile::TempDir;

const NOT_RUN: &str = "# not run by the docs test:";
const SLOW: &str = "# slow: run by scripts/docs-numbers.py";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// README.md and docs/*.md, as (name, text).
fn pages() -> Vec<(String, String)> {
    let mut names = vec!["README.md".to_owned()];
    let mut docs: Vec<String> = fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    docs.sort();
    names.extend(docs);
    names
        .into_iter()
        .map(|n| {
            let text = fs::read_to_string(root().join(&n)).unwrap();
            (n, text)
        })
        .collect()
}

/// The lines of a document's ```sh blocks.
fn sh_lines(text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if inside && line.starts_with("```") {
            inside = false;
        } else if inside {
            if !line.trim().is_empty() {
                lines.push(line.to_owned());
            }
        } else if line.trim() == "```sh" {
            inside = true;
        }
    }
    lines
}

/// A fresh folder with `examples/` and `monge` (this build) on the PATH of
/// `sh -c`.
struct Shell {
    dir: TempDir,
    path: String,
}

impl Shell {
    fn new() -> Shell {
        let dir = TempDir::new().unwrap();
        std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
        let bin = dir.path().join(".bin");
        fs::create_dir(&bin).unwrap();
        std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_monge"), bin.join("monge")).unwrap();
        let path = format!(
            "{}:{}",
            bin.display(),
            std::env::var("PATH").unwrap_or_default()
        );
        Shell { dir, path }
    }

    /// Runs `line`; its standard output and error, or the failure.
    fn run(&self, line: &str) -> Result<(String, String), String> {
        let out = Command::new("sh")
            .arg("-c")
            .arg(line)
            .current_dir(self.dir.path())
            .env("PATH", &self.path)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        if out.status.success() {
            Ok((stdout, stderr))
        } else {
            Err(format!(
                "`{line}` failed ({}):\n{stdout}{stderr}",
                out.status
            ))
        }
    }
}

/// One line of scripts/docs-numbers.txt.
struct Number {
    name: String,
    cheap: bool,
    format: String,
    after: String,
    command: String,
}

fn numbers() -> Vec<Number> {
    fs::read_to_string(root().join("scripts/docs-numbers.txt"))
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.splitn(5, '|').map(str::trim).collect();
            assert_eq!(f.len(), 5, "scripts/docs-numbers.txt: `{l}`");
            assert!(matches!(f[1], "cheap" | "slow"), "class of `{l}`");
            Number {
                name: f[0].to_owned(),
                cheap: f[1] == "cheap",
                format: f[2].to_owned(),
                after: f[3].to_owned(),
                command: f[4].to_owned(),
            }
        })
        .collect()
}

#[test]
fn every_command_line_of_the_documents_runs_as_typed() {
    let slow: Vec<String> = numbers().into_iter().map(|n| n.command).collect();
    let mut ran = Vec::new();
    for (page, text) in pages() {
        let shell = Shell::new();
        for line in sh_lines(&text) {
            if line.contains(NOT_RUN) {
                continue;
            }
            if let Some(k) = line.find(SLOW) {
                let command = line[..k].trim();
                assert!(
                    slow.iter().any(|s| s.contains(command)),
                    "{page}: `{command}` is marked slow but scripts/docs-numbers.txt does not run it"
                );
                continue;
            }
            let line = match line.strip_prefix("cargo run --release -p monge-cli -- ") {
                Some(rest) => format!("monge {rest}"),
                None => line,
            };
            assert!(
                line.starts_with("monge "),
                "{page}: `{line}` is neither a `monge` command nor marked `{NOT_RUN} <why>`"
            );
            if let Err(e) = shell.run(&line) {
                panic!("{page}: {e}");
            }
            ran.push(format!("{page}: {line}"));
        }
    }
    eprintln!("ran {} command lines:\n{}", ran.len(), ran.join("\n"));
    assert!(ran.len() >= 14, "{ran:?}");
}

/// The first number after the last of `after`'s pieces (` ... `), each found
/// after the one before it; the same rule as scripts/docs-numbers.py.
fn number_after<'a>(output: &'a str, after: &str) -> &'a str {
    let mut at = 0;
    for piece in after.split(" ... ") {
        let k = output[at..]
            .find(piece)
            .unwrap_or_else(|| panic!("`{piece}` is not in:\n{output}"));
        at += k + piece.len();
    }
    let bytes = output.as_bytes();
    let digit = |k: usize| bytes.get(k).is_some_and(u8::is_ascii_digit);
    let start = (at..bytes.len())
        .find(|&k| digit(k) || (bytes[k] == b'-' && digit(k + 1)))
        .unwrap_or_else(|| panic!("no number after `{after}` in:\n{output}"));
    let mut end = start + 1;
    while digit(end) {
        end += 1;
    }
    if bytes.get(end) == Some(&b'.') && digit(end + 1) {
        end += 1;
        while digit(end) {
            end += 1;
        }
    }
    if matches!(bytes.get(end), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(bytes.get(end + 1), Some(b'-' | b'+')));
        if digit(end + 1 + sign) {
            end += 1 + sign;
            while digit(end) {
                end += 1;
            }
        }
    }
    &output[start..end]
}

/// A number as the documents write it (the same rules as the script).
fn formatted(number: &str, format: &str) -> String {
    let x: f64 = number.parse().unwrap();
    let digits = || format[1..].parse::<usize>().unwrap();
    match format {
        "int" => format!("{}", x as i64),
        f if f.starts_with('f') => format!("{x:.*}", digits()),
        f if f.starts_with('e') => format!("{x:.*e}", digits()),
        f => panic!("unknown format {f}"),
    }
}

/// Every `<!-- num:NAME -->VALUE<!-- /num -->` and `<!-- out:NAME -->…<!-- /out -->`
/// of the documents: (page, name, value).
fn markers() -> Vec<(String, String, String)> {
    let mut found = Vec::new();
    for (page, text) in pages() {
        for (open, close) in [
            ("<!-- num:", "<!-- /num -->"),
            ("<!-- out:", "<!-- /out -->"),
        ] {
            let mut rest = text.as_str();
            while let Some(k) = rest.find(open) {
                rest = &rest[k + open.len()..];
                let (name, after) = rest.split_once(" -->").unwrap();
                let (value, _) = after
                    .split_once(close)
                    .unwrap_or_else(|| panic!("{page}: marker {name} is not closed"));
                found.push((page.clone(), name.to_owned(), value.to_owned()));
            }
        }
    }
    found
}

#[test]
fn every_marked_number_is_made_by_the_script_and_the_cheap_ones_are_current() {
    let numbers = numbers();
    let markers = markers();
    let named: BTreeSet<&str> = numbers.iter().map(|n| n.name.as_str()).collect();
    let marked: BTreeSet<&str> = markers.iter().map(|m| m.1.as_str()).collect();
    assert_eq!(
        named, marked,
        "scripts/docs-numbers.txt and the documents' markers name different numbers"
    );
    let shell = Shell::new();
    let mut outputs: BTreeMap<&str, (String, String)> = BTreeMap::new();
    let mut checked = Vec::new();
    for n in numbers.iter().filter(|n| n.cheap) {
        let (stdout, stderr) = outputs
            .entry(&n.command)
            .or_insert_with(|| shell.run(&n.command).unwrap())
            .clone();
        let want = if n.format == "block" {
            format!("\n```text\n{}\n```\n", stdout.trim_end_matches('\n'))
        } else {
            formatted(number_after(&(stdout + &stderr), &n.after), &n.format)
        };
        for (page, _, value) in markers.iter().filter(|m| m.1 == n.name) {
            assert_eq!(
                value, &want,
                "{page}: {} is out of date: run scripts/docs-numbers.py",
                n.name
            );
        }
        checked.push(format!("{} = {}", n.name, want.trim()));
    }
    eprintln!("checked:\n{}", checked.join("\n"));
}

#[test]
fn number_formats_match_the_script() {
    assert_eq!(formatted("0.000337254", "e1"), "3.4e-4");
    assert_eq!(formatted("1.207e-14", "e0"), "1e-14");
    assert_eq!(formatted("129.559", "f1"), "129.6");
    assert_eq!(formatted("41", "int"), "41");
    let line = "result: mesh → target max 0.0129913 RMS 0.000337254, target → mesh max 0.00112057 RMS 0.000135304";
    assert_eq!(number_after(line, "result: ... RMS"), "0.000337254");
    assert_eq!(number_after(line, "result: ... RMS ... RMS"), "0.000135304");
    assert_eq!(number_after("a: 41 × 33 vertices", "a: ... ×"), "33");
}

#[test]
fn every_relative_link_of_the_documents_exists() {
    let mut pages = pages();
    pages.push((
        "ARCHITECTURE.md".to_owned(),
        fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap(),
    ));
    for (page, text) in pages {
        let base = root().join(&page).parent().unwrap().to_owned();
        for part in text.split("](").skip(1) {
            let target = part.split(')').next().unwrap();
            let file = target.split('#').next().unwrap();
            if target.starts_with("http") || file.is_empty() {
                continue;
            }
            assert!(
                base.join(file).exists(),
                "{page}: link to {target} leads nowhere"
            );
        }
    }
}

#[test]
fn the_readme_and_architecture_list_every_command_of_monge_help() {
    let help = Command::new(env!("CARGO_BIN_EXE_monge"))
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    let commands: Vec<&str> = help
        .split("Commands:")
        .nth(1)
        .unwrap()
        .split("\n\n")
        .next()
        .unwrap()
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert_eq!(commands.len(), 14, "{commands:?}");
    let readme = fs::read_to_string(root().join("README.md")).unwrap();
    let architecture = fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    for c in commands {
        assert!(
            readme.contains(&format!("| `monge {c}")),
            "README.md's command table has no `monge {c}`"
        );
        assert!(
            architecture.contains(&format!("`{c}`")),
            "ARCHITECTURE.md does not list `{c}`"
        );
    }
}
