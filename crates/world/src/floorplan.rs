//! Corridor-and-room floor plans, the generator behind `office` and `hospital`.
//!
//! The plan is laid out in metres, then rasterised:
//!
//! 1. Long corridors run along the building's longer side, spanning it wall to wall; between
//!    them lie double-loaded blocks of rooms, along the outer walls single rows of rooms.
//! 2. With two or more long corridors, cross corridors join them (one per
//!    `cross_pitch` metres of length), cutting the inner blocks.
//! 3. Blocks deeper than `depth_max` are split into two rows (each touching one corridor);
//!    rows are chopped into rooms `room_w` wide, sometimes a wider one.
//! 4. Every region (room or corridor piece) is a rectangle bounded by wall centre lines; its
//!    free cells lie between the walls (walls [`WALL_M`] thick, at least one cell).
//! 5. Corridor pieces that meet are joined by openings as wide as the narrower one. Each
//!    room gets one door (0.9–1.2 m) to a corridor it touches, or else — rooms of a second
//!    row that touch no corridor — to a room already reached; a few extra doors between rooms
//!    make loops. Door placement only uses wall stretches shared by both regions' free
//!    cells, so a door never cuts a crossing wall.
//!
//! Room ids: each room and each corridor piece (a long corridor, or the part of a cross
//! corridor between two long corridors) is one region. The cells of a door belong to the room
//! it opens into: a door between a corridor and a room belongs to the room; a door made to
//! reach a room from a room already reached belongs to the newly reached room; an extra loop
//! door belongs to the room listed first in the plan; an opening where a cross corridor meets
//! a long corridor belongs to the cross corridor.

use std::collections::BTreeMap;

use grid::{Grid, Occ};

use crate::raster::{Scale, WALL_M, fill_rect};
use crate::rng::Draws;

/// Shape parameters of a floor plan, in metres.
#[derive(Clone, Copy, Debug)]
pub struct FloorParams {
    /// Range of a corridor's clear width.
    pub corridor_w: (f64, f64),
    /// Target distance between neighbouring long corridors.
    pub strip_pitch: f64,
    /// Target spacing of cross corridors along the long side.
    pub cross_pitch: f64,
    /// Range of a room's width along its corridor.
    pub room_w: (f64, f64),
    /// Deeper blocks are split into two rows of rooms.
    pub depth_max: f64,
    /// Probability that a room is chopped wider than `room_w` (a lab, a ward).
    pub big_room_p: f64,
    /// Probability of an extra door between two neighbouring rooms.
    pub extra_door_p: f64,
}

/// Range of a door's clear width in metres.
const DOOR_M: (f64, f64) = (0.9, 1.2);
/// Preferred distance of a door from the corners of its wall, in metres.
const DOOR_MARGIN_M: f64 = 0.3;
/// Tolerance when comparing metric coordinates that were computed from the same numbers.
const EPS: f64 = 1e-9;

/// An axis-aligned rectangle in metres, bounded by wall centre lines or the building edge.
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Rect {
    fn transposed(self) -> Rect {
        Rect {
            x0: self.y0,
            x1: self.y1,
            y0: self.x0,
            y1: self.x1,
        }
    }
}

/// What a region is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// A long corridor.
    Corridor,
    /// A piece of a cross corridor between two long corridors.
    Cross,
    /// A room.
    Room,
}

impl Kind {
    fn is_corridor(self) -> bool {
        self != Kind::Room
    }
}

/// A region with its metric rectangle and its free cells `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug)]
struct Region {
    rect: Rect,
    kind: Kind,
    cx: (i64, i64),
    cy: (i64, i64),
}

/// Two regions sharing a wall: `across` are the wall's cells between them, `along` the
/// stretch of the wall where both have free cells; `vertical` if the wall runs along y.
#[derive(Clone, Copy, Debug)]
struct Adj {
    a: usize,
    b: usize,
    across: (i64, i64),
    along: (i64, i64),
    vertical: bool,
}

impl Adj {
    fn len(&self) -> i64 {
        self.along.1 - self.along.0
    }
    fn other(&self, r: usize) -> usize {
        if self.a == r { self.b } else { self.a }
    }
}

