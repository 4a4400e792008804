//! Files that are not regular files (devices, pipes, directories), given as a map or named as
//! a ROS YAML's image, are refused before a byte is read, with an error naming them.
#![cfg(unix)]

mod common;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use grid::io::{LoadOptions, MapErrorKind, load_map, read_bytes, read_bytes_at_most};

/// A ROS map YAML in `dir` whose image is `image`; returns the YAML's path.
fn yaml_naming(dir: &Path, image: &str) -> PathBuf {
    let yaml = dir.join("office.yaml");
    std::fs::write(
        &yaml,
        format!(
            "image: {image}\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n\
             occupied_thresh: 0.65\nfree_thresh: 0.196\n"
        ),
    )
    .expect("write yaml");
    yaml
}

/// A named pipe at `path` (nothing ever writes to it, so reading it would wait for ever).
fn fifo(path: &Path) {
    let made = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo {}", path.display());
}

/// Load `yaml`, which must fail at once; the error's message.
fn refused_quickly(yaml: &Path) -> String {
    let started = Instant::now();
    let e = load_map(yaml, &LoadOptions::default())
        .expect_err("a special file is not a map image")
        .to_string();
    assert!(
        started.elapsed() < Duration::from_secs(2),
        "took {:?}",
        started.elapsed()
    );
    e
}

/// Regression: a YAML whose image was a link to `/dev/zero` was read until memory ran out
/// (2 GB in 3 s); the image is refused unread, the error naming the YAML and the image.
#[test]
fn regression_ros_image_dev_zero_is_refused() {
    let dir = scratch("dev-zero");
    let image = dir.join("zero.pgm");
    std::os::unix::fs::symlink("/dev/zero", &image).expect("symlink");
    let yaml = yaml_naming(&dir, "zero.pgm");
    let e = refused_quickly(&yaml);
    assert_eq!(
        e,
        format!(
            "{}: image file '{}': not a regular file: a device, pipe or socket",
            yaml.display(),
            image.display()
        )
    );
}

/// Regression: a YAML whose image was a named pipe waited for ever for a writer.
#[test]
fn regression_ros_image_fifo_is_refused() {
    let dir = scratch("fifo");
    let image = dir.join("pipe.png");
    fifo(&image);
    let yaml = yaml_naming(&dir, "pipe.png");
    let e = refused_quickly(&yaml);
    assert_eq!(
        e,
        format!(
            "{}: image file '{}': not a regular file: a device, pipe or socket",
            yaml.display(),
            image.display()
        )
    );
}

/// Regression: the image's extension was checked only after reading it, so an image of an
/// unreadable format was read whole (or for ever) first; here a directory named like one.
#[test]
fn regression_ros_image_extension_is_checked_before_reading() {
    let dir = scratch("extension");
    std::fs::create_dir(dir.join("plan.bmp")).expect("mkdir");
    let yaml = yaml_naming(&dir, "plan.bmp");
    let e = refused_quickly(&yaml);
    assert_eq!(
        e,
        format!(
            "{}: field 'image': expected a .pgm or .png file, found \"plan.bmp\"",
            yaml.display()
        )
    );
    // With a readable format's name, the directory is refused as an image.
    std::fs::create_dir(dir.join("plan.pgm")).expect("mkdir");
    let yaml = yaml_naming(&dir, "plan.pgm");
    let e = refused_quickly(&yaml);
    assert_eq!(
        e,
        format!(
            "{}: image file '{}': not a regular file: a directory",
            yaml.display(),
            dir.join("plan.pgm").display()
        )
    );
}

/// Regression: the bounded reader was private to this crate, so other front ends read
/// their files unbounded; it refuses special files and files over the limit by name.
#[test]
fn regression_read_bytes_is_public_and_bounded() {
    let dir = scratch("read-bytes");
    let zero = dir.join("zero.png");
    std::os::unix::fs::symlink("/dev/zero", &zero).expect("symlink");
    let e = read_bytes(&zero).expect_err("a device");
    assert_eq!(
        e.to_string(),
        format!(
            "{}: not a regular file: a device, pipe or socket",
            zero.display()
        )
    );
    let pipe = dir.join("pipe.png");
    fifo(&pipe);
    let e = read_bytes(&pipe).expect_err("a pipe");
    assert!(matches!(e.kind, MapErrorKind::WrongFormat { .. }), "{e}");
    let small = dir.join("small.png");
    std::fs::write(&small, b"0123456789").expect("write");
    assert_eq!(read_bytes(&small).expect("a small file"), b"0123456789");
    assert_eq!(
        read_bytes_at_most(&small, 10).expect("at the limit").len(),
        10
    );
    let e = read_bytes_at_most(&small, 9).expect_err("over the limit");
    assert_eq!(
        e.to_string(),
        format!(
            "{}: file is 10 bytes, more than the limit of 9 bytes",
            small.display()
        )
    );
}

/// A fresh scratch folder for one test, removed when the test ends.
fn scratch(test: &str) -> common::Scratch {
    common::scratch("io-special", test)
}
