//! # monge-render
//!
//! Pictures of the quad meshes of monge: a shaded 3D view of a
//! [`QuadGrid`] with its guide curves highlighted,
//! optionally beside its Gauss map (the node axes drawn as a quad net on the
//! unit sphere, Figure 9 of the paper), and contact sheets of several meshes
//! with captions (the θ family of Figure 14).
//!
//! Pictures come out as PNG bytes ([`render_png`], [`sheet_png`], rasterised
//! by tiny-skia, anti-aliased) or SVG text ([`render_svg`], [`sheet_svg`]).
//! No file I/O. Rendering is deterministic: the same input gives the same bytes
//! (single-threaded, no hash maps, a stable depth sort).
//!
//! How a picture is drawn: the mesh is seen from a [`View`] (azimuth and
//! elevation of the eye, z up) with a mild perspective ([`Projection`]) and
//! fitted to its panel. Faces are filled with two-sided Lambert shading from a
//! light near the eye, the side facing the viewer in one colour and the other
//! side in another (so folds show), drawn back to front (painter's algorithm
//! on the depth of face centres) with thin edges. The highlighted polylines
//! (the guides: red guide_u, blue guide_v) are drawn last, on top.
//!
//! ```
//! use glam::DVec3;
//! use monge_core::QuadGrid;
//! use monge_render::{render_png, render_svg, RenderOptions, Scene};
//!
//! // A 3 × 3 saddle.
//! let vertices = (0..9)
//!     .map(|k| {
//!         let (x, y) = ((k / 3) as f64 - 1.0, (k % 3) as f64 - 1.0);
//!         DVec3::new(x, y, 0.3 * (x * x - y * y))
//!     })
//!     .collect();
//! let scene = Scene::new(QuadGrid::new(3, 3, vertices, Vec::new()));
//! let options = RenderOptions { width: 120, height: 80, ..RenderOptions::default() };
//! let png = render_png(&scene, &options).unwrap();
//! assert_eq!(&png[1..4], b"PNG");
//! assert_eq!(png, render_png(&scene, &options).unwrap()); // deterministic
//! assert!(render_svg(&scene, &options).unwrap().starts_with("<svg"));
//! ```

mod compose;
mod font;
mod raster;
mod svg;

use std::fmt;

use glam::DVec3;
use monge_core::QuadGrid;

/// An opaque colour, 8 bits a channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Rgb {
    /// The colour `(r, g, b)`.
    pub const fn new(r: u8, g: u8, b: u8) -> Rgb {
        Rgb { r, g, b }
    }

    /// White, the default background.
    pub const WHITE: Rgb = Rgb::new(255, 255, 255);
}

/// Colour of guide_u (column 0 of a grid): red.
pub const GUIDE_U_COLOR: Rgb = Rgb::new(214, 39, 40);
/// Colour of guide_v (row 0 of a grid): blue.
pub const GUIDE_V_COLOR: Rgb = Rgb::new(31, 100, 200);

/// Where the eye is: z is up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Angle of the eye around the z axis, in degrees from +x towards +y.
    pub azimuth_deg: f64,
    /// Angle of the eye above the xy plane, in degrees, in [−89, 89].
    pub elevation_deg: f64,
}

impl Default for View {
    /// A three-quarter view from above: azimuth −55°, elevation 30° (the eye at
    /// +x, −y, above; guide_u, which usually runs along +x, goes to the right).
    fn default() -> Self {
        View {
            azimuth_deg: -55.0,
            elevation_deg: 30.0,
        }
    }
}

/// How 3D points become 2D.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel projection along the view direction.
    Orthographic,
    /// Central projection from an eye on the view direction.
    Perspective {
        /// Distance of the eye from the centre of the bounding box, in bounding-box
        /// diagonals (at least 1; 3 is mild).
        distance: f64,
    },
}

impl Default for Projection {
    /// A mild perspective: the eye three bounding-box diagonals away.
    fn default() -> Self {
        Projection::Perspective { distance: 3.0 }
    }
}

