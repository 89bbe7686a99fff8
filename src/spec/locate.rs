//! Where a key path (`scenes[0].crank.steps`) is in the YAML text: 1-based line and column for
//! messages.

use crate::error::{Error, Location};

/// The second `key:` at the same column as the first, inside the mapping at `parent`.
pub fn locate_duplicate(text: &str, parent: &str, key: &str) -> Option<(usize, usize)> {
    let start = if parent.is_empty() {
        0
    } else {
        locate_offset(text, parent)?
    };
    let first = find_key(text, start, key)?;
    let column = line_column(text, first).1;
    let mut from = first + key.len();
    loop {
        let next = find_key(text, from, key)?;
        let (line, col) = line_column(text, next);
        if col == column {
            return Some((line, col));
        }
        from = next + key.len();
    }
}

/// Attach a location to a value/design error of loading a spec: its key's, else the start of
/// the file (an error of loading a spec always says which file).
pub fn locate_error(error: Error, path: &str, text: &str) -> Error {
    let mut error = locate_key(error, path, text);
    if error.location.is_none() {
        error.location = Some(Location::new(path, 1, 1));
    }
    error
}

/// Attach the location of an error's key path, when it has none yet and the key is in the
/// text: the one locator of errors about a spec's keys, at load and after.
pub fn locate_key(mut error: Error, path: &str, text: &str) -> Error {
    if error.location.is_none() {
        if let Some((line, column)) = error.key_path.as_deref().and_then(|k| locate(text, k)) {
            error.location = Some(Location::new(path, line, column));
        }
    }
    error
}

/// Find the 1-based line and column of a dotted key path (`scenes[0].crank.steps`) in YAML text.
/// Best effort: keys are matched in order as `key:` outside comments; list items of block
/// sequences by indentation, of flow sequences (`[a, b]`) by commas. A list item's location is
/// its value (after `- `), so `scenes[0].effects[1]` points at the effect's name.
pub fn locate(text: &str, key_path: &str) -> Option<(usize, usize)> {
    locate_offset(text, key_path).map(|offset| line_column(text, offset))
}

/// Byte offset of a dotted key path in YAML text (see `locate`).
pub fn locate_offset(text: &str, key_path: &str) -> Option<usize> {
    let mut pos = 0usize;
    let mut hit = None;
    for segment in key_path.split('.') {
        let (key, indices) = match segment.find('[') {
            Some(b) => (&segment[..b], &segment[b..]),
            None => (segment, ""),
        };
        if !key.is_empty() {
            pos = find_key(text, pos, key)?;
            hit = Some(pos);
        }
        for index in indices.split(']').filter(|s| !s.is_empty()) {
            let index = index.strip_prefix('[')?.parse::<usize>().ok()?;
            pos = find_item(text, pos, index)?;
            hit = Some(pos);
        }
    }
    hit
}

fn find_key(text: &str, from: usize, key: &str) -> Option<usize> {
    let mut start = from;
    while let Some(rel) = text[start..].find(key) {
        let (at, end) = quoted_key(text, start + rel, key.len());
        let before_ok = text[..at]
            .chars()
            .next_back()
            .is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        let after = text[end..].trim_start_matches(' ');
        let (line_start, _) = line_of(text, at);
        let in_comment = text[line_start..at].contains('#');
        if before_ok && after.starts_with(':') && !in_comment {
            return Some(at);
        }
        start = start + rel + key.len();
    }
    None
}

/// The span of a key found at `at` (`len` bytes), with the quotes around it when it is
/// written quoted (`"teeth": 9`, `'teeth': 9`): YAML reads those as the same key.
fn quoted_key(text: &str, at: usize, len: usize) -> (usize, usize) {
    let end = at + len;
    for q in ['"', '\''] {
        if text[..at].ends_with(q) && text[end..].starts_with(q) {
            return (at - 1, end + 1);
        }
    }
    (at, end)
}

