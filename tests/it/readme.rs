//! The README's spec-key table is one table (a blank line once cut it, and 26 keys rendered as
//! raw text), and it documents every limit of the registry.

#[test]
fn the_spec_key_table_is_whole_and_lists_every_limit() {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let start = readme
        .find("| key | unit | default | meaning |")
        .expect("the spec-key table");
    let section_end = readme[start..]
        .find("\n#")
        .map_or(readme.len(), |i| start + i);
    let lines: Vec<&str> = readme[start..section_end].lines().collect();
    let rows = lines.iter().take_while(|l| l.starts_with('|')).count();
    let stray: Vec<&&str> = lines[rows..]
        .iter()
        .filter(|l| l.starts_with("| `"))
        .collect();
    assert!(
        stray.is_empty(),
        "rows cut off the table by a blank line: {stray:?}"
    );
    let table = lines[..rows].join("\n");
    for l in cycloid::model::quantity::LIMITS {
        let key = format!("| `limits.{}` |", l.key);
        assert!(table.contains(&key), "{key} is not documented");
    }
}
