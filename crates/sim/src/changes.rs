//! Where the belief changed: the bounding box of the changed cells since someone last asked.
//!
//! A consumer that keeps its own copy of the belief (the Python environments' observation
//! arrays) brings it up to date by copying this box instead of the whole map: a step's
//! scans change a few hundred cells around the robot, while a copy of a 250 × 250 map
//! moves 62,500. Tracking costs a division per changed cell, so a session tracks only when
//! asked ([`crate::Session::track_changes`]).

/// An axis-aligned box of cells, bounds inclusive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellBox {
    /// Leftmost column.
    pub x0: u32,
    /// Top row.
    pub y0: u32,
    /// Rightmost column.
    pub x1: u32,
    /// Bottom row.
    pub y1: u32,
}

impl CellBox {
    /// The box of the one cell (x, y).
    pub fn cell(x: u32, y: u32) -> Self {
        Self {
            x0: x,
            y0: y,
            x1: x,
            y1: y,
        }
    }

    /// The smallest box holding both.
    pub fn union(self, o: Self) -> Self {
        Self {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }

    /// `a` ∪ `b`, where `None` is the empty box.
    pub fn join(a: Option<Self>, b: Option<Self>) -> Option<Self> {
        match (a, b) {
            (Some(a), Some(b)) => Some(a.union(b)),
            (a, b) => a.or(b),
        }
    }
}

/// The box of the cells changed since the last [`ChangeTracker::take`] on a grid of
/// `width` columns (cells by row-major index).
#[derive(Clone, Debug, Default)]
pub struct ChangeTracker {
    width: u32,
    changed: Option<CellBox>,
}

impl ChangeTracker {
    /// A tracker for a grid `width` cells wide, with nothing changed.
    pub fn new(width: usize) -> Self {
        Self {
            width: width.max(1) as u32,
            changed: None,
        }
    }

    /// Note that the cells of indices `cells` changed.
    pub fn record(&mut self, cells: &[u32]) {
        let w = self.width;
        let mut b = self.changed;
        for &c in cells {
            let at = CellBox::cell(c % w, c / w);
            b = Some(b.map_or(at, |b| b.union(at)));
        }
        self.changed = b;
    }

    /// The box of the cells changed since the last call (`None`: none), forgetting them.
    pub fn take(&mut self) -> Option<CellBox> {
        self.changed.take()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_holds_every_recorded_cell_and_no_more() {
        let mut t = ChangeTracker::new(10);
        assert_eq!(t.take(), None);
        t.record(&[]);
        assert_eq!(t.take(), None);
        // (3, 1), (7, 0), (2, 5)
        t.record(&[13, 7]);
        t.record(&[52]);
        assert_eq!(
            t.take(),
            Some(CellBox {
                x0: 2,
                y0: 0,
                x1: 7,
                y1: 5
            })
        );
        assert_eq!(t.take(), None, "taking forgets");
        t.record(&[99]);
        assert_eq!(t.take(), Some(CellBox::cell(9, 9)));
    }

    #[test]
    fn join_treats_none_as_empty() {
        let a = CellBox::cell(1, 2);
        let b = CellBox::cell(4, 0);
        assert_eq!(CellBox::join(None, None), None);
        assert_eq!(CellBox::join(Some(a), None), Some(a));
        assert_eq!(CellBox::join(None, Some(b)), Some(b));
        assert_eq!(
            CellBox::join(Some(a), Some(b)),
            Some(CellBox {
                x0: 1,
                y0: 0,
                x1: 4,
                y1: 2
            })
        );
    }
}
