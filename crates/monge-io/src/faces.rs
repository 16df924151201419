//! The faces of a quad mesh, gone through in parts side by side: listed one by
//! one, or a grid's, wound as its orientation says. What the OBJ, PLY and glTF
//! writers share.

use std::io::{self, Write};
use std::ops::Range;

use monge_core::QuadGrid;

use crate::text::Out;

/// Faces that can be gone through in parts, side by side.
pub(crate) trait Faces: Sync {
    /// The number of faces.
    fn count(&self) -> usize;
    /// The faces numbered `range` (within `0..count`), in order.
    fn range(&self, range: Range<usize>) -> impl Iterator<Item = [usize; 4]>;

    /// Appends `face(corners)` for every face, in order, side by side.
    fn each<W: Write + ?Sized>(
        &self,
        out: &mut Out<'_, W>,
        face: impl Fn(&mut Out<'_, Vec<u8>>, [usize; 4]) + Sync,
    ) -> io::Result<()> {
        out.each_range(self.count(), |o, range| {
            self.range(range).for_each(|corners| face(o, corners));
        })
    }
}

/// Quads listed one by one.
impl Faces for &[[usize; 4]] {
    fn count(&self) -> usize {
        self.len()
    }

    fn range(&self, range: Range<usize>) -> impl Iterator<Item = [usize; 4]> {
        self[range].iter().copied()
    }
}

/// A grid's faces, wound as [`QuadGrid::oriented_faces`].
pub(crate) struct GridFaces<'a> {
    pub(crate) grid: &'a QuadGrid,
    reversed: bool,
}

impl<'a> GridFaces<'a> {
    /// The faces of `grid`, their winding decided now ([`QuadGrid::faces_reversed`]).
    pub(crate) fn of(grid: &'a QuadGrid) -> Self {
        GridFaces {
            grid,
            reversed: grid.faces_reversed(),
        }
    }
}

impl Faces for GridFaces<'_> {
    fn count(&self) -> usize {
        self.grid.face_count()
    }

    fn range(&self, range: Range<usize>) -> impl Iterator<Item = [usize; 4]> {
        self.grid.faces_wound(self.reversed, range)
    }
}
