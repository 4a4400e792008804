//! A fixed ground truth's line of sight, remembered per cell: what [`LosSensor`] sees from
//! a cell depends on the ground truth alone, so runs on the same map (a study's trials,
//! a batch of runs) can share the answer.
//!
//! A study runs thousands of trials on each of a few maps: the `faigl2013` suite runs about
//! 8,500 on each of its nine maps and ranges, and every robot of every trial scans from
//! every cell it enters. Shadow casting ([`crate::shadow`]) costs about the cells it sees
//! plus its shadows' edges, most on maps of scattered obstacles. A [`SightCache`] keeps,
//! per cell of one ground truth, the set of cells seen from it as one bit per cell of the
//! box in range, row after row. The set is made the second time a scan comes from the
//! cell, so that cells scanned from once cost no more than without the cache. A scan from
//! a remembered cell reads its bits 64 at a time against those the robot has still to
//! learn from ([`Unseen::telling_bits`]) and reports them in the same order as
//! [`LosSensor`], through a bitmap of the template's ranks: the same observation, bit for
//! bit (property tests check it).
//!
//! The cache takes its bytes from a [`SightBudget`] it may share with other caches; past
//! them, scans from cells it has not remembered are made as [`LosSensor`] makes them. It
//! can be shared between threads: a cell's set is made once, by whichever scan comes
//! first, and never changes.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};

use grid::{Grid, Occ};

use crate::los::LosSensor;
use crate::sensor::{Observation, Pose, Sensor, observed};
use crate::shadow;
use crate::unseen::Unseen;

/// Per cell of one ground truth, the cells a [`LosSensor`] sees from it (module doc).
#[derive(Debug)]
pub struct SightCache {
    truth: Grid<Occ>,
    sensor: LosSensor,
    /// ⌊range⌋: a set covers offsets `-reach..=reach` on both axes.
    reach: i64,
    /// Per target rank of the sensor's template, its flat-index offset from the origin.
    delta: Vec<isize>,
    /// Per offset of the box (row-major), its target rank (`u32::MAX`: out of range).
    rank: Vec<u32>,
    /// Words of one cell's set: one bit per offset of the box, row after row.
    words: usize,
    /// Per cell, its set once made.
    sets: Vec<OnceLock<Box<[u64]>>>,
    /// Per cell, whether a scan was made from it: a set is made at the second scan from a
    /// cell, so that cells scanned from once cost no more than without the cache.
    visited: Vec<AtomicBool>,
    /// The bytes the sets may still take, shared with other caches.
    budget: Arc<SightBudget>,
    /// The bytes this cache took from `budget`, given back when it is dropped.
    held: AtomicU64,
}

/// Bytes that [`SightCache`]s may still take, shared by the caches a caller makes so that
/// together they stay within what it set aside.
#[derive(Debug)]
pub struct SightBudget {
    left: AtomicU64,
}

impl SightBudget {
    /// A budget of `bytes`.
    pub fn new(bytes: u64) -> Arc<Self> {
        Arc::new(Self {
            left: AtomicU64::new(bytes),
        })
    }

    /// The bytes left.
    pub fn left(&self) -> u64 {
        self.left.load(Ordering::Relaxed)
    }

    /// Take `bytes` if they are left; returns whether they were.
    fn take(&self, bytes: u64) -> bool {
        self.left
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |l| {
                l.checked_sub(bytes)
            })
            .is_ok()
    }

    /// Give back `bytes` taken.
    fn give(&self, bytes: u64) {
        self.left.fetch_add(bytes, Ordering::Relaxed);
    }
}

