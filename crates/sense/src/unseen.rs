//! What a scan can still tell: which cells some robot of a team has sensed, which two
//! robots have, and the blocks of the map where a scan by a given robot would report
//! anything new.
//!
//! A ray reaches a cell only through a free cell next to it (the sensor's own cell is
//! free), so a cell that is not free in the ground truth and has no free 8-neighbour (the
//! inside of a wall, the world outside the plan) is never seen. With a belief whose classes
//! cannot change once known (a ternary or reflection belief with an exact sensor: a free
//! cell is only ever passed, an obstacle only ever hit) a cell sensed once is known for
//! good, so reporting it again to the robot that sensed it, or to anyone once two robots
//! have (the team's overlap counts a cell once), changes nothing.
//! [`Sensor::scan_unseen`](crate::Sensor::scan_unseen) leaves such cells out and stops
//! looking where only blocks without anything to tell are left. Most of what a robot
//! crossing explored space sees is known, so its scans report little and the belief has
//! little to integrate.
//!
//! The same records give the team's overlap: [`Unseen::record`] counts the cells a scan
//! senses first and those it senses after another robot did.

use grid::{Grid, Occ};

/// Who has sensed what, and where a scan can still tell something (module doc).
#[derive(Clone, Debug)]
pub struct Unseen {
    /// log₂ of the block side in cells.
    shift: u32,
    /// Grid and block-grid sizes.
    width: usize,
    height: usize,
    blocks_wide: usize,
    /// The robot scanning now (see [`look_as`](Self::look_as)).
    viewer: usize,
    /// One bit per cell: some ray could reach it.
    seeable: Vec<u64>,
    /// One bit per cell: some robot sensed it.
    sensed: Vec<u64>,
    /// Teams: one bit per cell: two robots sensed it.
    twice: Vec<u64>,
    /// Teams: per cell, the robot that sensed it first (`u32::MAX`: none).
    first: Vec<u32>,
    /// Words per bitmap of one bit per cell.
    words: usize,
    /// Per robot (`robot * words + word`), one bit per cell: the cell tells that robot
    /// nothing (it sensed the cell, or two robots did). The scans' only question, asked at
    /// every cell a beam enters, is then one bit of a small bitmap instead of reads in
    /// `sensed`, `first` (4 bytes per cell) and `twice`.
    quiet: Vec<u64>,
    /// Where the viewer's row of `quiet` starts.
    viewer_row: usize,
    /// Per block (row-major): seeable cells nobody has sensed.
    unsensed: Vec<u32>,
    /// Teams: per block, the cells sensed by exactly one robot.
    once: Vec<u32>,
    /// Teams: per robot and block (`robot * blocks + block`), the cells sensed by that
    /// robot only.
    own: Vec<u32>,
}

impl Unseen {
    /// Nothing sensed yet by any of `robots` robots in `truth`, counted on blocks of
    /// `2^shift` cells a side (`shift` at most 8).
    pub fn new(truth: &Grid<Occ>, robots: usize, shift: u32) -> Self {
        let shift = shift.min(8);
        let robots = robots.max(1);
        let (w, h) = (truth.width(), truth.height());
        let side = 1usize << shift;
        let (bw, bh) = (w.div_ceil(side), h.div_ceil(side));
        let blocks = bw * bh;
        let words = (w * h).div_ceil(64);
        let team = robots > 1;
        let mut u = Self {
            shift,
            width: w,
            height: h,
            blocks_wide: bw,
            viewer: 0,
            seeable: vec![0; words],
            sensed: vec![0; words],
            twice: if team { vec![0; words] } else { Vec::new() },
            first: if team {
                vec![u32::MAX; w * h]
            } else {
                Vec::new()
            },
            words,
            quiet: vec![0; words * robots],
            viewer_row: 0,
            unsensed: vec![0; blocks],
            once: if team { vec![0; blocks] } else { Vec::new() },
            own: if team {
                vec![0; blocks * robots]
            } else {
                Vec::new()
            },
        };
        let t = truth.data();
        let is_free = |x: usize, y: usize| t[y * w + x] == Occ::Free;
        for y in 0..h {
            for x in 0..w {
                let seeable = is_free(x, y)
                    || (y.saturating_sub(1)..=(y + 1).min(h - 1)).any(|ny| {
                        (x.saturating_sub(1)..=(x + 1).min(w - 1)).any(|nx| is_free(nx, ny))
                    });
                if seeable {
                    let i = y * w + x;
                    u.seeable[i / 64] |= 1 << (i % 64);
                    let b = u.block_of(i);
                    u.unsensed[b] += 1;
                }
            }
        }
        u
    }

