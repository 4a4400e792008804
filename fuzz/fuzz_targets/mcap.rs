//! MCAP recordings given as a map (`--map run.mcap`): raw bytes, the last OccupancyGrid on
//! the only grid topic, and on `/map`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = record::mcap_read::last_map(bytes, None);
    let _ = record::mcap_read::last_map(bytes, Some("/map"));
});
