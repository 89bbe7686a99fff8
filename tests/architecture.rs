//! The library's layers point one way: each module imports only the layers below it
//! (README "Architecture"). This test reads every source file and fails on an import of a
//! higher layer, or of another module of the same layer, naming the file and the line.

use std::path::{Path, PathBuf};

/// The layers, lowest first. A module may use the modules of lower layers only.
const LAYERS: &[&[&str]] = &[
    &["error", "units", "numeric", "progress"],
    &["files"],
    &["model"],
    &["spec"],
    &["geometry"],
    &["measure"],
    &["contact"],
    &["equilibrium"],
    &["engine"],
    &["report"],
    &["cli"],
];

fn rank(module: &str) -> Option<usize> {
    // `crate::Error`, `crate::Result`, `crate::ErrorKind`: the crate root's re-exports of `error`.
    let module = if module.starts_with(char::is_uppercase) {
        "error"
    } else {
        module
    };
    LAYERS.iter().position(|l| l.contains(&module))
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file belongs to (`src/engine/optimise/mod.rs` → `engine`).
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The top-level modules a line of code names as `crate::x` or in `crate::{x, y::z}`
/// (comments removed; a re-export at the crate root such as `crate::Error` counts as itself).
fn named_modules(line: &str) -> Vec<String> {
    let code = match line.find("//") {
        Some(i) => &line[..i],
        None => line,
    };
    let ident = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut names = Vec::new();
    for (i, m) in code.match_indices("crate::") {
        if code[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[i + m.len()..];
        match rest.strip_prefix('{') {
            Some(group) => {
                let group = &group[..group.find('}').unwrap_or(group.len())];
                names.extend(group.split(',').map(ident).filter(|n| !n.is_empty()));
            }
            None => names.push(ident(rest)),
        }
    }
    names
}

/// Every `crate::` import of a higher layer, or of a sibling of the same layer.
fn violations(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    sources(src, &mut files);
    files.sort();
    let mut found = Vec::new();
    for file in files {
        let module = module_of(src, &file);
        if module == "lib" || module == "main" {
            continue;
        }
        let own = rank(&module).unwrap_or_else(|| {
            panic!(
                "{}: module `{module}` has no layer in LAYERS",
                file.display()
            )
        });
        let text = std::fs::read_to_string(&file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for used in named_modules(line) {
                if used == module {
                    continue;
                }
                let ok = rank(&used).is_some_and(|r| r < own);
                if !ok {
                    found.push(format!(
                        "{}:{}: `{module}` uses `crate::{used}`",
                        file.display(),
                        n + 1
                    ));
                }
            }
        }
    }
    found
}

#[test]
fn every_module_imports_only_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = violations(&src);
    assert!(
        found.is_empty(),
        "imports against the layers:\n{}",
        found.join("\n")
    );
}

/// The check itself can fail: an engine module that used the report, or geometry that used the
/// engine, is found with its file and line.
#[test]
fn an_upward_import_is_found() {
    let dir = std::env::temp_dir().join(format!("cycloid-arch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("geometry")).unwrap();
    std::fs::create_dir_all(dir.join("engine")).unwrap();
    std::fs::write(
        dir.join("geometry/mod.rs"),
        "// crate::engine in a comment is fine\nuse crate::model::Design;\nfn f() { crate::engine::run(); }\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("engine/check.rs"),
        "use crate::report::table;\nuse crate::{model, cli::run};\nfn g() -> crate::Result<()> { Ok(()) }\n",
    )
    .unwrap();
    let found = violations(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(found.len(), 3, "{found:?}");
    assert!(
        found[0].ends_with("check.rs:1: `engine` uses `crate::report`"),
        "{found:?}"
    );
    assert!(
        found[1].ends_with("check.rs:2: `engine` uses `crate::cli`"),
        "{found:?}"
    );
    assert!(
        found[2].ends_with("mod.rs:3: `geometry` uses `crate::engine`"),
        "{found:?}"
    );
}
