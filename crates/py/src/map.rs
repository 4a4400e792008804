//! `frontier.Map`: a ground-truth map loaded from a file, generated, or made from a numpy
//! array.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use grid::{Grid, GridMap, Occ};
use numpy::{
    PyArray1, PyArrayDescrMethods, PyArrayMethods, PyReadonlyArray2, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use world::{EnvKind, EnvSpec};

use crate::{
    bool_arg, int_arg, pair_arg, path_arg, real_arg, real_item, str_arg, u64_arg, value_error,
};

/// A ground-truth occupancy map: cells (0 unknown, 1 free, 2 occupied), resolution in metres
/// per cell, and the name runs report.
#[pyclass(module = "frontier._native", frozen)]
#[derive(Clone)]
pub struct Map {
    /// The map (shared by runs without copying).
    pub map: Arc<GridMap>,
    /// The name runs report: the file's stem or the environment's name.
    pub name: String,
    /// The start the map file marks (a dungeon PNG's), used when a run gives none.
    pub start: Option<grid::Cell>,
}

/// What a resolution is, for messages.
const RESOLUTION: &str = "a number of metres per cell";

/// `border=` of `Map.load`.
fn border_arg(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    bool_arg(v, "border")
}

/// `dungeon=` of `Map.load`.
fn dungeon_arg(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    bool_arg(v, "dungeon")
}

/// `seed=` of `Map.generate`.
fn seed_arg(v: &Bound<'_, PyAny>) -> PyResult<u64> {
    u64_arg(v, "seed")
}

/// `kind=` of `Map.generate`.
fn kind_arg(v: &Bound<'_, PyAny>) -> PyResult<String> {
    str_arg(v, "kind", "a str")
}

/// `name=` of `Map.from_numpy`.
fn name_arg(v: &Bound<'_, PyAny>) -> PyResult<String> {
    str_arg(v, "name", "a str")
}

/// `topic=` of `Map.load`.
fn topic_arg(v: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
    if v.is_none() {
        return Ok(None);
    }
    str_arg(v, "topic", "a str or None").map(Some)
}

/// `memory_mb=` of `Map.load` and the environments: None, or a positive number of MiB (a
/// Python or numpy int), as `explore`'s.
pub(crate) fn memory_mb_arg(v: &Bound<'_, PyAny>) -> PyResult<Option<u64>> {
    if v.is_none() {
        return Ok(None);
    }
    let mb: u64 = int_arg(v, "memory_mb", |n| {
        value_error(if n.starts_with('-') {
            format!("memory_mb: expected a positive number of MiB, found {n}")
        } else {
            format!("memory_mb: expected less than 2^64 MiB, found {n}")
        })
    })?;
    if mb == 0 {
        return Err(value_error(
            "memory_mb: expected a positive number of MiB, found 0",
        ));
    }
    Ok(Some(mb))
}

/// `path=` of `Map.load` and `Map.save`.
fn file_arg(v: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    path_arg(v, "path")
}

/// Metres per cell as the CLI's `--resolution` takes it: one number or (x, y).
fn resolution_arg(v: Option<&Bound<'_, PyAny>>) -> PyResult<Option<(f64, f64)>> {
    let Some(v) = v else { return Ok(None) };
    if v.is_none() {
        return Ok(None);
    }
    let (x, y) = if let Ok(r) = real_arg(v, "resolution", RESOLUTION) {
        (r, r)
    } else {
        pair_arg(
            v,
            "resolution",
            "a number of metres per cell or a pair (x, y)",
            real_item,
        )?
    };
    for r in [x, y] {
        check_resolution(r)?;
    }
    Ok(Some((x, y)))
}

/// The CLI's `--resolution` rule and message: a positive number of metres per cell, at most
/// [`grid::io::MAX_RESOLUTION_M`].
pub(crate) fn check_resolution(r: f64) -> PyResult<()> {
    if grid::io::is_valid_resolution(r) {
        Ok(())
    } else {
        Err(value_error(format!(
            "--resolution: expected a positive number of metres per cell, at most {}, found '{}'",
            grid::io::MAX_RESOLUTION_M,
            grid::Num(r)
        )))
    }
}

/// Refuse a generated map's size that is not two positive, finite numbers of metres.
pub(crate) fn check_size((w, h): (f64, f64)) -> PyResult<()> {
    if w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0 {
        Ok(())
    } else {
        Err(value_error(format!(
            "--size: expected WxH in metres (e.g. 25x20), found '{}x{}'",
            grid::Num(w),
            grid::Num(h)
        )))
    }
}

/// A size in metres: (width, height), any sequence of two numbers.
fn size_arg(v: Option<&Bound<'_, PyAny>>) -> PyResult<Option<(f64, f64)>> {
    let v = match v.filter(|v| !v.is_none()) {
        Some(v) => Some(pair_arg(v, "size", "(width, height) in metres", real_item)?),
        None => None,
    };
    v.map(check_size).transpose()?;
    Ok(v)
}

impl Map {
    /// Wrap a map.
    pub fn new(map: GridMap, name: String) -> Self {
        Self {
            map: Arc::new(map),
            name,
            start: None,
        }
    }
}

/// The name runs report for a map file: its stem (`plans/h12.json` is `h12`).
pub fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "map".into())
}

