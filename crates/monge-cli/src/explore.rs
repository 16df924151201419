//! `monge explore`: the design explorer, a web page served on the local machine
//! that regenerates the mesh while a designer drags θ and the guides' control
//! points (§1, §5.1: real-time exploration of the design space).
//!
//! The page computes the mesh itself, with monge-core compiled to WebAssembly
//! (`crates/monge-wasm`), and works from any static file server; this server
//! serves it, hands it the design given on the command line (`GET
//! /api/design`), and answers the same computations over HTTP for other
//! clients (`POST /api/generate`, `POST /api/export`). The server is
//! [`crate::http`]: small, synchronous, bounded (connections, time to send a
//! request, requests computed at a time). It answers only its own page
//! ([`guard`]: `Host` and `Origin` checked). The page's
//! files (HTML, CSS, the module `monge_wasm_bg.wasm`, and the JS bundled with
//! three.js and the module's glue by `npm run build` in `web/`) are embedded in the binary from
//! `crates/monge-cli/web-dist/` (a committed copy of `web/dist`), so a copied or
//! installed `monge` serves its page; `--web-dir` serves another directory instead.
//!
//! Routes:
//! * `GET /`, `GET /<file>`: the page, embedded or from `--web-dir`.
//! * `GET /api/design`: the design to start from (DESIGN, or a built-in one of
//!   100 × 100 faces).
//! * `POST /api/generate[?offset=D][&arrays=f32][&metrics=later][&name=FILE][&format=toml]`:
//!   a design (JSON, or TOML with `format=toml`) → the mesh as JSON: see
//!   [`mesh_json`]. `metrics=later` leaves the metrics out (`"metrics": null`),
//!   for the page while θ or a point is being dragged: it asks again, with them,
//!   when the drag stops. Errors are 4xx with `{"error": message}`, the message the
//!   CLI prints (naming FILE when given).
//! * `POST /api/export?format=obj|ply|json[&offset=D]`: the mesh as a file,
//!   exactly as `monge generate` writes it.

use std::fs;
use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpListener};
use std::path::{Component, Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context};
use glam::DVec3;
use include_dir::{include_dir, Dir};
use monge_core::conical::conical_dual;
use monge_core::offset::{face_offset, vertex_offset};
use monge_core::{generate, inspect, Design, GenerateError, GenerateOptions, MeshKind, QuadGrid};
use monge_io::generated::{json_extras, kind_name, layer_extras, metrics_json, report_json};
use monge_io::{parse_design, write_mesh_json, write_mesh_to, DesignFormat, MeshFormat};
use serde_json::{json, Map, Value};
use socket2::{Domain, Protocol, Socket, Type};

use crate::generate::{mode_name, near_singular, range_text};
use crate::http;
use crate::output::{num, print};
use crate::Outcome;

/// Largest request body accepted, in bytes.
pub const MAX_BODY: usize = 1 << 20;

/// Default largest grid (`rows · cols` vertices) of one request: 500 × 500.
pub const MAX_VERTICES: usize = 250_000;

/// The server's bounds: 256 connections, 4 requests computed at a time, 10 s
/// to send a request, 60 s idle between requests, 30 s to take an answer.
const LIMITS: http::Limits = http::Limits {
    max_connections: 256,
    workers: 4,
    request_timeout: Duration::from_secs(10),
    idle_timeout: Duration::from_secs(60),
    write_timeout: Duration::from_secs(30),
    max_header: 16 << 10,
    max_body: MAX_BODY,
};

/// Below this smallest crossing sine the page warns that the mesh nearly pinches (§5.2).
const LOW_CROSSING_SINE: f64 = 1e-3;

/// The design shown when `monge explore` is given none: the page's own default
/// (`web/src/default-design.json`), the `monge bench` design at 100 × 100 faces
/// (two cubic B-splines, characteristic case, θ = 30°).
const DEFAULT_DESIGN: &str = include_str!("../web-dist/default-design.json");

