//! What a command reads and writes, checked against each other before any work: an output
//! is never one of the files the command reads (the map, the image a ROS YAML names, the
//! clutter map), nor the file another of its outputs writes, under whatever name it is
//! given (`./x` and `/abs/x`, a symbolic link, a hard link). A folder of outputs is checked
//! file by file.

use std::path::{Path, PathBuf};

use anyhow::{Result, bail};

/// Where writing to `path` puts the bytes: through symbolic links (also one whose target
/// does not exist yet), in an absolute folder. Falls back to `path` where a folder cannot
/// be resolved (the write then fails on its own).
pub fn written_at(path: &Path) -> PathBuf {
    let mut path = path.to_path_buf();
    // A chain of links; 40 as the kernel's limit.
    for _ in 0..40 {
        match std::fs::read_link(&path) {
            Ok(target) => {
                path = match path.parent() {
                    Some(dir) if target.is_relative() => dir.join(target),
                    _ => target,
                }
            }
            Err(_) => break,
        }
    }
    if let Ok(full) = path.canonicalize() {
        return full;
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    match (dir.canonicalize(), path.file_name()) {
        (Ok(dir), Some(name)) => dir.join(name),
        _ => path,
    }
}

/// Whether `a` and `b` name one file: the same file that exists (also through hard links,
/// [`grid::io::same_existing_file`]), or the same place for a file not made yet.
pub fn same_file(a: &Path, b: &Path) -> bool {
    if a.exists() && b.exists() {
        return grid::io::same_existing_file(a, b);
    }
    written_at(a) == written_at(b)
}

/// The files a map file's loading opens: the file and, for a ROS YAML, the image it names.
pub fn files_of_map(path: &Path) -> Vec<PathBuf> {
    let mut files = vec![path.to_path_buf()];
    files.extend(grid::io::ros_image_of(path));
    files
}

/// The files one command reads and writes, each named by the flag that gave it.
#[derive(Default)]
pub struct Files {
    reads: Vec<(String, PathBuf)>,
    /// (flag, path, whether it is a folder of outputs)
    writes: Vec<(String, PathBuf, bool)>,
}

impl Files {
    /// No file read or written yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The command reads the map file `path` (given as `flag`): the file and, for a ROS
    /// YAML, its image.
    pub fn reads_map(&mut self, flag: &str, path: &Path) {
        for (k, file) in files_of_map(path).into_iter().enumerate() {
            let what = if k == 0 {
                format!("the {flag} it reads")
            } else {
                format!("the image of the {flag} it reads")
            };
            self.reads.push((what, file));
        }
    }

    /// The command reads the files of the map source (`--map`, `--clutter-map`).
    pub fn reads_source(&mut self, source: &crate::args::MapSource) {
        if let Some(map) = &source.map {
            self.reads_map("--map", map);
        }
        if let Some(clutter) = &source.clutter_map {
            self.reads_map("--clutter-map", clutter);
        }
    }

    /// The command writes the file `path` given as `flag`: refused if it cannot be
    /// written ([`crate::args::check_output_file`]), is `-`, or is a file the command
    /// reads or another of its outputs.
    pub fn writes(&mut self, flag: &str, path: &Path) -> Result<()> {
        if path.as_os_str() == "-" {
            bail!(
                "{flag} -: expected a file name, found '-' (standard output is not written \
                 to; name /dev/stdout for it)"
            );
        }
        self.clash(flag, path, path, "file")?;
        crate::args::check_output_file(flag, path)?;
        self.writes
            .push((flag.to_string(), path.to_path_buf(), false));
        Ok(())
    }

    /// [`Files::writes`] for a file of one format, whose name must end in one of `exts`
    /// (lower case, any case accepted): `--gif run.png` wrote a GIF under a PNG's name.
    pub fn writes_as(&mut self, flag: &str, path: &Path, exts: &[&str], what: &str) -> Result<()> {
        // An input it would lose, or a folder, is the worse mistake: said first.
        self.writes(flag, path)?;
        // A link (/dev/stdout) or a device names no format.
        if std::fs::symlink_metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
            return Ok(());
        }
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !ext.as_deref().is_some_and(|e| exts.contains(&e)) {
            let names = exts
                .iter()
                .map(|e| format!(".{e}"))
                .collect::<Vec<_>>()
                .join(" or ");
            let found = match path.extension() {
                Some(e) => format!("'.{}'", e.to_string_lossy()),
                None => "no extension".to_string(),
            };
            bail!(
                "{flag} {}: expected a file name ending in {names} (it writes {what}), found {found}",
                path.display()
            );
        }
        Ok(())
    }

    /// The command writes the files `names` into the folder `dir` given as `flag`:
    /// refused if `dir` is a file, or one of its files is a folder, a file the command
    /// reads or another output. The folder is made later ([`make_output_folder`]).
    pub fn writes_into(&mut self, flag: &str, dir: &Path, names: &[&str]) -> Result<()> {
        crate::args::check_output_folder(flag, dir)?;
        self.clash(flag, dir, dir, "folder")?;
        self.writes
            .push((flag.to_string(), dir.to_path_buf(), true));
        for name in names {
            let path = dir.join(name);
            if path.is_dir() {
                bail!(
                    "{flag} {}: expected a folder where {name} can be written, found a folder \
                     {}",
                    dir.display(),
                    path.display()
                );
            }
            self.clash(flag, dir, &path, "file")?;
            self.writes.push((flag.to_string(), path, false));
        }
        Ok(())
    }

    /// Refuse `path` (written for `flag` given `given`: the file or folder (`kind`), or
    /// the folder it is in) if it is a file read or written.
    fn clash(&self, flag: &str, given: &Path, path: &Path, kind: &str) -> Result<()> {
        let (expected, own) = if given == path {
            (
                format!("a {kind} other than the files the command reads"),
                format!("a {kind} of its own"),
            )
        } else {
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            (
                format!("a folder whose {name} is not a file the command reads"),
                format!("a folder whose {name} is a file of its own"),
            )
        };
        if let Some((what, r)) = self.reads.iter().find(|(_, r)| same_file(r, path)) {
            bail!(
                "{flag} {}: expected {expected}, found {what} ({})",
                given.display(),
                r.display()
            );
        }
        if let Some((other, w, folder)) = self.writes.iter().find(|(_, w, _)| same_file(w, path)) {
            bail!(
                "{flag} {}: expected {own}, found the {} {other} writes ({})",
                given.display(),
                if *folder { "folder" } else { "file" },
                w.display()
            );
        }
        Ok(())
    }
}

