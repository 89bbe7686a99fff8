//! The library's layers point one way: each module imports only the layers below it
//! (README "Architecture"). This test reads every source file and fails on an import of a
//! higher layer, or of another module of the same layer, naming the file and the line. Inside
//! a folder, files import one way too: no circle of imports between the files (and sub-folders)
//! of one folder. A folder's `mod.rs` is its interface, not one of its files: it declares and
//! re-exports them, and they may use what it declares.

use std::collections::{BTreeMap, BTreeSet};
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

/// A module path (`["engine", "optimise", "problem"]`) for every source file under `src`.
fn module_files(src: &Path) -> BTreeMap<Vec<String>, PathBuf> {
    let mut files = Vec::new();
    sources(src, &mut files);
    let mut modules = BTreeMap::new();
    for file in files {
        let rel = file.strip_prefix(src).unwrap();
        let mut path: Vec<String> = rel
            .components()
            .map(|c| {
                c.as_os_str()
                    .to_string_lossy()
                    .trim_end_matches(".rs")
                    .to_string()
            })
            .collect();
        if matches!(
            path.last().map(String::as_str),
            Some("mod" | "lib" | "main")
        ) {
            path.pop();
        }
        if rel == Path::new("main.rs") {
            continue;
        }
        modules.insert(path, file);
    }
    modules
}

/// The code of a file without comments, string literals and its `#[cfg(test)]` tail (test
/// modules, at the end of a file by convention, may use what the code does not).
fn code_of(text: &str) -> String {
    let text = match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    };
    let chars: Vec<char> = text.chars().collect();
    let ident = |i: usize| i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_');
    let mut code = String::new();
    let mut i = 0;
    while i < chars.len() {
        let (c, next) = (chars[i], chars.get(i + 1).copied());
        i = match c {
            '/' if next == Some('/') => (i..chars.len())
                .find(|&j| chars[j] == '\n')
                .unwrap_or(chars.len()),
            '"' => string_end(&chars, i + 1, 0),
            'r' if !(i > 0 && ident(i - 1)) && matches!(next, Some('"' | '#')) => {
                let hashes = chars[i + 1..].iter().take_while(|&&h| h == '#').count();
                match chars.get(i + 1 + hashes) {
                    Some('"') => string_end(&chars, i + 2 + hashes, hashes),
                    _ => {
                        code.push(c);
                        i + 1
                    }
                }
            }
            // A char literal ('"', '\''), not a lifetime ('a).
            '\'' if next == Some('\\') => (i + 2..chars.len())
                .find(|&j| chars[j] == '\'')
                .map_or(chars.len(), |j| j + 1),
            '\'' if chars.get(i + 2) == Some(&'\'') => i + 3,
            _ => {
                code.push(c);
                i + 1
            }
        };
    }
    code
}

/// Where a string whose text starts at `from` ends (after its closing quote and `hashes` #s of
/// a raw string); escapes count only in ordinary strings.
fn string_end(chars: &[char], from: usize, hashes: usize) -> usize {
    let mut j = from;
    while j < chars.len() {
        if chars[j] == '\\' && hashes == 0 && !raw_before(chars, from) {
            j += 2;
            continue;
        }
        if chars[j] == '"'
            && chars[j + 1..]
                .iter()
                .take(hashes)
                .filter(|&&h| h == '#')
                .count()
                == hashes
        {
            return j + 1 + hashes;
        }
        j += 1;
    }
    chars.len()
}

/// Whether the string starting at `from` is raw (`r"…"`).
fn raw_before(chars: &[char], from: usize) -> bool {
    from >= 2 && chars[from - 2] == 'r'
}

/// Every path a piece of code names from `starts` (`crate`, `super`, `self`, or a child module
/// of a `mod.rs`), with `{a, b::c}` groups expanded: `crate::x::{y, z::w}` gives `crate::x::y`
/// and `crate::x::z::w`.
fn paths_in(code: &str, starts: &BTreeSet<String>) -> Vec<Vec<String>> {
    let chars: Vec<char> = code.chars().collect();
    let ident_char = |c: char| c.is_alphanumeric() || c == '_';
    let mut found = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        if !ident_char(chars[i]) || (i > 0 && (ident_char(chars[i - 1]) || chars[i - 1] == ':')) {
            i += 1;
            continue;
        }
        let (word, end) = ident_at(&chars, i);
        if starts.contains(&word) && chars[end..].starts_with(&[':', ':']) {
            let mut out = Vec::new();
            tree_at(&chars, i, Vec::new(), &mut out);
            found.extend(out);
        }
        i = end.max(i + 1);
    }
    found
}

