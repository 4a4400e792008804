//! `clutter`: furniture outside the laser plane — table tops and chair seats — as a second
//! obstacle layer beside a generated environment's map.
//!
//! Follows Yamauchi (1997), §2.1: in a real office a planar laser misses table tops and
//! chair seats, while sonar and the robot's body meet them. The layer is a `Grid<bool>` of
//! the map's size (true = off-plane obstacle) that sensors which hear it (sonar) and the
//! robot's body read beside the planar map; the map itself, and so every fingerprint, is
//! untouched, and clutter is opt-in (nothing calls [`furnish`] unless asked).
//!
//! Pieces are axis-aligned rectangles placed in rooms and corridor pieces (region ids of
//! the environment): a piece and a one-cell ring around it must lie on free cells of one
//! region, and a piece is kept only if the free space without clutter stays one component
//! under 8-connected motion without corner squeezing, so the robot can still reach every
//! free cell not covered by furniture (deviation: the robot's clearance is not taken into
//! account for this check). Randomness comes only from a generator seeded with the given
//! seed, so the same environment and seed give the same clutter.

use grid::components::{Connectivity, label};
use grid::{Grid, Occ};

use crate::Environment;
use crate::rng::Draws;

/// How densely to furnish an environment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClutterParams {
    /// Tables tried per region.
    pub tables_per_room: usize,
    /// Chairs tried per region.
    pub chairs_per_room: usize,
    /// Table side lengths (long, short) range in metres.
    pub table_m: ((f64, f64), (f64, f64)),
    /// Chair side length range in metres.
    pub chair_m: (f64, f64),
}

impl Default for ClutterParams {
    /// Office furniture: one table (1.2–1.8 m × 0.6–0.9 m) and two chairs (0.4–0.6 m) tried
    /// per region.
    fn default() -> Self {
        Self {
            tables_per_room: 1,
            chairs_per_room: 2,
            table_m: ((1.2, 1.8), (0.6, 0.9)),
            chair_m: (0.4, 0.6),
        }
    }
}

/// The off-plane clutter of `env` for `seed`: true where a table top or chair seat is.
///
/// Environments without room labels get no clutter (an all-false grid).
pub fn furnish(env: &Environment, seed: u64, params: &ClutterParams) -> Grid<bool> {
    let cells = &env.map.cells;
    let (w, h) = (cells.width(), cells.height());
    let mut clutter = Grid::new(w, h, false);
    let Some(rooms) = &env.rooms else {
        return clutter;
    };
    let res = env.map.resolution;
    let mut rng = Draws::new(seed ^ 0x636c_7574_7465_7221); // "clutter!"
    let side = |m: f64| ((m / res).round() as usize).max(1);
    for room in 1..=env.room_count {
        let mut pieces = Vec::with_capacity(params.tables_per_room + params.chairs_per_room);
        for _ in 0..params.tables_per_room {
            let long = side(rng.range(params.table_m.0.0, params.table_m.0.1));
            let short = side(rng.range(params.table_m.1.0, params.table_m.1.1));
            pieces.push(if rng.chance(0.5) {
                (long, short)
            } else {
                (short, long)
            });
        }
        for _ in 0..params.chairs_per_room {
            let s = side(rng.range(params.chair_m.0, params.chair_m.1));
            pieces.push((s, s));
        }
        // Candidate top-left corners: the region's cells, in row-major order.
        let region: Vec<usize> = (0..cells.len()).filter(|&i| rooms[i] == room).collect();
        if region.is_empty() {
            continue;
        }
        for (pw, ph) in pieces {
            let at = region[rng.below(region.len())];
            let (x0, y0) = (at % w, at / w);
            if !fits(cells, rooms, &clutter, room, x0, y0, pw, ph) {
                continue;
            }
            set_rect(&mut clutter, x0, y0, pw, ph, true);
            if !connected(cells, &clutter) {
                set_rect(&mut clutter, x0, y0, pw, ph, false);
            }
        }
    }
    clutter
}

/// Whether a `pw × ph` piece at `(x0, y0)` and a one-cell ring around it lie on free,
/// uncluttered cells of region `room`.
#[allow(clippy::too_many_arguments)]
fn fits(
    cells: &Grid<Occ>,
    rooms: &Grid<u32>,
    clutter: &Grid<bool>,
    room: u32,
    x0: usize,
    y0: usize,
    pw: usize,
    ph: usize,
) -> bool {
    let (w, h) = (cells.width(), cells.height());
    if x0 == 0 || y0 == 0 || x0 + pw + 1 > w || y0 + ph + 1 > h {
        return false;
    }
    (y0 - 1..=y0 + ph).all(|y| {
        (x0 - 1..=x0 + pw).all(|x| {
            let i = y * w + x;
            cells[i] == Occ::Free && rooms[i] == room && !clutter[i]
        })
    })
}

fn set_rect(clutter: &mut Grid<bool>, x0: usize, y0: usize, pw: usize, ph: usize, v: bool) {
    let w = clutter.width();
    for y in y0..y0 + ph {
        for x in x0..x0 + pw {
            clutter[y * w + x] = v;
        }
    }
}

/// Whether the free, uncluttered cells form at most one motion-connected component.
fn connected(cells: &Grid<Occ>, clutter: &Grid<bool>) -> bool {
    let (_, count) = label(
        cells.width(),
        cells.height(),
        |i| cells[i] == Occ::Free && !clutter[i],
        Connectivity::Motion,
    );
    count <= 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{EnvKind, EnvSpec, generate};

    #[test]
    fn offices_get_connected_deterministic_clutter_on_free_cells() {
        let env = generate(&EnvSpec::new(EnvKind::Office, 3)).expect("office");
        let before = env.fingerprint();
        let a = furnish(&env, 5, &ClutterParams::default());
        let b = furnish(&env, 5, &ClutterParams::default());
        assert_eq!(a, b);
        assert_ne!(a, furnish(&env, 6, &ClutterParams::default()));
        assert_eq!(env.fingerprint(), before, "the map itself is untouched");
        let n = a.data().iter().filter(|&&c| c).count();
        assert!(n > 0, "some furniture was placed");
        for i in 0..a.len() {
            if a[i] {
                assert_eq!(env.map.cells[i], Occ::Free);
            }
        }
        assert!(connected(&env.map.cells, &a));
    }

    #[test]
    fn kinds_without_rooms_stay_bare() {
        let env = generate(&EnvSpec::new(EnvKind::Cave, 1)).expect("cave");
        let c = furnish(&env, 1, &ClutterParams::default());
        assert!(c.data().iter().all(|&v| !v));
    }
}
