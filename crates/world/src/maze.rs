//! `maze`: a perfect random maze, as in the multi-robot coordination study (50 × 40 cells
//! at 0.5 m by default).
//!
//! The maze lives on a lattice of 1 m pitch: every lattice square has a wall on its top
//! and left side (0.2 m thick, at least one cell) and a corridor in the rest, so at 0.5 m a
//! corridor and a wall are one cell each, and at finer resolutions the same maze is drawn with
//! thinner walls and wider corridors. The maze is carved by a randomised depth-first search
//! (recursive backtracker), so it is a spanning tree of the lattice: exactly one path between
//! any two squares. Space left over at the right and bottom edge, less than one pitch, is
//! wall.

use grid::{Grid, Occ};

use crate::raster::{Scale, fill_rect};
use crate::rng::Draws;

/// Distance between lattice lines in metres.
pub const PITCH_M: f64 = 1.0;
/// Wall thickness of the maze in metres (at least one cell).
pub const MAZE_WALL_M: f64 = 0.2;

/// Generate a maze of `width_m × height_m` metres at `res` m/cell.
pub fn maze(width_m: f64, height_m: f64, res: f64, rng: &mut Draws) -> Grid<Occ> {
    let scale = Scale { res };
    let (w, h) = (
        scale.cell(width_m).max(1) as usize,
        scale.cell(height_m).max(1) as usize,
    );
    let tw = scale.cells_at_least_one(MAZE_WALL_M);
    let wall_m = tw as f64 * res;
    let nx = (((width_m - wall_m) / PITCH_M).floor() as usize).max(1);
    let ny = (((height_m - wall_m) / PITCH_M).floor() as usize).max(1);
    // first cell of lattice line i
    let line = |i: usize| scale.cell(i as f64 * PITCH_M);
    let mut cells = Grid::new(w, h, Occ::Occupied);
    for j in 0..ny {
        for i in 0..nx {
            fill_rect(
                &mut cells,
                line(i) + tw,
                line(i + 1),
                line(j) + tw,
                line(j + 1),
                Occ::Free,
            );
        }
    }
    // randomised depth-first search over lattice squares
    let mut visited = vec![false; nx * ny];
    let mut stack = vec![0usize];
    visited[0] = true;
    let mut options = [0usize; 4];
    while let Some(&s) = stack.last() {
        let (i, j) = (s % nx, s / nx);
        let mut n = 0;
        if i + 1 < nx && !visited[s + 1] {
            options[n] = s + 1;
            n += 1;
        }
        if j + 1 < ny && !visited[s + nx] {
            options[n] = s + nx;
            n += 1;
        }
        if i > 0 && !visited[s - 1] {
            options[n] = s - 1;
            n += 1;
        }
        if j > 0 && !visited[s - nx] {
            options[n] = s - nx;
            n += 1;
        }
        if n == 0 {
            stack.pop();
            continue;
        }
        let t = options[rng.below(n)];
        visited[t] = true;
        stack.push(t);
        // knock down the wall between squares s and t
        let (a, b) = (s.min(t), s.max(t));
        let (ai, aj) = (a % nx, a / nx);
        if b == a + 1 {
            let x = line(ai + 1);
            fill_rect(
                &mut cells,
                x,
                x + tw,
                line(aj) + tw,
                line(aj + 1),
                Occ::Free,
            );
        } else {
            let y = line(aj + 1);
            fill_rect(
                &mut cells,
                line(ai) + tw,
                line(ai + 1),
                y,
                y + tw,
                Occ::Free,
            );
        }
    }
    cells
}