fn ident_at(chars: &[char], mut i: usize) -> (String, usize) {
    let start = i;
    while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
        i += 1;
    }
    (chars[start..i].iter().collect(), i)
}

fn skip_space(chars: &[char], mut i: usize) -> usize {
    while i < chars.len() && chars[i].is_whitespace() {
        i += 1;
    }
    i
}

/// The paths of a use tree at `i` (`a::b`, `a::{b, c::d}`, nested), each prefixed by `prefix`;
/// returns where the tree ends.
fn tree_at(chars: &[char], i: usize, mut prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
    let mut i = skip_space(chars, i);
    loop {
        if chars.get(i) == Some(&'{') {
            i += 1;
            loop {
                i = skip_space(chars, i);
                match chars.get(i) {
                    None => return i,
                    Some('}') => return i + 1,
                    Some(',') => i += 1,
                    Some(_) => {
                        let next = tree_at(chars, i, prefix.clone(), out);
                        i = if next > i { next } else { i + 1 };
                    }
                }
            }
        }
        let (word, end) = ident_at(chars, i);
        if word.is_empty() {
            out.push(prefix);
            return i;
        }
        prefix.push(word);
        i = end;
        if chars[i..].starts_with(&[':', ':']) {
            i = skip_space(chars, i + 2);
        } else {
            out.push(prefix);
            return i;
        }
    }
}

/// The module a path names, as the longest prefix of it that is a file's module; `None` for
/// paths outside the crate.
fn target<'a>(
    own: &[String],
    is_mod: bool,
    path: &[String],
    modules: &'a BTreeMap<Vec<String>, PathBuf>,
) -> Option<&'a Vec<String>> {
    // Where `self` is: a `mod.rs` is its folder's module, a file its own.
    let here: Vec<String> = own.to_vec();
    let mut full = match path.first().map(String::as_str) {
        Some("crate") => Vec::new(),
        Some("self") => here.clone(),
        Some("super") => here[..here.len().saturating_sub(1)].to_vec(),
        // A child module named from its parent's file.
        Some(_) if is_mod => here.clone(),
        _ => return None,
    };
    let rest = match path.first().map(String::as_str) {
        Some("crate" | "self" | "super") => &path[1..],
        _ => path,
    };
    full.extend(rest.iter().cloned());
    (0..=full.len())
        .rev()
        .find_map(|n| modules.get_key_value(&full[..n]).map(|(k, _)| k))
}

/// The import graph of each folder: (folder, from, to) over the folder's direct children
/// (files and sub-folders), its `mod.rs` left out; the crate root is the layers' business.
fn folder_edges(src: &Path) -> BTreeSet<(Vec<String>, String, String)> {
    let modules = module_files(src);
    let mut edges = BTreeSet::new();
    for (own, file) in &modules {
        let is_mod = file
            .file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs");
        let text = std::fs::read_to_string(file).unwrap();
        let code = code_of(&text);
        let mut starts: BTreeSet<String> = ["crate", "super", "self"].map(String::from).into();
        if is_mod {
            starts.extend(
                modules
                    .keys()
                    .filter(|k| k.len() == own.len() + 1 && k.starts_with(own))
                    .map(|k| k[own.len()].clone()),
            );
        }
        for path in paths_in(&code, &starts) {
            let Some(to) = target(own, is_mod, &path, &modules) else {
                continue;
            };
            if to == own {
                continue;
            }
            let common = own.iter().zip(to).take_while(|(a, b)| a == b).count();
            let node = |m: &Vec<String>| m.get(common).cloned().unwrap_or_else(|| "mod".into());
            let (from, to) = (node(own), node(to));
            if common > 0 && from != "mod" && to != "mod" {
                edges.insert((own[..common].to_vec(), from, to));
            }
        }
    }
    edges
}