    fn block_of(&self, i: usize) -> usize {
        let (x, y) = (i % self.width, i / self.width);
        (y >> self.shift) * self.blocks_wide + (x >> self.shift)
    }

    fn bit(bits: &[u64], i: usize) -> bool {
        bits[i / 64] & (1 << (i % 64)) != 0
    }

    /// Record that robot `r` sensed the cells of flat indices `cells` (in the grid; repeats
    /// allowed). Returns how many it sensed first, and how many it sensed after another
    /// robot had (each cell counted once, when a second robot senses it).
    pub fn record(&mut self, r: usize, cells: impl IntoIterator<Item = u32>) -> (usize, usize) {
        let (mut first, mut overlap) = (0, 0);
        let team = !self.first.is_empty();
        let blocks = self.unsensed.len();
        let own_row = self.row_of(r);
        for c in cells {
            let i = c as usize;
            if i >= self.width * self.height {
                continue;
            }
            let b = self.block_of(i);
            if !Self::bit(&self.sensed, i) {
                self.sensed[i / 64] |= 1 << (i % 64);
                self.quiet[own_row + i / 64] |= 1 << (i % 64);
                if Self::bit(&self.seeable, i) {
                    self.unsensed[b] -= 1;
                }
                first += 1;
                if team {
                    self.first[i] = r as u32;
                    self.once[b] += 1;
                    self.own[r * blocks + b] += 1;
                }
            } else if team && self.first[i] != r as u32 && !Self::bit(&self.twice, i) {
                self.twice[i / 64] |= 1 << (i % 64);
                for q in self.quiet.iter_mut().skip(i / 64).step_by(self.words) {
                    *q |= 1 << (i % 64);
                }
                overlap += 1;
                self.once[b] -= 1;
                self.own[self.first[i] as usize * blocks + b] -= 1;
            }
        }
        (first, overlap)
    }

    /// Make robot `r` the one whose scans [`tells`](Self::tells) and
    /// [`for_each_telling_block`](Self::for_each_telling_block) answer for.
    pub fn look_as(&mut self, r: usize) {
        self.viewer = r;
        self.viewer_row = self.row_of(r);
    }

    /// Where robot `r`'s row of `quiet` starts (a robot beyond the team's counts as the
    /// last one, as a lone robot is robot 0).
    fn row_of(&self, r: usize) -> usize {
        r.min((self.quiet.len() / self.words.max(1)).saturating_sub(1)) * self.words
    }

    /// Whether reporting the cell of flat index `i` (in the grid) to the robot scanning now
    /// changes anything: nobody has sensed it, or one other robot has.
    #[inline]
    pub fn tells(&self, i: usize) -> bool {
        // quiet = sensed by the viewer, or by two robots (a team's second robot to sense a
        // cell sets `twice`, so "sensed by another robot only" is exactly "not quiet")
        !Self::bit(&self.quiet[self.viewer_row..], i)
    }

    /// Whether each of the 64 cells of flat indices `i..i + 64` would tell the robot
    /// scanning now anything, as bit k for cell `i + k` ([`tells`](Self::tells); cells past
    /// the grid's end tell).
    #[inline]
    pub fn telling_bits(&self, i: usize) -> u64 {
        let row = &self.quiet[self.viewer_row..self.viewer_row + self.words];
        let (w, s) = (i / 64, i % 64);
        let lo = row.get(w).map_or(0, |&q| q >> s);
        let hi = match row.get(w + 1) {
            Some(&q) if s > 0 => q << (64 - s),
            _ => 0,
        };
        !(lo | hi)
    }

    /// Whether cell `(x, y)` would tell the robot scanning now anything ([`tells`](Self::tells)).
    pub fn tells_at(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.tells(y * self.width + x)
    }