/// Read a map file as `frontier.Map.load` does (`resolution` already checked): the map, its
/// [`stem`] and the start it marks (a dungeon PNG's). A file (or a recording's map) whose
/// loading would need more than `memory_mb` MiB or the memory available is refused before it
/// is loaded. Errors name the file.
pub fn read_file(
    path: &Path,
    resolution: Option<(f64, f64)>,
    border: bool,
    topic: Option<&str>,
    dungeon: bool,
    memory_mb: Option<u64>,
) -> Result<(GridMap, String, Option<grid::Cell>), String> {
    use record::map_file::MapFileError;
    let opts = grid::io::LoadOptions {
        resolution,
        border,
        memory: sim::memory::limit(memory_mb, grid::machine::available()),
    };
    // As the CLI's --dungeon: `border` adds a wall (and moves the start with the cells).
    let record::map_file::MapFile { map, start, .. } =
        record::map_file::load(path, &opts, topic, dungeon).map_err(|e| match e {
            MapFileError::TopicWithoutMcap => format!(
                "topic: chooses the map topic of an MCAP recording (a .mcap file), found {}",
                path.display()
            ),
            MapFileError::McapOption(name) => format!(
                "{name}: an MCAP recording's map carries its own resolution and cells, so \
                 {name} does not apply to {}",
                path.display()
            ),
            MapFileError::DungeonResolution(found) => format!(
                "dungeon: expected one resolution (square cells) for {}, found {}",
                path.display(),
                match found {
                    Some((x, y)) => format!("({x}, {y})"),
                    None => "none".into(),
                }
            ),
            // In the CLI's words, as the other messages are.
            MapFileError::ResolutionRequired(file, what) => {
                format!("{file}: --resolution is required for {what}")
            }
            MapFileError::Load(message) => message,
        })?;
    Ok((map, stem(path), start))
}

