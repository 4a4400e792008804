//! A recording's map is checked against the memory available before that memory is spent:
//! the recording is read a record at a time, never whole; a record longer than the memory
//! left is refused from its length; and a map message whose loading would need more is
//! refused from its header, before its cells are copied or decoded. Measured by a counting
//! allocator.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

use grid::memory::Available;
use record::RecordError;
use record::mcap_read::{load_map, read_last_map};
use record::msgs::{OccupancyGrid, RosMessage};

/// The system allocator, counting the bytes live and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::SeqCst) + layout.size();
            PEAK.fetch_max(live, Ordering::SeqCst);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::SeqCst);
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// One test at a time: the tests of this file share the counters.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// This test's turn with the counters.
fn turn() -> MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

/// The result of `f` and the most bytes it held at once beyond what was live before it
/// (call it during a [`turn`]).
fn peak_of<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = LIVE.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let out = f();
    (out, PEAK.load(Ordering::SeqCst) - before)
}

/// A fresh scratch folder for one test, removed when the test ends (also when it fails).
struct Scratch(PathBuf);

impl Scratch {
    fn new(test: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "frontier-record-memory-{}-{test}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch folder");
        Self(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// An OccupancyGrid message (CDR) stating `width × height` cells in its header, with `data`
/// as its cells (which need not be that many).
fn grid_message(width: u32, height: u32, data: Vec<i8>) -> Vec<u8> {
    let mut msg = OccupancyGrid::default();
    msg.header.frame_id = "map".into();
    msg.info.resolution = 0.05;
    msg.info.width = width;
    msg.info.height = height;
    msg.info.origin.orientation.w = 1.0;
    msg.data = data;
    record::cdr::encode(&msg)
}

/// `n` bytes that do not compress, different for each `seed`.
fn noise(n: usize, seed: u64) -> Vec<u8> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64 ^ seed.wrapping_mul(0x2545_f491_4f6c_dd1d);
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        })
        .collect()
}

/// A recording in zstd-compressed chunks: `noise` messages on `/noise`, then the map
/// messages `maps` on `/map`, all logged at 1 ns.
fn recording(noise: &[Vec<u8>], maps: &[Vec<u8>]) -> Vec<u8> {
    let mut out = mcap::WriteOptions::new()
        .profile("ros2")
        .compression(Some(mcap::Compression::Zstd))
        .create(std::io::Cursor::new(Vec::new()))
        .expect("writer");
    let schema = out
        .add_schema(
            OccupancyGrid::TYPE,
            "ros2msg",
            OccupancyGrid::definition().as_bytes(),
        )
        .expect("schema");
    let map = out
        .add_channel(schema, "/map", "cdr", &Default::default())
        .expect("channel");
    let other = out
        .add_channel(0, "/noise", "application/octet-stream", &Default::default())
        .expect("channel");
    let messages = noise
        .iter()
        .map(|m| (other, m))
        .chain(maps.iter().map(|m| (map, m)));
    for (k, (channel_id, data)) in messages.enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: k as u32,
            log_time: 1,
            publish_time: 0,
        };
        out.write_to_known_channel(&header, data).expect("message");
    }
    out.finish().expect("finish");
    out.into_inner().into_inner()
}

/// [`read_last_map`] of `bytes` on `/map` within `memory`.
fn read(bytes: &[u8], memory: Option<Available>) -> Result<grid::GridMap, RecordError> {
    read_last_map(bytes, bytes.len() as u64, Some("/map"), memory).map(|(map, _)| map)
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
    let map = result.expect("the map");
    assert_eq!((map.width(), map.height()), (3, 2));
    assert!(peak < 4 << 20, "{peak} bytes to read a 20 MiB recording");
}