/// Generate a floor plan of `width_m × height_m` metres at `res` m/cell: the occupancy grid
/// (walls Occupied, everything else Free) and the region id of every free cell (ids from 1,
/// not yet compacted).
pub fn floorplan(
    width_m: f64,
    height_m: f64,
    res: f64,
    p: &FloorParams,
    rng: &mut Draws,
) -> (Grid<Occ>, Grid<u32>) {
    let transpose = height_m > width_m;
    let (long, short) = if transpose {
        (height_m, width_m)
    } else {
        (width_m, height_m)
    };
    let mut plan = layout(long, short, p, rng);
    if transpose {
        for (r, _) in &mut plan {
            *r = r.transposed();
        }
    }
    let scale = Scale { res };
    let (w, h) = (
        scale.cell(width_m).max(1) as usize,
        scale.cell(height_m).max(1) as usize,
    );
    let edge_t = scale.cells_at_least_one(WALL_M);
    let span = |b0: f64, b1: f64, extent: f64, n: usize| -> (i64, i64) {
        let lo = if b0 <= EPS {
            edge_t
        } else {
            scale.wall_end(b0, WALL_M)
        };
        let hi = if b1 >= extent - EPS {
            n as i64 - edge_t
        } else {
            scale.wall_start(b1, WALL_M)
        };
        (lo, hi.max(lo))
    };
    let regions: Vec<Region> = plan
        .iter()
        .map(|&(rect, kind)| Region {
            rect,
            kind,
            cx: span(rect.x0, rect.x1, width_m, w),
            cy: span(rect.y0, rect.y1, height_m, h),
        })
        .collect();

    let mut cells = Grid::new(w, h, Occ::Occupied);
    let mut rooms = Grid::new(w, h, 0u32);
    for (i, r) in regions.iter().enumerate() {
        fill_rect(&mut cells, r.cx.0, r.cx.1, r.cy.0, r.cy.1, Occ::Free);
        fill_rect(&mut rooms, r.cx.0, r.cx.1, r.cy.0, r.cy.1, i as u32 + 1);
    }
    let adjs = adjacencies(&regions);
    doors(&regions, &adjs, p, scale, rng, &mut cells, &mut rooms);
    (cells, rooms)
}

/// The metric plan in canonical orientation (`long` along x): regions in creation order.
fn layout(long: f64, short: f64, p: &FloorParams, rng: &mut Draws) -> Vec<(Rect, Kind)> {
    let mut out = Vec::new();
    // 1. strips across the short side: block, corridor, block, ..., corridor, block
    let mut kh = ((short / p.strip_pitch).round() as usize).max(1);
    let (strips, corridor_pitches) = loop {
        let cws: Vec<f64> = (0..kh)
            .map(|_| rng.range(p.corridor_w.0, p.corridor_w.1) + WALL_M)
            .collect();
        let weights: Vec<f64> = (0..=kh)
            .map(|i| if i == 0 || i == kh { 1.0 } else { 2.0 } * rng.range(0.85, 1.15))
            .collect();
        let avail = short - cws.iter().sum::<f64>();
        let wsum: f64 = weights.iter().sum();
        let depths: Vec<f64> = weights.iter().map(|w| avail * w / wsum).collect();
        let edge_min = depths[0].min(depths[kh]);
        if kh > 1 && edge_min < p.room_w.0 {
            kh -= 1;
            continue;
        }
        // boundaries: y of each block start / corridor start
        let mut strips = Vec::with_capacity(2 * kh + 1);
        let mut y = 0.0;
        for i in 0..=kh {
            let y1 = if i == kh { short } else { y + depths[i] };
            strips.push((y, y1, false));
            y = y1;
            if i < kh {
                strips.push((y, y + cws[i], true));
                y += cws[i];
            }
        }
        break (strips, cws);
    };
    for &(y0, y1, is_corridor) in &strips {
        if is_corridor {
            out.push((
                Rect {
                    x0: 0.0,
                    x1: long,
                    y0,
                    y1,
                },
                Kind::Corridor,
            ));
        }
    }
    // 2. cross corridors, only when there are inner blocks to cut
    let mut crosses: Vec<(f64, f64)> = Vec::new();
    if kh >= 2 {
        let kv = ((long / p.cross_pitch).round() as usize).max(1);
        let gap = long / (kv + 1) as f64;
        for i in 0..kv {
            let cw = corridor_pitches[i % corridor_pitches.len()];
            let c = gap * (i + 1) as f64 + rng.range(-0.25, 0.25) * gap;
            crosses.push((c - cw / 2.0, c + cw / 2.0));
        }
    }
    // 3. blocks: edge strips whole, inner strips cut by the cross corridors
    let n_strips = strips.len();
    for (s, &(y0, y1, is_corridor)) in strips.iter().enumerate() {
        if is_corridor {
            continue;
        }
        let inner = s != 0 && s != n_strips - 1;
        if inner && !crosses.is_empty() {
            let mut x = 0.0;
            for &(c0, c1) in &crosses {
                split_block(
                    Rect {
                        x0: x,
                        x1: c0,
                        y0,
                        y1,
                    },
                    p,
                    rng,
                    &mut out,
                );
                out.push((
                    Rect {
                        x0: c0,
                        x1: c1,
                        y0,
                        y1,
                    },
                    Kind::Cross,
                ));
                x = c1;
            }
            split_block(
                Rect {
                    x0: x,
                    x1: long,
                    y0,
                    y1,
                },
                p,
                rng,
                &mut out,
            );
        } else {
            split_block(
                Rect {
                    x0: 0.0,
                    x1: long,
                    y0,
                    y1,
                },
                p,
                rng,
                &mut out,
            );
        }
    }
    out
}

