//! Fabrication schedules (§6): panels, beams, beam segments and nodes as CSV,
//! and everything as one JSON document.
//!
//! Every number is written so that it parses back to the same `f64`; angles
//! are in degrees in the CSV files and in radians in the JSON document (as in
//! [`monge_core::fabrication`]). Lists inside one CSV cell are separated by `;`.

use std::io::{self, Write};

use glam::DVec3;
use monge_core::fabrication::{
    Beam, Fabrication, LineFamily, Panel, PlaneFrame, SegmentShape, Summary,
};
use serde::Serialize;

use crate::text::{emit, Out};

/// The label of a panel (§6): `L<layer>-P<i>.<j>`.
pub fn panel_label(p: &Panel) -> String {
    label_string(|o| put_panel_label(o, p))
}

/// The label of a beam (§6): `L<layer>-R<i>` for row `i`, `L<layer>-C<j>` for column `j`.
pub fn beam_label(b: &Beam) -> String {
    label_string(|o| put_beam_label(o, b))
}

/// A label written by `put` into a new string.
fn label_string(put: impl FnOnce(&mut Out<'_, Vec<u8>>)) -> String {
    let mut v = Vec::new();
    emit(&mut v, |o| {
        put(o);
        Ok(())
    })
    .expect("writing to a Vec cannot fail");
    String::from_utf8(v).expect("labels are ASCII")
}

/// Appends [`panel_label`] to `o` without allocating.
pub(crate) fn put_panel_label<W: Write + ?Sized>(o: &mut Out<'_, W>, p: &Panel) {
    o.push(b'L');
    o.int(p.layer);
    o.str("-P");
    o.int(p.i);
    o.push(b'.');
    o.int(p.j);
}

/// Appends [`beam_label`] to `o` without allocating.
pub(crate) fn put_beam_label<W: Write + ?Sized>(o: &mut Out<'_, W>, b: &Beam) {
    o.push(b'L');
    o.int(b.layer);
    o.str(match b.family {
        LineFamily::Row => "-R",
        LineFamily::Column => "-C",
    });
    o.int(b.index);
}

/// `,a,b,c`: each value as its own CSV cell, after a comma.
fn cells<W: Write + ?Sized>(o: &mut Out<'_, W>, values: impl IntoIterator<Item = f64>) {
    for v in values {
        o.push(b',');
        o.float(v);
    }
}

/// `a;b;c`: a list in one CSV cell.
fn list<W: Write + ?Sized>(o: &mut Out<'_, W>, values: impl IntoIterator<Item = f64>) {
    for (k, v) in values.into_iter().enumerate() {
        if k > 0 {
            o.push(b';');
        }
        o.float(v);
    }
}

/// `,x,y,z` of each vector: a plane frame's origin, x axis and normal.
fn frame_cells<W: Write + ?Sized>(o: &mut Out<'_, W>, frame: &PlaneFrame) {
    for v in [frame.origin, frame.x_axis, frame.normal] {
        cells(o, v.to_array());
    }
}

/// The panel schedule (§2.2, §6): one line per panel with its flat outline
/// (corner k at `xk, yk` in the panel's plane frame), edge lengths, corner angles
/// (degrees), area, circumradius, residuals and the plane frame in space.
pub fn write_panels_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    emit(w, |o| {
        o.str(
            "label,layer,i,j,x0,y0,x1,y1,x2,y2,x3,y3,edge0,edge1,edge2,edge3,angle0_deg,angle1_deg,\
             angle2_deg,angle3_deg,area,circumradius,planarity,circularity,origin_x,origin_y,origin_z,\
             x_axis_x,x_axis_y,x_axis_z,normal_x,normal_y,normal_z",
        );
        o.end()?;
        // Panels computed and formatted in chunks side by side.
        o.each_range(f.panels().len(), |o, range| {
            for p in f.panels_in(range) {
                put_panel_label(o, &p);
                for n in [p.layer, p.i, p.j] {
                    o.push(b',');
                    o.int(n);
                }
                cells(o, p.outline.iter().flat_map(|q| [q.x, q.y]));
                cells(o, p.edge_lengths);
                cells(o, p.angles.map(f64::to_degrees));
                cells(o, [p.area, p.circumradius, p.planarity, p.circularity]);
                frame_cells(o, &p.frame);
                o.push(b'\n');
            }
        })
    })
}

/// The beam schedule (§4.6, §6): one line per beam with its node count, its
/// developed length along its arcs ([`Beam::length`](monge_core::fabrication::Beam::length))
/// and the length of the polyline through its nodes, number of circular
/// segments, split nodes, radii, largest torsion, plane residual and plane in space.
pub fn write_beams_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    emit(w, |o| {
        o.str(
            "label,layer,family,index,nodes,length,polyline_length,segments,splits,radii,\
             plane_residual,max_torsion,\
             origin_x,origin_y,origin_z,x_axis_x,x_axis_y,x_axis_z,normal_x,normal_y,normal_z",
        );
        o.end()?;
        for b in f.beams() {
            put_beam_label(o, &b);
            o.push(b',');
            o.int(b.layer);
            o.push(b',');
            o.str(family(b.family));
            o.push(b',');
            o.int(b.index);
            o.push(b',');
            o.int(b.nodes.len());
            cells(o, [b.length(), b.edge_lengths.iter().sum::<f64>()]);
            o.push(b',');
            o.int(b.segments.len());
            o.push(b',');
            for (k, s) in b.splits().iter().enumerate() {
                if k > 0 {
                    o.push(b';');
                }
                o.int(*s);
            }
            o.push(b',');
            list(
                o,
                b.segments.iter().filter_map(|s| match s.shape {
                    SegmentShape::Arc { radius, .. } => Some(radius),
                    SegmentShape::Straight { .. } => None,
                }),
            );
            cells(
                o,
                [
                    b.plane_residual,
                    b.torsion.iter().copied().fold(0.0, f64::max),
                ],
            );
            frame_cells(o, &b.frame);
            o.end()?;
        }
        Ok(())
    })
}

