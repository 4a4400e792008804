//! The guide is checked: every command block marked `sh runnable` in README.md,
//! CONTRIBUTING.md, CHANGELOG.md, maps/README.md and docs/*.md runs (line by line,
//! `frontier` being this build's binary, in a fresh directory per block) and succeeds, and
//! every relative link of those pages points at a file of the repository.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root (two levels above this crate).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("repository root")
}

/// The guide's pages.
fn pages() -> Vec<PathBuf> {
    let root = root();
    let mut pages: Vec<PathBuf> = [
        "README.md",
        "CONTRIBUTING.md",
        "CHANGELOG.md",
        "maps/README.md",
    ]
    .iter()
    .map(|p| root.join(p))
    .collect();
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// The `sh runnable` blocks of a page: (first line number, lines).
fn runnable_blocks(text: &str) -> Vec<(usize, Vec<String>)> {
    let mut blocks = Vec::new();
    let mut current: Option<(usize, Vec<String>)> = None;
    for (n, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some(block) = current.as_mut() {
            if t.starts_with("```") {
                blocks.push(current.take().expect("open block"));
            } else {
                block.1.push(line.to_string());
            }
        } else if t.starts_with("```") && t.trim_start_matches('`').trim() == "sh runnable" {
            current = Some((n + 2, Vec::new()));
        }
    }
    blocks
}

/// A command line without its comment, split into words (no quoting is used in the guide's
/// runnable blocks).
fn words(line: &str) -> Vec<String> {
    let code = line.split(" #").next().unwrap_or("").trim();
    code.split_whitespace().map(str::to_string).collect()
}

#[test]
fn runnable_blocks_run() {
    let exe = env!("CARGO_BIN_EXE_frontier");
    let mut ran = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("page");
        for (line_no, lines) in runnable_blocks(&text) {
            let dir = tempfile::tempdir().expect("temp dir");
            for (k, line) in lines.iter().enumerate() {
                let w = words(line);
                let Some((cmd, args)) = w.split_first() else {
                    continue;
                };
                assert_eq!(
                    cmd,
                    "frontier",
                    "{}:{}: runnable blocks hold frontier commands only",
                    page.display(),
                    line_no + k
                );
                let out = Command::new(exe)
                    .args(args)
                    .current_dir(dir.path())
                    .output()
                    .expect("run frontier");
                assert!(
                    out.status.success(),
                    "{}:{}: `{}` failed: {}",
                    page.display(),
                    line_no + k,
                    line.trim(),
                    String::from_utf8_lossy(&out.stderr)
                );
                ran += 1;
            }
        }
    }
    assert!(ran > 0, "no runnable command found in the guide");
}

#[test]
fn relative_links_resolve() {
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("page");
        let dir = page.parent().expect("page directory");
        let mut rest = text.as_str();
        while let Some(i) = rest.find("](") {
            rest = &rest[i + 2..];
            let Some(end) = rest.find(')') else { break };
            let target = &rest[..end];
            let file = target.split('#').next().unwrap_or("");
            if file.is_empty() || file.contains("://") || file.starts_with("mailto:") {
                continue;
            }
            assert!(
                dir.join(file).exists(),
                "{}: broken link to {target}",
                page.display()
            );
        }
    }
}

#[test]
fn blocks_are_found() {
    let page = "text\n```sh runnable\nfrontier list  # all\n```\n```sh\nnot this\n```\n";
    let blocks = runnable_blocks(page);
    assert_eq!(blocks, vec![(3, vec!["frontier list  # all".to_string()])]);
    assert_eq!(words(&blocks[0].1[0]), vec!["frontier", "list"]);
}
