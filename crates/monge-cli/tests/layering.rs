//! The layering of the workspace's source, read from its `use` lines and paths:
//! no source file depends on a file that depends back on it (no import circle,
//! within any crate), and inside monge-core the folders point one way
//! (`construction` ← `measure` ← `smooth`, `fabrication` ← `tools`).
//!
//! A dependency is a `use` of, or a `crate::`/`super::` path into, another file of
//! the same crate, outside `#[cfg(test)]` items and comments. A module's
//! `pub use` re-exports are its table of contents, not a dependency: they are
//! followed to the file that defines the item. Which crate may use which is
//! checked from the manifests (front ends → monge-io, monge-render → monge-core).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One crate's modules: module path (`["construction", "guide"]`) → its file.
struct Crate {
    files: BTreeMap<Vec<String>, PathBuf>,
    /// `pub use` re-exports: (module, name) → the path it stands for.
    aliases: BTreeMap<(Vec<String>, String), Vec<String>>,
    /// Each module's code, without comments and test items.
    code: BTreeMap<Vec<String>, String>,
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The module path of a source file under `src/`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !matches!(stem, "mod" | "lib" | "main") {
        parts.push(stem.to_string());
    }
    parts
}

/// The source without comments, string contents and `#[cfg(test)]` items.
fn strip(text: &str) -> String {
    // Comments and string literals (their braces would upset the item skipping).
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
            }
            '"' => {
                out.push('"');
                let mut escaped = false;
                for c in chars.by_ref() {
                    if !escaped && c == '"' {
                        break;
                    }
                    escaped = !escaped && c == '\\';
                }
                out.push('"');
            }
            '\'' => {
                // A char literal ('{', '\'') or a lifetime ('a).
                let rest: String = chars.clone().take(3).collect();
                if rest.starts_with("\\") {
                    let n = rest.find('\'').map_or(0, |_| {
                        chars.clone().skip(1).position(|c| c == '\'').unwrap() + 2
                    });
                    for _ in 0..n {
                        chars.next();
                    }
                } else if rest.chars().nth(1) == Some('\'') {
                    chars.next();
                    chars.next();
                } else {
                    out.push('\'');
                }
            }
            _ => out.push(c),
        }
    }
    // `#[cfg(test)]` items: drop from the attribute to the end of the item.
    let mut code = String::with_capacity(out.len());
    let mut rest = out.as_str();
    while let Some(at) = rest.find("#[cfg(test)]") {
        code.push_str(&rest[..at]);
        let after = &rest[at..];
        let end = match (after.find(';'), after.find('{')) {
            (Some(semi), Some(brace)) if semi < brace => semi + 1,
            (_, Some(brace)) => {
                let mut depth = 0usize;
                let mut end = after.len();
                for (i, c) in after[brace..].char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                end = brace + i + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                end
            }
            (Some(semi), None) => semi + 1,
            (None, None) => after.len(),
        };
        rest = &after[end..];
    }
    code.push_str(rest);
    code
}

