//! The command line: every command, flag and help text of `monge`.

use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand, ValueEnum};
use monge_core::cyclidic::CyclidicOptions;
use monge_core::{BasePoint, GenerateOptions, MeshKind};
use monge_io::{is_stdio, MeshFormat};
use monge_render::MAX_SIDE;

/// The θ convention, in one line, shared by the help texts.
const THETA: &str = "θ (`theta_deg`, degrees, taken modulo 360 into (−180°, 180°]) places the \
pencil axis {tan(θ/2)·N_p + s·t_v} of the Gauss map (t_u, t_v the unit start tangents, \
N_p = t_u × t_v normalised): θ = 0 gives a moulding surface with guide_u as its rail, \
θ = ±180° one with guide_v as its rail, θ = +90° is singular.";

/// Exit statuses, shared by the help texts.
const EXIT: &str = "Exit status: 0 success; 1 `monge check` found a metric above --tol; \
2 any error (unreadable, malformed or invalid design or mesh, unwritable output, bad \
arguments), reported on stderr as `error: <message>`.";

/// `monge`: exact circular meshes with planar curvature lines.
#[derive(Debug, Parser)]
#[command(
    name = "monge",
    version,
    about = "Exact circular quad meshes with planar curvature lines, from two planar guide curves and an angle θ",
    long_about = format!(
        "Exact circular quad meshes with planar curvature lines (Tellier et al. 2019, \"Surfaces \
         with planar curvature lines\", Automation in Construction 106, 102880), generated from two planar guide curves that start at the same \
         point and meet at 90°, and one angle θ.\n\n\
         A design file (JSON or TOML) gives `theta_deg`, `guide_u` and `guide_v`; each guide is one \
         of `points`, `bspline`, `arc` or `parabola`. Vertex (i, j) of the mesh lies on row i \
         (along guide_v) and column j (along guide_u): vertex (i, 0) is guide_u's sample i and \
         vertex (0, j) is guide_v's sample j.\n\n{THETA}"
    ),
    after_help = format!(
        "Examples:\n  \
         monge info examples/fig13-freeform.json\n  \
         monge generate examples/fig13-freeform.json -o mesh.obj\n  \
         monge check mesh.obj\n  \
         monge bench --sizes 100,1000\n\n{EXIT}"
    )
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands of `monge`.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Generate the mesh of a design and write it as OBJ, PLY or JSON.
    #[command(
        long_about = format!(
            "Generate the mesh of a design and write it as OBJ, PLY or JSON.\n\n\
             Reads DESIGN (`.json` or `.toml`), validates it (guides planar, starting at the same \
             point, meeting at 90°, θ admissible), builds the mesh exactly (§3) and writes it to OUT \
             in the format of OUT's extension (`.obj`, `.ply` or `.json`; `--format ply-binary` \
             or `ply-f32` for binary PLY with double or float coordinates), atomically: on any error \
             no file is created and an existing OUT is left untouched (with --offset, no file at \
             all). JSON output has `rows`, `cols`, `vertices`, `kind` and `offset`; a circular \
             mesh adds its node axes `normals`, a conical mesh its `face_normals` (§2.3), and \
             both `theta_deg`, `mode` and `report` (folded faces, first fold, smallest crossing \
             sine); a developable mesh (§3.3) adds `normals` and its slope `alpha_deg`. A one-paragraph summary (grid \
             size, mode, θ, admissible range, time taken, warnings about folds and pinches) goes \
             to stderr.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge generate examples/fig13-freeform.json -o mesh.obj\n  \
             monge generate examples/fig14-family.toml -o - --format ply > mesh.ply\n\n{EXIT}"
        )
    )]
    Generate(GenerateArgs),

    /// Build the smooth C¹ surface of a design: a cyclidic net of Dupin cyclide patches.
    #[command(
        long_about = format!(
            "Build the cyclidic net of a design (§4.4): one Dupin cyclide patch per face of its \
             circular mesh, with the frames of §4.4, so that patches share their boundary arcs and \
             tangent planes (C¹) and every curvature line is a planar chain of circular arcs: \
             one arc where the mesh line is inscribed in a circle, bi-arcs where it is inscribed \
             in two (§4.6).\n\n\
             OUT `.json`: `patches` (per face (i, j): the patch sampled on a K × K grid of its own \
             (u, v), row-major, (0, 0) at vertex (i, j), u towards (i+1, j), v towards (i, j+1)) and \
             `lines` (per mesh line: family `u` or `v`, index, and its arcs: center, radius, \
             normal, start, end). OUT `.igs`: the whole net as one exact NURBS surface (IGES \
             entity 128, rational, degree 2 × 2), which Rhino and other CAD tools open. OUT `.obj` \
             or `.ply`: the dense mesh of the whole net. A mesh \
             with folded faces (§5.2: crossed or non-convex, or turned over against the others; \
             the faces `monge check` counts) is refused unless --allow-folded, naming the first."
        ),
        after_help = format!(
            "Examples:\n  \
             monge smooth examples/fig12-dupin-theta30.json -o net.json --samples 9\n  \
             monge smooth examples/fig13-freeform.json -o smooth.obj\n\n{EXIT}"
        )
    )]
    Smooth(SmoothArgs),

    /// Measure a quad mesh: planarity, circularity, planar lines, node axes.
    #[command(
        long_about = format!(
            "Measure a quad mesh (from `monge generate` or any row-major quad grid) independently \
             of how it was made.\n\n\
             Reads MESH (`.obj`, `.ply` or `.json` by extension, or `-` for standard input with \
             --format) and prints, for each metric, its worst value and where it occurs, and PASS \
             or FAIL against --tol: face planarity (distance between the diagonals' lines), \
             circularity (distance of a corner from the circle through the other three), row and \
             column planarity (distance of a vertex from the best-fit plane of its curvature \
             line), all relative to the bounding-box diagonal; and, when the mesh has normals, \
             torsion (|det(edge, n_p, n_q)| over edges, also relative to the diagonal: 0 when the \
             node axes at both ends of every edge are coplanar) and normal length (| |n| − 1 |). \
             A conical mesh (--kind conical; by default the `kind` a JSON mesh names) has the \
             conical condition at every vertex instead of circularity, torsion and normal length."
        ),
        after_help = format!(
            "Examples:\n  \
             monge check mesh.obj\n  \
             monge generate examples/fig2-enneper.json -o - | monge check - --format json --json\n\n{EXIT}"
        )
    )]
    Check(CheckArgs),

    /// Validate a design and print what generation would use, without generating.
    #[command(
        long_about = format!(
            "Validate a design and print what generation would use, without building the mesh.\n\n\
             For each guide: its kind, number of samples, planarity deviation (absolute and \
             relative to the guide's size, against the design's tolerance), size (bounding-box \
             diagonal), unit start tangent and plane normal. Then the mode (characteristic §3.1: \
             every θ works; arbitrary §3.2: θ has an admissible range), the admissible θ in \
             degrees (both signs), whether the design's θ is admissible (an inadmissible θ is \
             reported, not an error), the singular θ = +90°, and the grid size.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge info examples/fig10-arbitrary.json\n  \
             monge info examples/fig14-family.toml --json\n\n{EXIT}"
        )
    )]
    Info(InfoArgs),

    /// Time the generator in-process on standard designs of n × n faces.
    #[command(
        long_about = format!(
            "Time the generator in-process on standard designs of n × n faces.\n\n\
             The design is built in code (no file I/O): two cubic B-spline guides in the \
             characteristic case (§3.1), guide_u with control points (0,0,0) (4,0,0) (8,0,2.5) \
             (12,0,1) (16,0,3.5) in the plane y = 0, guide_v with control points (0,0,0) (0,3,0) \
             (0,6,−1.5) (0,10,1) in the plane x = 0, θ = 30°, each guide sampled at n + 1 points. \
             Each timed run is a whole `generate` call, guide sampling included. After a warm-up, \
             prints one JSON line per size: \
             {{\"faces\":\"NxN\",\"median_ms\":M,\"runs\":R,\"min_ms\":A,\"max_ms\":B}}."
        ),
        after_help = format!(
            "Examples:\n  \
             monge bench\n  \
             monge bench --sizes 10,100 --runs 20\n  \
             monge bench --all\n\n{EXIT}"
        )
    )]
    Bench(BenchArgs),

    /// Draw designs as a shaded picture (PNG or SVG), or a sheet of θ values.
    #[command(
        long_about = format!(
            "Draw the mesh of a design as a picture: PNG or SVG by OUT's extension, written \
             atomically.\n\n\
             The mesh is seen from --view (z up) in a mild perspective (or --orthographic), \
             fitted to the picture. Its faces are shaded (light steel blue on the side facing \
             you, sand on the other, so folds show) and outlined; the guides are drawn on top: \
             guide_u (column 0) in red, guide_v (row 0) in blue. A design with \
             `\"mesh\": \"conical\"` is drawn as its conical dual (§2.3), with the guide samples \
             highlighted. With --gauss the Gauss map is drawn on the right: the node axes as a \
             quad net on the unit sphere (Figure 9), the normals along the guides in red and \
             blue.\n\n\
             Several DESIGNs make a contact sheet, one captioned cell each (any error stops \
             the command). --theta-sweep draws one DESIGN at several θ (the family of \
             Figure 14); a θ that cannot be built (the singular +90°, an inadmissible θ) \
             gets an empty crossed cell captioned with the reason. PNG captions use a \
             small pixel font in capitals.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge render examples/fig13-freeform.json -o freeform.png\n  \
             monge render examples/fig10-arbitrary.json -o gauss.svg --gauss --size 1500x700\n  \
             monge render examples/fig12-torus.json examples/fig12-dupin-theta30.json -o sheet.png\n  \
             monge render examples/fig14-family.toml --theta-sweep=-180,-90,0,45,90,150 -o family.png\n  \
             monge render examples/fig2-enneper.json -o top.png --view=-90,89 --orthographic\n\n{EXIT}"
        )
    )]
    Render(RenderArgs),

    /// Fabrication output of a gridshell: layers, panels, beams, nodes (§6).
    #[command(
        long_about = "Fabrication output of a gridshell built on the design's mesh (§6, Figure 25).\n\n\
             Generates the mesh (the conical dual for `\"mesh\": \"conical\"`), offsets it to every \
             --layers distance (node offsets along the node axes §2.2, face offsets §2.3), and writes \
             into DIR, all files or none (if one cannot be written, no file in DIR changes): panels.csv (every face flattened exactly in its plane: \
             outline, edges, angles, area, circumradius, residuals), beams.csv and segments.csv \
             (every row and column in its plane, split into circular arcs where the circle changes, \
             §4.6: radius, sweep, centre, split nodes, length along the arcs: the roller-bender list), nodes.csv (axis, \
             beam angles, height across the layers, torsion, node type), schedule.json (the \
             summary and the layers; with --full-json also every panel, beam and node), panels.dxf and beams.dxf (R12 drawings, labelled), overview.svg (plan) and \
             gridshell.glb (glTF of all layers, beams swept with a rectangular section). Prints a \
             summary: counts, segments per beam, distinct radii, node types, node heights, worst \
             residuals. Lengths and residuals in the files and the summary are in the model's \
             units; --tol is relative to the model's size (the summary prints it).",
        after_help = format!(
            "Examples:\n  \
             monge fabricate examples/fig12-dupin-theta30.json -o out --layers 0,0.1,0.2\n  \
             monge fabricate examples/fig25-biarc.json -o out --layers 0,-0.1,-0.2 --section 0.05,0.1\n\n{EXIT}"
        )
    )]
    Fabricate(crate::fabricate::FabricateArgs),

    /// Build a multi-patch mesh (§4.7), optionally assembled by symmetry (§4.5).
    #[command(
        long_about = format!(
            "Build a mesh with piecewise planar curvature lines from a multi-patch design \
             (§4.7, Figures 20 and 21) and write it as OBJ, PLY or JSON.\n\n\
             A multi-patch design (`.json` or `.toml`) has `patches`: the first with `theta_deg`, \
             `guide_u` and `guide_v` like a design file; every later one with its own \
             `theta_deg`, `attach`: {{\"patch\": K, \"side\": S}} (S = `last_row`, `first_row`, \
             `last_column` or `first_column` of the earlier patch K, in K's own grid) and \
             `guide`: the continuation, which must start at the first vertex of that line. The \
             line becomes one guide of the new patch, the continuation the other (for a row \
             side it continues guide_u, for a column side guide_v; a `first_` side runs \
             backwards). Start tangents are forced so that the node axes continue across the \
             seam: draw the continuation in the plane of the guide it continues (one planar \
             bottom guide cut in pieces) and the beams are C¹ there. All patches must follow \
             each other along rows, or all along columns: the result is one grid, shared lines \
             stored once.\n\n\
             Optional `symmetry`: a list of {{\"mirror\": {{\"point\", \"normal\"}}}} and \
             {{\"rotate\": {{\"point\", \"axis\", \"order\"}}}}, applied in order to all copies so \
             far (Figure 18: a mirror then order 5); the copies are merged where vertices \
             coincide (1e-9 of the size) into one quad mesh (OBJ/PLY/JSON with `quads`).\n\n\
             Without symmetry, JSON output has the grid plus `patches` (range, θ, mode, measured \
             max error, seam and axis gaps, kink) and `line_planes` (for each row and column the \
             plane it lies in within each patch it crosses). A summary goes to stderr.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge patches examples/fig20-piecewise.patches.json -o dome.obj\n  \
             monge patches examples/fig21-hippohaus.patches.json -o - > hippo.json\n\n{EXIT}"
        )
    )]
    Patches(PatchesArgs),

    /// Fit θ (and guide coordinates) of a multi-patch design to a target with BOBYQA (§4.7).
    #[command(
        long_about = format!(
            "Choose free parameters of a multi-patch design so that a patch boundary comes as \
             close as possible to a target (§4.7, the HippoHaus of Figure 21), with BOBYQA \
             (Powell 2009), and write the design with the fitted values to FITTED_DESIGN (the \
             `fit` section is kept, so the file can be fitted again or built with `monge \
             patches`). Prints the largest and rms distances before and after, and each value.\n\n\
             The design's `fit` key: `free`: a list of {{\"theta\": {{\"patch\": K, \"bounds\": \
             [lo, hi]}}}} (bounds optional) and {{\"control_point\": {{\"patch\": K, \"guide\": \
             \"guide_u\"|\"guide_v\"|\"guide\", \"index\": I, \"coordinate\": 0|1|2, \"bounds\": \
             [lo, hi]}}}} (a point of a `points` guide or a control point of a `bspline`); \
             `boundary`: {{\"patch\": K, \"side\": S}}; `target`: {{\"polyline\": [[x, y, z], …]}} \
             or {{\"plane\": {{\"point\", \"normal\"}}}} (e.g. the plane a patch must end in for a \
             mirror, Figure 20); optional `max_distance` (fail above it) and `max_evaluations`. \
             θ stays in its patch's admissible range at the start values (on the start's side of \
             0 when the range excludes 0) and 1° away from the singular +90°."
        ),
        after_help = format!(
            "Examples:\n  \
             monge fit examples/fig21-hippohaus-fit.patches.json -o fitted.json\n  \
             monge patches fitted.json -o hippo.obj\n\n{EXIT}"
        )
    )]
    Fit(FitArgs),

    /// Explore a design in the browser: drag θ and the guides, see the mesh live.
    #[command(
        long_about = "Serve the design explorer on this machine and print its address: a web page \
             with a 3D view of the mesh (guides highlighted, Gauss map beside it), a θ slider, \
             draggable control points of B-spline guides (kept in their planes, start tangents \
             kept), sample counts, circular/conical switch, offset distance, live metrics and \
             warnings where the mesh folds or θ is not admissible; designs load and save in the \
             design-file format, meshes export as OBJ or JSON.\n\n\
             The page computes the mesh in the browser (monge-core in WebAssembly, the same code \
             as `monge generate`); this server only serves the page and the start design \
             (GET /api/design), and computes nothing. It listens on 127.0.0.1 unless --host says \
             otherwise (and warns when it listens beyond this machine), answers GET and HEAD \
             only, and closes a connection whose request has not arrived whole within 10 s or \
             whose answer has not been taken within 30 s. The page is built into this binary; \
             --web-dir serves one from disk instead (`npm ci && npm run build` in web/ writes it \
             to web/dist).",
        after_help = format!(
            "Examples:\n  \
             monge explore\n  \
             monge explore examples/fig13-freeform.json --port 0\n\n{EXIT}"
        )
    )]
    Explore(crate::explore::ExploreArgs),

    /// Scan θ (or any number of a design) over a range: CSV table and SVG plot (§4.3, Figure 14).
    #[command(
        long_about = format!(
            "Generate the design at each value of θ (--theta START:END:STEP) or of any number of \
             the design (--param PATH --range START:END:STEP, PATH as in the design's JSON, e.g. \
             `guide_v.bspline.control_points[2][2]`), in parallel, and write one CSV row per value: \
             status (fair, folded, inadmissible, degenerate, invalid), admissible, folded faces and \
             the smallest crossing sine (pinching and self-intersection, §5.2), panel area min, max, \
             spread (max/min), mean and variance, the longest edge, the measured max error and the \
             generator's error message. --plot draws area spread and folded faces against the \
             value with folded (red), inadmissible (grey), degenerate (orange) and invalid (blue) \
             intervals shaded. A summary of the intervals goes to stderr; a progress bar too when \
             it is a terminal.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge scan examples/fig14-family.toml --theta -180:180:2 -o scan.csv --plot scan.svg\n  \
             monge scan examples/fig14-family.toml --param guide_v.bspline.control_points[2][2] \
             --range 1:5:0.5 -o scan.csv\n\n{EXIT}"
        )
    )]
    Scan(crate::scan::ScanArgs),

    /// Find the design whose exact mesh is nearest to a target mesh or point cloud.
    #[command(
        long_about = "Find the design (corner, two planar guides, θ) whose exactly generated mesh is \
                      nearest to TARGET both ways (mesh → target and target → mesh), with BOBYQA from \
                      the target's principal directions at its corners; prints the deviation before \
                      and after, relative to the target's size, and the measured exactness.",
        after_help = format!("Example:\n  monge approximate examples/targets/roof-pcl.obj -o roof.json --grid 20x20\n\n{EXIT}")
    )]
    Approximate(crate::approximate::ApproximateArgs),

    /// Choose where B-spline guides are sampled so that panel areas vary least (§4.8, Figure 22).
    #[command(
        long_about = format!(
            "Choose the sample parameters of the `bspline` guides of DESIGN (a monotone \
             reparametrisation: positive gaps, ends fixed) that minimise the variance of the panel \
             areas (divided by the squared mean), with BOBYQA, refusing samplings that fold the mesh \
             (§5.2), and write the design with each B-spline's `parameters` to OPTIMISED_DESIGN. \
             The samples stay on the same curves, so every exactness property still holds. Prints \
             the area variance, min and max before and after, and the measured max error."
        ),
        after_help = format!(
            "Examples:\n  \
             monge optimise-panels examples/fig22-panels.json -o even.json\n  \
             monge generate even.json -o even.obj\n\n{EXIT}"
        )
    )]
    OptimisePanels(crate::optimise_panels::OptimisePanelsArgs),

    /// Write a design whose mesh has its boundary rows and columns in four planes (§4.5, Figures 16–18).
    #[command(
        long_about = format!(
            "Write a design (two circular-arc guides and θ) whose mesh, from `monge generate`, has \
             its first row (guide_v) in `first_row` (P1), its last row in `last_row` (P2), its first \
             column (guide_u) in `first_column` (P3) and its last column in `last_column` (P4), to \
             round-off. PLANES is JSON:\n\n  \
             {{\"first_row\":    {{\"point\": [0,0,0], \"normal\": [0,0,1]}},\n   \
             \"last_row\":     {{\"point\": [2,0,0], \"normal\": [1,0,0]}},\n   \
             \"first_column\": {{\"point\": [0,0,0], \"normal\": [0,1,0]}},\n   \
             \"last_column\":  {{\"point\": [0,0,0], \"normal\": [-0.588,0.809,0]}},\n   \
             \"corner\": [5,0,0], \"theta_deg\": -60, \"samples\": 21}}\n\n\
             (a point and a normal per plane; `corner`, `theta_deg`, `samples` optional). The lines \
             P1 ∩ P2 and P3 ∩ P4 must have orthogonal directions (the Gauss circles of the four \
             boundary lines, {{n·p_k = c_k}}, then satisfy c_i·c_j = p_i·p_j, one free scale = θ). The \
             guides start at `corner` projected onto P1 ∩ P3 (default: the point of that line \
             nearest the mean of the planes' points). Without θ, monge scans θ in 1° steps and takes \
             the middle of the longest run that gives an unfolded mesh in the planes.\n\n\
             --facade (Figure 16): four vertical planes forming a rectangle in plan (P1 ∥ P2 ⊥ P3 ∥ P4); \
             the guides are S-shaped bi-arcs with horizontal end tangents, rising by `rise` \
             ({{\"guide_u\": h, \"guide_v\": h}}, default a quarter of each run); every θ but +90° \
             works.\n\n\
             Prints θ, the c_k, each boundary's distance from its plane (relative to the mesh size) \
             and the measured max error.\n\n{THETA}"
        ),
        after_help = format!(
            "Examples:\n  \
             monge align examples/fig17.planes.json -o fig17.json && monge generate fig17.json -o fig17.obj\n  \
             monge align examples/fig16-facade.planes.json --facade --samples 31 -o fig16.json\n\n{EXIT}"
        )
    )]
    Align(crate::align::AlignArgs),
}

