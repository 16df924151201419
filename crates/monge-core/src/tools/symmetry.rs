//! Symmetry and assembly (§4.5 Figure 18, §4.7 Figure 20): mirror and rotate
//! patches into a whole structure and merge coincident vertices into one quad mesh.
//!
//! Isometries keep every property of a circular mesh with planar lines (planar,
//! circular faces, planar lines, torsion-free node axes), so each transformed copy
//! is as exact as the patch; [`Assembly::copies`] keeps every copy as a
//! [`QuadGrid`] so that it can be measured. The merged mesh is no longer one grid:
//! it is a [`QuadMesh`] (vertices, node axes, quads), with, for every copy, the map
//! from its grid vertices to mesh vertices. Merged vertices keep the bits of the
//! first copy that has them.

use std::collections::HashMap;

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use crate::design::Xyz;
use crate::QuadGrid;

/// A symmetry operation of a design file (§4.5, §4.7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SymmetrySpec {
    /// Add the mirror image of every copy so far in the plane through `point`
    /// orthogonal to `normal` (Figure 20's mirrored domes).
    Mirror {
        /// A point of the mirror plane.
        point: Xyz,
        /// Normal of the mirror plane (need not be unit).
        normal: Xyz,
    },
    /// Add the images of every copy so far under the rotations by `k·360°/order`,
    /// `k = 1 … order − 1`, about the axis through `point` along `axis` (Figure 18's order 5).
    Rotate {
        /// A point of the axis.
        point: Xyz,
        /// Direction of the axis (need not be unit).
        axis: Xyz,
        /// Order of the rotation (≥ 1; 1 adds nothing).
        order: u32,
    },
}

/// Why a symmetry cannot be applied (§4.5).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum SymmetryError {
    /// A mirror normal or rotation axis is zero or not finite.
    #[error(
        "symmetry {index}: the {what} {value:?} is zero or not finite; give a non-zero direction"
    )]
    BadDirection {
        /// Index of the operation in the list.
        index: usize,
        /// `mirror normal` or `rotation axis`.
        what: &'static str,
        /// The direction given.
        value: Xyz,
    },
    /// A rotation order of 0.
    #[error(
        "symmetry {index}: a rotation of order 0 makes no copies; give order ≥ 1 (5 for Figure 18)"
    )]
    ZeroOrder {
        /// Index of the operation in the list.
        index: usize,
    },
    /// The group would have more copies than allowed.
    #[error(
        "the symmetries make {copies:.0} copies of the mesh, more than the {max} its size allows \
         (the vertex limit over the vertices of one copy): give fewer symmetries or lower orders"
    )]
    TooManyCopies {
        /// Copies the operations would make (the product of 2 a mirror and the orders).
        copies: f64,
        /// The most copies allowed.
        max: usize,
    },
    /// A point is not finite.
    #[error("symmetry {index}: the point {value:?} is not finite")]
    BadPoint {
        /// Index of the operation in the list.
        index: usize,
        /// The point given.
        value: Xyz,
    },
}

/// A rigid motion `x ↦ linear·x + translation` (rotation or reflection) (§4.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Isometry {
    /// An orthogonal matrix.
    pub linear: DMat3,
    /// The translation.
    pub translation: DVec3,
}

impl Isometry {
    /// The identity (§4.5).
    pub const IDENTITY: Isometry = Isometry {
        linear: DMat3::IDENTITY,
        translation: DVec3::ZERO,
    };

    /// The reflection in the plane through `point` orthogonal to `normal` (§4.7).
    pub fn mirror(point: DVec3, normal: DVec3) -> Isometry {
        let n = normal.normalize();
        let linear = DMat3::IDENTITY - 2.0 * DMat3::from_cols(n * n.x, n * n.y, n * n.z);
        Isometry {
            linear,
            translation: point - linear * point,
        }
    }

    /// The rotation by `angle` radians about the axis through `point` along `axis` (§4.5).
    pub fn rotation(point: DVec3, axis: DVec3, angle: f64) -> Isometry {
        let linear = DMat3::from_axis_angle(axis.normalize(), angle);
        Isometry {
            linear,
            translation: point - linear * point,
        }
    }

