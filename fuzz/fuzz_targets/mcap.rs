//! MCAP recordings given as a map (`--map run.mcap`): raw bytes, the last OccupancyGrid on
//! the only grid topic, and on `/map`; read a record at a time within a 1 MiB budget; and
//! with a file size that the bytes do not match (a file that shrank or grew while read).
#![no_main]
use grid::memory::Available;
use libfuzzer_sys::fuzz_target;
use record::mcap_read::{last_map, read_last_map};

fuzz_target!(|bytes: &[u8]| {
    let _ = last_map(bytes, None);
    let _ = last_map(bytes, Some("/map"));
    let len = bytes.len() as u64;
    let _ = read_last_map(bytes, len, Some("/map"), Some(Available::budget(1 << 20)));
    let _ = read_last_map(bytes, len / 2, None, None);
    let _ = read_last_map(bytes, len.saturating_mul(2) + 64, None, None);
});