/// Arguments of `monge patches`.
#[derive(Debug, clap::Args)]
pub struct PatchesArgs {
    /// The multi-patch design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Output file (`.obj`, `.ply` or `.json`), or `-` for standard output.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Output format, for `-o -` (default json) or an OUT whose extension names none; it must
    /// agree with OUT's extension.
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Refuse patches of more than N grid vertices each.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Arguments of `monge fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// The multi-patch design file with a `fit` key (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Where to write the fitted design (`.json` or `.toml`).
    #[arg(short, long, value_name = "FITTED_DESIGN")]
    pub output: PathBuf,
    /// Refuse patches of more than N grid vertices each.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Mesh formats on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// Wavefront OBJ.
    Obj,
    /// ASCII PLY.
    Ply,
    /// Binary little-endian PLY, `double` coordinates (exact; `.ply`).
    PlyBinary,
    /// Binary little-endian PLY, `float` coordinates (f32, for viewers; `.ply`).
    PlyF32,
    /// JSON (`rows`, `cols`, `vertices`, `normals`).
    Json,
    /// Binary glTF, for viewers (f32 coordinates; not read back by `check`).
    Glb,
}

/// The format of a mesh output OUT: `--format`, else OUT's extension (JSON for
/// `-`); a `--format` that contradicts OUT's extension is refused.
pub fn output_format(format: Option<FormatArg>, out: &Path) -> anyhow::Result<MeshFormat> {
    if is_stdio(out) {
        return Ok(format.map_or(MeshFormat::Json, MeshFormat::from));
    }
    let Some(format) = format.map(MeshFormat::from) else {
        return Ok(MeshFormat::from_path(out)?);
    };
    match MeshFormat::from_path(out) {
        Ok(by_extension) if by_extension.extension() != format.extension() => anyhow::bail!(
            "--format {} but OUT `{}` ends in `.{}`: name it `.{f}`, or leave --format out",
            format.name(),
            out.display(),
            by_extension.extension(),
            f = format.extension()
        ),
        _ => Ok(format),
    }
}

/// Mesh formats that are read back (glTF is written for viewers only, in f32).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ReadFormatArg {
    /// Wavefront OBJ.
    Obj,
    /// PLY, ASCII or binary little-endian.
    Ply,
    /// JSON (`rows`, `cols`, `vertices`, `normals`).
    Json,
}

impl From<ReadFormatArg> for MeshFormat {
    fn from(f: ReadFormatArg) -> MeshFormat {
        match f {
            ReadFormatArg::Obj => MeshFormat::Obj,
            ReadFormatArg::Ply => MeshFormat::Ply,
            ReadFormatArg::Json => MeshFormat::Json,
        }
    }
}

impl From<FormatArg> for MeshFormat {
    fn from(f: FormatArg) -> MeshFormat {
        match f {
            FormatArg::Obj => MeshFormat::Obj,
            FormatArg::Ply => MeshFormat::Ply,
            FormatArg::PlyBinary => MeshFormat::PlyBinary,
            FormatArg::PlyF32 => MeshFormat::PlyF32,
            FormatArg::Json => MeshFormat::Json,
            FormatArg::Glb => MeshFormat::Glb,
        }
    }
}

/// Arguments of `monge generate`.
#[derive(Debug, clap::Args)]
pub struct GenerateArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Output file (`.obj`, `.ply` or `.json`), or `-` for standard output.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Output format, for `-o -` (default json) or an OUT whose extension names none; it must
    /// agree with OUT's extension.
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Refuse grids of more than N vertices (rows × cols; of a developable design, rulings ×
    /// heights), before allocating anything.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
    /// Also write the offset at distance D (repeatable): the node offset along the node axes
    /// of a circular mesh (§2.2), the face offset of a conical mesh (§2.3). Each is written
    /// next to OUT as `STEM.offset+D.EXT` (or `-D`), in OUT's format.
    #[arg(long = "offset", value_name = "D", allow_negative_numbers = true, value_parser = parse_finite)]
    pub offsets: Vec<f64>,
    /// Write coordinates relative to a base point: `start` (the guides' common start point) or
    /// X,Y,Z. Far from the origin (beyond about 1e3 times the design's size) this keeps the
    /// mesh exact to 1e-9 of its size, which absolute f64 coordinates cannot. The mesh is
    /// computed relative to the point, and the file records it: JSON `base_point`, OBJ
    /// `# base_point x y z`, PLY `comment base_point x y z` (add it to every vertex for the
    /// true coordinates), glTF the node's translation. Off by default.
    #[arg(long, value_name = "start|X,Y,Z", allow_hyphen_values = true)]
    pub base_point: Option<BasePoint>,
}

