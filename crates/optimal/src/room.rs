//! Room in the search's caches, grown in steps the memory budget sees coming.
//!
//! The caches (the positions' views, distance orders and path-cost fields) are vectors
//! appended a position at a time. Left to `Vec`'s doubling, a cache emptied once its
//! entries passed its share of the budget could hold twice that share, and one append
//! could add half of what the search counts between two looks at its budget. Here a cache
//! grows by a quarter of its length (at least the next position's entries), never past its
//! cap, and [`room_bytes`] says beforehand what the next growth would take.

/// Positions whose per-position data (fields, orders) a cache makes room for on first use:
/// a corridor floor start visits about 50, and growing a cache by copying it whole was
/// 3.5 % of that benchmark's time.
pub(crate) const RESERVED_POSITIONS: usize = 64;

/// The capacity [`room_for`] adds to a vector of `len` entries and capacity `cap` for
/// `most` more: none if they fit; else up to a quarter of its length more (at least `most`,
/// and on first use at least `first`), within `limit` entries (or `most`, if more). `None`
/// if `limit` leaves no room: the caller empties the cache.
pub(crate) fn growth(
    len: usize,
    cap: usize,
    most: usize,
    first: usize,
    limit: usize,
) -> Option<usize> {
    let want = len.saturating_add(most);
    if want <= cap {
        return Some(0);
    }
    let limit = limit.max(most);
    if want > limit {
        return None;
    }
    let step = if cap == 0 {
        first.max(most)
    } else {
        most.max(len / 4)
    };
    Some(len.saturating_add(step).min(limit) - cap)
}

/// Make room in `v` for `most` more entries as [`growth`] says; false if `limit` leaves
/// none.
pub(crate) fn room_for<T>(v: &mut Vec<T>, most: usize, first: usize, limit: usize) -> bool {
    match growth(v.len(), v.capacity(), most, first, limit) {
        None => false,
        Some(0) => true,
        Some(g) => {
            v.reserve_exact(v.capacity() + g - v.len());
            true
        }
    }
}

/// The bytes [`room_for`] would add to `v`, or, if `limit` leaves no room, would add once
/// the cache is emptied (it keeps its allocation).
pub(crate) fn room_bytes<T>(v: &Vec<T>, most: usize, first: usize, limit: usize) -> usize {
    growth(v.len(), v.capacity(), most, first, limit)
        .or_else(|| growth(0, v.capacity(), most, first, limit))
        .unwrap_or(0)
        * std::mem::size_of::<T>()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Appending a position at a time, a cache holds at most its limit (or one
        /// position, if more), grows by what `room_bytes` said beforehand, and always has
        /// room for the position it makes room for.
        #[test]
        fn a_cache_grows_as_announced_and_within_its_limit(
            sizes in proptest::collection::vec(1usize..400, 1..200),
            first in 0usize..2000,
            limit in 1usize..5000,
        ) {
            let mut v: Vec<u64> = Vec::new();
            for most in sizes {
                let before = v.capacity();
                let said = room_bytes(&v, most, first, limit);
                if !room_for(&mut v, most, first, limit) {
                    v.clear();
                    prop_assert!(room_for(&mut v, most, first, limit));
                }
                prop_assert_eq!((v.capacity() - before) * 8, said);
                prop_assert!(v.capacity() - v.len() >= most);
                v.extend(std::iter::repeat_n(0, most));
                let most_held = limit.max(most).max(before);
                prop_assert!(v.capacity() <= most_held, "{} > {}", v.capacity(), most_held);
            }
        }
    }
}