/// Write the file `path` whole or not at all: `write` fills a new file beside it, which
/// then takes its name, so that a command stopped while writing (Ctrl-C during a long
/// recording) leaves the file that was there, or none, never a cut-off one under the name
/// (the new one stays as a hidden `.NAME.PID.part`). A path that is not a plain file or
/// nothing yet (a symbolic link such as `/dev/stdout`, a device, a pipe) is written in
/// place, through it.
pub fn write_whole(path: &Path, write: impl FnOnce(std::fs::File) -> Result<()>) -> Result<()> {
    let plain = match std::fs::symlink_metadata(path) {
        Ok(m) => m.is_file(),
        Err(e) => e.kind() == std::io::ErrorKind::NotFound,
    };
    let Some(name) = path.file_name().filter(|_| plain) else {
        return write(std::fs::File::create(path)?);
    };
    let part = path.with_file_name(format!(
        ".{}.{}.part",
        name.to_string_lossy(),
        std::process::id()
    ));
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&part)?;
    match write(file).and_then(|()| Ok(std::fs::rename(&part, path)?)) {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = std::fs::remove_file(&part);
            Err(e)
        }
    }
}

/// An output folder a command made: removed again when it is dropped still empty (the
/// command failed before it wrote anything), so that a failing command leaves no folder.
#[must_use]
pub struct MadeFolder {
    dir: PathBuf,
    made: bool,
}

impl Drop for MadeFolder {
    fn drop(&mut self) {
        if self.made {
            // Fails, as it should, once the folder holds anything.
            let _ = std::fs::remove_dir(&self.dir);
        }
    }
}

/// Create the output folder `flag` names (or reuse it) and check that files can be
/// written in it, so that a bad path is refused before the work rather than after it.
pub fn make_output_folder(flag: &str, dir: &Path) -> Result<MadeFolder> {
    crate::args::check_output_folder(flag, dir)?;
    let made = !dir.exists();
    if let Err(e) = std::fs::create_dir_all(dir) {
        bail!(
            "{flag} {}: expected a folder that can be made, found {e}",
            dir.display()
        );
    }
    let folder = MadeFolder {
        dir: dir.to_path_buf(),
        made,
    };
    // A folder that is there may not be ours to write in (another user's, read-only).
    let probe = dir.join(format!(".frontier-write-check-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(folder)
        }
        Err(e) => bail!(
            "{flag} {}: expected a folder files can be written in, found {e}",
            dir.display()
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// Regression: an `--mcap` recording was written in place, so a run stopped while
    /// writing it left a cut-off file under its name (4.5 MiB of willow's). A write that
    /// fails half-way leaves the file that was there, and a whole one replaces it; no part
    /// file is left either way.
    #[test]
    fn a_file_is_written_whole_or_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.mcap");
        std::fs::write(&path, b"the earlier recording").unwrap();
        let e = write_whole(&path, |mut f| {
            f.write_all(b"half of a new one")?;
            anyhow::bail!("stopped")
        });
        assert!(e.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"the earlier recording");
        write_whole(&path, |mut f| Ok(f.write_all(b"a new recording")?)).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"a new recording");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["run.mcap"]);
    }
}