#[pymethods]
impl Map {
    /// Load a map file the CLI reads: ROS map_server YAML + PGM/PNG, a bare PGM/PNG bitmap
    /// (needs `resolution`), MovingAI `.map`, HouseExpo `.json` (needs `resolution`), ASCII
    /// `.txt`, or an MCAP recording (`.mcap`: its last OccupancyGrid, on `topic` if it has
    /// several). `dungeon=True` reads a PNG as a dungeon map of learned-exploration work
    /// (free above 150, the start marked by pixels of value 208, kept as `start`).
    /// `border=True` adds a wall one cell thick around the map, of any file but an MCAP
    /// recording (the origin and a dungeon PNG's start move with the cells). A `resolution` given with a ROS YAML overrides the YAML's. A map whose
    /// loading would need more than `memory_mb` MiB (the CLI's `--memory-mb`) or the memory
    /// available is refused before it is loaded.
    #[staticmethod]
    #[pyo3(signature = (
        path, resolution=None, border=false, *, topic=None, dungeon=false, memory_mb=None
    ))]
    fn load(
        py: Python<'_>,
        #[pyo3(from_py_with = file_arg)] path: PathBuf,
        resolution: Option<&Bound<'_, PyAny>>,
        #[pyo3(from_py_with = border_arg)] border: bool,
        #[pyo3(from_py_with = topic_arg)] topic: Option<String>,
        #[pyo3(from_py_with = dungeon_arg)] dungeon: bool,
        #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
    ) -> PyResult<Self> {
        crate::check_not_empty(&path, "path")?;
        let resolution = resolution_arg(resolution)?;
        let (map, name, start) = crate::run::interruptible(py, move || {
            read_file(
                &path,
                resolution,
                border,
                topic.as_deref(),
                dungeon,
                memory_mb,
            )
        })?
        .map_err(value_error)?;
        let mut m = Self::new(map, name);
        m.start = start;
        Ok(m)
    }

    /// A map from a 2-D numpy array: bool (True = occupied) or uint8 (0 unknown, 1 free,
    /// 2 occupied); row 0 is the top row.
    // The default is written out for the signature: PyO3 shows only a literal default.
    #[staticmethod]
    #[pyo3(
        signature = (array, resolution, name=String::from("array")),
        text_signature = "(array, resolution, name=\"array\")"
    )]
    fn from_numpy(
        array: &Bound<'_, PyAny>,
        resolution: &Bound<'_, PyAny>,
        #[pyo3(from_py_with = name_arg)] name: String,
    ) -> PyResult<Self> {
        let resolution = real_arg(resolution, "resolution", RESOLUTION)?;
        check_resolution(resolution)?;
        let cells: Vec<Occ>;
        let (h, w);
        if let Some(a) = bool_bytes(array)? {
            (h, w) = (a.shape()[0], a.shape()[1]);
            check_cells(w, h)?;
            // numpy takes any nonzero byte of a bool array for True (a view of other bytes
            // as bool holds them): so does this, and no Rust bool is read from the array.
            cells = a
                .as_array()
                .iter()
                .map(|&o| if o != 0 { Occ::Occupied } else { Occ::Free })
                .collect();
        } else if let Ok(a) = array.extract::<PyReadonlyArray2<'_, u8>>() {
            (h, w) = (a.shape()[0], a.shape()[1]);
            check_cells(w, h)?;
            let mut out = Vec::with_capacity(h * w);
            for (k, &v) in a.as_array().iter().enumerate() {
                out.push(match v {
                    0 => Occ::Unknown,
                    1 => Occ::Free,
                    2 => Occ::Occupied,
                    _ => {
                        return Err(value_error(format!(
                            "array: expected cell values 0 (unknown), 1 (free) or 2 (occupied), \
                             found {v} at row {}, column {}",
                            k / w,
                            k % w
                        )));
                    }
                });
            }
            cells = out;
        } else {
            let what = match (array.getattr("dtype"), array.getattr("ndim")) {
                (Ok(d), Ok(n)) => format!("a {n}-D array of dtype {d}"),
                _ => format!("{}", array.get_type().name()?),
            };
            return Err(PyTypeError::new_err(format!(
                "array: expected a 2-D numpy array of bool (True = occupied) or uint8 \
                 (0 unknown, 1 free, 2 occupied), found {what}"
            )));
        }
        if w == 0 || h == 0 {
            return Err(value_error(format!(
                "array: empty map: width {w} and height {h} must both be positive"
            )));
        }
        let grid = Grid::from_vec(w, h, cells).ok_or_else(|| value_error("array: bad shape"))?;
        Ok(Self::new(GridMap::new(grid, resolution), name))
    }

    /// Generate a built-in environment (office, hospital, cave, maze, potholes, empty) from
    /// its seed, size in metres (width, height) and resolution (defaults: the kind's).
    #[staticmethod]
    #[pyo3(signature = (kind, seed=0, size=None, resolution=None))]
    fn generate(
        py: Python<'_>,
        #[pyo3(from_py_with = kind_arg)] kind: String,
        #[pyo3(from_py_with = seed_arg)] seed: u64,
        size: Option<&Bound<'_, PyAny>>,
        resolution: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let kind: EnvKind = kind
            .parse()
            .map_err(|e| value_error(format!("--env: {e}")))?;
        let resolution = resolution
            .filter(|r| !r.is_none())
            .map(|r| real_arg(r, "resolution", RESOLUTION))
            .transpose()?;
        if let Some(r) = resolution {
            check_resolution(r)?;
        }
        let spec = EnvSpec {
            kind,
            seed,
            size_m: size_arg(size)?,
            resolution,
        };
        bench::explore::check_generate_memory(&spec, None).map_err(value_error)?;
        let env = crate::run::interruptible(py, move || world::generate(&spec))?
            .map_err(|e| value_error(format!("generating {kind}: {e}")))?;
        Ok(Self::new(env.map, env.name))
    }

    /// The cells as a (height, width) uint8 array: 0 unknown, 1 free, 2 occupied.
    fn to_numpy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let cells = &self.map.cells;
        let data: Vec<u8> = cells.data().iter().map(|&o| o as u8).collect();
        let a = PyArray1::from_vec(py, data);
        Ok(a.reshape([cells.height(), cells.width()])?.into_any())
    }

    /// Write the map, in the format of the path's extension: `.yaml` (ROS map_server YAML +
    /// PGM), `.pgm`, `.png`, `.map` (MovingAI: unknown cells are written as out of bounds
    /// and read back as occupied) or `.txt`. Only the YAML keeps the resolution and origin.
    fn save(&self, #[pyo3(from_py_with = file_arg)] path: PathBuf) -> PyResult<()> {
        crate::check_not_empty(&path, "path")?;
        grid::io::save_map(&self.map, &path).map_err(value_error)
    }

    /// Width in cells.
    #[getter]
    fn width(&self) -> usize {
        self.map.width()
    }

    /// Height in cells.
    #[getter]
    fn height(&self) -> usize {
        self.map.height()
    }

    /// (height, width), as numpy orders it.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.map.height(), self.map.width())
    }

    /// Metres per cell.
    #[getter]
    fn resolution(&self) -> f64 {
        self.map.resolution
    }

    /// The name runs report.
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// World pose (x, y, yaw) of the lower-left corner (ROS `origin`).
    #[getter]
    fn origin(&self) -> (f64, f64, f64) {
        let [x, y, t] = self.map.origin;
        (x, y, t)
    }

    /// Number of free cells.
    #[getter]
    fn free_cells(&self) -> usize {
        self.map.cells.data().iter().filter(|o| o.is_free()).count()
    }

    /// The start the file marks, (x, y) in cells (a dungeon PNG's), or None; runs on the
    /// map start there unless given a `start`.
    #[getter]
    fn start(&self) -> Option<(i32, i32)> {
        self.start.map(|c| (c.x, c.y))
    }

    /// Pickled as its cells, size, resolution, origin, name and start, which
    /// `frontier._native._restore_map` makes a map of again (so that maps reach worker
    /// processes started with `spawn`).
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, MapState<'py>)> {
        let restore = py.import("frontier._native")?.getattr("_restore_map")?;
        let cells: Vec<u8> = self.map.cells.data().iter().map(|&o| o as u8).collect();
        Ok((
            restore,
            (
                PyBytes::new(py, &cells),
                self.map.width(),
                self.map.height(),
                self.map.resolution,
                self.origin(),
                self.name.clone(),
                self.start(),
            ),
        ))
    }

    /// The map itself: a map never changes, so a copy may share it.
    fn __copy__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    /// The map itself: a map never changes, so a deep copy may share it.
    fn __deepcopy__(slf: Py<Self>, _memo: &Bound<'_, PyAny>) -> Py<Self> {
        slf
    }

    /// Maps are equal when their name, cells, resolution, origin and marked start are (a
    /// pickled and unpickled map equals the map).
    fn __eq__(&self, other: &Self) -> bool {
        self.name == other.name
            && self.start == other.start
            && (Arc::ptr_eq(&self.map, &other.map) || *self.map == *other.map)
    }

    /// A hash that equal maps share: of the name, size, resolution, origin and start, not of
    /// every cell, so that it costs nothing on large maps (a map is immutable).
    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.name.hash(&mut h);
        (self.map.width(), self.map.height()).hash(&mut h);
        self.map.resolution.to_bits().hash(&mut h);
        self.map.origin.map(f64::to_bits).hash(&mut h);
        self.start.hash(&mut h);
        h.finish()
    }

    fn __repr__(&self) -> String {
        format!(
            "Map('{}', {}x{} cells at {} m)",
            self.name,
            self.map.width(),
            self.map.height(),
            grid::Num(self.map.resolution)
        )
    }
}