/// What kind of mesh `monge check` measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum KindArg {
    /// A circular mesh: planar circular faces, planar lines, torsion-free node axes (§2.2).
    Circular,
    /// A conical mesh: planar faces tangent to a cone at each vertex, planar lines (§2.3).
    Conical,
}

impl From<MeshKind> for KindArg {
    fn from(kind: MeshKind) -> Self {
        match kind {
            MeshKind::Circular => KindArg::Circular,
            MeshKind::Conical => KindArg::Conical,
        }
    }
}

impl From<KindArg> for MeshKind {
    fn from(kind: KindArg) -> Self {
        match kind {
            KindArg::Circular => MeshKind::Circular,
            KindArg::Conical => MeshKind::Conical,
        }
    }
}

/// Arguments of `monge check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// The mesh file (`.obj`, `.ply` or `.json`), or `-` for standard input (needs --format).
    #[arg(value_name = "MESH")]
    pub mesh: PathBuf,
    /// Largest accepted value of each metric (a non-negative number).
    #[arg(
        long,
        value_name = "TOL",
        default_value = "1e-9",
        value_parser = parse_tolerance,
        allow_negative_numbers = true
    )]
    pub tol: f64,
    /// Format of standard input when MESH is `-` (files are read by their extension).
    #[arg(long, value_enum)]
    pub format: Option<ReadFormatArg>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// What MESH is: which properties to measure (default: the `kind` a JSON mesh
    /// written by monge names, else circular).
    #[arg(long, value_enum)]
    pub kind: Option<KindArg>,
    /// MESH is an offset of BASE (same grid): also measure how far the offset distance varies
    /// (vertex distances for a circular mesh, face-plane distances for a conical one).
    #[arg(long, value_name = "BASE")]
    pub offset_from: Option<PathBuf>,
}

