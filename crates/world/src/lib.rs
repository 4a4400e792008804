//! `world`: ground-truth environments for frontier, generated deterministically from
//! `(kind, seed, size, resolution)`.
//!
//! The kinds follow the environments of the papers frontier reproduces:
//!
//! | kind | after | default |
//! |---|---|---|
//! | `office` | the multi-robot coordination study's offices | 25 m × 20 m at 0.5 m |
//! | `hospital` | Stage's "hospital" (Holz et al. 2010) | 40 m × 24 m at 0.2 m |
//! | `cave` | Stage's "cave" (Holz et al. 2010) | 16 m × 16 m at 0.1 m |
//! | `maze` | the multi-robot coordination study's mazes | 25 m × 20 m (50 × 40 cells) at 0.5 m |
//! | `potholes` | Faigl & Kulich (2013) "potholes" | 40 m × 40 m at 0.2 m |
//! | `empty` | Faigl & Kulich (2013) "em" | 21 m × 24 m at 0.2 m |
//!
//! Every generator designs its world in metres and rasterises it at the requested
//! resolution, so a kind gives a sensible map at 0.5 m and at 0.05 m. The outer boundary is
//! a wall; the free space is one component under 8-connected motion without corner
//! squeezing (guaranteed by construction and, as a last step, by filling any stray pocket);
//! `office` and `hospital` also label every free cell with a room id (rooms and corridor
//! pieces are regions; see [`floorplan`] for which region a door's cells belong to).
//!
//! Randomness comes only from `rand_pcg::Pcg64Mcg::seed_from_u64(seed)`, so an environment
//! is the same, byte for byte, on every run.
//!
//! ```
//! use world::{EnvKind, EnvSpec, generate};
//! let env = generate(&EnvSpec::new(EnvKind::Office, 7)).unwrap();
//! assert_eq!(env.name, "office-s7");
//! assert_eq!((env.map.width(), env.map.height()), (50, 40));
//! assert!(env.room_count > 0);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod cave;
pub mod clutter;
pub mod empty;
pub mod error;
pub mod finish;
pub mod floorplan;
pub mod hospital;
pub mod kind;
pub mod maze;
pub mod office;
pub mod potholes;
pub mod raster;
pub mod rng;

use grid::{Grid, GridMap, Occ};

pub use error::WorldError;
pub use kind::{EnvKind, KindInfo};

/// Largest number of cells a generated grid may have.
pub const MAX_CELLS: usize = 1 << 28;

/// What to generate: a kind, a seed, and optionally a size and resolution other than the
/// kind's defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvSpec {
    /// The kind of environment.
    pub kind: EnvKind,
    /// Seed of the generator's random source.
    pub seed: u64,
    /// Size `(width, height)` in metres; `None` for the kind's default.
    pub size_m: Option<(f64, f64)>,
    /// Resolution in metres per cell; `None` for the kind's default.
    pub resolution: Option<f64>,
}

/// Peak bytes per cell while one environment is generated (measured: 8 for `empty`, 10
/// for `office`, 18 for `cave`, on 20–25 M cells), rounded up: what an estimate made
/// before generating counts.
pub const GENERATE_BYTES_PER_CELL: u64 = 24;

impl EnvSpec {
    /// The number of cells the environment will have, or the spec's error, found without
    /// generating it.
    pub fn cells(&self) -> Result<u64, WorldError> {
        let (_, _, _, w, h) = self.resolve()?;
        Ok((w as u64).saturating_mul(h as u64))
    }

    /// A spec for `kind` and `seed` at the kind's default size and resolution.
    pub fn new(kind: EnvKind, seed: u64) -> Self {
        Self {
            kind,
            seed,
            size_m: None,
            resolution: None,
        }
    }

    /// The same spec with size `(width, height)` in metres.
    pub fn with_size(self, width_m: f64, height_m: f64) -> Self {
        Self {
            size_m: Some((width_m, height_m)),
            ..self
        }
    }

    /// The same spec with `resolution` metres per cell.
    pub fn with_resolution(self, resolution: f64) -> Self {
        Self {
            resolution: Some(resolution),
            ..self
        }
    }

    /// The stable name of the environment this spec generates, e.g. `office-s7`, or
    /// `office-s7-100x100m-r0.05` when size or resolution differ from the defaults.
    pub fn name(&self) -> String {
        let mut name = format!("{}-s{}", self.kind, self.seed);
        if let Some((w, h)) = self.size_m {
            name.push_str(&format!("-{w}x{h}m"));
        }
        if let Some(r) = self.resolution {
            name.push_str(&format!("-r{r}"));
        }
        name
    }

