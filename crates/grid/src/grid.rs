//! `Grid<T>`: a flat, row-major raster.

use crate::cell::{Cell, NEIGHBOURS8};

/// A `width × height` raster stored row-major in one flat `Vec`; index = `y * width + x`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Grid<T> {
    width: usize,
    height: usize,
    data: Vec<T>,
}

impl<T: Clone> Grid<T> {
    /// A grid of `width × height` cells, each set to `fill`.
    pub fn new(width: usize, height: usize, fill: T) -> Self {
        Self {
            width,
            height,
            data: vec![fill; width * height],
        }
    }

    /// Set every cell to `value`.
    pub fn fill(&mut self, value: T) {
        self.data.fill(value);
    }
}

impl<T> Default for Grid<T> {
    /// The empty 0 × 0 grid.
    fn default() -> Self {
        Self {
            width: 0,
            height: 0,
            data: Vec::new(),
        }
    }
}

impl<T> Grid<T> {
    /// A grid over existing row-major data; `None` if `data.len() != width * height`.
    pub fn from_vec(width: usize, height: usize, data: Vec<T>) -> Option<Self> {
        (width.checked_mul(height) == Some(data.len())).then_some(Self {
            width,
            height,
            data,
        })
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.data.len()
    }

    /// Whether the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Whether `cell` lies inside the grid.
    pub fn contains(&self, cell: Cell) -> bool {
        cell.x >= 0
            && cell.y >= 0
            && (cell.x as usize) < self.width
            && (cell.y as usize) < self.height
    }

    /// Flat index of `cell`, which must lie inside the grid.
    #[inline]
    pub fn index(&self, cell: Cell) -> usize {
        debug_assert!(
            self.contains(cell),
            "{cell} outside {}x{}",
            self.width,
            self.height
        );
        cell.y as usize * self.width + cell.x as usize
    }

    /// Flat index of `cell`, or `None` outside the grid.
    #[inline]
    pub fn checked_index(&self, cell: Cell) -> Option<usize> {
        self.contains(cell)
            .then(|| cell.y as usize * self.width + cell.x as usize)
    }

    /// The cell at flat index `i`.
    #[inline]
    pub fn cell(&self, i: usize) -> Cell {
        Cell::new((i % self.width) as i32, (i / self.width) as i32)
    }

    /// The value at `cell` (panics outside the grid).
    #[inline]
    pub fn get(&self, cell: Cell) -> &T {
        &self.data[self.index(cell)]
    }

    /// The value at `cell`, or `None` outside the grid.
    #[inline]
    pub fn try_get(&self, cell: Cell) -> Option<&T> {
        self.checked_index(cell).map(|i| &self.data[i])
    }

    /// Set the value at `cell` (panics outside the grid).
    #[inline]
    pub fn set(&mut self, cell: Cell, value: T) {
        let i = self.index(cell);
        self.data[i] = value;
    }

    /// The cells' values, row-major.
    pub fn data(&self) -> &[T] {
        &self.data
    }

    /// The cells' values, row-major, mutable.
    pub fn data_mut(&mut self) -> &mut [T] {
        &mut self.data
    }

    /// Consume the grid, returning its row-major values.
    pub fn into_vec(self) -> Vec<T> {
        self.data
    }

    /// A grid of the same size with `f` applied to every value.
    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> Grid<U> {
        Grid {
            width: self.width,
            height: self.height,
            data: self.data.iter().map(f).collect(),
        }
    }

    /// Flat indices of the in-grid 8-neighbours of flat index `i`.
    #[inline]
    pub fn neighbours8(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        let c = self.cell(i);
        NEIGHBOURS8
            .iter()
            .filter_map(move |&(dx, dy)| self.checked_index(c.offset(dx, dy)))
    }

    /// Every cell of the grid in row-major order.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        (0..self.data.len()).map(|i| self.cell(i))
    }
}

impl<T> std::ops::Index<usize> for Grid<T> {
    type Output = T;
    #[inline]
    fn index(&self, i: usize) -> &T {
        &self.data[i]
    }
}

impl<T> std::ops::IndexMut<usize> for Grid<T> {
    #[inline]
    fn index_mut(&mut self, i: usize) -> &mut T {
        &mut self.data[i]
    }
}