/// How to draw; every field has a documented default ([`RenderOptions::default`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Width of the picture in pixels, 1 to [`MAX_SIDE`] (default 1200).
    pub width: u32,
    /// Height of the picture in pixels, 1 to [`MAX_SIDE`] (default 800).
    pub height: u32,
    /// Background (default white).
    pub background: Rgb,
    /// Where the eye is (default [`View::default`]: azimuth −55°, elevation 30°).
    pub view: View,
    /// Projection (default [`Projection::default`]: perspective from 3 diagonals).
    pub projection: Projection,
    /// Fill of the faces' side that faces the viewer, fully lit (default light steel blue).
    pub front_color: Rgb,
    /// Fill of the faces' other side, fully lit (default sand).
    pub back_color: Rgb,
    /// Colour of the mesh edges (default dark slate).
    pub edge_color: Rgb,
    /// Width of the mesh edges in pixels (default 0.6).
    pub edge_width: f32,
    /// Width of the highlighted polylines in pixels (default 3).
    pub highlight_width: f32,
    /// Height of capital letters in captions, in pixels (default 14; PNG
    /// captions use a 5 × 7 pixel font scaled by a whole factor, capitals only).
    pub text_size: f32,
    /// Empty border around each mesh, as a fraction of its panel's smaller side (default 0.05).
    pub margin: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1200,
            height: 800,
            background: Rgb::WHITE,
            view: View::default(),
            projection: Projection::default(),
            front_color: Rgb::new(168, 196, 226),
            back_color: Rgb::new(236, 206, 150),
            edge_color: Rgb::new(52, 62, 78),
            edge_width: 0.6,
            highlight_width: 3.0,
            text_size: 14.0,
            margin: 0.05,
        }
    }
}

/// Largest accepted width or height of a picture, in pixels.
pub const MAX_SIDE: u32 = 16384;

/// A polyline drawn on top of the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Highlight {
    /// Its points, in the mesh's coordinates.
    pub points: Vec<DVec3>,
    /// Its colour.
    pub color: Rgb,
}

/// A point drawn as a small disc on top of the mesh (e.g. a target point coloured by
/// its distance to a design).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dot {
    /// Where, in the mesh's coordinates.
    pub point: DVec3,
    /// Its colour (outlined in grey, so that white shows on white).
    pub color: Rgb,
}

/// What one picture (or one panel of a contact sheet) shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The mesh, drawn shaded.
    pub mesh: QuadGrid,
    /// Polylines drawn on top of it, in order (also fitted into the panel).
    pub highlights: Vec<Highlight>,
    /// If set, a grid of unit vectors drawn beside the mesh as a quad net on the
    /// unit sphere, with its row 0 and column 0 highlighted like the guides (see
    /// [`gauss_net`]).
    pub gauss: Option<QuadGrid>,
    /// If set, one colour per vertex of `mesh`: each face is filled with the mean of
    /// its corners' colours (shaded), front and back alike, instead of the options'
    /// front and back colours (see [`heat`]).
    pub vertex_colors: Option<Vec<Rgb>>,
    /// Points drawn over the mesh, far ones first, under the highlights (also fitted
    /// into the panel); a scene may be dots alone, on a mesh without vertices.
    pub dots: Vec<Dot>,
}

impl Scene {
    /// `mesh` with its guides highlighted (column 0 in [`GUIDE_U_COLOR`], row 0
    /// in [`GUIDE_V_COLOR`]) and no Gauss map.
    pub fn new(mesh: QuadGrid) -> Scene {
        let highlights = guide_highlights(
            &mesh.column(0).collect::<Vec<_>>(),
            &mesh.row(0).collect::<Vec<_>>(),
        );
        Scene {
            mesh,
            highlights,
            gauss: None,
            vertex_colors: None,
            dots: Vec::new(),
        }
    }
}