/// Arguments of `monge explore`.
#[derive(Debug, clap::Args)]
pub struct ExploreArgs {
    /// The design to start from (`.json` or `.toml`) [default: a built-in
    /// design of 100 × 100 faces].
    #[arg(value_name = "DESIGN")]
    pub design: Option<PathBuf>,
    /// TCP port; 0 picks a free one (the address is printed).
    #[arg(long, default_value_t = 8642)]
    pub port: u16,
    /// Address to listen on. The default, 127.0.0.1, is reachable from this
    /// machine only. Another address (e.g. 0.0.0.0: every network interface)
    /// exposes the explorer, its API and its start design to everyone who can
    /// reach this machine on the network, who can then make it compute (no
    /// password, no encryption); requests must still name the server by an IP
    /// address or `localhost` in `Host`. Keep the default unless you mean it.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    pub host: IpAddr,
    /// Serve the page's files from DIR (e.g. `web/dist`, built by `npm ci && npm run build`
    /// in `web/`) instead of the copy embedded in this binary.
    #[arg(long, value_name = "DIR")]
    pub web_dir: Option<PathBuf>,
    /// Refuse designs of more than N grid vertices (rows × cols).
    #[arg(long, value_name = "N", default_value_t = MAX_VERTICES)]
    pub max_vertices: usize,
}

/// The page built by `npm run build` in `web/`, as committed in `web-dist/`.
static EMBEDDED_PAGE: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/web-dist");

/// Where the page's files come from.
enum Page {
    /// The copy embedded in the binary.
    Embedded,
    /// A directory given with `--web-dir`.
    Directory(PathBuf),
}

/// What every request handler shares.
struct Shared {
    /// The start design, as JSON text.
    design: String,
    /// The page's files.
    page: Page,
    /// The grid limit.
    options: GenerateOptions,
    /// Where the server listens.
    address: SocketAddr,
}

/// Runs `monge explore`: serves until the process is stopped.
pub fn run(args: &ExploreArgs) -> anyhow::Result<Outcome> {
    let design = match &args.design {
        Some(path) => {
            let design = monge_io::read_design(path)?;
            serde_json::to_string_pretty(&design).context("cannot encode the design as JSON")?
        }
        None => DEFAULT_DESIGN.to_owned(),
    };
    let listener = listen(SocketAddr::new(args.host, args.port))
        .map_err(|e| anyhow!("cannot listen on {}:{}: {e}", args.host, args.port))?;
    let address = listener.local_addr().context("the server has no address")?;
    let page = match &args.web_dir {
        Some(dir) if !dir.join("index.html").is_file() => bail!(
            "--web-dir `{}` has no index.html: build the page with `npm ci && npm run build` in \
             web/ and give `--web-dir web/dist`, or leave --web-dir out to serve the page built \
             into monge",
            dir.display()
        ),
        Some(dir) => Page::Directory(dir.clone()),
        None => Page::Embedded,
    };
    print(&format!(
        "monge explore: open http://{address}/ (Ctrl-C to stop)\n"
    ))?;
    let shared = Shared {
        design,
        page,
        options: GenerateOptions {
            max_vertices: args.max_vertices,
        },
        address,
    };
    http::serve(listener, LIMITS, move |request| answer(request, &shared))
        .with_context(|| format!("the server on {address} stopped"))?;
    Ok(Outcome::Success)
}

/// A TCP listener on `address` whose connections send without delay.
///
/// Answers are written in one piece, but small answers still go out at once
/// with `TCP_NODELAY` (measured with Nagle's algorithm and separate writes:
/// 44 ms for every small POST answer in Chromium). Linux passes `TCP_NODELAY`
/// on from the listener to the connections it accepts.
fn listen(address: SocketAddr) -> Result<TcpListener, std::io::Error> {
    let socket = Socket::new(
        Domain::for_address(address),
        Type::STREAM,
        Some(Protocol::TCP),
    )?;
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket.bind(&address.into())?;
    socket.listen(128)?;
    Ok(socket.into())
}

/// An answer: status, content type, body, and an optional download name.
#[derive(Debug)]
struct Reply {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
    download: Option<String>,
}

impl Reply {
    /// A JSON reply.
    fn json(status: u16, value: &Value) -> Reply {
        Reply {
            status,
            content_type: "application/json",
            body: value.to_string().into_bytes(),
            download: None,
        }
    }

    /// `{"error": message}` with `status`.
    fn error(status: u16, message: impl Into<String>) -> Reply {
        Reply::json(status, &json!({ "error": message.into() }))
    }
}

/// Answers one request, once [`guard`] lets it through.
fn answer(request: &http::Request, shared: &Shared) -> http::Response {
    let reply = match guard(request, shared.address) {
        Ok(()) => route(&request.method, &request.target, &request.body, shared),
        Err(reply) => reply,
    };
    let mut headers = Vec::new();
    if let Some(name) = reply.download {
        headers.push((
            "Content-Disposition",
            format!("attachment; filename=\"{name}\""),
        ));
    }
    http::Response {
        status: reply.status,
        content_type: reply.content_type,
        headers,
        body: reply.body,
        head_only: false,
    }
}