/// Arguments of `monge info`.
#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Refuse designs of more than N grid vertices (as `monge generate` would).
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Arguments of `monge smooth`.
#[derive(Debug, clap::Args)]
pub struct SmoothArgs {
    /// The design file (`.json` or `.toml`).
    #[arg(value_name = "DESIGN")]
    pub design: PathBuf,
    /// Output: `.json` (patches and arcs), `.igs` (exact NURBS), `.obj`, `.ply` or `.glb` (dense
    /// mesh).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Samples per patch side, K ≥ 2 (K × K points a patch).
    #[arg(long, value_name = "K", default_value_t = 9, value_parser = clap::value_parser!(u32).range(2..=1000))]
    pub samples: u32,
    /// Refuse outputs estimated above this many gigabytes (10⁹ bytes), before computing
    /// them: about 60 bytes a sample point in `.json`, 190 a dense vertex in `.obj`.
    #[arg(long, value_name = "GB", default_value_t = crate::output::MAX_OUTPUT_GB, value_parser = crate::output::parse_gigabytes)]
    pub max_output: f64,
    /// Build the net over folded faces (those `monge check` counts) instead of refusing the mesh.
    #[arg(long)]
    pub allow_folded: bool,
    /// Largest accepted non-circularity of a face: |Im q| / |q| for the cross-ratio q of
    /// its corners (0 for a circle). Raise it for a mesh that is only nearly circular.
    #[arg(long, value_name = "TOL", default_value_t = CyclidicOptions::default().circularity_tolerance, value_parser = parse_tolerance)]
    pub circularity_tol: f64,
    /// DESIGN is a circular quad mesh (`.obj`, `.ply` or `.json`, row-major grid), not a design:
    /// the net is built on it (its lines need not be planar; then neither are the net's).
    #[arg(long)]
    pub mesh: bool,
    /// The frame at vertex (0, 0), carried over the whole mesh by reflections (§4.4), as
    /// `t1x,t1y,t1z,t2x,t2y,t2z` (orthonormal; t1 towards (1, 0), t2 towards (0, 1)).
    /// Default: the frames of §4.4 from the node axes, which make the curvature lines planar.
    #[arg(
        long,
        value_name = "T1,T2",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub frame: Option<Vec<f64>>,
}

