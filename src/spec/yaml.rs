//! YAML text → the raw spec (`raw`), with serde's errors turned into the spec's words and
//! located at `file:line:column`.

use super::locate::locate_duplicate;
use super::raw::*;
use crate::error::{Error, ErrorKind, Location, Result};

pub(crate) fn parse_raw(path: &str, text: &str) -> Result<RawSpec> {
    // Integers too large for any YAML value are left to the typed pass too.
    let typed_error = |m: &str| {
        [
            "duplicate entry with key",
            "invalid type: ",
            "invalid value: ",
        ]
        .iter()
        .any(|p| m.contains(p))
    };
    let empty = "the spec is empty; it needs at least `name`, `reducer` and `scenes`";
    requirements_file(path, text, &syntax(path, text, empty, typed_error)?)?;
    match typed::<RawSpec>(path, text) {
        // An untagged `optimise` that matched no form: parse again as the form the YAML has
        // (a mapping is one study, a list is many) to get the precise key and location.
        Err(e) if e.key_path.as_deref() == Some("optimise") => {
            let shape: serde_yaml::Value = serde_yaml::from_str(text).unwrap_or_default();
            let precise = match shape.get("optimise") {
                Some(serde_yaml::Value::Sequence(_)) => {
                    typed::<RawSpecOf<Vec<RawStudy>>>(path, text).err()
                }
                _ => typed::<RawSpecOf<RawStudy>>(path, text).err(),
            };
            Err(precise.unwrap_or(e))
        }
        other => other,
    }
}

/// YAML syntax first, on an untyped value: a syntax error then carries no key path (the typed
/// pass would name whatever key it had reached, e.g. `name` for a tab on line 2). An empty
/// document is refused with `empty`; the errors `typed_error` picks (duplicate keys) are left
/// to the typed pass, which knows their key path (the value is then null).
fn syntax(
    path: &str,
    text: &str,
    empty: &str,
    typed_error: impl Fn(&str) -> bool,
) -> Result<serde_yaml::Value> {
    let at = |line, column| Location::new(path, line, column);
    match serde_yaml::from_str::<serde_yaml::Value>(text) {
        Ok(serde_yaml::Value::Null) => Err(Error::new(ErrorKind::Syntax, empty).at(at(1, 1))),
        Err(err) if !typed_error(&err.to_string()) => {
            let (line, column) = err.location().map_or((1, 1), |l| (l.line(), l.column()));
            Err(Error::new(ErrorKind::Syntax, yaml_message(&err.to_string())).at(at(line, column)))
        }
        Ok(value) => Ok(value),
        Err(_) => Ok(serde_yaml::Value::Null),
    }
}

/// A requirements file where a spec is read (a top-level key of a requirements file and no
/// `reducer`): refused at that key, pointing to `cycloid design`, rather than as an unknown key.
fn requirements_file(path: &str, text: &str, value: &serde_yaml::Value) -> Result<()> {
    use super::requirements_raw::REQUIREMENTS_KEYS;
    if value.get("reducer").is_some() {
        return Ok(());
    }
    let Some(key) = REQUIREMENTS_KEYS.iter().find(|k| value.get(**k).is_some()) else {
        return Ok(());
    };
    let (line, column) = super::locate::locate(text, key).unwrap_or((1, 1));
    Err(Error::new(
        ErrorKind::Syntax,
        format!(
            "this is a requirements file (top-level `{key}`, no `reducer`), not a spec: \
             `cycloid design {path}` searches the designs that meet it"
        ),
    )
    .at(Location::new(path, line, column)))
}

/// A YAML document of another kind than a spec (a requirements file), with the spec's located
/// errors: syntax first (no key path), then the typed pass (its key path); `what` names the
/// document in the error of an empty file.
pub(crate) fn parse_document<T: serde::de::DeserializeOwned>(
    path: &str,
    text: &str,
    what: &str,
) -> Result<T> {
    let duplicate = |m: &str| m.contains("duplicate entry with key");
    syntax(path, text, &format!("the {what} is empty"), duplicate)?;
    typed(path, text)
}

/// The typed pass: serde's error turned into the spec's words, at its key and location.
fn typed<T: serde::de::DeserializeOwned>(path: &str, text: &str) -> Result<T> {
    let at = |line, column| Location::new(path, line, column);
    let de = serde_yaml::Deserializer::from_str(text);
    serde_path_to_error::deserialize(de).map_err(|err| {
        let key_path = err.path().to_string();
        let key_path = if key_path == "." {
            String::new()
        } else {
            key_path
        };
        let inner = err.into_inner();
        let (line, column) = inner.location().map_or((1, 1), |l| (l.line(), l.column()));
        let (key_path, message, relocated) =
            user_message(text, &key_path, &yaml_message(&inner.to_string()));
        let (line, column) = relocated.unwrap_or((line, column));
        let mut error = Error::new(ErrorKind::Syntax, message).at(at(line, column));
        if !key_path.is_empty() {
            error = error.at_key(key_path);
        }
        error
    })
}

