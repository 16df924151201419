//! Fabrication schedules (§6): panels, beams, beam segments and nodes as CSV,
//! and everything as one JSON document.
//!
//! Every number is written so that it parses back to the same `f64`; angles
//! are in degrees in the CSV files and in radians in the JSON document (as in
//! [`monge_core::fabrication`]). Lists inside one CSV cell are separated by `;`.

use std::io::{self, Write};

use monge_core::fabrication::{Beam, Fabrication, LineFamily, Panel, SegmentShape, Summary};
use serde::Serialize;

/// The label of a panel (§6): `L<layer>-P<i>.<j>`.
pub fn panel_label(p: &Panel) -> String {
    format!("L{}-P{}.{}", p.layer, p.i, p.j)
}

/// The label of a beam (§6): `L<layer>-R<i>` for row `i`, `L<layer>-C<j>` for column `j`.
pub fn beam_label(b: &Beam) -> String {
    let family = match b.family {
        LineFamily::Row => 'R',
        LineFamily::Column => 'C',
    };
    format!("L{}-{}{}", b.layer, family, b.index)
}

/// `a;b;c`: a list in one CSV cell.
fn list(values: impl IntoIterator<Item = f64>) -> String {
    values
        .into_iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(";")
}

/// The panel schedule (§2.2, §6): one line per panel with its flat outline
/// (corner k at `xk, yk` in the panel's plane frame), edge lengths, corner angles
/// (degrees), area, circumradius, residuals and the plane frame in space.
pub fn write_panels_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    writeln!(
        w,
        "label,layer,i,j,x0,y0,x1,y1,x2,y2,x3,y3,edge0,edge1,edge2,edge3,angle0_deg,angle1_deg,\
         angle2_deg,angle3_deg,area,circumradius,planarity,circularity,origin_x,origin_y,origin_z,\
         x_axis_x,x_axis_y,x_axis_z,normal_x,normal_y,normal_z"
    )?;
    for p in &f.panels {
        let mut cells = vec![
            panel_label(p),
            p.layer.to_string(),
            p.i.to_string(),
            p.j.to_string(),
        ];
        cells.extend(
            p.outline
                .iter()
                .flat_map(|q| [q.x.to_string(), q.y.to_string()]),
        );
        cells.extend(p.edge_lengths.iter().map(|v| v.to_string()));
        cells.extend(p.angles.iter().map(|v| v.to_degrees().to_string()));
        cells.extend(
            [p.area, p.circumradius, p.planarity, p.circularity]
                .iter()
                .map(|v| v.to_string()),
        );
        for v in [p.frame.origin, p.frame.x_axis, p.frame.normal] {
            cells.extend(v.to_array().iter().map(|c| c.to_string()));
        }
        writeln!(w, "{}", cells.join(","))?;
    }
    Ok(())
}

/// The beam schedule (§4.6, §6): one line per beam with its node count, length
/// along the nodes, number of circular segments, split nodes, radii, largest
/// torsion, plane residual and plane in space.
pub fn write_beams_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    writeln!(
        w,
        "label,layer,family,index,nodes,length,segments,splits,radii,plane_residual,max_torsion,\
         origin_x,origin_y,origin_z,x_axis_x,x_axis_y,x_axis_z,normal_x,normal_y,normal_z"
    )?;
    for b in &f.beams {
        let radii = b.segments.iter().filter_map(|s| match s.shape {
            SegmentShape::Arc { radius, .. } => Some(radius),
            SegmentShape::Straight { .. } => None,
        });
        let mut cells = vec![
            beam_label(b),
            b.layer.to_string(),
            family(b.family).to_owned(),
            b.index.to_string(),
            b.nodes.len().to_string(),
            b.edge_lengths.iter().sum::<f64>().to_string(),
            b.segments.len().to_string(),
            b.splits()
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(";"),
            list(radii),
            b.plane_residual.to_string(),
            b.torsion.iter().copied().fold(0.0, f64::max).to_string(),
        ];
        for v in [b.frame.origin, b.frame.x_axis, b.frame.normal] {
            cells.extend(v.to_array().iter().map(|c| c.to_string()));
        }
        writeln!(w, "{}", cells.join(","))?;
    }
    Ok(())
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
    writeln!(
        w,
        "beam,segment,start_node,end_node,kind,radius,sweep_deg,length,center_u,center_v,\
         center_x,center_y,center_z,residual"
    )?;
    for b in &f.beams {
        for (k, s) in b.segments.iter().enumerate() {
            let shape = match s.shape {
                SegmentShape::Arc {
                    center,
                    center_3d,
                    radius,
                    sweep,
                    length,
                } => format!(
                    "arc,{radius},{},{length},{},{},{},{},{}",
                    sweep.to_degrees(),
                    center.x,
                    center.y,
                    center_3d.x,
                    center_3d.y,
                    center_3d.z
                ),
                SegmentShape::Straight { length } => format!("straight,,0,{length},,,,,"),
            };
            writeln!(
                w,
                "{},{k},{},{},{shape},{}",
                beam_label(b),
                s.start,
                s.end,
                s.residual
            )?;
        }
    }
    Ok(())
}

/// The node schedule (§2.2, §6): one line per node with its position on the
/// base layer, axis, the edge directions present, beam and axis angles
/// (degrees), height across the layers, torsion and node type.
pub fn write_nodes_csv(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    writeln!(
        w,
        "i,j,x,y,z,axis_x,axis_y,axis_z,directions,beam_angles_deg,axis_angles_deg,height,torsion,type"
    )?;
    for n in &f.nodes {
        let deg = |v: &[f64]| list(v.iter().map(|a| a.to_degrees()));
        writeln!(
            w,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            n.i,
            n.j,
            n.position.x,
            n.position.y,
            n.position.z,
            n.axis.x,
            n.axis.y,
            n.axis.z,
            n.directions.join(";"),
            deg(&n.beam_angles),
            deg(&n.axis_angles),
            n.height,
            n.torsion,
            n.node_type
        )?;
    }
    Ok(())
}

/// The whole fabrication as one JSON document (§6): `summary`, `layers`
/// (distances), `panels`, `beams` (with `label` and `segments`) and `nodes`.
pub fn write_schedule_json(f: &Fabrication, w: &mut dyn Write) -> io::Result<()> {
    #[derive(Serialize)]
    struct Labelled<'a, T> {
        label: String,
        #[serde(flatten)]
        item: &'a T,
    }
    #[derive(Serialize)]
    struct Doc<'a> {
        summary: &'a Summary,
        layers: Vec<f64>,
        panels: Vec<Labelled<'a, Panel>>,
        beams: Vec<Labelled<'a, Beam>>,
        nodes: &'a [monge_core::fabrication::Node],
    }
    let doc = Doc {
        summary: &f.summary,
        layers: f.layers.iter().map(|l| l.distance).collect(),
        panels: f
            .panels
            .iter()
            .map(|p| Labelled {
                label: panel_label(p),
                item: p,
            })
            .collect(),
        beams: f
            .beams
            .iter()
            .map(|b| Labelled {
                label: beam_label(b),
                item: b,
            })
            .collect(),
        nodes: &f.nodes,
    };
    serde_json::to_writer(&mut *w, &doc).map_err(io::Error::other)?;
    writeln!(w)
}