fn family(f: LineFamily) -> &'static str {
    match f {
        LineFamily::Row => "row",
        LineFamily::Column => "column",
    }
}

/// The roller-bender list (§4.6): one line per circular or straight segment of
/// every beam, with its node range, radius, sweep (degrees, signed), length and
/// centre (in the beam's plane and in space); radius and centre are empty for
/// straight segments.
pub fn write_segments_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    emit(w, |o| {
        o.str(
            "beam,segment,start_node,end_node,kind,radius,sweep_deg,length,center_u,center_v,\
             center_x,center_y,center_z,residual",
        );
        o.end()?;
        for b in f.beams() {
            for (k, s) in b.segments.iter().enumerate() {
                put_beam_label(o, &b);
                for n in [k, s.start, s.end] {
                    o.push(b',');
                    o.int(n);
                }
                match s.shape {
                    SegmentShape::Arc {
                        center,
                        center_3d,
                        radius,
                        sweep,
                        length,
                    } => {
                        o.str(",arc");
                        cells(o, [radius, sweep.to_degrees(), length, center.x, center.y]);
                        cells(o, center_3d.to_array());
                    }
                    SegmentShape::Straight { length } => {
                        o.str(",straight,,0");
                        cells(o, [length]);
                        o.str(",,,,,");
                    }
                }
                cells(o, [s.residual]);
                o.end()?;
            }
        }
        Ok(())
    })
}

/// The node schedule (§2.2, §6): one line per node with its position on the
/// base layer, axis, the edge directions present, beam and axis angles
/// (degrees), height across the layers, torsion and node type.
pub fn write_nodes_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    emit(w, |o| {
        o.str(
            "i,j,x,y,z,axis_x,axis_y,axis_z,directions,beam_angles_deg,axis_angles_deg,height,\
             torsion,type",
        );
        o.end()?;
        // Nodes computed and formatted in chunks side by side.
        o.each_range(f.nodes().len(), |o, range| {
            for n in f.nodes_in(range) {
                o.int(n.i);
                o.push(b',');
                o.int(n.j);
                cells(o, n.position.to_array());
                cells(o, n.axis.to_array());
                o.push(b',');
                for (k, d) in n.directions.iter().enumerate() {
                    if k > 0 {
                        o.push(b';');
                    }
                    o.str(d);
                }
                for angles in [&n.beam_angles, &n.axis_angles] {
                    o.push(b',');
                    list(o, angles.iter().map(|a| a.to_degrees()));
                }
                cells(o, [n.height, n.torsion]);
                o.push(b',');
                o.int(n.node_type);
                o.push(b'\n');
            }
        })
    })
}

/// What `schedule.json` holds (§6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ScheduleJson {
    /// `summary` and `layers` (distances): the schedules themselves are the CSV
    /// files (`monge fabricate`'s default; at 1000 × 1000 faces the full
    /// document is 1.7 GB, 40 % of the bytes written).
    #[default]
    Summary,
    /// Also every panel, beam (with its nodes in its plane, turning angles,
    /// torsion and `segments`) and node, each panel and beam with its `label`.
    Full,
}

/// The fabrication as one JSON document (§6): `summary` and `layers`
/// (distances), `base_point` when the coordinates are relative to one, and
/// with [`ScheduleJson::Full`] also `panels`, `beams` (with `label` and
/// `segments`) and `nodes`.
pub fn write_schedule_json(
    f: &Fabrication,
    content: ScheduleJson,
    base: Option<DVec3>,
    w: &mut dyn Write,
) -> io::Result<()> {
    #[derive(Serialize)]
    struct Labelled<T> {
        label: String,
        #[serde(flatten)]
        item: T,
    }
    /// A list serialized item by item (from a copy of the iterator).
    struct Seq<I>(I);
    impl<I> Serialize for Seq<I>
    where
        I: Iterator + Clone,
        I::Item: Serialize,
    {
        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            s.collect_seq(self.0.clone())
        }
    }
    #[derive(Serialize)]
    struct Doc<'a, P: Serialize, B: Serialize, N: Serialize> {
        summary: &'a Summary,
        layers: Vec<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        base_point: Option<[f64; 3]>,
        #[serde(skip_serializing_if = "Option::is_none")]
        panels: Option<P>,
        #[serde(skip_serializing_if = "Option::is_none")]
        beams: Option<B>,
        #[serde(skip_serializing_if = "Option::is_none")]
        nodes: Option<N>,
    }
    let full = content == ScheduleJson::Full;
    let doc = Doc {
        summary: &f.summary,
        layers: f.layers.iter().map(|l| l.distance).collect(),
        base_point: base.map(|b| b.to_array()),
        panels: full.then(|| {
            Seq(f.panels().map(|p| Labelled {
                label: panel_label(&p),
                item: p,
            }))
        }),
        beams: full.then(|| {
            Seq(f.beams().map(|b| Labelled {
                label: beam_label(&b),
                item: b,
            }))
        }),
        nodes: full.then(|| Seq(f.nodes())),
    };
    serde_json::to_writer(&mut *w, &doc).map_err(io::Error::other)?;
    writeln!(w)
}
