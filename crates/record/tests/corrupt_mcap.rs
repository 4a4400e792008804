//! Corrupt recordings are refused with an error, never read into huge allocations: the test
//! binary's allocator records the largest single request.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

mod common;

/// The system allocator, recording the largest size asked for and the total.
struct Largest;

static LARGEST: AtomicUsize = AtomicUsize::new(0);
static TOTAL: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        TOTAL.fetch_add(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    // The system's zeroed allocation, so that a large zero-filled test message costs no
    // memory until written.
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        TOTAL.fetch_add(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        TOTAL.fetch_add(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Largest = Largest;

/// Read `bytes` as a map recording: the error, and the largest allocation asked for (one
/// test at a time, so that the largest is this read's).
fn read(bytes: &[u8]) -> (String, usize) {
    let (e, largest, _) = read_built(|| bytes.to_vec());
    (e, largest)
}

/// [`read`] the recording `build` makes, also giving the bytes allocated in all by the first
/// of its two reads. The recording is built in the test's turn too, so that building a large
/// one counts in no other test's read.
fn read_built(build: impl FnOnce() -> Vec<u8>) -> (String, usize, usize) {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let bytes = &build()[..];
    LARGEST.store(0, Ordering::Relaxed);
    TOTAL.store(0, Ordering::Relaxed);
    // Not `unwrap_err`: printing a wrongly accepted map of millions of cells takes minutes.
    let e = match record::last_map(bytes, None) {
        Ok((map, _)) => panic!(
            "expected an error, read a {}x{} map",
            map.width(),
            map.height()
        ),
        Err(e) => e.to_string(),
    };
    let total = TOTAL.load(Ordering::Relaxed);
    assert!(record::last_map(bytes, Some("/map")).is_err());
    (e, LARGEST.load(Ordering::Relaxed), total)
}

/// Regression (found by the `mcap` fuzz target): a record inside a compressed chunk whose
/// length field reads 0x6e6f72662f000009 bytes made `mcap::MessageStream` try to allocate
/// that much and abort the process.
#[test]
fn a_corrupt_chunk_record_length_is_refused_not_allocated() {
    let (e, largest) = read(include_bytes!("data/corrupt-chunk-length.mcap"));
    assert!(e.starts_with("expected an MCAP file, found: "), "{e}");
    assert!(e.contains("length exceeds limit"), "{e}");
    assert!(largest < 16 << 20, "asked for {largest} bytes");
}

/// Regression (the same fuzz target): a 195-byte file whose header record gives a string
/// length of 3.3 GB made mcap's record parser reserve that much before finding the record
/// short. Only schema, channel and message records are read now, with every inner length
/// checked against the record.
#[test]
fn a_corrupt_string_length_is_not_allocated() {
    let (e, largest) = read(include_bytes!("data/header-string-length.mcap"));
    assert!(
        e.starts_with("expected") || e.contains("shorter than its fields"),
        "{e}"
    );
    assert!(largest < 16 << 20, "asked for {largest} bytes");
}

/// A recording of one all-free `width × height` map on `/map` (logged at 1 ns), built
/// without holding the map: the message is a zeroed allocation whose pages are only read.
/// A message of 320 KB of noise on another topic comes first, so that the file is as
/// large as a real recording of such a map (a bare one compresses to 10 KB, whose records
/// are refused as expanding more than any map does).
fn recording_of_free_map(width: u32, height: u32) -> Vec<u8> {
    // Without cells the message ends with the cell count (0); write the real count there
    // and leave the cells (0, free) to the zeroed allocation.
    let head = common::grid_message(width, height, Vec::new());
    let cells = width as usize * height as usize;
    let count = head.len() - 4;
    let mut data = vec![0u8; head.len() + cells];
    data[..count].copy_from_slice(&head[..count]);
    data[count..head.len()].copy_from_slice(&(cells as u32).to_le_bytes());
    common::recording(&[common::noise(320 << 10, 0)], &[data])
}

/// Regression: a recording of about 300 KB holding one 16384×16385 all-free map
/// (268,451,840 cells, over the 2^28 a map file may have) passed the recording's own limit
/// of 2^30 cells: `map info` used 2 GB on it. The message is refused from its record
/// length, before its cells are decompressed.
#[test]
fn regression_mcap_map_over_the_cell_limit_is_refused_before_decompressing() {
    let (e, largest, _) = read_built(|| {
        let bytes = recording_of_free_map(16384, 16385);
        assert!(
            (300 << 10..400 << 10).contains(&bytes.len()),
            "{} bytes",
            bytes.len()
        );
        bytes
    });
    assert!(
        e.starts_with("expected messages of at most 268439552 bytes (a map of at most 268435456 cells and its header), found one of "),
        "{e}"
    );
    assert!(largest < 16 << 20, "asked for {largest} bytes");
}

/// A map just over the cell limit fits the record limit (which leaves room for the message's
/// other fields), so its record is decompressed; it is refused from its header, before its
/// cells are copied or decoded.
#[test]
fn a_map_just_over_the_cell_limit_is_refused_from_its_header() {
    let over = record::occupancy::MAX_CELLS as u32 + 1;
    let (e, largest, total) = read_built(|| recording_of_free_map(1, over));
    assert_eq!(
        e,
        format!(
            "topic /map, message at 1 ns: map message: expected at most 268435456 cells, found 1x{over}"
        )
    );
    // The decompressed record, once.
    assert!(largest < 300 << 20, "asked for {largest} bytes");
    assert!(total < 300 << 20, "allocated {total} bytes in all");
}
