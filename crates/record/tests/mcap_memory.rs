//! A recording is read a record at a time, never whole. Measured by a counting allocator.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

use record::mcap_read::load_map;
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
    let (result, peak) = peak_of(|| load_map(&path, None));
    let map = result.expect("the map");
    assert_eq!((map.width(), map.height()), (3, 2));
    assert!(peak < 4 << 20, "{peak} bytes to read a 20 MiB recording");
}