/// What a pickled map holds: cells (one byte each, row by row), width, height, resolution,
/// origin, name and start.
type MapState<'py> = (
    Bound<'py, PyBytes>,
    usize,
    usize,
    f64,
    (f64, f64, f64),
    String,
    Option<(i32, i32)>,
);

/// A map from what `Map.__reduce__` gives (unpickling a map).
#[pyfunction]
#[pyo3(name = "_restore_map", signature = (cells, width, height, resolution, origin, name, start))]
pub fn restore_map(
    cells: &Bound<'_, PyBytes>,
    #[pyo3(from_py_with = width_arg)] width: usize,
    #[pyo3(from_py_with = height_arg)] height: usize,
    #[pyo3(from_py_with = resolution_value)] resolution: f64,
    origin: (f64, f64, f64),
    #[pyo3(from_py_with = name_arg)] name: String,
    #[pyo3(from_py_with = start_arg)] start: Option<(i32, i32)>,
) -> PyResult<Map> {
    check_resolution(resolution)?;
    check_cells(width, height)?;
    if ![origin.0, origin.1, origin.2].iter().all(|v| v.is_finite()) {
        return Err(value_error(format!(
            "origin: expected finite numbers (x, y, yaw), found ({}, {}, {})",
            origin.0, origin.1, origin.2
        )));
    }
    if let Some((x, y)) = start
        && (x < 0 || y < 0 || x as usize >= width || y as usize >= height)
    {
        return Err(value_error(format!(
            "start: expected a cell of the {width}x{height} map, found ({x}, {y})"
        )));
    }
    let bytes = cells.as_bytes();
    if bytes.len() != width.saturating_mul(height) || bytes.is_empty() {
        return Err(value_error(format!(
            "cells: expected {width} x {height} cells, found {}",
            bytes.len()
        )));
    }
    let cells = bytes
        .iter()
        .map(|&b| match b {
            0 => Ok(Occ::Unknown),
            1 => Ok(Occ::Free),
            2 => Ok(Occ::Occupied),
            v => Err(value_error(format!(
                "cells: expected 0 (unknown), 1 (free) or 2 (occupied), found {v}"
            ))),
        })
        .collect::<PyResult<Vec<Occ>>>()?;
    let grid =
        Grid::from_vec(width, height, cells).ok_or_else(|| value_error("cells: bad shape"))?;
    let mut map = GridMap::new(grid, resolution);
    map.origin = [origin.0, origin.1, origin.2];
    let mut m = Map::new(map, name);
    m.start = start.map(|(x, y)| grid::Cell::new(x, y));
    Ok(m)
}

