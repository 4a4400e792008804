//! Helpers shared by the fuzz targets.

use std::path::PathBuf;

/// A file named `name` in a directory private to this fuzzing process, holding `bytes`
/// (parsers that read files, like the map loader and the results store, are fed this way).
pub fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("frontier-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create the fuzzing directory");
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write the input file");
    path
}

/// Remove `path` and the files SQLite keeps beside a database.
pub fn remove_database(path: &std::path::Path) {
    for suffix in ["", "-wal", "-shm", "-journal"] {
        let mut p = path.as_os_str().to_owned();
        p.push(suffix);
        let _ = std::fs::remove_file(PathBuf::from(p));
    }
}
