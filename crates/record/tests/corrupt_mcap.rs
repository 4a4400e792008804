//! Corrupt recordings are refused with an error, never read into huge allocations: the test
//! binary's allocator records the largest single request.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, recording the largest size asked for.
struct Largest;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Largest = Largest;

/// Read `bytes` as a map recording: the error, and the largest allocation asked for (one
/// test at a time, so that the largest is this read's).
fn read(bytes: &[u8]) -> (String, usize) {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    LARGEST.store(0, Ordering::Relaxed);
    let e = record::last_map(bytes, None).unwrap_err().to_string();
    assert!(record::last_map(bytes, Some("/map")).is_err());
    (e, LARGEST.load(Ordering::Relaxed))
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
