//! Scoring a segmentation against ground-truth rooms: room precision, recall and F1 and the
//! adjusted Rand index (Hubert & Arabie 1985), as room-segmentation benchmarks report them
//! (e.g. Bormann et al. 2016).
//!
//! A ground-truth room is *recovered* when one segment covers at least [`OVERLAP`] of it and
//! at least [`OVERLAP`] of that segment lies in it. With a threshold above one half a room
//! matches at most one segment and a segment at most one room, so recall = matches / rooms
//! and precision = matches / segments.
//!
//! Both are counted over the cells that are free and labelled in both partitions: cells the
//! ground truth leaves out (doorways drawn closed) and cells outside the segmentation (not
//! free) are ignored, and so are segments and rooms with no such cell.

use super::graph::NONE;

/// Fraction of overlap, both ways, for a room to count as recovered.
pub const OVERLAP: f64 = 0.8;

/// The scores of one segmentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoomScores {
    /// Matched segments / segments.
    pub precision: f64,
    /// Matched rooms / rooms.
    pub recall: f64,
    /// Harmonic mean of precision and recall (0 when both are 0).
    pub f1: f64,
    /// Adjusted Rand index of the two partitions of the common cells.
    pub ari: f64,
    /// Segments with common cells.
    pub segments: usize,
    /// Rooms with common cells.
    pub rooms: usize,
    /// Rooms recovered.
    pub matched: usize,
}

/// Score `segments` (one label per cell, [`NONE`] = not segmented) against `truth` (one
/// room id per cell, 0 = no room). Both slices describe the same grid.
pub fn score(segments: &[u32], truth: &[u32]) -> RoomScores {
    assert_eq!(segments.len(), truth.len(), "partitions of different grids");
    // the contingency table as sorted (segment, room) keys with counts
    let mut keys: Vec<u64> = segments
        .iter()
        .zip(truth)
        .filter(|&(&s, &t)| s != NONE && t != 0)
        .map(|(&s, &t)| (u64::from(s) << 32) | u64::from(t))
        .collect();
    keys.sort_unstable();
    let mut table: Vec<(u32, u32, u64)> = Vec::new();
    let mut k = 0;
    while k < keys.len() {
        let mut e = k;
        while e < keys.len() && keys[e] == keys[k] {
            e += 1;
        }
        table.push(((keys[k] >> 32) as u32, keys[k] as u32, (e - k) as u64));
        k = e;
    }
    let n = keys.len() as u64;
    // marginals, as sorted (id, count)
    let mut seg_sizes: Vec<(u32, u64)> = Vec::new();
    for &(s, _, c) in &table {
        match seg_sizes.last_mut() {
            Some((id, total)) if *id == s => *total += c,
            _ => seg_sizes.push((s, c)),
        }
    }
    let mut by_room: Vec<(u32, u64)> = table.iter().map(|&(_, t, c)| (t, c)).collect();
    by_room.sort_unstable();
    let mut room_sizes: Vec<(u32, u64)> = Vec::new();
    for (t, c) in by_room {
        match room_sizes.last_mut() {
            Some((id, total)) if *id == t => *total += c,
            _ => room_sizes.push((t, c)),
        }
    }
    let size_of = |v: &[(u32, u64)], id: u32| -> u64 {
        v.binary_search_by_key(&id, |p| p.0)
            .map(|i| v[i].1)
            .unwrap_or(0)
    };
    let mut matched = 0;
    for &(s, t, c) in &table {
        let (ss, ts) = (size_of(&seg_sizes, s), size_of(&room_sizes, t));
        if c as f64 >= OVERLAP * ts as f64 && c as f64 >= OVERLAP * ss as f64 {
            matched += 1;
        }
    }
    let (segs, rooms) = (seg_sizes.len(), room_sizes.len());
    let ratio = |a: usize, b: usize| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    let precision = ratio(matched, segs);
    let recall = ratio(matched, rooms);
    let f1 = if precision + recall > 0.0 {
        2.0 * precision * recall / (precision + recall)
    } else {
        0.0
    };
    let pairs = |c: u64| (c as f64) * (c as f64 - 1.0) / 2.0;
    let index: f64 = table.iter().map(|e| pairs(e.2)).sum();
    let sum_a: f64 = seg_sizes.iter().map(|e| pairs(e.1)).sum();
    let sum_b: f64 = room_sizes.iter().map(|e| pairs(e.1)).sum();
    let total = pairs(n);
    let ari = if total == 0.0 {
        1.0
    } else {
        let expected = sum_a * sum_b / total;
        let max = 0.5 * (sum_a + sum_b);
        if max == expected {
            // both partitions trivial (one block each, or all singletons)
            if index == max { 1.0 } else { 0.0 }
        } else {
            (index - expected) / (max - expected)
        }
    };
    RoomScores {
        precision,
        recall,
        f1,
        ari,
        segments: segs,
        rooms,
        matched,
    }
}
