//! The faces of a mesh, gone through in parts side by side: quads listed one by
//! one, a grid's, wound as its orientation says, or polygons (a trimmed mesh's).
//! What the OBJ, PLY and glTF writers share.

use std::io::{self, Write};
use std::ops::Range;

use monge_core::QuadGrid;

use crate::text::Out;

/// Faces that can be gone through in parts, side by side.
pub(crate) trait Faces: Sync {
    /// A face: its corners, in order.
    type Face: AsRef<[usize]>;
    /// The number of faces.
    fn count(&self) -> usize;
    /// The faces numbered `range` (within `0..count`), in order.
    fn range(&self, range: Range<usize>) -> impl Iterator<Item = Self::Face>;

    /// Appends `face(corners)` for every face, in order, side by side.
    fn each<W: Write + ?Sized>(
        &self,
        out: &mut Out<'_, W>,
        face: impl Fn(&mut Out<'_, Vec<u8>>, Self::Face) + Sync,
    ) -> io::Result<()> {
        out.each_range(self.count(), |o, range| {
            self.range(range).for_each(|corners| face(o, corners));
        })
    }
}

/// Quads listed one by one.
impl Faces for &[[usize; 4]] {
    type Face = [usize; 4];

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
    type Face = [usize; 4];

    fn count(&self) -> usize {
        self.grid.face_count()
    }

    fn range(&self, range: Range<usize>) -> impl Iterator<Item = [usize; 4]> {
        self.grid.faces_wound(self.reversed, range)
    }
}

/// Polygons listed one by one (a trimmed mesh's faces).
impl<'a> Faces for &'a [Vec<usize>] {
    type Face = &'a [usize];

    fn count(&self) -> usize {
        self.len()
    }

    fn range(&self, range: Range<usize>) -> impl Iterator<Item = &'a [usize]> {
        let faces: &'a [Vec<usize>] = self;
        faces[range].iter().map(Vec::as_slice)
    }
}
