//! A recording's map is checked against the memory available before that memory is spent:
//! the recording is read a record at a time, never whole; a record longer than the memory
//! left is refused from its length; and a map message whose loading would need more is
//! refused from its header, before its cells are copied or decoded. Measured by a counting
//! allocator.

use grid::memory::Available;
use record::RecordError;
use record::mcap_read::{load_map, read_last_map};

mod common;
#[path = "../../grid/tests/common/counting.rs"]
mod counting;

use common::{Scratch, grid_message, noise, recording};
use counting::{peak_of, turn};

/// [`read_last_map`] of `bytes` on `/map` within `memory`.
fn read(bytes: &[u8], memory: Option<Available>) -> Result<grid::GridMap, RecordError> {
    read_last_map(bytes, bytes.len() as u64, Some("/map"), memory).map(|r| r.map)
}

/// Regression: a recording's map was checked against the cell limit only, so a map message
/// whose header claims 16384 x 16384 cells was copied and decoded whatever the memory left;
/// it is refused from its header, naming the topic, the size stated, the bytes needed and
/// the limit, before anything of the map's size is allocated.
#[test]
fn mcap_map_larger_than_memory_is_refused_before_decoding() {
    let _turn = turn();
    // The header claims 2^28 cells (the most a map may have); the data holds 16.
    let message = grid_message(16384, 16384, vec![0; 16]);
    let bytes = recording(&[], std::slice::from_ref(&message));
    let budget = Available::budget(64 << 20);
    let (result, peak) = peak_of(|| read(&bytes, Some(budget)));
    let e = result.expect_err("over the budget");
    assert!(matches!(e, RecordError::OutOfMemory { .. }), "{e:?}");
    // The message, a copy of its cells and the grid: 2 bytes a cell besides the message.
    let needed = (message.len() as u64 + 2 * (1 << 28)).div_ceil(1 << 20);
    assert_eq!(
        e.to_string(),
        format!(
            "topic /map, message at 1 ns: loading this 16384x16384 OccupancyGrid needs about \
             {needed} MiB, more than the memory budget of 64 MiB; record the map with fewer, \
             larger cells (a coarser resolution)"
        )
    );
    assert!(peak < 1 << 20, "{peak} bytes to refuse the map");
    // Unchecked, the same message is refused later, for its data: the memory check comes
    // first.
    let e = read(&bytes, None).expect_err("data too short").to_string();
    assert!(
        e.contains("expected 268435456 cells (16384x16384), found 16"),
        "{e}"
    );

    // From a file, the refusal names it.
    let dir = Scratch::new("claimed");
    let path = dir.0.join("claimed.mcap");
    std::fs::write(&path, &bytes).expect("write");
    let e = load_map(&path, None, Some(budget)).expect_err("over the budget");
    assert!(
        e.starts_with(&format!(
            "{}: topic /map, message at 1 ns: loading this 16384x16384 OccupancyGrid",
            path.display()
        )),
        "{e}"
    );
}

/// The estimate of a map message's loading is what it holds at most: a map recorded
/// honestly (zstd-compressed) loads within the bytes its refusal would name, and is refused
/// below them, before its cells are copied.
#[test]
fn the_estimate_bounds_what_loading_a_recorded_map_holds() {
    let _turn = turn();
    let (w, h) = (1500u32, 1200u32);
    let cells = (w * h) as usize;
    // Rooms of free and unknown cells, some walls: compresses as a real map does.
    let data: Vec<i8> = (0..cells)
        .map(|k| match (k % w as usize / 50 + k / w as usize / 40) % 3 {
            0 => 0,
            1 => -1,
            _ => 100,
        })
        .collect();
    let message = grid_message(w, h, data);
    let bytes = recording(&[noise(64 << 10, 0)], std::slice::from_ref(&message));
    let needed = message.len() as u64 + 2 * cells as u64;

    let (result, peak) = peak_of(|| read(&bytes, None));
    let map = result.expect("an honest map");
    assert_eq!((map.width(), map.height()), (w as usize, h as usize));
    drop(map);
    assert!(
        peak as u64 <= needed,
        "loading held {peak} bytes, more than the {needed} estimated"
    );
    assert!(read(&bytes, Some(Available::budget(needed))).is_ok());

    let (result, peak) = peak_of(|| read(&bytes, Some(Available::budget(needed - 1))));
    let e = result.expect_err("a byte short").to_string();
    assert!(e.contains("loading this 1500x1200 OccupancyGrid"), "{e}");
    // The record is read; neither its copy nor the grid is made.
    assert!(
        (peak as u64) < message.len() as u64 + cells as u64 / 2,
        "{peak} bytes to refuse a message of {} bytes",
        message.len()
    );
}

/// A record longer than the memory left is refused from its length, before it is read.
#[test]
fn a_record_longer_than_the_memory_left_is_refused_unread() {
    let _turn = turn();
    let small = grid_message(2, 2, vec![0; 4]);
    let bytes = recording(&[noise((3 << 20) - (64 << 10), 0)], &[small]);
    let (result, peak) = peak_of(|| read(&bytes, Some(Available::budget(1 << 20))));
    let e = result.expect_err("over the budget");
    assert!(matches!(e, RecordError::RecordOutOfMemory(_)), "{e:?}");
    assert!(
        e.to_string().starts_with(
            "reading a record of 3 MiB needs about 3 MiB, more than the memory budget of 1 MiB; "
        ),
        "{e}"
    );
    assert!(peak < 1 << 20, "{peak} bytes to refuse a 3 MiB record");
    assert!(read(&bytes, Some(Available::budget(8 << 20))).is_ok());
}

/// Regression: a recording was read whole before its map was looked for, so a recording
/// of a long run (many messages, a small map) needed its whole size in memory; it is read a
/// record at a time.
#[test]
fn a_recording_is_read_a_record_at_a_time() {
    let _turn = turn();
    let dir = Scratch::new("stream");
    let path = dir.0.join("run.mcap");
    let chatter: Vec<Vec<u8>> = (0..320).map(|k| noise(64 << 10, k)).collect();
    let bytes = recording(&chatter, &[grid_message(3, 2, vec![0, 100, -1, 0, 0, 0])]);
    assert!(bytes.len() > 20 << 20, "{} bytes", bytes.len());
    std::fs::write(&path, &bytes).expect("write");
    drop(bytes);
    let (result, peak) = peak_of(|| load_map(&path, None, None));
    let r = result.expect("the map");
    assert_eq!((r.map.width(), r.map.height()), (3, 2));
    assert_eq!(r.topic, "/map");
    assert!(peak < 4 << 20, "{peak} bytes to read a 20 MiB recording");
}