thread_local! {
    /// One bit per target rank: the cells a scan reports, put in the sensor's order.
    static RANKS: std::cell::RefCell<Vec<u64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The `n ≤ 64` bits of `bits` from bit `at` on, as the low bits of a word.
#[inline]
fn bits_at(bits: &[u64], at: usize, n: usize) -> u64 {
    let (w, s) = (at / 64, at % 64);
    let lo = bits[w] >> s;
    let hi = if s > 0 && s + n > 64 {
        bits[w + 1] << (64 - s)
    } else {
        0
    };
    let word = lo | hi;
    if n == 64 { word } else { word & ((1 << n) - 1) }
}

impl SightCache {
    /// Bytes one remembered cell takes for `sensor`: its set and the allocator's header.
    pub fn set_bytes(sensor: &LosSensor) -> u64 {
        let side = 2 * sensor.template().range().floor() as u64 + 1;
        (side * side).div_ceil(64) * 8 + 16
    }

    /// Bytes the cache takes before it remembers any cell, for a truth of `cells` cells:
    /// its copy of the truth, a slot and a mark per cell, and its tables.
    pub fn base_bytes(cells: usize, sensor: &LosSensor) -> u64 {
        let side = 2 * sensor.template().range().floor() as u64 + 1;
        let per_cell = std::mem::size_of::<OnceLock<Box<[u64]>>>()
            + std::mem::size_of::<AtomicBool>()
            + std::mem::size_of::<Occ>();
        (cells * per_cell) as u64 + sensor.template().targets() as u64 * 8 + side * side * 4
    }

    /// Bytes the cache takes with every cell of a truth of `cells` cells remembered.
    pub fn full_bytes(cells: usize, sensor: &LosSensor) -> u64 {
        Self::base_bytes(cells, sensor) + cells as u64 * Self::set_bytes(sensor)
    }

    /// A cache of what `sensor` sees in `truth` (a copy is kept), taking its bytes, its
    /// own ([`base_bytes`](Self::base_bytes)) and its sets', from `budget`; `None` if the
    /// budget cannot pay for its own.
    pub fn new(truth: &Grid<Occ>, sensor: LosSensor, budget: Arc<SightBudget>) -> Option<Self> {
        let base = Self::base_bytes(truth.len(), &sensor);
        if !budget.take(base) {
            return None;
        }
        let t = sensor.template();
        let reach = t.range().floor() as i64;
        let side = (2 * reach + 1) as usize;
        let w = truth.width() as isize;
        let mut delta = vec![0isize; t.targets()];
        let mut rank = vec![u32::MAX; side * side];
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                if let Some(k) = t.rank(dx as i32, dy as i32) {
                    delta[k as usize] = dy as isize * w + dx as isize;
                    rank[(dy + reach) as usize * side + (dx + reach) as usize] = k;
                }
            }
        }
        let mut sets = Vec::new();
        sets.resize_with(truth.len(), OnceLock::new);
        let mut visited = Vec::new();
        visited.resize_with(truth.len(), AtomicBool::default);
        Some(Self {
            truth: truth.clone(),
            sensor,
            reach,
            delta,
            rank,
            words: (side * side).div_ceil(64),
            sets,
            visited,
            held: AtomicU64::new(base),
            budget,
        })
    }

    /// Whether this cache answers for scans of `truth` with the line-of-sight sensor of
    /// range `range_cells`: the same ground truth, cell for cell, and the same targets.
    pub fn serves(&self, truth: &Grid<Occ>, range_cells: f64) -> bool {
        let same_range = LosSensor::new(range_cells)
            .is_ok_and(|s| s.template().max_d2() == self.sensor.template().max_d2());
        same_range
            && self.truth.width() == truth.width()
            && self.truth.height() == truth.height()
            && self.truth.data() == truth.data()
    }

    /// The sensor whose scans this cache remembers.
    pub fn sensor(&self) -> &LosSensor {
        &self.sensor
    }

    /// The set of cell `i`, made now if it is not yet and the budget allows.
    fn set_of(&self, i: usize) -> Option<&[u64]> {
        let slot = &self.sets[i];
        if let Some(s) = slot.get() {
            return Some(s);
        }
        if !self.visited[i].swap(true, Ordering::Relaxed) {
            return None;
        }
        let bytes = Self::set_bytes(&self.sensor);
        if !self.budget.take(bytes) {
            return None;
        }
        let mut made = false;
        let set = slot.get_or_init(|| {
            made = true;
            self.make(i)
        });
        if made {
            self.held.fetch_add(bytes, Ordering::Relaxed);
        } else {
            self.budget.give(bytes);
        }
        Some(set)
    }

    /// Scan from cell `i` and keep the offsets seen.
    fn make(&self, i: usize) -> Box<[u64]> {
        let mut set = vec![0u64; self.words].into_boxed_slice();
        let origin = self.truth.cell(i);
        let w = self.truth.width() as i64;
        let side = 2 * self.reach + 1;
        let mut obs = Observation::new();
        self.sensor
            .scan(&self.truth, Pose::new(origin, 0.0), &mut obs);
        for &(j, _) in &obs.cells {
            let (dx, dy) = (
                i64::from(j) % w - i64::from(origin.x),
                i64::from(j) / w - i64::from(origin.y),
            );
            let b = ((dy + self.reach) * side + dx + self.reach) as usize;
            set[b / 64] |= 1 << (b % 64);
        }
        set
    }

    /// Report the cells of cell `i`'s set whose bits `tells(flat index)` gives (bit k for
    /// the cell at index + k, 64 at a time), in the sensor's order.
    fn report(
        &self,
        i: usize,
        set: &[u64],
        tells: impl Fn(usize) -> u64,
        out: &mut Vec<(u32, Occ)>,
    ) {
        let data = self.truth.data();
        let (w, h) = (self.truth.width() as i64, self.truth.height() as i64);
        let (ox, oy) = ((i as i64) % w, (i as i64) / w);
        let r = self.reach;
        let side = 2 * r + 1;
        // The box clipped to the grid, in offsets.
        let (dx0, dx1) = ((-r).max(-ox), r.min(w - 1 - ox));
        let (dy0, dy1) = ((-r).max(-oy), r.min(h - 1 - oy));
        RANKS.with(|ranks| {
            let mut ranks = ranks.borrow_mut();
            let words = self.delta.len().div_ceil(64);
            if ranks.len() < words {
                ranks.resize(words, 0);
            }
            let (mut first, mut last) = (usize::MAX, 0usize);
            for dy in dy0..=dy1 {
                let row = (dy + r) * side;
                let at_grid = ((oy + dy) * w + ox) as usize;
                let mut dx = dx0;
                while dx <= dx1 {
                    let n = ((dx1 - dx + 1) as usize).min(64);
                    let b = (row + dx + r) as usize;
                    let mut hits = bits_at(set, b, n) & tells((at_grid as i64 + dx) as usize);
                    while hits != 0 {
                        let bb = b + hits.trailing_zeros() as usize;
                        hits &= hits - 1;
                        let k = self.rank[bb] as usize;
                        ranks[k / 64] |= 1 << (k % 64);
                        first = first.min(k / 64);
                        last = last.max(k / 64);
                    }
                    dx += n as i64;
                }
            }
            for wi in first..=last.min(words.saturating_sub(1)) {
                let mut bits = std::mem::take(&mut ranks[wi]);
                while bits != 0 {
                    let k = wi * 64 + bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let j = (i as isize + self.delta[k]) as usize;
                    out.push((j as u32, observed(data[j])));
                }
            }
        });
    }
}