/// Arguments of `monge bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Timed runs per size [default: enough for about 1 s per size, at least 5; with
    /// --all, runs of each command and size: 1].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: Option<u32>,
    /// Comma-separated grid sizes n (n × n faces, n + 1 samples per guide), each ≥ 2
    /// (a curved guide has 3 samples or more) [default: 100,1000; with --all 100,400,1000].
    #[arg(
        long,
        value_name = "N,N,…",
        value_delimiter = ',',
        value_parser = clap::value_parser!(u32).range(2..)
    )]
    pub sizes: Option<Vec<u32>>,
    /// Time every command instead (generate to .json/.obj/.ply (ASCII and binary)/.glb, check, fabricate,
    /// smooth to .json and .igs), each run --runs times as a child process of this binary
    /// in a temporary directory, each time into a new output (the last run's removed
    /// first, untimed): one JSON line per command and size with the median wall
    /// time, bytes written, time per million faces, the largest peak RSS, and the ratio to
    /// the median raw-write time of as many bytes (`write_all` and `sync_all` of a new file in
    /// the same directory, after each run).
    #[arg(long)]
    pub all: bool,
    /// Time `monge approximate` of the shipped 10 m roof target (2000 points, the default
    /// 40 × 40 grid) as a child process: one JSON line with wall time and peak RSS
    /// (after the lines of --all when both are given; the target is ≤ 10 s).
    #[arg(long)]
    pub approximate: bool,
    /// Refuse grids of more than N vertices.
    #[arg(long, value_name = "N", default_value_t = GenerateOptions::default().max_vertices)]
    pub max_vertices: usize,
}

