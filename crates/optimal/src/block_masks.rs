//! Counting the unperceived entries of a long target list a block at a time.
//!
//! The order statistic ([`crate::heuristic`]) walks a position's targets by descending bound
//! until it has passed s + 1 unperceived ones: hundreds of entries per bounded state, one bit
//! test each. Consecutive entries of such a list are near one another on the map, so their
//! bits fall in a few words of the perceived bitset. Each block of 64 entries is kept here
//! as its (word, bits) pairs; the unperceived entries of a block are then counted with a
//! few popcounts, and only the block that holds the answer is walked entry by entry.
//!
//! Where a list's neighbours are scattered (rings of equal distance on an open map: 62
//! words per block on a warehouse map, 11 on the corridor floor), a block of more than
//! [`MAX_PAIRS`] words keeps no pairs and is counted entry by entry, as without blocks: no
//! slower and no larger than the list itself.

use crate::heuristic::has;
use crate::room::{room_bytes, room_for};

/// Entries per block.
pub(crate) const BLOCK: usize = 64;
/// Most (word, bits) pairs a block keeps; a block spread over more words is counted entry
/// by entry.
const MAX_PAIRS: usize = 32;

/// The blocks of any number of target lists, appended one list after another.
#[derive(Default)]
pub(crate) struct BlockMasks {
    /// Per block: the first of its pairs in `pairs` (one more entry closes the last block;
    /// a block without pairs is counted entry by entry).
    start: Vec<u32>,
    /// Per block: its targets as (word of the bitset, bits), one pair per word touched.
    pairs: Vec<(u32, u64)>,
    /// Scratch: one block's bits by word (all zero between blocks).
    acc: Vec<u64>,
    /// Scratch: the words of `acc` the block touched.
    touched: Vec<u32>,
}

impl BlockMasks {
    /// Forget every list.
    pub(crate) fn clear(&mut self) {
        self.start.clear();
        self.pairs.clear();
    }

    /// Append the blocks of the list `targets` (its entries in list order); its blocks are
    /// numbered on from those of the lists before it.
    pub(crate) fn push_list(&mut self, targets: impl ExactSizeIterator<Item = u32>) {
        if self.start.is_empty() {
            self.start.push(0);
        }
        // Room first, so that what the memory budget counts grows as it was told.
        let n = targets.len();
        room_for(&mut self.start, n.div_ceil(BLOCK), 0, usize::MAX);
        room_for(&mut self.pairs, n, 0, usize::MAX);
        let mut targets = targets.peekable();
        while targets.peek().is_some() {
            // Gather the block's bits by word (pairs in first-seen order: order is free).
            self.touched.clear();
            for t in targets.by_ref().take(BLOCK) {
                let word = (t >> 6) as usize;
                if word >= self.acc.len() {
                    self.acc.resize(word + 1, 0);
                }
                if self.acc[word] == 0 {
                    self.touched.push(word as u32);
                }
                self.acc[word] |= 1u64 << (t & 63);
            }
            let keep = self.touched.len() <= MAX_PAIRS;
            for &word in &self.touched {
                if keep {
                    self.pairs.push((word, self.acc[word as usize]));
                }
                self.acc[word as usize] = 0;
            }
            self.start.push(self.pairs.len() as u32);
        }
    }

    /// Whether block `b` keeps its pairs (else [`BlockMasks::open`] counts it entry by
    /// entry).
    #[inline]
    pub(crate) fn has_pairs(&self, b: usize) -> bool {
        self.start[b] < self.start[b + 1]
    }

    /// Entries of block `b`, whose (value, target) entries are `entries`, not set in `bits`.
    #[inline]
    pub(crate) fn open(&self, b: usize, bits: &[u64], entries: &[(f64, u32)]) -> usize {
        let (lo, hi) = (self.start[b] as usize, self.start[b + 1] as usize);
        if lo == hi {
            return entries.iter().filter(|&&(_, t)| !has(bits, t)).count();
        }
        self.pairs[lo..hi]
            .iter()
            .map(|&(word, m)| (m & !bits[word as usize]).count_ones() as usize)
            .sum()
    }

    /// The bytes [`BlockMasks::push_list`] may add for a list of `n` targets.
    pub(crate) fn growth_bytes(&self, n: usize) -> usize {
        room_bytes(&self.start, n.div_ceil(BLOCK), 0, usize::MAX)
            + room_bytes(&self.pairs, n, 0, usize::MAX)
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.start.capacity() * 4
            + self.pairs.capacity() * 16
            + self.acc.capacity() * 8
            + self.touched.capacity() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Every block's count equals the bit tests of its entries, over several lists of
        /// distinct targets, in order (blocks of few words, kept as pairs) or shuffled over
        /// 64 words (blocks counted entry by entry), and random perceived sets.
        #[test]
        fn block_counts_are_the_unperceived_entries(
            lists in proptest::collection::vec(
                (any::<bool>(), proptest::sample::subsequence((0u32..4096).collect::<Vec<_>>(), 0..300))
                    .prop_flat_map(|(shuffle, list)| {
                        let kept = Just(list.clone()).boxed();
                        if shuffle { Just(list).prop_shuffle().boxed() } else { kept }
                    }),
                1..4,
            ),
            seen in proptest::collection::vec(any::<u64>(), 64),
        ) {
            let mut masks = BlockMasks::default();
            for list in &lists {
                masks.push_list(list.iter().copied());
            }
            let mut b = 0;
            for list in &lists {
                let entries: Vec<(f64, u32)> = list.iter().map(|&t| (0.0, t)).collect();
                for block in entries.chunks(BLOCK) {
                    let want = block
                        .iter()
                        .filter(|&&(_, t)| !has(&seen, t))
                        .count();
                    prop_assert_eq!(masks.open(b, &seen, block), want);
                    b += 1;
                }
            }
        }
    }
}