/// Only the explorer's own page may use the server: a request whose `Host` is
/// not this server by an IP address or `localhost` (a page of another site
/// whose name was made to resolve to 127.0.0.1: DNS rebinding) is refused with
/// 403, and so is a `POST` whose `Origin` is another site (any page can send a
/// simple cross-origin `POST`). A request without `Origin` (not from a browser,
/// or a same-origin `GET`) passes.
fn guard(request: &http::Request, address: SocketAddr) -> Result<(), Reply> {
    let header = |name| request.header(name).map_err(|m| Reply::error(400, m));
    let host = header("host")?.unwrap_or("");
    if !is_own_host(host, address) {
        return Err(Reply::error(
            403,
            format!(
                "Host `{host}` is not this server: open http://{address}/ (or \
                 http://localhost:{}/) itself",
                address.port()
            ),
        ));
    }
    if request.method != "GET" && request.method != "HEAD" {
        if let Some(origin) = header("origin")? {
            let own = origin
                .strip_prefix("http://")
                .is_some_and(|host| is_own_host(host, address));
            if !own {
                return Err(Reply::error(
                    403,
                    format!(
                        "a page of `{origin}` may not use this server: only the explorer's \
                         own page at http://{address}/ may"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Whether `host` (a `Host` header, `NAME:PORT`) names this server: `localhost`
/// or an IP address (a name other than `localhost` can be made to resolve to any
/// address; an IP address cannot), with this server's port.
fn is_own_host(host: &str, address: SocketAddr) -> bool {
    let Some((name, port)) = host.rsplit_once(':') else {
        return false;
    };
    let name = name
        .strip_prefix('[')
        .and_then(|n| n.strip_suffix(']'))
        .unwrap_or(name);
    port.parse() == Ok(address.port())
        && (name.eq_ignore_ascii_case("localhost") || name.parse::<IpAddr>().is_ok())
}

/// Dispatches a request by method and path.
fn route(method: &str, url: &str, body: &[u8], shared: &Shared) -> Reply {
    // HEAD is GET without the body (the server leaves the body out).
    let method = if method == "HEAD" { "GET" } else { method };
    let (path, query) = url.split_once('?').unwrap_or((url, ""));
    let query = Query::parse(query);
    match (method, path) {
        ("POST", "/api/generate") => api_generate(body, &query, shared),
        ("POST", "/api/export") => api_export(body, &query, shared),
        ("GET", "/api/design") => Reply {
            status: 200,
            content_type: "application/json",
            body: shared.design.clone().into_bytes(),
            download: None,
        },
        (_, "/api/generate" | "/api/export" | "/api/design") => {
            Reply::error(405, format!("{method} is not allowed on {path}"))
        }
        ("GET", _) => static_file(&shared.page, path),
        _ => Reply::error(404, format!("no route {method} {path}")),
    }
}

/// The query parameters the API understands.
#[derive(Debug, Default)]
struct Query {
    /// `offset=D`: the offset distance (node offset, or face offset of a conical mesh).
    offset: Option<String>,
    /// `arrays=f32`: answer in [`binary_reply`]'s format, for the page.
    f32: bool,
    /// `metrics=later`: leave the metrics out (the page is in a drag).
    metrics_later: bool,
    /// `name=FILE`: the file the design came from, named in error messages.
    name: Option<String>,
    /// `format=…`: `toml` for a TOML design (generate), or the mesh format (export).
    format: Option<String>,
}

impl Query {
    /// Parses `a=b&c=d` (percent-decoding the values).
    fn parse(query: &str) -> Query {
        let mut q = Query::default();
        for pair in query.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
            let value = percent_decode(value);
            match key {
                "offset" => q.offset = Some(value),
                "arrays" => q.f32 = value == "f32",
                "metrics" => q.metrics_later = value == "later",
                "name" => q.name = Some(value),
                "format" => q.format = Some(value),
                _ => {}
            }
        }
        q
    }

    /// The offset distance, 0 by default; a 400 reply if it is not a finite number.
    fn offset(&self) -> Result<f64, Reply> {
        match self.offset.as_deref().map(str::trim) {
            None | Some("") => Ok(0.0),
            Some(s) => s
                .parse::<f64>()
                .ok()
                .filter(|d| d.is_finite())
                .ok_or_else(|| Reply::error(400, format!("offset `{s}` is not a finite number"))),
        }
    }
}

/// `%XX` and `+` decoded; invalid escapes are kept as they are.
fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        let hex = bytes
            .get(k + 1..k + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[k], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                k += 3;
            }
            (b'+', _) => {
                out.push(b' ');
                k += 1;
            }
            (b, _) => {
                out.push(b);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// A generated mesh ready to send: the design's mesh (circular, or its conical
/// dual) at the requested offset, with what was learnt on the way.
struct Built {
    design: Design,
    generated: monge_core::Generated,
    /// The mesh to show or export.
    mesh: QuadGrid,
    /// The conical dual's face normals, when the design asks for it.
    face_normals: Option<Vec<DVec3>>,
    offset: f64,
    generate_ms: f64,
}

/// Parses and generates a request's design, or the 4xx reply with the CLI's message.
///
/// `format` is the design's format; the query gives its file name and the offset.
fn build(
    body: &[u8],
    format: DesignFormat,
    query: &Query,
    shared: &Shared,
) -> Result<Built, Reply> {
    let name = query.name.as_deref().unwrap_or("<input>");
    let offset = query.offset()?;
    let text = std::str::from_utf8(body)
        .map_err(|_| Reply::error(400, format!("{name}: the design is not UTF-8 text")))?;
    let design = parse_design(text, format).map_err(|e| {
        let message = e.to_string();
        let message = match message.strip_prefix("<input>") {
            Some(rest) => format!("{name}{rest}"),
            None => message,
        };
        Reply::error(400, message)
    })?;
    let start = Instant::now();
    let generated = generate(&design, &shared.options).map_err(|e| {
        let status = match e {
            GenerateError::GridTooLarge { .. } => 413,
            _ => 422,
        };
        let mut value = json!({ "error": format!("{name}: {e}") });
        // The admissible θ, when the guides themselves are valid, so the page can
        // show where θ may go.
        if let Ok(info) = inspect(&design, &shared.options) {
            value["mode"] = json!(mode_name(info.mode));
            value["theta_range"] = json!({
                "min_deg": info.theta_range.min_deg,
                "max_deg": info.theta_range.max_deg,
            });
        }
        Reply::json(status, &value)
    })?;
    let generate_ms = start.elapsed().as_secs_f64() * 1e3;
    let (mesh, face_normals) = match design.mesh {
        MeshKind::Circular => (vertex_offset(&generated.grid, offset), None),
        MeshKind::Conical => {
            let g = &generated.grid;
            if g.rows < 3 || g.cols < 3 {
                return Err(Reply::error(
                    422,
                    format!(
                        "{name}: a conical mesh needs at least 3 samples on each guide, the \
                         circular mesh has {} × {}",
                        g.rows, g.cols
                    ),
                ));
            }
            let conical = conical_dual(g);
            let face_normals = conical.face_normals.clone();
            (face_offset(&conical, offset).grid, Some(face_normals))
        }
    };
    Ok(Built {
        design,
        generated,
        mesh,
        face_normals,
        offset,
        generate_ms,
    })
}

/// `POST /api/generate`.
fn api_generate(body: &[u8], query: &Query, shared: &Shared) -> Reply {
    let format = match query.format.as_deref() {
        Some("toml") => DesignFormat::Toml,
        _ => DesignFormat::Json,
    };
    match build(body, format, query, shared) {
        Ok(built) if query.f32 => {
            let mut arrays = Vec::new();
            let header = mesh_json(&built, !query.metrics_later, |points| {
                arrays.extend(points.iter().flat_map(|p| p.to_array()).map(|x| x as f32));
                json!({ "f32": points.len() * 3 })
            });
            binary_reply(&header, &arrays)
        }
        Ok(built) => Reply::json(
            200,
            &mesh_json(&built, !query.metrics_later, |points| {
                json!(points
                    .iter()
                    .flat_map(|p| p.to_array())
                    .collect::<Vec<f64>>())
            }),
        ),
        Err(reply) => reply,
    }
}

/// `POST /api/export`: the mesh file `monge generate` would write (the design is JSON).
fn api_export(body: &[u8], query: &Query, shared: &Shared) -> Reply {
    let format = match query.format.as_deref() {
        Some("obj") => MeshFormat::Obj,
        Some("ply") => MeshFormat::Ply,
        Some("json") => MeshFormat::Json,
        other => {
            return Reply::error(
                400,
                format!(
                    "format `{}` is not a mesh format: give format=obj, ply or json",
                    other.unwrap_or("")
                ),
            )
        }
    };
    let built = match build(body, DesignFormat::Json, query, shared) {
        Ok(built) => built,
        Err(reply) => return reply,
    };
    let mut out = Vec::new();
    let written = match format {
        MeshFormat::Json => write_mesh_json(&built.mesh, &export_extras(&built), &mut out),
        other => write_mesh_to(&built.mesh, other, &mut out),
    };
    if let Err(e) = written {
        return Reply::error(422, format!("cannot write the mesh: {e}"));
    }
    Reply {
        status: 200,
        content_type: match format {
            MeshFormat::Json => "application/json",
            _ => "text/plain; charset=utf-8",
        },
        body: out,
        download: Some(format!("mesh.{}", format.extension())),
    }
}

/// The extra keys `monge generate` writes into JSON meshes.
fn export_extras(b: &Built) -> Map<String, Value> {
    let mut extra = json_extras(&b.generated);
    let kind = kind_name(b.design.mesh);
    extra.extend(layer_extras(b.offset, kind, b.face_normals.as_deref()));
    extra
}

/// The answer of `POST /api/generate`:
///
/// * `rows`, `cols`, `kind` (`circular`/`conical`), `offset`, `vertices`
///   (row-major, flat `[x, y, z, x, …]`);
/// * `gauss`: `{rows, cols, normals}`, the node axes of the circular mesh (its
///   Gauss map, Figure 9), flat;
/// * `guides`: for `u` and `v`, the samples (flat), unit start `tangent` and
///   `plane_normal`;
/// * `theta_deg`, `mode`, `theta_range` (`min_deg`, `max_deg`, `text`);
/// * `report` (folds and pinches, §5.2) and `markers`: the centres of the first
///   folded face and of the face with the smallest crossing sine, when worth a warning;
/// * `warnings`: sentences for the designer;
/// * `metrics`: [`metrics_json`] of the mesh (`measure`, plus `conical` for conical meshes,
///   `max_error`, `faces`, `panel_area` and `edge_length`);
///   `null` unless `with_metrics` (most of the answer's time: 2.5 ms of 3 at
///   100 × 100 faces);
/// * `timing_ms` and `design` (the parsed design, re-encoded).
///
/// `flat` encodes each array of points; it is called in the order above.
fn mesh_json(b: &Built, with_metrics: bool, mut flat: impl FnMut(&[DVec3]) -> Value) -> Value {
    let start = Instant::now();
    let g = &b.generated;
    let circular = &g.grid;
    let vertices = flat(&b.mesh.vertices);
    let normals = flat(&circular.normals);
    let mut guide = |guide: &monge_core::guide::Guide| {
        json!({
            "points": flat(&guide.points),
            "tangent": guide.tangent.to_array(),
            "plane_normal": guide.plane_normal.to_array(),
        })
    };
    let guides = json!({ "u": guide(&g.info.guide_u), "v": guide(&g.info.guide_v) });
    let face_centre = |(i, j): (usize, usize)| {
        let f = circular.face(i, j);
        ((f[0] + f[1] + f[2] + f[3]) / 4.0).to_array()
    };
    let r = &g.report;
    let mut markers = Vec::new();
    let mut warnings = Vec::new();
    if near_singular(g.info.theta_deg) {
        warnings.push(format!(
            "θ = {}° is at or near the singular θ = +90°, where every Gauss circle passes \
             through the corner normal: expect a degenerate mesh.",
            num(g.info.theta_deg)
        ));
    }
    if let Some(face) = r.first_fold {
        warnings.push(format!(
            "The mesh folds over itself / pinches (§5.2) in {} faces, first at face ({}, {}) \
             (marked in red).",
            r.folded_faces, face.0, face.1
        ));
        markers.push(json!({ "kind": "fold", "face": [face.0, face.1], "at": face_centre(face) }));
    }
    if r.min_crossing.sine < LOW_CROSSING_SINE {
        let face = r.min_crossing.face;
        warnings.push(format!(
            "Low crossing sine {:.1e} at face ({}, {}): the mesh nearly pinches there (§5.2) \
             (marked in orange).",
            r.min_crossing.sine, face.0, face.1
        ));
        markers.push(json!({ "kind": "pinch", "face": [face.0, face.1], "at": face_centre(face) }));
    }
    let metrics = if with_metrics {
        metrics_json(&b.mesh, b.design.mesh)
    } else {
        Value::Null
    };
    let measure_ms = start.elapsed().as_secs_f64() * 1e3;
    json!({
        "rows": b.mesh.rows,
        "cols": b.mesh.cols,
        "kind": kind_name(b.design.mesh),
        "offset": b.offset,
        "vertices": vertices,
        "gauss": { "rows": circular.rows, "cols": circular.cols, "normals": normals },
        "guides": guides,
        "theta_deg": g.info.theta_deg,
        "mode": mode_name(g.info.mode),
        "theta_range": {
            "min_deg": g.info.theta_range.min_deg,
            "max_deg": g.info.theta_range.max_deg,
            "text": range_text(g.info.mode, &g.info.theta_range),
        },
        "report": report_json(&g.report),
        "markers": markers,
        "warnings": warnings,
        "metrics": metrics,
        "timing_ms": { "generate": b.generate_ms, "measure_and_encode": measure_ms },
        "design": b.design,
    })
}

/// The page's answer: a little-endian `u32` byte length, the JSON `header`,
/// spaces up to a multiple of 4 bytes, then `arrays` as little-endian `f32`
/// (the header says how many floats each array has, in order). f32 is plenty
/// for drawing and halves what the browser receives (about 15 ms a megabyte in
/// headless Chromium).
fn binary_reply(header: &Value, arrays: &[f32]) -> Reply {
    let mut text = header.to_string().into_bytes();
    text.resize(text.len().next_multiple_of(4), b' ');
    let length = u32::try_from(text.len()).unwrap_or(u32::MAX);
    let mut body = Vec::with_capacity(4 + text.len() + 4 * arrays.len());
    body.extend(length.to_le_bytes());
    body.extend(text);
    body.extend(arrays.iter().flat_map(|x| x.to_le_bytes()));
    Reply {
        status: 200,
        content_type: "application/octet-stream",
        body,
        download: None,
    }
}

/// `GET /<file>`: a file of the page, by a path of plain names only.
fn static_file(page: &Page, path: &str) -> Reply {
    let relative = match path.trim_start_matches('/') {
        "" => "index.html",
        p => p,
    };
    let relative = Path::new(relative);
    let plain = relative
        .components()
        .all(|c| matches!(c, Component::Normal(_)));
    let body = match page {
        _ if !plain => None,
        Page::Embedded => EMBEDDED_PAGE
            .get_file(relative)
            .map(|f| f.contents().to_vec()),
        Page::Directory(dir) => fs::read(dir.join(relative)).ok(),
    };
    match body {
        Some(body) => Reply {
            status: 200,
            content_type: content_type(relative),
            body,
            download: None,
        },
        None => Reply::error(404, format!("no file {path}")),
    }
}

/// The content type of a static file, by extension.
fn content_type(file: &Path) -> &'static str {
    match file.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("json") => "application/json",
        Some("wasm") => "application/wasm",
        Some("png") => "image/png",
        Some("svg") => "image/svg+xml",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_replies_align_their_floats() {
        let reply = binary_reply(&json!({ "a": 1 }), &[1.0, -2.0]);
        // `{"a":1}` is 7 bytes, padded to 8.
        assert_eq!(&reply.body[..4], &8u32.to_le_bytes());
        assert_eq!(&reply.body[4..12], b"{\"a\":1} ");
        assert_eq!(&reply.body[12..16], &1f32.to_le_bytes());
        assert_eq!(&reply.body[16..], &(-2f32).to_le_bytes());
    }

    #[test]
    fn queries_are_decoded() {
        let q = Query::parse("offset=-0.5&arrays=f32&name=my%20design.json&format=toml");
        assert_eq!(q.offset().ok(), Some(-0.5));
        assert!(q.f32);
        assert_eq!(q.name.as_deref(), Some("my design.json"));
        assert_eq!(q.format.as_deref(), Some("toml"));
        assert!(!q.metrics_later);
        assert!(Query::parse("metrics=later").metrics_later);
        assert!(Query::parse("offset=nan").offset().is_err());
        assert_eq!(Query::parse("").offset().ok(), Some(0.0));
        assert_eq!(percent_decode("a+b%2"), "a b%2");
    }

    #[test]
    fn static_paths_stay_in_the_web_directory() {
        let dir = std::env::temp_dir().join("monge-explore-static-test");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("index.html"), "<p>hi</p>").unwrap();
        for page in [Page::Directory(dir), Page::Embedded] {
            let index = static_file(&page, "/");
            assert_eq!(
                (index.status, index.content_type),
                (200, "text/html; charset=utf-8")
            );
            assert_eq!(static_file(&page, "/../Cargo.toml").status, 404);
            assert_eq!(static_file(&page, "/missing.js").status, 404);
        }
    }
}
