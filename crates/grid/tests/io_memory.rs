//! What reading a map allocates, measured by a counting allocator: a reader may hold the
//! file and the map, and little more, whatever the file claims or repeats.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use grid::io::parse_ascii;

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

/// One measurement at a time: the tests of this file share the counters.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// The result of `f` and the most bytes it held at once beyond what was live before it.
fn peak_of<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let before = LIVE.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    let out = f();
    (out, PEAK.load(Ordering::SeqCst) - before)
}

/// Regression: an ASCII map's lines were collected into a list first, 16 bytes a line, so a
/// 200 MB file of newlines needed 3.2 GB (and aborted under a 4 GB address-space limit)
/// before it was refused as empty. The lines are now walked, not kept.
#[test]
fn regression_ascii_lines_are_not_collected() {
    let blank = "\n".repeat(4_000_000);
    let (result, peak) = peak_of(|| parse_ascii(&blank, 1.0));
    assert!(result.is_err(), "a file of blank lines is empty");
    assert!(peak < 1 << 20, "{peak} bytes to refuse 4 MB of blank lines");

    let column = ".\n".repeat(1_000_000);
    let (result, peak) = peak_of(|| parse_ascii(&column, 1.0));
    let map = result.expect("a 1 x 1000000 map");
    assert_eq!((map.width(), map.height()), (1, 1_000_000));
    // The map's cells (a byte each) and nothing of the lines' size.
    assert!(
        peak < 2_000_000,
        "{peak} bytes for a map of 1,000,000 cells"
    );
}
