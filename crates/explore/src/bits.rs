//! A set of cells as one bit per cell of the map.
//!
//! The sets that decisions keep over the whole map (frontier cells, goal candidates, the
//! visited and inaccessible goals, region marks) hold few cells scattered along the
//! frontiers. As bits, a 4 KiB page covers 32,768 cells (16 rows of a 2000-cell map) where
//! a `u32` per cell covers 1,024 cells of one row: a set of frontier cells then touches a
//! few dozen pages instead of thousands, and on a new map every first touch of a page is a
//! page fault.

/// Cells `0..len` as bits, all absent at first (a zeroed allocation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CellBits {
    words: Vec<u64>,
    len: usize,
}

impl CellBits {
    /// No cell of `0..len` present.
    pub fn new(len: usize) -> Self {
        Self {
            words: vec![0; len.div_ceil(64)],
            len,
        }
    }

    /// Number of cells the set is for.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the set is for no cells at all.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether cell `i` is present (false for `i ≥ len`).
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        i < self.len && (self.words[i >> 6] >> (i & 63)) & 1 != 0
    }

    /// Add cell `i < len`.
    #[inline]
    pub fn insert(&mut self, i: usize) {
        assert!(i < self.len, "cell {i} outside a set of {} cells", self.len);
        self.words[i >> 6] |= 1 << (i & 63);
    }

    /// Remove cell `i < len`.
    #[inline]
    pub fn remove(&mut self, i: usize) {
        assert!(i < self.len, "cell {i} outside a set of {} cells", self.len);
        self.words[i >> 6] &= !(1 << (i & 63));
    }

    /// Add cell `i < len` if `present`, else remove it.
    #[inline]
    pub fn set(&mut self, i: usize, present: bool) {
        if present {
            self.insert(i);
        } else {
            self.remove(i);
        }
    }

    /// Add (`present`) or remove every cell of `a..=b` (`a ≤ b < len`), a word at a time.
    pub fn set_range(&mut self, a: usize, b: usize, present: bool) {
        assert!(
            a <= b && b < self.len,
            "cells {a}..={b} outside a set of {}",
            self.len
        );
        let (ka, kb) = (a >> 6, b >> 6);
        for k in ka..=kb {
            let lo = if k == ka { a & 63 } else { 0 };
            let hi = if k == kb { b & 63 } else { 63 };
            let mask = (u64::MAX << lo) & (u64::MAX >> (63 - hi));
            if present {
                self.words[k] |= mask;
            } else {
                self.words[k] &= !mask;
            }
        }
    }

    /// The 64 cells `64 k..64 k + 64` as a word (bit j: cell `64 k + j`).
    #[inline]
    pub fn word(&self, k: usize) -> u64 {
        self.words[k]
    }

    /// Cells `from..from + out.len()` as bytes, 1 present and 0 absent (a row of an
    /// observation layer): eight cells per table look-up, not a bit test per cell.
    ///
    /// # Panics
    /// If the cells run past `len`.
    pub fn bytes_into(&self, from: usize, out: &mut [u8]) {
        assert!(
            from + out.len() <= self.len,
            "cells {from}..{} outside a set of {} cells",
            from + out.len(),
            self.len
        );
        let mut i = from;
        let mut out = out;
        // Up to the next multiple of 8, one cell at a time.
        while !i.is_multiple_of(8) && !out.is_empty() {
            out[0] = u8::from(self.contains(i));
            out = &mut out[1..];
            i += 1;
        }
        let mut chunks = out.chunks_exact_mut(8);
        for chunk in &mut chunks {
            let byte = (self.words[i >> 6] >> (i & 63)) as u8;
            chunk.copy_from_slice(&BYTES_OF_BITS[byte as usize].to_le_bytes());
            i += 8;
        }
        for b in chunks.into_remainder() {
            *b = u8::from(self.contains(i));
            i += 1;
        }
    }
}

/// For each byte of bits, the eight bytes 0 or 1 they stand for (bit j → byte j, little
/// endian).
static BYTES_OF_BITS: [u64; 256] = {
    let mut t = [0u64; 256];
    let mut b = 0;
    while b < 256 {
        let mut j = 0;
        while j < 8 {
            if b >> j & 1 != 0 {
                t[b] |= 1 << (8 * j);
            }
            j += 1;
        }
        b += 1;
    }
    t
};

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Inserts and removes in any order: the bits hold what a `Vec<bool>` holds.
        #[test]
        fn behaves_as_a_bool_per_cell(
            len in 0usize..200,
            ops in proptest::collection::vec((0usize..200, any::<bool>()), 0..300),
        ) {
            let mut bits = CellBits::new(len);
            let mut oracle = vec![false; len];
            for (i, add) in ops {
                if i >= len {
                    prop_assert!(!bits.contains(i));
                    continue;
                }
                if add {
                    bits.insert(i);
                } else {
                    bits.remove(i);
                }
                oracle[i] = add;
                for (c, &o) in oracle.iter().enumerate() {
                    prop_assert_eq!(bits.contains(c), o);
                }
            }
            prop_assert_eq!(bits.len(), len);
        }

        /// Any run of cells as bytes is each cell's `contains`, at any alignment.
        #[test]
        fn bytes_into_is_contains_per_cell(
            len in 0usize..300,
            present in proptest::collection::vec(0usize..300, 0..150),
            from in 0usize..300,
            n in 0usize..300,
        ) {
            let mut bits = CellBits::new(len);
            for i in present.into_iter().filter(|&i| i < len) {
                bits.insert(i);
            }
            let from = from.min(len);
            let n = n.min(len - from);
            let mut out = vec![7u8; n];
            bits.bytes_into(from, &mut out);
            for (k, &b) in out.iter().enumerate() {
                prop_assert_eq!(b, u8::from(bits.contains(from + k)), "cell {}", from + k);
            }
        }

        /// Ranges set and cleared a word at a time: the bits hold what a `Vec<bool>` holds.
        #[test]
        fn ranges_behave_as_a_bool_per_cell(
            len in 1usize..300,
            ops in proptest::collection::vec((0usize..300, 0usize..300, any::<bool>()), 0..40),
        ) {
            let mut bits = CellBits::new(len);
            let mut oracle = vec![false; len];
            for (a, b, add) in ops {
                let (a, b) = (a.min(b) % len, a.max(b) % len);
                let (a, b) = (a.min(b), a.max(b));
                bits.set_range(a, b, add);
                oracle[a..=b].fill(add);
                for (c, &o) in oracle.iter().enumerate() {
                    prop_assert_eq!(bits.contains(c), o, "cell {}", c);
                }
            }
        }
    }
}