/// A map's size in cells along one side (`what`), as `_restore_map` takes it.
fn side_arg(v: &Bound<'_, PyAny>, what: &str) -> PyResult<usize> {
    let range = |n: &str| {
        value_error(format!(
            "{what}: expected a number of cells in 1..2^64, found {n}"
        ))
    };
    match int_arg(v, what, range)? {
        0 => Err(range("0")),
        n => Ok(n),
    }
}

/// `width=` of `_restore_map`.
fn width_arg(v: &Bound<'_, PyAny>) -> PyResult<usize> {
    side_arg(v, "width")
}

/// `height=` of `_restore_map`.
fn height_arg(v: &Bound<'_, PyAny>) -> PyResult<usize> {
    side_arg(v, "height")
}

/// `resolution=` of `_restore_map`: a number (checked by [`check_resolution`]).
fn resolution_value(v: &Bound<'_, PyAny>) -> PyResult<f64> {
    real_arg(v, "resolution", RESOLUTION)
}

/// `start=` of `_restore_map`: None, or a cell (x, y) of 32-bit integers.
fn start_arg(v: &Bound<'_, PyAny>) -> PyResult<Option<(i32, i32)>> {
    if v.is_none() {
        return Ok(None);
    }
    let (x, y) = pair_arg(v, "start", "a cell (x, y) or None", crate::run::start_item)?;
    match (x.0, y.0) {
        (Some(x), Some(y)) => Ok(Some((x, y))),
        _ => Err(value_error(format!(
            "start: expected a cell (x, y) of 32-bit integers, found ({}, {})",
            x.1, y.1
        ))),
    }
}

/// A 2-D numpy bool array's bytes, as a view of them as uint8 (`None` for anything else).
/// Its bytes may be other than 0 and 1 (`np.array([5], np.uint8).view(bool)`), which a Rust
/// `bool` must not be, so the array is read as bytes only.
fn bool_bytes<'py>(array: &Bound<'py, PyAny>) -> PyResult<Option<PyReadonlyArray2<'py, u8>>> {
    let py = array.py();
    let Ok(a) = array.cast::<PyUntypedArray>() else {
        return Ok(None);
    };
    if a.ndim() != 2 || !a.dtype().is_equiv_to(&numpy::dtype::<bool>(py)) {
        return Ok(None);
    }
    let bytes = array.call_method1("view", (numpy::dtype::<u8>(py),))?;
    Ok(bytes.extract::<PyReadonlyArray2<'py, u8>>().ok())
}

/// Refuse an array of more cells than any map file may hold ([`grid::io::MAX_CELLS`]),
/// before it is copied: cells are numbered in 32 bits.
fn check_cells(w: usize, h: usize) -> PyResult<()> {
    let cells = (w as u64).saturating_mul(h as u64);
    if cells > grid::io::MAX_CELLS {
        return Err(value_error(format!(
            "array: map too large: {w}x{h} cells is more than the limit of {} cells",
            grid::io::MAX_CELLS
        )));
    }
    Ok(())
}