    /// Call `f(x0, y0, x1, y1)` with the cell box (inclusive, clipped to the grid) of every
    /// block overlapping columns `x0..=x1` and rows `y0..=y1` that holds a seeable cell that
    /// would tell the robot scanning now something; returns how many there were.
    pub fn for_each_telling_block(
        &self,
        (x0, y0): (i64, i64),
        (x1, y1): (i64, i64),
        mut f: impl FnMut(i64, i64, i64, i64),
    ) -> usize {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x0, y0, x1, y1) = (x0.max(0), y0.max(0), x1.min(w - 1), y1.min(h - 1));
        if x0 > x1 || y0 > y1 {
            return 0;
        }
        let s = self.shift;
        let side = 1i64 << s;
        let own = if self.first.is_empty() {
            &[][..]
        } else {
            let n = self.unsensed.len();
            &self.own[self.viewer * n..(self.viewer + 1) * n]
        };
        let mut n = 0;
        for by in (y0 >> s)..=(y1 >> s) {
            for bx in (x0 >> s)..=(x1 >> s) {
                let b = by as usize * self.blocks_wide + bx as usize;
                let others = !own.is_empty() && self.once[b] > own[b];
                if self.unsensed[b] != 0 || others {
                    n += 1;
                    let (cx, cy) = (bx * side, by * side);
                    f(
                        cx,
                        cy,
                        (cx + side - 1).min(w - 1),
                        (cy + side - 1).min(h - 1),
                    );
                }
            }
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::Cell;

    fn boxes(u: &Unseen, to: (i64, i64)) -> Vec<(i64, i64, i64, i64)> {
        let mut v = Vec::new();
        u.for_each_telling_block((0, 0), to, |a, b, c, d| v.push((a, b, c, d)));
        v
    }

    #[test]
    fn walls_inside_and_the_outside_never_tell() {
        let rows = "#####\n#...#\n#####\n#####\n#####\n#####\n";
        let truth = grid::io::parse_ascii(rows, 1.0).unwrap();
        let u = Unseen::new(&truth.cells, 1, 1);
        // Blocks of 2 × 2; the last column is one cell wide; rows 4-5 hold nothing to see.
        assert_eq!(
            boxes(&u, (4, 5)),
            vec![
                (0, 0, 1, 1),
                (2, 0, 3, 1),
                (4, 0, 4, 1),
                (0, 2, 1, 3),
                (2, 2, 3, 3),
                (4, 2, 4, 3)
            ]
        );
    }

    #[test]
    fn a_robot_learns_nothing_from_its_own_cells_and_nobody_from_shared_ones() {
        let truth = grid::io::parse_ascii("....\n....\n", 1.0).unwrap();
        let idx = |x, y| truth.cells.index(Cell::new(x, y)) as u32;
        let left = [idx(0, 0), idx(1, 0), idx(0, 1), idx(1, 1)];
        // One robot: its cells are done.
        let mut one = Unseen::new(&truth.cells, 1, 1);
        assert_eq!(one.record(0, left), (4, 0));
        assert_eq!(one.record(0, left), (0, 0));
        assert!(!one.tells_at(1, 1) && one.tells_at(2, 1));
        assert_eq!(boxes(&one, (3, 1)), vec![(2, 0, 3, 1)]);
        // Two robots: robot 1 still learns from robot 0's cells, until it has sensed them.
        let mut two = Unseen::new(&truth.cells, 2, 1);
        assert_eq!(two.record(0, left), (4, 0));
        two.look_as(1);
        assert!(two.tells_at(0, 0));
        assert_eq!(boxes(&two, (3, 1)).len(), 2);
        two.look_as(0);
        assert!(!two.tells_at(0, 0));
        assert_eq!(boxes(&two, (3, 1)), vec![(2, 0, 3, 1)]);
        assert_eq!(two.record(1, [idx(0, 0), idx(0, 0), idx(1, 0)]), (0, 2));
        two.look_as(1);
        assert!(!two.tells_at(0, 0) && two.tells_at(0, 1));
        assert_eq!(two.record(1, [idx(0, 1), idx(1, 1)]), (0, 2));
        // Everything on the left was sensed by both: no block there tells either robot.
        for r in 0..2 {
            two.look_as(r);
            assert_eq!(boxes(&two, (3, 1)), vec![(2, 0, 3, 1)]);
        }
    }
}