/// Expands a use tree (`a::{b, c::{d, e as f}}`) into paths.
fn expand(tree: &str) -> Vec<Vec<String>> {
    fn go(prefix: &[String], tree: &str, out: &mut Vec<Vec<String>>) {
        // Split at top-level commas.
        let mut depth = 0;
        let mut start = 0;
        let mut parts = Vec::new();
        for (i, c) in tree.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(tree[start..i].trim());
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(tree[start..].trim());
        for part in parts.into_iter().filter(|p| !p.is_empty()) {
            let mut p = prefix.to_vec();
            if let Some(open) = part.find('{') {
                let head = part[..open].trim().trim_end_matches("::");
                p.extend(
                    head.split("::")
                        .filter(|s| !s.is_empty())
                        .map(|s| s.trim().to_string()),
                );
                go(
                    &p,
                    &part[open + 1..part.rfind('}').unwrap_or(part.len())],
                    out,
                );
            } else {
                // `e as f` names `e`.
                let path = part.split_whitespace().next().unwrap_or(part);
                p.extend(path.split("::").map(String::from));
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    go(&[], tree, &mut out);
    out
}

/// The `use` statements of `code`: (is `pub use`, the paths it names).
fn uses(code: &str) -> Vec<(bool, Vec<Vec<String>>)> {
    let mut found = Vec::new();
    let bytes = code.as_bytes();
    let mut i = 0;
    while let Some(at) = code[i..].find("use ") {
        let start = i + at;
        i = start + 4;
        // A whole word, at the start of an item.
        let before = code[..start].trim_end();
        let is_pub = before.ends_with("pub") || before.ends_with("pub(crate)");
        let boundary =
            start == 0 || !(bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_');
        if !boundary {
            continue;
        }
        let Some(end) = code[i..].find(';') else {
            break;
        };
        let tree = &code[i..i + end];
        if tree.contains('(') || tree.contains('=') || tree.contains('"') {
            continue;
        }
        found.push((is_pub, expand(tree)));
    }
    found
}

/// Inline paths `crate::a::b` and `super::a` in code.
fn inline_paths(code: &str) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    for root in ["crate::", "super::"] {
        let mut i = 0;
        while let Some(at) = code[i..].find(root) {
            let start = i + at;
            i = start + root.len();
            if start > 0 {
                let b = code.as_bytes()[start - 1];
                if b.is_ascii_alphanumeric() || b == b'_' || b == b':' {
                    continue;
                }
            }
            let path: String = code[start..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            found.push(
                path.trim_end_matches(':')
                    .split("::")
                    .map(String::from)
                    .collect(),
            );
        }
    }
    found
}

fn read_crate(src: &Path) -> Crate {
    let mut files = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.insert(module_of(src, &path), path);
            }
        }
    }
    let mut code = BTreeMap::new();
    let mut aliases = BTreeMap::new();
    for (module, path) in &files {
        let text = strip(&std::fs::read_to_string(path).unwrap());
        for (is_pub, paths) in uses(&text) {
            if !is_pub {
                continue;
            }
            for p in paths {
                let name = p.last().unwrap().clone();
                if name == "*" || name == "self" {
                    continue;
                }
                let target = absolute(module, &p, &files);
                // A name can be both a module and an item (`generate`): the
                // module is the one a longer path goes through.
                let key = (module.clone(), name);
                let keep = aliases
                    .get(&key)
                    .is_some_and(|old: &Vec<String>| files.contains_key(old) || target.is_empty());
                if !keep {
                    aliases.insert(key, target);
                }
            }
        }
        code.insert(module.clone(), text);
    }
    Crate {
        files,
        aliases,
        code,
    }
}

/// A path as seen from `module`, made absolute (from the crate root).
fn absolute(
    module: &[String],
    path: &[String],
    files: &BTreeMap<Vec<String>, PathBuf>,
) -> Vec<String> {
    let mut base: Vec<String> = match path.first().map(String::as_str) {
        Some("crate") => return path[1..].to_vec(),
        Some("self") => return [module, &path[1..]].concat(),
        Some("super") => module[..module.len().saturating_sub(1)].to_vec(),
        _ => {
            // A child module, or a name in scope: relative to the module.
            let child: Vec<String> = [module, &path[..1]].concat();
            return if files.contains_key(&child) {
                [module, path].concat()
            } else {
                Vec::new()
            };
        }
    };
    let mut rest = &path[1..];
    while rest.first().map(String::as_str) == Some("super") {
        base.pop();
        rest = &rest[1..];
    }
    [base.as_slice(), rest].concat()
}

impl Crate {
    /// The file (module) an absolute path lands in, following re-exports.
    fn resolve(&self, path: &[String]) -> Option<Vec<String>> {
        let mut at: Vec<String> = Vec::new();
        let mut rest: Vec<String> = path.to_vec();
        for _ in 0..32 {
            let Some(seg) = rest.first().cloned() else {
                return Some(at);
            };
            let child = [at.clone(), vec![seg.clone()]].concat();
            if self.files.contains_key(&child) {
                at = child;
                rest.remove(0);
            } else if let Some(target) = self.aliases.get(&(at.clone(), seg)) {
                if target.is_empty() {
                    return Some(at);
                }
                let mut next = target.clone();
                next.extend(rest.drain(1..));
                at = Vec::new();
                rest = next;
            } else {
                return Some(at);
            }
        }
        None
    }

    /// File-level dependencies: module → modules it uses.
    fn edges(&self) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
        let mut edges = BTreeMap::new();
        for (module, code) in &self.code {
            let mut to = BTreeSet::new();
            let mut paths: Vec<Vec<String>> = uses(code)
                .into_iter()
                .filter(|(is_pub, _)| !is_pub)
                .flat_map(|(_, p)| p)
                .collect();
            // Inline paths outside use statements: the use statements' own
            // paths are counted once above, which is the same edge.
            paths.extend(inline_paths(code));
            for p in paths {
                let abs = absolute(module, &p, &self.files);
                if abs.is_empty() {
                    continue;
                }
                if let Some(target) = self.resolve(&abs) {
                    // The crate root only declares and re-exports.
                    if !target.is_empty() && &target != module {
                        to.insert(target);
                    }
                }
            }
            edges.insert(module.clone(), to);
        }
        edges
    }
}

/// Every circle of `edges` (one per strongly connected component, as a list).
fn circles(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    // Reachability by search from each node: small graphs.
    let reach = |from: &Vec<String>| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in edges.get(&n).into_iter().flatten() {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let all: BTreeMap<_, _> = edges.keys().map(|k| (k.clone(), reach(k))).collect();
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for (k, r) in &all {
        if done.contains(k) || !r.contains(k) {
            continue;
        }
        let component: Vec<_> = r
            .iter()
            .filter(|m| all.get(*m).is_some_and(|rm| rm.contains(k)))
            .cloned()
            .collect();
        done.extend(component.iter().cloned());
        out.push(component);
    }
    out
}

fn crates() -> Vec<(String, Crate)> {
    let root = workspace().join("crates");
    let mut names: Vec<String> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| root.join(n).join("src").is_dir())
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|n| {
            let c = read_crate(&root.join(&n).join("src"));
            (n, c)
        })
        .collect()
}