    /// `self ∘ other` (§4.5).
    pub fn compose(&self, other: &Isometry) -> Isometry {
        Isometry {
            linear: self.linear * other.linear,
            translation: self.linear * other.translation + self.translation,
        }
    }

    /// The image of a grid: points moved, node axes turned (§4.5).
    pub fn apply(&self, grid: &QuadGrid) -> QuadGrid {
        QuadGrid::new(
            grid.rows,
            grid.cols,
            grid.vertices
                .iter()
                .map(|&p| self.linear * p + self.translation)
                .collect(),
            grid.normals.iter().map(|&n| self.linear * n).collect(),
        )
    }
}

/// Every isometry of the group generated by `ops` applied in order (§4.5): the
/// identity first, then each operation adds the images of all copies so far. At most
/// `max_copies` of them, or [`SymmetryError::TooManyCopies`] before any is made.
///
/// ```
/// use monge_core::symmetry::{isometries, SymmetrySpec};
/// let ops = [
///     SymmetrySpec::Mirror { point: [0.0; 3], normal: [0.0, 1.0, 0.0] },
///     SymmetrySpec::Rotate { point: [0.0; 3], axis: [0.0, 0.0, 1.0], order: 5 },
/// ];
/// assert_eq!(isometries(&ops, 100).unwrap().len(), 10); // the dihedral group of Figure 18
/// assert!(isometries(&ops, 9).is_err());
/// ```
pub fn isometries(ops: &[SymmetrySpec], max_copies: usize) -> Result<Vec<Isometry>, SymmetryError> {
    let copies: f64 = ops
        .iter()
        .map(|op| match op {
            SymmetrySpec::Mirror { .. } => 2.0,
            SymmetrySpec::Rotate { order, .. } => f64::from(*order).max(1.0),
        })
        .product();
    if copies > max_copies as f64 {
        return Err(SymmetryError::TooManyCopies {
            copies,
            max: max_copies,
        });
    }
    let mut all = vec![Isometry::IDENTITY];
    for (index, op) in ops.iter().enumerate() {
        let check_point = |p: &Xyz| {
            if p.iter().all(|x| x.is_finite()) {
                Ok(DVec3::from_array(*p))
            } else {
                Err(SymmetryError::BadPoint { index, value: *p })
            }
        };
        let check_dir = |d: &Xyz, what| {
            let v = DVec3::from_array(*d);
            if v.is_finite() && v.length_squared() > 0.0 && v.length_squared().is_finite() {
                Ok(v)
            } else {
                Err(SymmetryError::BadDirection {
                    index,
                    what,
                    value: *d,
                })
            }
        };
        let new: Vec<Isometry> = match op {
            SymmetrySpec::Mirror { point, normal } => {
                let m = Isometry::mirror(check_point(point)?, check_dir(normal, "mirror normal")?);
                vec![m]
            }
            SymmetrySpec::Rotate { point, axis, order } => {
                if *order == 0 {
                    return Err(SymmetryError::ZeroOrder { index });
                }
                let (p, a) = (check_point(point)?, check_dir(axis, "rotation axis")?);
                (1..*order)
                    .map(|k| {
                        Isometry::rotation(p, a, std::f64::consts::TAU * k as f64 / *order as f64)
                    })
                    .collect()
            }
        };
        let before = all.clone();
        for g in &new {
            all.extend(before.iter().map(|c| g.compose(c)));
        }
    }
    Ok(all)
}

/// A quad mesh that is not one grid (§4.5): shared vertices, one node axis each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct QuadMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Unit node axes, one per vertex.
    pub normals: Vec<DVec3>,
    /// Quads as vertex indices, counter-clockwise seen from the side the node axes point to.
    pub quads: Vec<[usize; 4]>,
}

/// One transformed copy of a grid in an [`Assembly`] (§4.5).
#[derive(Clone, Debug)]
pub struct PlacedCopy {
    /// Index of the source grid in the list given to [`assemble`].
    pub source: usize,
    /// The motion applied.
    pub isometry: Isometry,
    /// The transformed grid, unmerged (measure it: it is as exact as its source).
    pub grid: QuadGrid,
    /// For every vertex of `grid`, its index in [`Assembly::mesh`].
    pub vertex_map: Vec<usize>,
}