/// Every circle of imports inside one folder: the folder, the files (and sub-folders) that
/// reach each other, and their imports of each other.
fn folder_circles(src: &Path) -> Vec<String> {
    let edges = folder_edges(src);
    let mut folders: BTreeMap<&Vec<String>, BTreeMap<&str, BTreeSet<&str>>> = BTreeMap::new();
    for (folder, from, to) in &edges {
        let graph = folders.entry(folder).or_default();
        graph.entry(from).or_default().insert(to);
        graph.entry(to).or_default();
    }
    let mut circles = Vec::new();
    for (folder, graph) in folders {
        let reach: BTreeMap<&str, BTreeSet<&str>> =
            graph.keys().map(|&n| (n, reachable(n, &graph))).collect();
        let mut placed = BTreeSet::new();
        for &n in graph.keys() {
            let circle: Vec<&str> = (graph.keys())
                .copied()
                .filter(|m| *m != n && reach[n].contains(m) && reach[m].contains(n))
                .chain([n])
                .collect::<BTreeSet<_>>()
                .into_iter()
                .collect();
            if circle.len() < 2 || !placed.insert(circle.clone()) {
                continue;
            }
            let inside: Vec<String> = (circle.iter())
                .flat_map(|&a| graph[a].iter().map(move |&b| (a, b)))
                .filter(|(_, b)| circle.contains(b))
                .map(|(a, b)| format!("{a} → {b}"))
                .collect();
            circles.push(format!(
                "src/{}: {} ({})",
                folder.join("/"),
                circle.join(", "),
                inside.join(", ")
            ));
        }
    }
    circles
}

/// The nodes reachable from `start` by one import or more.
fn reachable<'a>(
    start: &'a str,
    graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
) -> BTreeSet<&'a str> {
    let mut seen = BTreeSet::new();
    let mut todo: Vec<&str> = graph[start].iter().copied().collect();
    while let Some(n) = todo.pop() {
        if seen.insert(n) {
            todo.extend(graph[n].iter().copied());
        }
    }
    seen
}

#[test]
fn files_inside_a_folder_import_one_way() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let circles = folder_circles(&src);
    assert!(
        circles.is_empty(),
        "import circles between the files of a folder:\n{}",
        circles.join("\n")
    );
}

/// The circle check can fail: two files of one folder that import each other (through a use
/// group and a `super::` path in code), and a file and a sub-folder that do, are found, also
/// where the import follows a string holding `//` or a char literal `'"'` on its line; a
/// one-way import (`a → c`, `x → y`), `mod.rs` re-exports, paths in comments and strings (raw
/// ones too), and a test module's imports are not.
#[test]
fn a_circle_inside_a_folder_is_found() {
    let dir = std::env::temp_dir().join(format!("cycloid-circles-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files = [
        ("lib.rs", "pub mod engine;\npub mod model;\n"),
        (
            "engine/mod.rs",
            "pub mod a;\npub mod b;\npub mod c;\npub mod d;\npub use c::Go;\n",
        ),
        (
            "engine/a.rs",
            "use crate::engine::{b::{self, Thing}, c};\npub fn run() { c::go(); }\n",
        ),
        // The import after a string holding `//`, and after a char literal '"', still counts.
        (
            "engine/b.rs",
            "pub fn f() { let _ = \"x//y\"; super::a::run() }\n",
        ),
        (
            "engine/c.rs",
            "fn q() -> char { '\"' } use super::d::e;\npub struct T;\n#[cfg(test)]\nmod tests { use crate::engine::b; }\n",
        ),
        ("engine/d/mod.rs", "pub mod e;\n"),
        ("engine/d/e.rs", "use crate::engine::c::T;\n"),
        ("model/mod.rs", "pub mod x;\npub mod y;\n"),
        (
            "model/x.rs",
            "// crate::model::y in a comment\nuse crate::model::y::Y;\n",
        ),
        (
            "model/y.rs",
            "pub struct Y; fn s() -> &'static str { \"crate::model::x\" }\n\
             const R: &str = r#\"a \" crate::model::x\"#;\n",
        ),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let circles = folder_circles(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        circles,
        [
            "src/engine: a, b (a → b, b → a)",
            "src/engine: c, d (c → d, d → c)"
        ],
    );
}

/// The inherent `impl` blocks of a piece of code: the name of each type implemented (the last
/// segment of its path, generics left out); trait impls (`impl X for Y`) are not inherent.
fn inherent_impls(code: &str) -> Vec<String> {
    let chars: Vec<char> = code.chars().collect();
    let ident_char = |c: char| c.is_alphanumeric() || c == '_';
    let mut found = Vec::new();
    for (i, _) in code.match_indices("impl") {
        let i = code[..i].chars().count();
        let before = i.checked_sub(1).map(|j| chars[j]);
        let after = chars.get(i + 4).copied();
        // An item starts its line; `impl Trait` in an argument's or a result's type does not.
        let line = code[..code.char_indices().nth(i).map_or(code.len(), |(b, _)| b)]
            .rsplit('\n')
            .next()
            .unwrap_or_default()
            .trim();
        let item = matches!(line, "" | "unsafe");
        if !item || before.is_some_and(ident_char) || after.is_some_and(ident_char) {
            continue;
        }
        // The header, up to the block: `impl<T> a::Ty<T> where … {`.
        let end = (i..chars.len())
            .find(|&j| matches!(chars[j], '{' | ';'))
            .unwrap_or(chars.len());
        let mut header: String = chars[i + 4..end].iter().collect();
        if header.trim_start().starts_with('<') {
            header = skip_generics(header.trim_start());
        }
        let header = header.split(" where").next().unwrap_or_default();
        if header.split_whitespace().any(|w| w == "for") {
            continue;
        }
        let ty = header.trim().split('<').next().unwrap_or_default();
        let name = ty.rsplit("::").next().unwrap_or_default().trim();
        if !name.is_empty() && name.chars().all(ident_char) {
            found.push(name.to_string());
        }
    }
    found
}

/// The text after a leading `<…>` (nested brackets counted).
fn skip_generics(text: &str) -> String {
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        match c {
            '<' => depth += 1,
            '>' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            return text[i + 1..].to_string();
        }
    }
    String::new()
}

/// The types a piece of code defines (`struct`, `enum`, `union`, `type`).
fn defined_types(code: &str) -> BTreeSet<String> {
    let words: Vec<&str> = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .collect();
    words
        .windows(2)
        .filter(|w| matches!(w[0], "struct" | "enum" | "union" | "type"))
        .map(|w| w[1].to_string())
        .collect()
}

/// Every inherent `impl` of a type that its module does not define, outside the defining module
/// and its children: a type's methods live with its data, so a caller that names the type
/// depends (in the imports the layer checks see) on every module its methods come from.
fn scattered_impls(src: &Path) -> Vec<String> {
    let modules = module_files(src);
    let mut codes = BTreeMap::new();
    let mut defined: BTreeMap<String, Vec<&Vec<String>>> = BTreeMap::new();
    for (module, file) in &modules {
        let code = code_of(&std::fs::read_to_string(file).unwrap());
        for ty in defined_types(&code) {
            defined.entry(ty).or_default().push(module);
        }
        codes.insert(module, code);
    }
    let mut found = Vec::new();
    for (module, code) in &codes {
        for ty in inherent_impls(code) {
            let Some(homes) = defined.get(&ty) else {
                continue;
            };
            if homes.iter().any(|home| module.starts_with(home)) {
                continue;
            }
            let homes: Vec<String> = homes.iter().map(|h| h.join("::")).collect();
            found.push(format!(
                "src/{}: `impl {ty}` away from its type in {}",
                module.join("/"),
                homes.join(", ")
            ));
        }
    }
    found
}

#[test]
fn methods_live_with_their_type() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = scattered_impls(&src);
    assert!(
        found.is_empty(),
        "inherent impls away from their type's module:\n{}",
        found.join("\n")
    );
}