/// Item `index` of the sequence that is the value of the key (or item) at `from`.
fn find_item(text: &str, from: usize, index: usize) -> Option<usize> {
    let line_end = text[from..].find('\n').map_or(text.len(), |n| from + n);
    // The value on the key's own line: `key: [a, b]` or `- [a, b]`.
    let value = match text[from..line_end].find(": ") {
        Some(colon) => from + colon + 1,
        None => text[from..line_end]
            .find(':')
            .map_or(line_end, |colon| from + colon + 1),
    };
    let value = value + (text[value..line_end].len() - text[value..line_end].trim_start().len());
    if text[value..].starts_with('[') {
        return find_flow_item(text, value, index);
    }
    find_block_item(text, from, line_end, index)
}

/// Item `index` of the flow sequence whose `[` is at `open`.
fn find_flow_item(text: &str, open: usize, index: usize) -> Option<usize> {
    let mut depth = 0usize;
    let mut count = 0usize;
    let mut expect_item = false;
    let mut quote: Option<char> = None;
    let mut comment = false;
    let mut prev = ' ';
    for (rel, c) in text[open..].char_indices() {
        let at = open + rel;
        if comment {
            comment = c != '\n';
        } else if let Some(q) = quote {
            if c == q {
                quote = None;
            }
        } else if c == '#' && prev.is_whitespace() {
            comment = true;
        } else if expect_item && !c.is_whitespace() && c != ']' {
            if count == index {
                return Some(at);
            }
            count += 1;
            expect_item = false;
            if c == '"' || c == '\'' {
                quote = Some(c);
            } else if c == '[' || c == '{' {
                depth += 1;
            }
        } else {
            match c {
                '"' | '\'' => quote = Some(c),
                '[' | '{' => {
                    depth += 1;
                    expect_item = depth == 1;
                }
                ']' | '}' => {
                    depth = depth.checked_sub(1)?;
                    if depth == 0 {
                        return None;
                    }
                }
                ',' if depth == 1 => expect_item = true,
                _ => {}
            }
        }
        prev = c;
    }
    None
}

/// Item `index` of the block sequence on the lines after the key at `from`.
fn find_block_item(text: &str, from: usize, line_end: usize, index: usize) -> Option<usize> {
    let (_, key_indent) = line_of(text, from);
    let mut indent: Option<usize> = None;
    let mut count = 0;
    let mut offset = (line_end + 1).min(text.len());
    for line in text[offset..].split_inclusive('\n') {
        let trimmed = line.trim_start_matches(' ');
        let this_indent = line.len() - trimmed.len();
        let content = trimmed.trim_end();
        if content.is_empty() || content.starts_with('#') {
            offset += line.len();
            continue;
        }
        let is_item = trimmed.starts_with("- ") || content == "-";
        let list_indent = match indent {
            // The value is a block sequence only if its first line is an item under the key.
            None if is_item && this_indent >= key_indent => *indent.insert(this_indent),
            None => return None,
            Some(i) => i,
        };
        if this_indent < list_indent || (this_indent == list_indent && !is_item) {
            return None;
        }
        if this_indent == list_indent {
            if count == index {
                let after_dash = &trimmed[1..];
                let value = after_dash.trim_start_matches(' ');
                return Some(if value.trim_end().is_empty() {
                    offset + this_indent
                } else {
                    offset + this_indent + 1 + (after_dash.len() - value.len())
                });
            }
            count += 1;
        }
        offset += line.len();
    }
    None
}

pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let line = text[..offset].matches('\n').count() + 1;
    (line, line_of(text, offset).1 + 1)
}

/// The start of the line holding `offset`, and the column of `offset` in it (from 0).
pub(super) fn line_of(text: &str, offset: usize) -> (usize, usize) {
    let start = text[..offset].rfind('\n').map_or(0, |n| n + 1);
    (start, offset - start)
}