/// Arguments of `monge render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The design files (`.json` or `.toml`); several make a contact sheet.
    #[arg(value_name = "DESIGN", required = true)]
    pub designs: Vec<PathBuf>,
    /// The picture to write: `.png` or `.svg`.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Also draw the Gauss map (the node axes on the unit sphere) beside each mesh.
    #[arg(long)]
    pub gauss: bool,
    /// Size of the picture in pixels, WIDTHxHEIGHT (each from 1 to 16384).
    #[arg(long, value_name = "WxH", default_value = "1200x800", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Where the eye is, in degrees: azimuth around z from +x towards +y, and elevation
    /// above the xy plane (−89 to 89). Write `--view=-55,30` for a negative azimuth.
    #[arg(long, value_name = "AZ,EL", default_value = "-55,30", value_parser = parse_view, allow_hyphen_values = true)]
    pub view: (f64, f64),
    /// Parallel projection instead of the default mild perspective.
    #[arg(long)]
    pub orthographic: bool,
    /// Draw the one DESIGN at each of these θ (comma-separated degrees) as a contact sheet.
    #[arg(
        long,
        value_name = "θ,θ,…",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = parse_finite
    )]
    pub theta_sweep: Option<Vec<f64>>,
    /// Cells per row of a contact sheet [default: cells closest to 3:2].
    #[arg(long, value_name = "N", default_value_t = 0, hide_default_value = true)]
    pub columns: usize,
    /// Draw the smooth surface instead: the cyclidic net (§4.4), K samples a patch side, with
    /// every curvature line through the mesh vertices drawn as its chain of circular arcs.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(2..=64))]
    pub smooth: Option<u32>,
    /// Colour the mesh by its distance to TARGET (a mesh or point cloud: .obj, .ply,
    /// .json), as `monge approximate` measures it: white on the target, dark red at the
    /// 95th percentile (at least 1e-6 of the target's size) and beyond; the caption
    /// gives the scale and the deviation both ways. One DESIGN only.
    #[arg(long, value_name = "TARGET")]
    pub deviation: Option<PathBuf>,
}

