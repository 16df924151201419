//! What a designer looks at in a fit (§6's counts, monge's extension): [`fit_report`]
//! gives the panels, the distinct node types (as [`crate::fabrication`] groups them),
//! the deviation, and each patch's deviation and θ; [`target_distances`] colours the
//! target by its distance to the result.

use crate::conical::conical_dual;
use crate::design::MeshKind;
use crate::fabrication::{fabricate, BaseMesh, FabricationError, FabricationOptions};
use crate::generate::{generate, GenerateOptions};
use crate::grid::QuadGrid;
use crate::multipatch::build;

use super::patches::per_patch;
use super::trim::{trimmed_deviation, ResultFaces, TrimmedMesh};
use super::{Deviation, FitDesign, PatchFit, TargetCloud, ToleranceError};

/// What a designer looks at (§6's counts and the deviation).
#[derive(Clone, Debug, PartialEq)]
pub struct FitReport {
    /// Panels (faces of the mesh; of a trimmed mesh, its polygons).
    pub panels: usize,
    /// Distinct node types, as [`fabricate`] groups them at `node_angle_tol`; or why
    /// the nodes could not be grouped: fabrication's refusal of the mesh found (an
    /// edge or a face it calls degenerate), which does not make the fit less near.
    pub node_types: Result<usize, FabricationError>,
    /// Nodes whose beam angles agree within this many radians share a type
    /// ([`FabricationOptions::angle_tol`]).
    pub node_angle_tol: f64,
    /// Distances both ways, relative to the target's size.
    pub deviation: Deviation,
    /// Each patch, in design order.
    pub per_patch: Vec<PatchFit>,
}

/// The report of the fit `design` of `target`: panels, node types (nodes whose beam
/// and axis angles agree within `angle_tol` radians are one type, as [`fabricate`]
/// groups them; [`crate::fabrication::DESIGN_ANGLE_TOL_DEG`] is a designer's; of a
/// trimmed mesh, the untrimmed grid's nodes), deviation, and per patch its θ and
/// deviation.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{approximate, fit_report, FitDesign, TargetCloud};
/// use monge_core::approximate::ApproxOptions;
/// let target: Vec<DVec3> = (0..121)
///     .map(|k| {
///         let (x, y) = ((k % 11) as f64, (k / 11) as f64);
///         DVec3::new(x, y, 0.04 * x * x + 0.1 * y * y)
///     })
///     .collect();
/// let options = ApproxOptions { faces: (6, 4), starts: 1, max_evaluations: 40, ..Default::default() };
/// let fit = approximate(&target, &options, &mut |_| {}).unwrap();
/// let cloud = TargetCloud::new(&target).unwrap();
/// let report = fit_report(&cloud, &FitDesign::Single(fit.design.clone()), 0.1f64.to_radians()).unwrap();
/// assert_eq!(report.panels, 24);
/// assert_eq!(report.per_patch.len(), 1);
/// assert_eq!(report.deviation, fit.after);
/// ```
pub fn fit_report(
    target: &TargetCloud,
    design: &FitDesign,
    angle_tol: f64,
) -> Result<FitReport, ToleranceError> {
    let options = FabricationOptions {
        angle_tol,
        ..FabricationOptions::default()
    };
    let report = |base: BaseMesh<'_>, deviation: Deviation, per_patch: Vec<PatchFit>| {
        let panels = match base {
            BaseMesh::Circular(g) => g.face_count(),
            BaseMesh::Conical(c) => c.grid.face_count(),
        };
        FitReport {
            panels,
            node_types: fabricate(base, &options).map(|f| f.summary.node_types),
            node_angle_tol: options.angle_tol,
            deviation,
            per_patch,
        }
    };
    // The deviation of a mesh, trimmed where the result is.
    let trimmed = design.trimmed();
    let deviation = |grid: &QuadGrid| match trimmed {
        Some(mesh) => trimmed_deviation(target, mesh, 1),
        None => target.deviation(grid),
    };
    let mut r = match design {
        FitDesign::Single(d) | FitDesign::Trimmed(d, _) => {
            let circular = generate(d, &GenerateOptions::default())?.grid;
            let dual = (d.mesh == MeshKind::Conical).then(|| conical_dual(&circular));
            let (grid, base) = match &dual {
                Some(c) => (&c.grid, BaseMesh::Conical(c)),
                None => (&circular, BaseMesh::Circular(&circular)),
            };
            let deviation = deviation(grid);
            let one = PatchFit {
                block: (0, 0),
                theta_deg: d.theta_deg,
                target_points: target.points.len(),
                max: deviation.target_to_mesh_max,
                rms: deviation.target_to_mesh_rms,
            };
            report(base, deviation, vec![one])
        }
        FitDesign::Patches(d) | FitDesign::TrimmedPatches(d, _) => {
            let mp = build(d, &GenerateOptions::default())?;
            let patches = per_patch(target, &mp, trimmed);
            report(BaseMesh::Circular(&mp.grid), deviation(&mp.grid), patches)
        }
    };
    // A trimmed mesh's panels are its polygons.
    if let Some(mesh) = trimmed {
        r.panels = mesh.faces.len();
    }
    Ok(r)
}

/// The distance from each target point to the mesh `grid` (model units), or where the
/// result is `trimmed` (the trimmed mesh of `grid`) to that, as
/// [`Deviation::target_to_mesh_max`] measures it: to the nearest face. What a picture
/// of the target coloured by its distance to a result shows.
///
/// ```
/// use glam::DVec3;
/// use monge_core::approximate::{target_distances, TargetCloud};
/// use monge_core::QuadGrid;
/// let plane: Vec<DVec3> =
///     (0..100).map(|k| DVec3::new((k % 10) as f64, (k / 10) as f64, 0.0)).collect();
/// let target = TargetCloud::new(&plane).unwrap();
/// // A square 0.5 above the points of x, y in [3, 4].
/// let square = [DVec3::new(3.0, 3.0, 0.5), DVec3::new(3.0, 4.0, 0.5),
///               DVec3::new(4.0, 3.0, 0.5), DVec3::new(4.0, 4.0, 0.5)];
/// let grid = QuadGrid::new(2, 2, square.to_vec(), vec![DVec3::Z; 4]);
/// let d = target_distances(&target, &grid, None);
/// assert!((d[33] - 0.5).abs() < 1e-12);
/// assert!((d[0] - (18f64 + 0.25).sqrt()).abs() < 1e-12);
/// ```
pub fn target_distances(
    target: &TargetCloud,
    grid: &QuadGrid,
    trimmed: Option<&TrimmedMesh>,
) -> Vec<f64> {
    let faces = ResultFaces::new(grid, trimmed);
    target
        .points
        .iter()
        .map(|p| faces.distance_from(*p).0)
        .collect()
}