    /// Check the spec and resolve it to `(width_m, height_m, resolution, width, height)`.
    fn resolve(&self) -> Result<(f64, f64, f64, usize, usize), WorldError> {
        let info = self.kind.info();
        let (w_m, h_m) = self.size_m.unwrap_or(info.size_m);
        let res = self.resolution.unwrap_or(info.resolution);
        let kind = self.kind;
        let bad = |field, value, reason: String| WorldError::InvalidSpec {
            field,
            value,
            kind,
            reason,
        };
        for (field, v) in [("width_m", w_m), ("height_m", h_m), ("resolution", res)] {
            if !v.is_finite() || v <= 0.0 {
                return Err(bad(field, v, "expected a finite number > 0".into()));
            }
        }
        let (min_w, min_h) = kind.min_size_m();
        if w_m < min_w {
            return Err(bad(
                "width_m",
                w_m,
                format!("too small, expected at least {min_w} m"),
            ));
        }
        if h_m < min_h {
            return Err(bad(
                "height_m",
                h_m,
                format!("too small, expected at least {min_h} m"),
            ));
        }
        let max_res = kind.max_resolution();
        if res > max_res {
            return Err(bad(
                "resolution",
                res,
                format!("too coarse, expected at most {max_res} m"),
            ));
        }
        let (wc, hc) = ((w_m / res).round(), (h_m / res).round());
        let cells = wc * hc;
        if cells > MAX_CELLS as f64 {
            return Err(WorldError::TooLarge {
                width_m: w_m,
                height_m: h_m,
                resolution: res,
                cells,
                limit: MAX_CELLS,
            });
        }
        if wc < 3.0 {
            return Err(bad(
                "width_m",
                w_m,
                format!("gives {wc} cells at {res} m, need 3"),
            ));
        }
        if hc < 3.0 {
            return Err(bad(
                "height_m",
                h_m,
                format!("gives {hc} cells at {res} m, need 3"),
            ));
        }
        Ok((w_m, h_m, res, wc as usize, hc as usize))
    }
}

/// A generated ground-truth environment.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// Stable name, e.g. `office-s7`, used in file names and JSON (see [`EnvSpec::name`]).
    pub name: String,
    /// The kind it was generated as.
    pub kind: EnvKind,
    /// The seed it was generated from.
    pub seed: u64,
    /// Ground truth: Free and Occupied cells (no Unknown), boundary wall included.
    pub map: GridMap,
    /// Office and hospital: region id per cell (0 = not free), ids `1..=room_count`.
    pub rooms: Option<Grid<u32>>,
    /// Number of regions (rooms and corridor pieces); 0 for kinds without rooms.
    pub room_count: u32,
}

impl Environment {
    /// A 64-bit FNV-1a fingerprint of the size, resolution, cells and room ids; equal
    /// environments have equal fingerprints on every platform.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Fnv::new();
        h.write(&(self.map.width() as u64).to_le_bytes());
        h.write(&(self.map.height() as u64).to_le_bytes());
        h.write(&self.map.resolution.to_bits().to_le_bytes());
        for &c in self.map.cells.data() {
            h.write(&[c as u8]);
        }
        if let Some(rooms) = &self.rooms {
            for &r in rooms.data() {
                h.write(&r.to_le_bytes());
            }
        }
        h.0
    }
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Generate the environment described by `spec`.
///
/// Errors name the field at fault when the size or resolution is not finite and positive,
/// too small or too coarse for the kind, or gives more than [`MAX_CELLS`] cells.
pub fn generate(spec: &EnvSpec) -> Result<Environment, WorldError> {
    let (w_m, h_m, res, w, h) = spec.resolve()?;
    let mut rng = rng::Draws::new(spec.seed);
    let (mut cells, mut rooms) = match spec.kind {
        EnvKind::Office => {
            let (c, r) = office::office(w_m, h_m, res, &mut rng);
            (c, Some(r))
        }
        EnvKind::Hospital => {
            let (c, r) = hospital::hospital(w_m, h_m, res, &mut rng);
            (c, Some(r))
        }
        EnvKind::Cave => (cave::cave(w_m, h_m, res, &mut rng), None),
        EnvKind::Maze => (maze::maze(w_m, h_m, res, &mut rng), None),
        EnvKind::Potholes => (potholes::potholes(w_m, h_m, res, &mut rng), None),
        EnvKind::Empty => (empty::empty(w, h, res), None),
    };
    debug_assert_eq!((cells.width(), cells.height()), (w, h));
    // the boundary is a wall whatever a generator drew
    raster::border(&mut cells, 1);
    let room_count = finish::finish(&mut cells, rooms.as_mut());
    debug_assert!(cells.data().iter().all(|&c| c != Occ::Unknown));
    Ok(Environment {
        name: spec.name(),
        kind: spec.kind,
        seed: spec.seed,
        map: GridMap::new(cells, res),
        rooms,
        room_count,
    })
}