/// `--size`: `WIDTHxHEIGHT`, each from 1 to [`MAX_SIDE`].
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || {
        format!(
            "`{s}` is not a size: give WIDTHxHEIGHT in pixels, each from 1 to {MAX_SIDE}, e.g. \
             1200x800"
        )
    };
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let side = |t: &str| {
        let v = t.trim().parse::<u64>().map_err(|_| bad())?;
        match u32::try_from(v) {
            Ok(v @ 1..=MAX_SIDE) => Ok(v),
            _ => Err(format!(
                "`{s}`: a side of {v} pixels is outside 1 to {MAX_SIDE} (the largest picture monge \
                 draws is {MAX_SIDE} × {MAX_SIDE})"
            )),
        }
    };
    Ok((side(w)?, side(h)?))
}

/// `--view`: `AZ,EL` in degrees, the elevation from −89 to 89.
fn parse_view(s: &str) -> Result<(f64, f64), String> {
    let bad = || {
        format!(
            "`{s}` is not a view: give AZ,EL in degrees, e.g. -55,30 (elevation from -89 to 89)"
        )
    };
    let (a, e) = s.split_once(',').ok_or_else(bad)?;
    let az = parse_finite(a).map_err(|_| bad())?;
    let el = parse_finite(e).map_err(|_| bad())?;
    if !(-89.0..=89.0).contains(&el) {
        return Err(bad());
    }
    Ok((az, el))
}