#[test]
fn no_source_file_depends_on_a_file_that_depends_back() {
    let mut found = Vec::new();
    for (name, krate) in crates() {
        for circle in circles(&krate.edges()) {
            let names: Vec<String> = circle
                .iter()
                .map(|m| {
                    krate.files[m]
                        .strip_prefix(workspace())
                        .unwrap()
                        .display()
                        .to_string()
                })
                .collect();
            found.push(format!("{name}: {}", names.join(" ↔ ")));
        }
    }
    assert!(
        found.is_empty(),
        "import circles (move the shared items to a module below both):\n{}",
        found.join("\n")
    );
}

/// The folders of monge-core, lowest first: a file may use its own folder and
/// the folders before it only.
const CORE_LAYERS: [&[&str]; 4] = [
    &["tasks", "construction"],
    &["measure"],
    &["smooth", "fabrication"],
    &["tools"],
];

fn layer(module: &[String]) -> usize {
    let top = module.first().map_or("", String::as_str);
    CORE_LAYERS
        .iter()
        .position(|l| l.contains(&top))
        .unwrap_or_else(|| {
            panic!("monge-core's {module:?} is in no layer: add its folder to CORE_LAYERS")
        })
}

#[test]
fn monge_core_folders_point_one_way() {
    let (_, core) = crates()
        .into_iter()
        .find(|(n, _)| n == "monge-core")
        .unwrap();
    let mut wrong = Vec::new();
    for (from, tos) in core.edges() {
        if from.is_empty() {
            continue;
        }
        for to in tos {
            let (a, b) = (layer(&from), layer(&to));
            let measure_beyond_grid = from[0] == "measure"
                && to[0] == "construction"
                && to.get(1).map(String::as_str) != Some("grid");
            let sideways = a == b && from[0] != to[0] && a != 0;
            if b > a || measure_beyond_grid || sideways {
                wrong.push(format!("{} uses {}", from.join("::"), to.join("::")));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "monge-core's folders must point one way (construction ← measure ← smooth, fabrication ← tools; measure uses only construction's grid):\n{}",
        wrong.join("\n")
    );
}

#[test]
fn crates_depend_one_way() {
    // front ends → io, render → core: a crate depends only on the ones listed.
    let allowed: BTreeMap<&str, &[&str]> = BTreeMap::from([
        ("monge-core", &[][..]),
        ("monge-io", &["monge-core"][..]),
        ("monge-render", &["monge-core"][..]),
        ("monge-cli", &["monge-core", "monge-io", "monge-render"][..]),
        ("monge-py", &["monge-core", "monge-io"][..]),
        ("monge-wasm", &["monge-core", "monge-io"][..]),
    ]);
    for (krate, may) in allowed {
        let manifest =
            std::fs::read_to_string(workspace().join("crates").join(krate).join("Cargo.toml"))
                .unwrap();
        for line in manifest.lines() {
            if let Some(dep) = line.split('=').next().map(str::trim)
                && dep.starts_with("monge-")
                && dep != krate
            {
                assert!(may.contains(&dep), "{krate} depends on {dep}");
            }
        }
    }
}

#[test]
fn the_reader_sees_a_circle_and_a_re_export() {
    // Two files that use each other, one through a re-export at the root.
    let dir = std::env::temp_dir().join(format!("monge-layering-{}", std::process::id()));
    let src = dir.join("src");
    std::fs::create_dir_all(src.join("a")).unwrap();
    std::fs::write(
        src.join("lib.rs"),
        "mod a;\npub use a::b;\npub mod c;\n/// uses crate::c in a doc: not an edge\n",
    )
    .unwrap();
    std::fs::write(src.join("a/mod.rs"), "pub mod b;\npub use b::Thing;\n").unwrap();
    std::fs::write(
        src.join("a/b.rs"),
        "use crate::c::Other;\n// use crate::x;\npub struct Thing;\n",
    )
    .unwrap();
    std::fs::write(
        src.join("c.rs"),
        "pub struct Other;\nfn f() -> crate::b::Thing { let _ = \"crate::nothing {\"; crate::b::Thing }\n#[cfg(test)]\nmod tests { use crate::lib_only; }\n",
    )
    .unwrap();
    let krate = read_crate(&src);
    let edges = krate.edges();
    let s = |p: &[&str]| p.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert_eq!(edges[&s(&["a", "b"])], BTreeSet::from([s(&["c"])]));
    assert_eq!(edges[&s(&["c"])], BTreeSet::from([s(&["a", "b"])]));
    assert!(edges[&s(&["a"])].is_empty(), "a re-export is not an edge");
    assert_eq!(circles(&edges), vec![vec![s(&["a", "b"]), s(&["c"])]]);
    std::fs::remove_dir_all(&dir).unwrap();
}