/// The check can fail: a type's data in one file and its methods in a sibling folder's file
/// (the old `Coupling` split: `equilibrium/coupling.rs` and `equilibrium/friction/coupled.rs`)
/// is found; methods in the defining file, in a child of its module, generic impls, and trait
/// impls elsewhere (or in a comment, or a string) are not.
#[test]
fn methods_away_from_their_type_are_found() {
    let dir = std::env::temp_dir().join(format!("cycloid-impls-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files = [
        ("lib.rs", "pub mod equilibrium;\n"),
        (
            "equilibrium/mod.rs",
            "pub mod coupling;\npub mod friction;\npub mod wrap;\n",
        ),
        (
            "equilibrium/coupling.rs",
            "pub struct Coupling { pub roller: f64 }\npub enum Sliding { Running }\n\
             impl Coupling { pub fn active(&self) -> bool { true } }\n\
             pub struct Wrap<T>(T);\nimpl<T: Copy> Wrap<T> where T: Clone { fn get(&self) {} }\n",
        ),
        ("equilibrium/friction/mod.rs", "pub mod coupled;\n"),
        (
            "equilibrium/friction/coupled.rs",
            "pub use crate::equilibrium::coupling::Coupling;\n\
             // impl Sliding in a comment\nconst S: &str = \"impl Sliding {\";\n\
             impl Coupling {\n    pub fn roller_arm(&self) -> f64 { self.roller }\n}\n\
             impl std::fmt::Debug for Coupling { }\nfn implied(f: impl Fn() -> Coupling) {}\n",
        ),
        (
            "equilibrium/wrap/mod.rs",
            "impl<T> crate::equilibrium::coupling::Wrap<T> { fn f(&self) {} }\n",
        ),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let found = scattered_impls(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        found,
        [
            "src/equilibrium/friction/coupled: `impl Coupling` away from its type in equilibrium::coupling",
            "src/equilibrium/wrap: `impl Wrap` away from its type in equilibrium::coupling",
        ],
    );
}