/// `--offset`: a finite number.
fn parse_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{s}` is not a finite number")),
    }
}

/// `--tol`: a finite, non-negative number.
fn parse_tolerance(s: &str) -> Result<f64, String> {
    let t: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    if t.is_finite() && t >= 0.0 {
        Ok(t)
    } else {
        Err(format!("`{s}` is not a finite, non-negative number"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn sizes_and_views_parse() {
        assert_eq!(parse_size("900x600"), Ok((900, 600)));
        assert_eq!(parse_size("16384x1"), Ok((16384, 1)));
        for (size, side) in [("0x600", 0), ("20000x20000", 20000), ("900x16385", 16385)] {
            let err = parse_size(size).unwrap_err();
            assert!(
                err.contains(&format!("a side of {side} pixels is outside 1 to 16384")),
                "{err}"
            );
        }
        assert!(parse_size("900").is_err());
        assert_eq!(parse_view("-55,30"), Ok((-55.0, 30.0)));
        assert!(parse_view("0,90").is_err());
        assert!(parse_view("nan,0").is_err());
    }

    #[test]
    fn tolerance_must_be_finite_and_non_negative() {
        assert_eq!(parse_tolerance("1e-6"), Ok(1e-6));
        assert!(parse_tolerance("-1").is_err());
        assert!(parse_tolerance("nan").is_err());
        assert!(parse_tolerance("x").is_err());
    }
}