/// Chop a block into rooms: two rows if deeper than `depth_max`, then rooms along x.
fn split_block(b: Rect, p: &FloorParams, rng: &mut Draws, out: &mut Vec<(Rect, Kind)>) {
    let depth = b.y1 - b.y0;
    if depth > p.depth_max && depth >= 2.0 * p.room_w.0 {
        let mid = b.y0 + depth * rng.range(0.42, 0.58);
        split_block(Rect { y1: mid, ..b }, p, rng, out);
        split_block(Rect { y0: mid, ..b }, p, rng, out);
        return;
    }
    let (wmin, wmax) = p.room_w;
    let mut x = b.x0;
    loop {
        let rest = b.x1 - x;
        let want = if rng.chance(p.big_room_p) {
            rng.range(wmax, 2.0 * wmax)
        } else {
            rng.range(wmin, wmax)
        };
        // stop when what remains is one room, or when cutting would leave a sliver
        if rest <= want + wmin * 0.75 {
            out.push((Rect { x0: x, ..b }, Kind::Room));
            return;
        }
        out.push((
            Rect {
                x0: x,
                x1: x + want,
                ..b
            },
            Kind::Room,
        ));
        x += want;
    }
}

/// All pairs of regions sharing a wall, in a deterministic order.
fn adjacencies(regions: &[Region]) -> Vec<Adj> {
    // index regions by the coordinates where they start, keyed to a micrometre
    let key = |m: f64| (m * 1e6).round() as i64;
    let mut starts_x: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    let mut starts_y: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    for (i, r) in regions.iter().enumerate() {
        starts_x.entry(key(r.rect.x0)).or_default().push(i);
        starts_y.entry(key(r.rect.y0)).or_default().push(i);
    }
    let mut out = Vec::new();
    let overlap = |a: (f64, f64), b: (f64, f64)| a.0.max(b.0) < a.1.min(b.1) - EPS;
    for (i, ri) in regions.iter().enumerate() {
        // j to the right of i: a vertical wall at x = ri.x1
        for &j in starts_x.get(&key(ri.rect.x1)).into_iter().flatten() {
            let rj = &regions[j];
            if overlap((ri.rect.y0, ri.rect.y1), (rj.rect.y0, rj.rect.y1)) {
                let along = (ri.cy.0.max(rj.cy.0), ri.cy.1.min(rj.cy.1));
                out.push(Adj {
                    a: i,
                    b: j,
                    across: (ri.cx.1, rj.cx.0),
                    along,
                    vertical: true,
                });
            }
        }
        // j below i: a horizontal wall at y = ri.y1
        for &j in starts_y.get(&key(ri.rect.y1)).into_iter().flatten() {
            let rj = &regions[j];
            if overlap((ri.rect.x0, ri.rect.x1), (rj.rect.x0, rj.rect.x1)) {
                let along = (ri.cx.0.max(rj.cx.0), ri.cx.1.min(rj.cx.1));
                out.push(Adj {
                    a: i,
                    b: j,
                    across: (ri.cy.1, rj.cy.0),
                    along,
                    vertical: false,
                });
            }
        }
    }
    out
}

/// Carve the cells `along` (from `lo`, `n` long) through the wall of `adj`, owned by `owner`.
fn carve(adj: &Adj, lo: i64, n: i64, owner: usize, cells: &mut Grid<Occ>, rooms: &mut Grid<u32>) {
    let id = owner as u32 + 1;
    let (x0, x1, y0, y1) = if adj.vertical {
        (adj.across.0, adj.across.1, lo, lo + n)
    } else {
        (lo, lo + n, adj.across.0, adj.across.1)
    };
    fill_rect(cells, x0, x1, y0, y1, Occ::Free);
    fill_rect(rooms, x0, x1, y0, y1, id);
}

