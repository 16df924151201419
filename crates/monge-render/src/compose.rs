//! From scenes to a list of 2D shapes in pixels, shared by the PNG and SVG back ends.

use glam::DVec3;
use monge_core::QuadGrid;

use crate::{Dot, Highlight, Panel, Projection, RenderError, RenderOptions, Rgb, Scene, MAX_SIDE};

/// A colour with opacity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgba {
    pub r: u8,
    pub g: u8,
    pub b: u8,
    /// Opacity, 255 opaque.
    pub a: u8,
}

impl Rgba {
    /// `c`, opaque.
    pub const fn opaque(c: Rgb) -> Rgba {
        Rgba::new(c.r, c.g, c.b, 255)
    }

    /// The colour `(r, g, b, a)`.
    pub const fn new(r: u8, g: u8, b: u8, a: u8) -> Rgba {
        Rgba { r, g, b, a }
    }
}

/// A stroke: colour and width in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pen {
    pub color: Rgba,
    pub width: f32,
}

/// A point in pixels, y down.
pub type Pt = [f32; 2];

/// What the back ends draw, in order.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A closed polygon, filled and/or outlined.
    Polygon {
        points: Vec<Pt>,
        fill: Option<Rgba>,
        stroke: Option<Pen>,
    },
    /// An open polyline with round joins and caps.
    Polyline { points: Vec<Pt>, pen: Pen },
    /// A circle, filled and/or outlined.
    Circle {
        center: Pt,
        radius: f32,
        fill: Option<Rgba>,
        stroke: Option<Pen>,
    },
    /// One line of text centred on `center` (the middle of its capitals).
    Text {
        center: Pt,
        /// Height of capitals in pixels.
        size: f32,
        color: Rgba,
        text: String,
    },
}

/// One cell of a sheet, borrowed.
#[derive(Clone, Copy, Debug)]
pub struct Cell<'a> {
    pub scene: Option<&'a Scene>,
    pub caption: &'a str,
}

impl<'a> Cell<'a> {
    /// A captionless cell showing `scene`.
    pub fn of(scene: &'a Scene) -> Cell<'a> {
        Cell {
            scene: Some(scene),
            caption: "",
        }
    }
}

impl<'a> From<&'a Panel> for Cell<'a> {
    fn from(p: &'a Panel) -> Cell<'a> {
        Cell {
            scene: p.scene.as_ref(),
            caption: &p.caption,
        }
    }
}

/// A rectangle in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    x: f64,
    y: f64,
    w: f64,
    h: f64,
}

/// Caption text colour.
const TEXT: Rgba = Rgba::new(40, 44, 52, 255);
/// Colour of a cell without a scene, and of faint lines.
const FAINT: Rgba = Rgba::new(200, 204, 212, 255);
/// Share of a panel's width given to the mesh when the Gauss map is beside it.
const MESH_SHARE: f64 = 0.6;
/// Caption under the Gauss map.
const GAUSS_CAPTION: &str = "Gauss map";