/// A sequential colour scale for magnitudes such as a deviation: `t` = 0 white,
/// 0.5 orange, 1 (and beyond) dark red; NaN grey.
///
/// ```
/// use monge_render::{heat, Rgb};
/// assert_eq!(heat(0.0), Rgb::WHITE);
/// assert_eq!(heat(1.0), heat(7.0));
/// assert_eq!(heat(f64::NAN), Rgb::new(128, 128, 128));
/// ```
pub fn heat(t: f64) -> Rgb {
    if t.is_nan() {
        return Rgb::new(128, 128, 128);
    }
    // White → yellow → orange → red → dark red.
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [255.0, 255.0, 255.0]),
        (0.25, [255.0, 237.0, 111.0]),
        (0.5, [253.0, 141.0, 60.0]),
        (0.75, [227.0, 26.0, 28.0]),
        (1.0, [128.0, 0.0, 38.0]),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = STOPS.iter().rposition(|(x, _)| *x <= t).unwrap_or(0).min(3);
    let ((x0, c0), (x1, c1)) = (STOPS[k], STOPS[k + 1]);
    let f = (t - x0) / (x1 - x0);
    let mix = |i: usize| (c0[i] + f * (c1[i] - c0[i])).round() as u8;
    Rgb::new(mix(0), mix(1), mix(2))
}

/// The two guides as highlights: guide_u in [`GUIDE_U_COLOR`], guide_v in [`GUIDE_V_COLOR`].
pub fn guide_highlights(guide_u: &[DVec3], guide_v: &[DVec3]) -> Vec<Highlight> {
    vec![
        Highlight {
            points: guide_u.to_vec(),
            color: GUIDE_U_COLOR,
        },
        Highlight {
            points: guide_v.to_vec(),
            color: GUIDE_V_COLOR,
        },
    ]
}

/// The Gauss map of `grid`: the grid of its unit node axes (`None` when it has no normals).
pub fn gauss_net(grid: &QuadGrid) -> Option<QuadGrid> {
    (!grid.normals.is_empty())
        .then(|| QuadGrid::new(grid.rows, grid.cols, grid.normals.clone(), Vec::new()))
}

/// One cell of a contact sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// What to draw; `None` draws an empty, marked cell (e.g. a θ that failed).
    pub scene: Option<Scene>,
    /// Text under the cell; lines separated by `\n`.
    pub caption: String,
}

/// Why a picture cannot be made.
#[derive(Clone, Debug, PartialEq)]
pub enum RenderError {
    /// Width or height is 0 or above [`MAX_SIDE`].
    Size {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// An option is out of range (named, with the reason).
    Option(String),
    /// PNG encoding failed.
    Encode(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Size { width, height } => write!(
                f,
                "a picture of {width} × {height} pixels cannot be drawn: each side must be 1 to {MAX_SIDE}"
            ),
            RenderError::Option(reason) => f.write_str(reason),
            RenderError::Encode(reason) => write!(f, "cannot encode the PNG: {reason}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// `scene` as a PNG picture.
///
/// # Errors
/// [`RenderError`] if the options are out of range or encoding fails.
pub fn render_png(scene: &Scene, options: &RenderOptions) -> Result<Vec<u8>, RenderError> {
    let shapes = compose::sheet(&[compose::Cell::of(scene)], 1, options)?;
    raster::png(&shapes, options)
}

/// `scene` as an SVG document.
///
/// # Errors
/// [`RenderError`] if the options are out of range.
pub fn render_svg(scene: &Scene, options: &RenderOptions) -> Result<String, RenderError> {
    let shapes = compose::sheet(&[compose::Cell::of(scene)], 1, options)?;
    Ok(svg::document(&shapes, options))
}

/// A contact sheet as a PNG picture: `panels` in rows of `columns` cells
/// (0: the number that makes cells closest to 3:2), each with its caption.
/// All cells share one scale (the largest at which every mesh fits its cell),
/// so their sizes compare.
///
/// # Errors
/// [`RenderError`] if the options are out of range or encoding fails.
pub fn sheet_png(
    panels: &[Panel],
    columns: usize,
    options: &RenderOptions,
) -> Result<Vec<u8>, RenderError> {
    let cells: Vec<_> = panels.iter().map(compose::Cell::from).collect();
    let shapes = compose::sheet(&cells, columns, options)?;
    raster::png(&shapes, options)
}

/// A contact sheet as an SVG document (see [`sheet_png`]).
///
/// # Errors
/// [`RenderError`] if the options are out of range.
pub fn sheet_svg(
    panels: &[Panel],
    columns: usize,
    options: &RenderOptions,
) -> Result<String, RenderError> {
    let cells: Vec<_> = panels.iter().map(compose::Cell::from).collect();
    let shapes = compose::sheet(&cells, columns, options)?;
    Ok(svg::document(&shapes, options))
}
