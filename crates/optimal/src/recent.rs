//! The perceived sets and reachable components of recently expanded states, kept so that
//! a state's own are rebuilt from its nearest kept ancestor's instead of from the root.
//!
//! A state stores only its position and its parent; its perceived set is the union of what
//! the positions along its parent chain perceive, rebuilt on every expansion, and its
//! cluster actions need R, the perceived free cells the robot can reach
//! ([`crate::cluster_rows`]), found by a span fill over the whole of R. A child perceives
//! everything its ancestors did, and its R holds every ancestor's R (each ancestor's R is
//! connected, lies in the child's perceived free space, and holds the cell the robot left
//! it from; see [`crate::cluster_rows::ClusterRows::candidates`]). So from a kept
//! ancestor the perceived set needs only the positions below it, and the fill only the
//! cells the ancestor's R did not hold.
//!
//! The last [`Recent::new`]`(slots, ..)` expanded states are kept in a ring; a state's slot
//! is valid while the ring has not come round to it. Which states are kept changes only
//! the work, never a result (debug builds check each fill from an ancestor against a fill
//! from scratch). An engineering cache, not from the paper.
//!
//! On the corridor floor a state's parent was expanded up to a couple of thousand
//! expansions before it, half of them within 256; a ring of 1,024 (2.3 kB a slot there)
//! made the benchmark 3.5 % faster under criterion (7 % in a plain loop of solves), 256
//! about as much, 64 nothing; keeping every state was slower (its memory touched afresh).

use crate::cluster_rows::Reach;

/// Sentinel: no slot (and no state).
pub(crate) const NONE: u32 = u32::MAX;

/// A ring of recently expanded states' perceived sets (marks and rows) and reachable
/// components (rows and their row range).
pub(crate) struct Recent {
    /// Words of the marks' bitset.
    marks: usize,
    /// Words of a row set.
    rows: usize,
    /// Per slot: the state kept there, or `NONE`.
    owner: Vec<u32>,
    /// Per slot: marks, perceived rows, then R's rows.
    data: Vec<u64>,
    /// Per slot: R's first and last rows.
    span: Vec<(usize, usize)>,
    /// The slot written next.
    next: usize,
}

impl Recent {
    /// A ring of `slots` states (0: none kept) for `marks` words of marks and `rows` words
    /// of rows.
    pub(crate) fn new(slots: usize, marks: usize, rows: usize) -> Self {
        Self {
            marks,
            rows,
            owner: vec![NONE; slots],
            data: vec![0; slots * (marks + 2 * rows)],
            span: vec![(0, 0); slots],
            next: 0,
        }
    }

    /// Bytes per slot.
    pub(crate) fn slot_bytes(marks: usize, rows: usize) -> usize {
        8 * (marks + 2 * rows) + 4 + 16
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.owner.len() * Self::slot_bytes(self.marks, self.rows)
    }

    /// `slot` if it still holds state `id` (`slot` as [`Recent::keep`] returned it, or
    /// `NONE`).
    #[inline]
    pub(crate) fn find(&self, id: u32, slot: u32) -> Option<usize> {
        (slot != NONE && self.owner[slot as usize] == id).then_some(slot as usize)
    }

    /// The perceived marks kept in `slot`.
    pub(crate) fn marks(&self, slot: usize) -> &[u64] {
        let o = slot * (self.marks + 2 * self.rows);
        &self.data[o..o + self.marks]
    }

    /// The perceived rows kept in `slot`.
    pub(crate) fn seen_rows(&self, slot: usize) -> &[u64] {
        let o = slot * (self.marks + 2 * self.rows) + self.marks;
        &self.data[o..o + self.rows]
    }

    /// R's rows and row range kept in `slot`.
    pub(crate) fn reach(&self, slot: usize) -> Reach<'_> {
        let o = slot * (self.marks + 2 * self.rows) + self.marks + self.rows;
        (&self.data[o..o + self.rows], self.span[slot])
    }

    /// Keep state `id`'s perceived marks and rows and its R (rows and row range), in place
    /// of the oldest kept state; returns the slot (`NONE` if none is kept).
    pub(crate) fn keep(
        &mut self,
        id: u32,
        marks: &[u64],
        seen_rows: &[u64],
        reach: Reach<'_>,
    ) -> u32 {
        if self.owner.is_empty() {
            return NONE;
        }
        let slot = self.next;
        self.next = (self.next + 1) % self.owner.len();
        self.owner[slot] = id;
        self.span[slot] = reach.1;
        let o = slot * (self.marks + 2 * self.rows);
        let d = &mut self.data[o..o + self.marks + 2 * self.rows];
        let (m, rest) = d.split_at_mut(self.marks);
        let (s, r) = rest.split_at_mut(self.rows);
        m.copy_from_slice(marks);
        s.copy_from_slice(seen_rows);
        r.copy_from_slice(reach.0);
        slot as u32
    }
}