impl Drop for SightCache {
    fn drop(&mut self) {
        self.budget.give(*self.held.get_mut());
    }
}

impl SightCache {
    /// [`Sensor::scan`] of the cache's ground truth from `pose`: the same observation.
    pub fn scan(&self, pose: Pose, out: &mut Observation) {
        match self
            .truth
            .checked_index(pose.cell)
            .and_then(|i| Some((i, self.set_of(i)?)))
        {
            Some((i, set)) => {
                out.clear();
                out.origin = pose.cell;
                self.report(i, set, |_| u64::MAX, &mut out.cells);
            }
            None => self.sensor.scan(&self.truth, pose, out),
        }
    }

    /// [`Sensor::scan_unseen`] of the cache's ground truth from `pose`: the same
    /// observation.
    pub fn scan_unseen(&self, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        let columns = shadow::octant_columns(pose.cell, self.sensor.template().range(), unseen);
        let cached = columns.iter().any(|&c| c != 0).then(|| {
            let i = self.truth.checked_index(pose.cell)?;
            Some((i, self.set_of(i)?))
        });
        match cached.flatten() {
            Some((i, set)) => {
                out.clear();
                out.origin = pose.cell;
                self.report(i, set, |j| unseen.telling_bits(j), &mut out.cells);
            }
            None => self
                .sensor
                .scan_unseen_within(&self.truth, pose, unseen, &columns, out),
        }
    }
}