/// Put a door of random width and position in the shared stretch of `adj`.
fn door(
    adj: &Adj,
    owner: usize,
    scale: Scale,
    rng: &mut Draws,
    cells: &mut Grid<Occ>,
    rooms: &mut Grid<u32>,
) {
    let len = adj.len();
    let dw = scale.cells_at_least_one(rng.range(DOOR_M.0, DOOR_M.1));
    let margin = scale.cell(DOOR_MARGIN_M);
    let (pos, n) = if len >= dw + 2 * margin {
        (
            adj.along.0 + margin + rng.below((len - dw - 2 * margin + 1) as usize) as i64,
            dw,
        )
    } else if len >= dw {
        (adj.along.0 + rng.below((len - dw + 1) as usize) as i64, dw)
    } else {
        (adj.along.0, len)
    };
    carve(adj, pos, n, owner, cells, rooms);
}

/// Join corridors with openings, give every room a door, add a few loop doors.
fn doors(
    regions: &[Region],
    adjs: &[Adj],
    p: &FloorParams,
    scale: Scale,
    rng: &mut Draws,
    cells: &mut Grid<Occ>,
    rooms: &mut Grid<u32>,
) {
    let n = regions.len();
    let mut by_region: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (k, a) in adjs.iter().enumerate() {
        if a.len() > 0 {
            by_region[a.a].push(k);
            by_region[a.b].push(k);
        }
    }
    let mut connected = vec![false; n];
    // corridor network: openings wherever two corridor pieces meet
    for a in adjs.iter().filter(|a| a.len() > 0) {
        let (ka, kb) = (regions[a.a].kind, regions[a.b].kind);
        if ka.is_corridor() && kb.is_corridor() {
            let owner = if ka == Kind::Cross { a.a } else { a.b };
            carve(a, a.along.0, a.len(), owner, cells, rooms);
        }
    }
    // mark the corridor network reachable from the first corridor
    let mut stack = vec![0usize];
    if n > 0 && regions[0].kind.is_corridor() {
        connected[0] = true;
    } else {
        stack.clear();
    }
    while let Some(r) = stack.pop() {
        for &k in &by_region[r] {
            let o = adjs[k].other(r);
            if !connected[o] && regions[o].kind.is_corridor() && regions[r].kind.is_corridor() {
                connected[o] = true;
                stack.push(o);
            }
        }
    }
    let good_len = |a: &Adj| a.len() >= scale.cells_at_least_one(DOOR_M.1 + 2.0 * DOOR_MARGIN_M);
    // pick the adjacency of room r to use: a roomy one at random, else the longest
    let pick = |r: usize, want: &dyn Fn(usize) -> bool, rng: &mut Draws| -> Option<usize> {
        let cands: Vec<usize> = by_region[r]
            .iter()
            .copied()
            .filter(|&k| want(adjs[k].other(r)))
            .collect();
        let good: Vec<usize> = cands
            .iter()
            .copied()
            .filter(|&k| good_len(&adjs[k]))
            .collect();
        if !good.is_empty() {
            Some(good[rng.below(good.len())])
        } else {
            cands
                .iter()
                .copied()
                .max_by_key(|&k| (adjs[k].len(), std::cmp::Reverse(k)))
        }
    };
    // every room touching a connected corridor: a door to one of them
    let mut reached = connected.clone();
    for r in 0..n {
        if regions[r].kind != Kind::Room {
            continue;
        }
        let to_corridor = |o: usize| connected[o] && regions[o].kind.is_corridor();
        if let Some(k) = pick(r, &to_corridor, rng) {
            door(&adjs[k], r, scale, rng, cells, rooms);
            reached[r] = true;
        }
    }
    // rooms of inner rows: a door to a room already reached, until nothing changes
    loop {
        let mut changed = false;
        for r in 0..n {
            if reached[r] || regions[r].kind != Kind::Room {
                continue;
            }
            let snapshot = &reached;
            let to_reached = |o: usize| snapshot[o];
            if let Some(k) = pick(r, &to_reached, rng) {
                door(&adjs[k], r, scale, rng, cells, rooms);
                reached[r] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    // a few extra doors between neighbouring rooms
    for a in adjs {
        if regions[a.a].kind == Kind::Room
            && regions[a.b].kind == Kind::Room
            && good_len(a)
            && rng.chance(p.extra_door_p)
        {
            door(a, a.a, scale, rng, cells, rooms);
        }
    }
}