/// The shapes of a sheet of `cells` in rows of `columns` (0: automatic).
pub fn sheet(
    cells: &[Cell<'_>],
    columns: usize,
    o: &RenderOptions,
) -> Result<Vec<Shape>, RenderError> {
    validate(o)?;
    let (w, h) = (f64::from(o.width), f64::from(o.height));
    let n = cells.len().max(1);
    let columns = if columns == 0 {
        auto_columns(n, w, h)
    } else {
        columns.min(n)
    };
    let rows = n.div_ceil(columns);
    let (cw, ch) = (w / columns as f64, h / rows as f64);
    let text = f64::from(o.text_size);
    let mut layout = Vec::with_capacity(cells.len());
    for (k, cell) in cells.iter().enumerate() {
        let cell_rect = Rect {
            x: (k % columns) as f64 * cw,
            y: (k / columns) as f64 * ch,
            w: cw,
            h: ch,
        };
        let lines: Vec<&str> = if cell.caption.is_empty() {
            Vec::new()
        } else {
            cell.caption.lines().collect()
        };
        let caption_h = if lines.is_empty() {
            0.0
        } else {
            text * (1.8 * lines.len() as f64 + 0.6)
        };
        let body = Rect {
            h: (cell_rect.h - caption_h).max(0.0),
            ..cell_rect
        };
        layout.push((cell, cell_rect, body, lines));
    }
    // One scale for all cells (the largest that fits every mesh), so sizes compare.
    let scale = layout
        .iter()
        .filter_map(|(cell, _, body, _)| {
            let scene = cell.scene?;
            Projector::fit(
                &scene_points(scene),
                mesh_rect(scene, *body),
                o,
                f64::INFINITY,
            )
        })
        .map(|p| p.scale)
        .fold(f64::INFINITY, f64::min);
    let mut shapes = Vec::new();
    for (cell, cell_rect, body, lines) in layout {
        match cell.scene {
            Some(scene) => draw_scene(scene, body, o, scale, &mut shapes),
            None => draw_missing(body, o, &mut shapes),
        }
        for (l, line) in lines.iter().enumerate() {
            shapes.push(Shape::Text {
                center: pt(
                    cell_rect.x + cell_rect.w / 2.0,
                    body.y + body.h + text * (0.9 + 1.8 * l as f64),
                ),
                size: o.text_size,
                color: TEXT,
                text: (*line).to_owned(),
            });
        }
    }
    Ok(shapes)
}

/// Checks the options that could make a picture meaningless.
fn validate(o: &RenderOptions) -> Result<(), RenderError> {
    let bad = |reason: String| Err(RenderError::Option(reason));
    if !(1..=MAX_SIDE).contains(&o.width) || !(1..=MAX_SIDE).contains(&o.height) {
        return Err(RenderError::Size {
            width: o.width,
            height: o.height,
        });
    }
    if !o.view.azimuth_deg.is_finite() {
        return bad(format!(
            "the view azimuth is {}: give a finite angle in degrees",
            o.view.azimuth_deg
        ));
    }
    if !(-89.0..=89.0).contains(&o.view.elevation_deg) {
        return bad(format!(
            "the view elevation is {}: give an angle in degrees from -89 to 89",
            o.view.elevation_deg
        ));
    }
    if let Projection::Perspective { distance } = o.projection
        && !(distance >= 1.0 && distance.is_finite())
    {
        return bad(format!(
            "the perspective distance is {distance}: give at least 1 bounding-box diagonal"
        ));
    }
    if !(0.0..0.45).contains(&o.margin) {
        return bad(format!(
            "the margin is {}: give a fraction from 0 to 0.45",
            o.margin
        ));
    }
    for (name, value, max) in [
        ("edge width", o.edge_width, 100.0),
        ("highlight width", o.highlight_width, 100.0),
        ("text size", o.text_size, 500.0),
    ] {
        if !(0.0..=max).contains(&value) {
            return bad(format!(
                "the {name} is {value}: give a number of pixels from 0 to {max}"
            ));
        }
    }
    Ok(())
}

/// The number of columns whose cells are closest to 3:2 for `n` cells in `w × h`.
fn auto_columns(n: usize, w: f64, h: f64) -> usize {
    let misfit = |c: usize| {
        let aspect = (w / c as f64) / (h / n.div_ceil(c) as f64);
        (aspect / 1.5).ln().abs()
    };
    (1..=n)
        .min_by(|&a, &b| misfit(a).total_cmp(&misfit(b)))
        .unwrap_or(1)
}

/// A point in pixels from `f64` coordinates.
fn pt(x: f64, y: f64) -> Pt {
    [x as f32, y as f32]
}

/// The points that `scene`'s mesh panel is fitted to: the mesh's vertices, the
/// dots and the highlights' points.
fn scene_points(scene: &Scene) -> Vec<DVec3> {
    let mut all = scene.mesh.vertices.clone();
    all.extend(scene.dots.iter().map(|d| d.point));
    all.extend(
        scene
            .highlights
            .iter()
            .flat_map(|h| h.points.iter().copied()),
    );
    all
}

/// The part of `r` where `scene`'s mesh goes (the left part if the Gauss map is drawn).
fn mesh_rect(scene: &Scene, r: Rect) -> Rect {
    match scene.gauss {
        None => r,
        Some(_) => Rect {
            w: r.w * MESH_SHARE,
            ..r
        },
    }
}

/// `scene` in `r`, at most `scale` pixels per model unit: the mesh, and the
/// Gauss map to its right if any.
fn draw_scene(scene: &Scene, r: Rect, o: &RenderOptions, scale: f64, shapes: &mut Vec<Shape>) {
    let m = mesh_rect(scene, r);
    draw_mesh(scene, m, o, scale, shapes);
    if let Some(net) = &scene.gauss {
        let gauss = Rect {
            x: m.x + m.w,
            w: r.w - m.w,
            ..r
        };
        draw_gauss(net, gauss, o, shapes);
    }
}

/// A cell without a scene: a faint crossed box.
fn draw_missing(r: Rect, o: &RenderOptions, shapes: &mut Vec<Shape>) {
    let m = o.margin * r.w.min(r.h) + 4.0;
    let (x0, y0, x1, y1) = (r.x + m, r.y + m, r.x + r.w - m, r.y + r.h - m);
    if x1 <= x0 || y1 <= y0 {
        return;
    }
    let pen = Pen {
        color: FAINT,
        width: 1.0,
    };
    shapes.push(Shape::Polygon {
        points: vec![pt(x0, y0), pt(x1, y0), pt(x1, y1), pt(x0, y1)],
        fill: Some(Rgba::new(246, 247, 249, 255)),
        stroke: Some(pen),
    });
    shapes.push(Shape::Polyline {
        points: vec![pt(x0, y0), pt(x1, y1)],
        pen,
    });
    shapes.push(Shape::Polyline {
        points: vec![pt(x1, y0), pt(x0, y1)],
        pen,
    });
}

/// The eye's frame: `u` right, `v` up, `w` towards the eye.
#[derive(Clone, Copy, Debug)]
struct Camera {
    u: DVec3,
    v: DVec3,
    w: DVec3,
}

impl Camera {
    /// The frame of an eye at azimuth/elevation (degrees), z up.
    fn new(azimuth_deg: f64, elevation_deg: f64) -> Camera {
        let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
        let w = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let u = DVec3::Z.cross(w).normalize();
        Camera {
            u,
            v: w.cross(u),
            w,
        }
    }
}

/// Maps 3D points of one model to panel pixels.
struct Projector {
    camera: Camera,
    center: DVec3,
    /// Eye distance from `center` (infinite: orthographic).
    eye: f64,
    /// Pixels per model unit, and the model's 2D centre and the panel's centre.
    scale: f64,
    mid: [f64; 2],
    target: [f64; 2],
}

impl Projector {
    /// Camera-space `(x, y, depth)` of `p` (depth grows towards the eye), before fitting.
    fn camera_space(&self, p: DVec3) -> DVec3 {
        let d = p - self.center;
        let (x, y, z) = (
            d.dot(self.camera.u),
            d.dot(self.camera.v),
            d.dot(self.camera.w),
        );
        let f = if self.eye.is_finite() {
            self.eye / (self.eye - z)
        } else {
            1.0
        };
        DVec3::new(x * f, y * f, z)
    }

    /// The pixel of `p` and its depth, or `None` if `p` is not finite.
    fn project(&self, p: DVec3) -> Option<(Pt, f64)> {
        if !p.is_finite() {
            return None;
        }
        let c = self.camera_space(p);
        let x = self.target[0] + (c.x - self.mid[0]) * self.scale;
        let y = self.target[1] - (c.y - self.mid[1]) * self.scale;
        Some((pt(x, y), c.z))
    }

    /// Direction from `p` towards the eye.
    fn to_eye(&self, p: DVec3) -> DVec3 {
        if self.eye.is_finite() {
            (self.center + self.camera.w * self.eye - p).normalize_or_zero()
        } else {
            self.camera.w
        }
    }

    /// The projector that fits `points` (all of one model) into `r` at most
    /// `max_scale` pixels per model unit, or `None` if no point is finite.
    fn fit(points: &[DVec3], r: Rect, o: &RenderOptions, max_scale: f64) -> Option<Projector> {
        let mut finite = points.iter().copied().filter(|p| p.is_finite());
        let first = finite.next()?;
        let (lo, hi) = finite.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let diagonal = (hi - lo).length();
        let camera = Camera::new(o.view.azimuth_deg, o.view.elevation_deg);
        let eye = match o.projection {
            Projection::Orthographic => f64::INFINITY,
            Projection::Perspective { distance } => distance * diagonal.max(f64::MIN_POSITIVE),
        };
        let mut projector = Projector {
            camera,
            center: (lo + hi) / 2.0,
            eye,
            scale: 1.0,
            mid: [0.0; 2],
            target: [r.x + r.w / 2.0, r.y + r.h / 2.0],
        };
        let (mut a, mut b) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points.iter().filter(|p| p.is_finite()) {
            let c = projector.camera_space(*p);
            a = [a[0].min(c.x), a[1].min(c.y)];
            b = [b[0].max(c.x), b[1].max(c.y)];
        }
        let m = o.margin * r.w.min(r.h);
        let (room_w, room_h) = ((r.w - 2.0 * m).max(1.0), (r.h - 2.0 * m).max(1.0));
        let (span_w, span_h) = (b[0] - a[0], b[1] - a[1]);
        let scale = (room_w / span_w).min(room_h / span_h).min(max_scale);
        projector.scale = if scale.is_finite() { scale } else { 1.0 };
        projector.mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        Some(projector)
    }
}

/// The mean of four colours.
fn mean_color(c: [Rgb; 4]) -> Rgb {
    let mean = |f: fn(&Rgb) -> u8| {
        (c.iter().map(|c| u32::from(f(c))).sum::<u32>() as f64 / 4.0).round() as u8
    };
    Rgb::new(mean(|c| c.r), mean(|c| c.g), mean(|c| c.b))
}

/// `c` scaled by `k` (clamped to 0..=255).
fn shade(c: Rgb, k: f64) -> Rgba {
    let s = |x: u8| (f64::from(x) * k).round().clamp(0.0, 255.0) as u8;
    Rgba::new(s(c.r), s(c.g), s(c.b), 255)
}

/// A face to paint: its depth and its shape.
struct Face {
    depth: f64,
    index: usize,
    shape: Shape,
}

/// Sorts faces back to front (stable on the index) and moves their shapes to `shapes`.
fn paint(mut faces: Vec<Face>, shapes: &mut Vec<Shape>) {
    faces.sort_by(|a, b| a.depth.total_cmp(&b.depth).then(a.index.cmp(&b.index)));
    shapes.extend(faces.into_iter().map(|f| f.shape));
}

/// Pixels of the finite runs of `points` (a non-finite point breaks the line).
fn runs(points: &[DVec3], project: impl Fn(DVec3) -> Option<Pt>) -> Vec<Vec<Pt>> {
    let mut runs = vec![Vec::new()];
    for p in points {
        match project(*p) {
            Some(q) => runs.last_mut().expect("never empty").push(q),
            None => runs.push(Vec::new()),
        }
    }
    runs.retain(|r| r.len() >= 2);
    runs
}

/// The highlights, each over a thin white halo.
fn draw_highlights(
    highlights: &[Highlight],
    width: f32,
    project: impl Fn(DVec3) -> Option<Pt>,
    shapes: &mut Vec<Shape>,
) {
    if width <= 0.0 {
        return;
    }
    for h in highlights {
        for run in runs(&h.points, &project) {
            shapes.push(Shape::Polyline {
                points: run.clone(),
                pen: Pen {
                    color: Rgba::new(255, 255, 255, 200),
                    width: width + 2.0,
                },
            });
            shapes.push(Shape::Polyline {
                points: run,
                pen: Pen {
                    color: Rgba::opaque(h.color),
                    width,
                },
            });
        }
    }
}

/// Radius of a [`Dot`], pixels.
const DOT_RADIUS: f32 = 2.5;
/// Outline of a [`Dot`].
const DOT_OUTLINE: Pen = Pen {
    color: Rgba::new(110, 114, 124, 255),
    width: 0.6,
};

/// The dots, far ones first (stable on their order).
fn draw_dots(dots: &[Dot], projector: &Projector, shapes: &mut Vec<Shape>) {
    let discs = dots
        .iter()
        .enumerate()
        .filter_map(|(index, d)| {
            let (center, depth) = projector.project(d.point)?;
            Some(Face {
                depth,
                index,
                shape: Shape::Circle {
                    center,
                    radius: DOT_RADIUS,
                    fill: Some(Rgba::opaque(d.color)),
                    stroke: Some(DOT_OUTLINE),
                },
            })
        })
        .collect();
    paint(discs, shapes);
}

/// The edge pen, if edges are drawn.
fn edge_pen(o: &RenderOptions) -> Option<Pen> {
    (o.edge_width > 0.0).then_some(Pen {
        color: Rgba::opaque(o.edge_color),
        width: o.edge_width,
    })
}

/// The shaded mesh of `scene` and its highlights, fitted into `r` at most `scale`
/// pixels per model unit.
fn draw_mesh(scene: &Scene, r: Rect, o: &RenderOptions, scale: f64, shapes: &mut Vec<Shape>) {
    let (mesh, highlights) = (&scene.mesh, &scene.highlights);
    let Some(projector) = Projector::fit(&scene_points(scene), r, o, scale) else {
        return;
    };
    let cam = projector.camera;
    // A light near the eye, above and to the left.
    let light = (cam.w + 0.6 * cam.v - 0.45 * cam.u).normalize();
    let projected: Vec<Option<(Pt, f64)>> = mesh
        .vertices
        .iter()
        .map(|p| projector.project(*p))
        .collect();
    let stroke = edge_pen(o);
    let mut faces = Vec::with_capacity(mesh.face_count());
    // Faces wound about the node axes: the front is the side they point to.
    for ids in mesh.oriented_faces() {
        let Some(corners) = ids
            .iter()
            .map(|&k| projected[k])
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let [a, b, c, d] = ids.map(|k| mesh.vertices[k]);
        let normal = (c - a).cross(d - b).normalize_or_zero();
        let centre = (a + b + c + d) / 4.0;
        let facing = normal.dot(projector.to_eye(centre)) >= 0.0;
        let base = match &scene.vertex_colors {
            Some(colors) => mean_color(ids.map(|k| colors.get(k).copied().unwrap_or(Rgb::WHITE))),
            None if facing => o.front_color,
            None => o.back_color,
        };
        let lambert = normal.dot(light).abs();
        faces.push(Face {
            depth: corners.iter().map(|c| c.1).sum::<f64>() / 4.0,
            index: faces.len(),
            shape: Shape::Polygon {
                points: corners.iter().map(|c| c.0).collect(),
                fill: Some(shade(base, 0.4 + 0.65 * lambert)),
                stroke,
            },
        });
    }
    paint(faces, shapes);
    draw_dots(&scene.dots, &projector, shapes);
    draw_highlights(
        highlights,
        o.highlight_width,
        |p| projector.project(p).map(|c| c.0),
        shapes,
    );
}

/// The Gauss map: `net`'s points on a faint unit sphere, fitted into `r`,
/// orthographic from the same view, with its row 0 and column 0 highlighted.
fn draw_gauss(net: &QuadGrid, r: Rect, o: &RenderOptions, shapes: &mut Vec<Shape>) {
    let text = f64::from(o.text_size);
    let m = o.margin * r.w.min(r.h);
    let radius = ((r.w - 2.0 * m).min(r.h - 2.0 * m - 2.4 * text) / 2.0).max(1.0);
    let centre = [r.x + r.w / 2.0, r.y + m + radius];
    let cam = Camera::new(o.view.azimuth_deg, o.view.elevation_deg);
    let project = |n: DVec3| {
        n.is_finite().then(|| {
            pt(
                centre[0] + radius * n.dot(cam.u),
                centre[1] - radius * n.dot(cam.v),
            )
        })
    };
    shapes.push(Shape::Circle {
        center: pt(centre[0], centre[1]),
        radius: radius as f32,
        fill: Some(Rgba::new(246, 247, 250, 255)),
        stroke: None,
    });
    let back_pen = Pen {
        color: FAINT,
        width: o.edge_width.max(0.5),
    };
    let front_stroke = edge_pen(o);
    let mut back = Vec::new();
    let mut front = Vec::new();
    for i in 0..net.rows.saturating_sub(1) {
        for j in 0..net.cols.saturating_sub(1) {
            let corners =
                [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(a, b)| net.vertex(a, b));
            let Some(points) = corners
                .iter()
                .map(|n| project(*n))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let depth = corners.iter().map(|n| n.dot(cam.w)).sum::<f64>() / 4.0;
            if depth < 0.0 {
                back.push(Shape::Polygon {
                    points,
                    fill: None,
                    stroke: Some(back_pen),
                });
            } else {
                front.push(Face {
                    depth,
                    index: front.len(),
                    shape: Shape::Polygon {
                        points,
                        fill: Some(shade(o.front_color, 0.55 + 0.5 * depth)),
                        stroke: front_stroke,
                    },
                });
            }
        }
    }
    shapes.extend(back);
    paint(front, shapes);
    shapes.push(Shape::Circle {
        center: pt(centre[0], centre[1]),
        radius: radius as f32,
        fill: None,
        stroke: Some(Pen {
            color: Rgba::new(150, 156, 168, 255),
            width: 1.2,
        }),
    });
    let guides = crate::guide_highlights(
        &net.column(0).collect::<Vec<_>>(),
        &net.row(0).collect::<Vec<_>>(),
    );
    draw_highlights(&guides, o.highlight_width * 0.8, project, shapes);
    shapes.push(Shape::Text {
        center: pt(centre[0], centre[1] + radius + 1.4 * text),
        size: o.text_size,
        color: TEXT,
        text: GAUSS_CAPTION.to_owned(),
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_is_right_handed_with_z_up() {
        let c = Camera::new(-90.0, 0.0);
        assert!((c.u - DVec3::X).length() < 1e-12);
        assert!((c.v - DVec3::Z).length() < 1e-12);
        assert!((c.w + DVec3::Y).length() < 1e-12);
    }

    #[test]
    fn columns_keep_cells_near_three_by_two() {
        assert_eq!(auto_columns(1, 900.0, 600.0), 1);
        assert_eq!(auto_columns(3, 1500.0, 500.0), 3);
        assert_eq!(auto_columns(7, 1200.0, 800.0), 3);
        assert_eq!(auto_columns(4, 1200.0, 800.0), 2);
    }

    #[test]
    fn faces_are_painted_far_to_near() {
        let face = |depth: f64, index: usize| Face {
            depth,
            index,
            shape: Shape::Text {
                center: [0.0, 0.0],
                size: 1.0,
                color: TEXT,
                text: format!("{index}"),
            },
        };
        let mut shapes = Vec::new();
        paint(vec![face(1.0, 0), face(-1.0, 1), face(1.0, 2)], &mut shapes);
        let order: Vec<_> = shapes
            .iter()
            .map(|s| match s {
                Shape::Text { text, .. } => text.clone(),
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(order, ["1", "0", "2"]);
    }

    #[test]
    fn dots_alone_are_drawn_far_to_near_in_their_colours() {
        let o = RenderOptions::default();
        let w = Camera::new(o.view.azimuth_deg, o.view.elevation_deg).w;
        let (near, far) = (Rgb::new(1, 2, 3), Rgb::new(4, 5, 6));
        let scene = Scene {
            dots: vec![
                Dot {
                    point: w,
                    color: near,
                },
                Dot {
                    point: -w + DVec3::X,
                    color: far,
                },
            ],
            ..Scene::new(QuadGrid::new(0, 0, Vec::new(), Vec::new()))
        };
        let fills: Vec<Rgba> = sheet(&[Cell::of(&scene)], 1, &o)
            .unwrap()
            .into_iter()
            .filter_map(|s| match s {
                Shape::Circle { fill, .. } => fill,
                _ => None,
            })
            .collect();
        assert_eq!(fills, [Rgba::opaque(far), Rgba::opaque(near)]);
    }

    #[test]
    fn non_finite_points_break_lines() {
        let pts = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::NAN,
            DVec3::Y,
            DVec3::Z,
            DVec3::NAN,
        ];
        let r = runs(&pts, |p| p.is_finite().then(|| pt(p.x, p.y)));
        assert_eq!(r.len(), 2);
        assert_eq!(r[1], vec![[0.0, 1.0], [0.0, 0.0]]);
    }
}