/// serde_yaml's message without what the error already says elsewhere: its own key-path prefix
/// (`reducer: `) and the first ` at line L column C` (the location goes in front instead).
fn yaml_message(message: &str) -> String {
    if message.starts_with("deserializing from YAML containing more than one document") {
        return "more than one YAML document (`---`); a spec is a single document".to_string();
    }
    let mut message = message.to_string();
    if let Some((head, tail)) = message.split_once(": ") {
        let is_path = !head.is_empty()
            && head
                .chars()
                .all(|c| c.is_alphanumeric() || "_.[]?".contains(c));
        if is_path {
            message = tail.to_string();
        }
    }
    if let Some(start) = message.find(" at line ") {
        let rest = &message[start + " at line ".len()..];
        let number = |s: &str| s.len() - s.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        let n = number(rest);
        if n > 0 && rest[n..].starts_with(" column ") {
            let tail = &rest[n + " column ".len()..];
            let m = number(tail);
            if m > 0 {
                message = format!("{}{}", &message[..start], &tail[m..]);
            }
        }
    }
    message
}

/// The names between backticks in a serde message, in order.
fn backticked(message: &str) -> Vec<&str> {
    message.split('`').skip(1).step_by(2).collect()
}

/// Turn serde's wording (fields, Rust types) into the spec's (keys, numbers). Returns the key
/// path, the message and, for a duplicate key, the location of the second occurrence.
fn user_message(
    text: &str,
    key_path: &str,
    message: &str,
) -> (String, String, Option<(usize, usize)>) {
    let join = |parent: &str, key: &str| {
        if parent.is_empty() {
            key.to_string()
        } else {
            format!("{parent}.{key}")
        }
    };
    if let Some(rest) = message.strip_prefix("unknown field ") {
        // serde_path_to_error's path already ends with the unknown key.
        let names = backticked(rest);
        let (unknown, known) = names.split_first().map_or(("", &[][..]), |(u, k)| (*u, k));
        return (key_path.to_string(), unknown_key(unknown, known), None);
    }
    if let Some(rest) = message.strip_prefix("missing field ") {
        return (
            key_path.to_string(),
            format!("missing required key {rest}"),
            None,
        );
    }
    if let Some(rest) = message.strip_prefix("duplicate field ") {
        let key = backticked(rest).first().copied().unwrap_or("");
        let full = join(key_path, key);
        let second = locate_duplicate(text, key_path, key);
        return (full, "key appears twice".to_string(), second);
    }
    // An integer beyond i64: serde_yaml says "invalid value: integer `N`, expected i64" or
    // "invalid type: integer `N` as u128, expected i64".
    let integer = ["invalid value: integer `", "invalid type: integer `"]
        .iter()
        .any(|p| message.starts_with(p));
    if integer && message.ends_with(", expected i64") {
        let digits = backticked(message).first().copied().unwrap_or("");
        return (
            key_path.to_string(),
            format!("integer `{digits}` is out of range"),
            None,
        );
    }
    if message.contains("untagged enum RawObjective") {
        return (
            key_path.to_string(),
            "expected an objective name or a map of objective names to weights".to_string(),
            None,
        );
    }
    let message = message
        .replace("unit value", "null")
        .replace(", expected i64", ", expected an integer")
        .replace(", expected f64", ", expected a number");
    (key_path.to_string(), message, None)
}

/// The refusal of a key not among `known`: the closest known key, or all of them.
pub(crate) fn unknown_key(unknown: &str, known: &[&str]) -> String {
    match did_you_mean(unknown, known.iter().copied()) {
        Some(close) => format!("unknown key; did you mean `{close}`?"),
        None if known.is_empty() => "unknown key; this mapping takes no keys".to_string(),
        None => format!("unknown key; the keys here are {}", known.join(", ")),
    }
}

/// The closest of `known` to `unknown` when it is close enough to be a misspelling.
pub(crate) fn did_you_mean<'a>(
    unknown: &str,
    known: impl Iterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (unknown.chars().count() / 3).max(2);
    known
        .map(|k| (edit_distance(unknown, k), k))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Levenshtein distance over chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (prev + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            prev = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}