/// A merged structure (§4.5): the mesh and every copy it was made of.
#[derive(Clone, Debug)]
pub struct Assembly {
    /// The merged quad mesh.
    pub mesh: QuadMesh,
    /// Every copy, source by source and isometry by isometry.
    pub copies: Vec<PlacedCopy>,
    /// The merge distance: `1e-9 ×` the structure's bounding-box diagonal.
    pub merge_distance: f64,
    /// Largest distance between a merged vertex and the vertex it was merged into.
    pub max_merge_gap: f64,
    /// Largest angle (radians) between the node axes of merged vertices: 0 where
    /// the axes are continuous across a mirror plane, larger at a crease.
    pub max_axis_gap: f64,
}

/// Relative merge distance (of the structure's bounding-box diagonal).
pub const MERGE_RELATIVE: f64 = 1e-9;

/// Apply every isometry to every grid and merge vertices closer than
/// [`MERGE_RELATIVE`] of the structure's size into one [`QuadMesh`] (§4.5, §4.7).
/// Every quad turns counter-clockwise about its node axes
/// ([`QuadGrid::oriented_faces`] of each copy: a mirror turns axes and faces alike).
///
/// ```
/// use glam::DVec3;
/// use monge_core::symmetry::{assemble, Isometry};
/// use monge_core::QuadGrid;
/// let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::X + DVec3::Y], vec![DVec3::Z; 4]);
/// let m = Isometry::mirror(DVec3::X, DVec3::X); // mirror in x = 1: shares the edge x = 1
/// let a = assemble(&[g], &[Isometry::IDENTITY, m]);
/// assert_eq!((a.mesh.vertices.len(), a.mesh.quads.len()), (6, 2));
/// ```
pub fn assemble(grids: &[QuadGrid], isometries: &[Isometry]) -> Assembly {
    let mut copies: Vec<PlacedCopy> = Vec::with_capacity(grids.len() * isometries.len());
    for (source, grid) in grids.iter().enumerate() {
        for iso in isometries {
            copies.push(PlacedCopy {
                source,
                isometry: *iso,
                grid: iso.apply(grid),
                vertex_map: Vec::new(),
            });
        }
    }
    let all: Vec<DVec3> = copies
        .iter()
        .flat_map(|c| c.grid.vertices.iter().copied())
        .collect();
    let size = crate::grid::bbox_diagonal(&all);
    let merge_distance = MERGE_RELATIVE * if size > 0.0 { size } else { 1.0 };
    let mut mesh = QuadMesh::default();
    let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let cell_of = |p: DVec3| -> [i64; 3] {
        let c = (p / merge_distance).floor();
        [c.x as i64, c.y as i64, c.z as i64]
    };
    let (mut max_merge_gap, mut max_axis_gap) = (0.0f64, 0.0f64);
    for copy in &mut copies {
        let g = &copy.grid;
        copy.vertex_map = Vec::with_capacity(g.vertices.len());
        for (k, &p) in g.vertices.iter().enumerate() {
            let n = g.normals.get(k).copied().unwrap_or(DVec3::ZERO);
            let c = cell_of(p);
            let mut found = None;
            'search: for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(list) = cells.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &v in list {
                                if mesh.vertices[v].distance(p) <= merge_distance {
                                    found = Some(v);
                                    break 'search;
                                }
                            }
                        }
                    }
                }
            }
            let v = match found {
                Some(v) => {
                    max_merge_gap = max_merge_gap.max(mesh.vertices[v].distance(p));
                    let (a, b) = (mesh.normals[v], n);
                    if a != DVec3::ZERO && b != DVec3::ZERO {
                        max_axis_gap = max_axis_gap.max(a.angle_between(b));
                    }
                    v
                }
                None => {
                    mesh.vertices.push(p);
                    mesh.normals.push(n);
                    cells.entry(c).or_default().push(mesh.vertices.len() - 1);
                    mesh.vertices.len() - 1
                }
            };
            copy.vertex_map.push(v);
        }
        // The copy's own node axes orient its faces (a mirror turns both).
        mesh.quads
            .extend(g.oriented_faces().map(|q| q.map(|k| copy.vertex_map[k])));
    }
    Assembly {
        mesh,
        copies,
        merge_distance,
        max_merge_gap,
        max_axis_gap,
    }
}
