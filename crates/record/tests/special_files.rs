//! A recording path that is not a regular file (a device, a pipe, a directory) is refused
//! before a byte is read, with an error naming it.
#![cfg(unix)]

use std::path::Path;
use std::time::{Duration, Instant};

mod common;

use common::Scratch;

/// Load `path` as a recording, which must fail at once; the error's message.
fn refused_quickly(path: &Path) -> String {
    let started = Instant::now();
    let e = record::mcap_read::load_map(path, None, None).expect_err("not a recording");
    assert!(
        started.elapsed() < Duration::from_secs(2),
        "took {:?}",
        started.elapsed()
    );
    e
}

/// Regression: a recording that was a link to `/dev/zero` reported length 0 and was read
/// until memory ran out (2.6 GB in 3 s).
#[test]
fn regression_mcap_dev_zero_is_refused() {
    let dir = Scratch::new("dev-zero");
    let path = dir.0.join("zero.mcap");
    std::os::unix::fs::symlink("/dev/zero", &path).expect("symlink");
    assert_eq!(
        refused_quickly(&path),
        format!(
            "{}: not a regular file: a device, pipe or socket",
            path.display()
        )
    );
}

/// Regression: a recording that was a named pipe waited for ever for a writer.
#[test]
fn regression_mcap_fifo_is_refused() {
    let dir = Scratch::new("fifo");
    let path = dir.0.join("pipe.mcap");
    let made = std::process::Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo {}", path.display());
    assert_eq!(
        refused_quickly(&path),
        format!(
            "{}: not a regular file: a device, pipe or socket",
            path.display()
        )
    );
}

/// A directory is named as one, and a missing file says it cannot be read.
#[test]
fn a_directory_or_a_missing_recording_is_named() {
    let dir = Scratch::new("dir");
    let folder = dir.0.join("run.mcap");
    std::fs::create_dir(&folder).expect("mkdir");
    assert_eq!(
        refused_quickly(&folder),
        format!("{}: not a regular file: a directory", folder.display())
    );
    let missing = dir.0.join("missing.mcap");
    let e = refused_quickly(&missing);
    assert!(
        e.starts_with(&format!("{}: cannot read: ", missing.display())),
        "{e}"
    );
}
