//! The table of scenario keys in docs/usage.md names every key the scenario parser takes,
//! at the top level and in `[[env]]`, `[[strategy]]` and `[optimal]`, and no key it
//! refuses; and its table of CSV columns names every column `bench export` writes.

use bench::{Plan, Source, Unbuilt};

/// The keys the parser takes in the table `table` (`""`: the top level): those its
/// refusal of an unknown key lists.
fn parser_keys(table: &str) -> Vec<String> {
    let text = match table {
        "" => "zzz_unknown = 1\n".to_string(),
        "env" | "strategy" => format!("[[{table}]]\nzzz_unknown = 1\n"),
        _ => format!("[{table}]\nzzz_unknown = 1\n"),
    };
    let src = Source {
        file: "s.toml".into(),
        text,
        dir: None,
    };
    let e = Plan::resolve(&src, Unbuilt::Error)
        .expect_err("an unknown key is refused")
        .to_string();
    let list = e
        .split("expected one of ")
        .nth(1)
        .unwrap_or_else(|| panic!("no list of keys in: {e}"));
    list.lines()
        .next()
        .unwrap_or("")
        .split(", ")
        .map(|k| k.trim().trim_matches('`').to_string())
        .collect()
}

/// The rows of the keys table of docs/usage.md as (first column, whole row).
fn doc_rows() -> Vec<(String, String)> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/usage.md");
    let text = std::fs::read_to_string(path).expect("docs/usage.md");
    let start = text
        .find("| key | what | default |")
        .expect("the keys table");
    text[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let first = l.split('|').nth(1).unwrap_or("").trim();
            (first.trim_matches('`').to_string(), l.to_string())
        })
        .collect()
}

#[test]
fn usage_md_names_every_scenario_key() {
    let rows = doc_rows();
    let row_of = |name: &str| {
        rows.iter()
            .find(|(k, _)| k == name)
            .map(|(_, r)| r.clone())
            .unwrap_or_else(|| panic!("docs/usage.md's keys table has no row `{name}`"))
    };
    let top = parser_keys("");
    for key in &top {
        let row = match key.as_str() {
            "env" => "[[env]]",
            "strategy" => "[[strategy]]",
            "optimal" => "[optimal]",
            k => k,
        };
        row_of(row);
    }
    for (k, _) in &rows {
        let bare = k.trim_matches(|c| c == '[' || c == ']');
        assert!(
            top.iter().any(|t| t == bare),
            "documented key `{k}` is refused"
        );
    }
    for (table, row) in [
        ("env", "[[env]]"),
        ("strategy", "[[strategy]]"),
        ("optimal", "[optimal]"),
    ] {
        let text = row_of(row);
        for key in parser_keys(table) {
            assert!(
                text.contains(&format!("`{key}`")),
                "docs/usage.md's `{row}` row does not name `{key}`"
            );
        }
    }
}

/// The columns table of docs/usage.md names every column of `bench export`'s CSV, and no
/// other.
#[test]
fn usage_md_names_every_csv_column() {
    let dir = tempfile::tempdir().unwrap();
    let text = "name = \"c\"\nstrategies = [\"cf\"]\n[[env]]\nkind = \"maze\"\nseeds = [0]\n\
                size = [6, 5]\nresolution = 0.5\n";
    let src = Source {
        file: "c.toml".into(),
        text: text.into(),
        dir: None,
    };
    let plan = Plan::resolve(&src, Unbuilt::Error).unwrap();
    let db = dir.path().join("c.sqlite");
    bench::runner::run(&plan, &db, &bench::RunOptions::default()).unwrap();
    let csv = dir.path().join("c.csv");
    bench::Store::open_read_only(&db)
        .unwrap()
        .export_csv(&csv)
        .unwrap();
    let out = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = out.lines().next().unwrap().split(',').collect();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/usage.md");
    let doc = std::fs::read_to_string(path).expect("docs/usage.md");
    let start = doc.find("| column | what |").expect("the columns table");
    let mut documented = Vec::new();
    for line in doc[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
    {
        let first = line
            .split(" | ")
            .next()
            .unwrap_or("")
            .trim_start_matches("| ");
        documented.extend(first.split(", ").map(|c| c.trim_matches('`').to_string()));
    }
    assert_eq!(
        documented, header,
        "docs/usage.md's columns table, in CSV order"
    );
}
