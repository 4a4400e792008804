//! Results databases: any bytes as a file, opened read-only (export, report, merge inputs)
//! and read in full, then opened for writing (resume) and claimed.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let path = frontier_fuzz::temp_file("fuzz.sqlite", bytes);
    if let Ok(store) = bench::Store::open_read_only(&path) {
        let _ = store.study();
        let _ = store.rows();
        let _ = store.envs();
        let _ = store.optimal_paths();
    }
    if let Ok(store) = bench::Store::open_raw(&path) {
        let _ = store.claim("fuzz", "0");
        let _ = store.finished();
        let _ = store.rows();
    }
    frontier_fuzz::remove_database(&path);
});
