//! `monge explore`: the design explorer, a web page served on the local machine
//! that regenerates the mesh while a designer drags θ and the guides' control
//! points (§1, §5.1: real-time exploration of the design space).
//!
//! The page computes the mesh itself, with monge-core compiled to WebAssembly
//! (`crates/monge-wasm`), and works from any static file server; this server
//! serves it and hands it the design given on the command line (`GET
//! /api/design`). It computes nothing: every answer is a file, of the page or
//! the start design. The server is [`crate::http`]: small, synchronous,
//! bounded (connections, time to send a request, time to take an answer),
//! `GET` and `HEAD` only. It answers only its own page ([`guard`]: `Host` and
//! `Origin` checked). The page's files (HTML, CSS, the module
//! `monge_wasm_bg.wasm`, and the JS bundled with three.js and the module's glue
//! by `npm run build` in `web/`) are embedded in the binary from
//! `crates/monge-cli/web-dist/` (a committed copy of `web/dist`), so a copied or
//! installed `monge` serves its page; `--web-dir` serves another directory instead.
//!
//! Routes:
//! * `GET /`, `GET /<file>`: the page, embedded or from `--web-dir`; its
//!   `index.html` marked ([`DESIGN_MARK`]) so that it asks for its start
//!   design here.
//! * `GET /api/design`: the design to start from (DESIGN, or a built-in one of
//!   100 × 100 faces).

use std::borrow::Cow;
use std::fs;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr, TcpListener};
use std::path::{Component, Path, PathBuf};
use std::time::Duration;

use anyhow::{anyhow, bail, Context};
use include_dir::{include_dir, Dir};
use socket2::{Domain, Protocol, Socket, Type};

use crate::http;
use crate::shared::help::EXIT;
use crate::shared::output::{eprint, print};
use crate::shared::Outcome;

/// The server's bounds: 256 connections; 10 s for a request to arrive whole,
/// from the connection's opening or the previous answer (a connection that
/// sends nothing is closed then); 30 s for an answer to be taken whole (the
/// largest file of the page, the 1.3 MB module, at 45 kB/s).
const LIMITS: http::Limits = http::Limits {
    max_connections: 256,
    request_timeout: Duration::from_secs(10),
    write_timeout: Duration::from_secs(30),
    max_header: 16 << 10,
};

/// The design shown when `monge explore` is given none: the page's own default
/// (`web/src/default-design.json`), the `monge bench` design at 100 × 100 faces
/// (two cubic B-splines, characteristic case, θ = 30°).
const DEFAULT_DESIGN: &str = include_str!("../../web-dist/default-design.json");

/// Explore a design in the browser: drag θ and the guides, see the mesh live.
#[derive(Debug, clap::Args)]
#[command(
    long_about = "Serve the design explorer on this machine and print its address: a web page \
         with a 3D view of the mesh (guides highlighted, Gauss map beside it), a θ slider, \
         draggable guide points (B-spline control points, points, a parabola's control points, \
         an arc's end; kept in their planes, start tangents kept), sample counts, \
         circular/conical switch, offset distance, live metrics and warnings where the mesh \
         folds or θ is not admissible; every edit can be undone (Ctrl+Z) and redone \
         (Ctrl+Shift+Z); a refused edit is marked and the last valid design stays shown and \
         exportable; designs load and save in the design-file format, meshes export as OBJ \
         or JSON.\n\n\
         The page computes the mesh in the browser (monge-core in WebAssembly, the same code \
         as `monge generate`); this server only serves the page (marking it so that it asks \
         for its start design here) and the start design (GET /api/design), and computes \
         nothing. It listens on 127.0.0.1 unless --host says \
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
    /// lets everyone who can reach this machine on the network open the
    /// explorer and read its start design (no password, no encryption; a
    /// warning says so at start); requests must name the server by the address
    /// they reach in `Host`. Keep the default unless you mean it.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    pub host: IpAddr,
    /// Serve the page's files from DIR (e.g. `web/dist`, built by `npm ci && npm run build`
    /// in `web/`) instead of the copy embedded in this binary.
    #[arg(long, value_name = "DIR")]
    pub web_dir: Option<PathBuf>,
}

/// The page built by `npm run build` in `web/`, as committed in `web-dist/`.
static EMBEDDED_PAGE: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/web-dist");

/// What `monge explore` adds to the `<head>` of the page it serves: the page
/// then asks for its start design at `/api/design`. A page from a plain static
/// server has no such mark and opens its own `default-design.json`, so that it
/// asks for no file the server lacks.
const DESIGN_MARK: &str = "\n  <meta name=\"monge-design\" content=\"api/design\">";

/// `index.html` with [`DESIGN_MARK`] after its `<head>` (or first, if it has none).
fn marked(html: &[u8]) -> Vec<u8> {
    const HEAD: &[u8] = b"<head>";
    let at = html
        .windows(HEAD.len())
        .position(|w| w.eq_ignore_ascii_case(HEAD))
        .map_or(0, |i| i + HEAD.len());
    [&html[..at], DESIGN_MARK.as_bytes(), &html[at..]].concat()
}

/// Where the page's files come from.
enum Page {
    /// The copy embedded in the binary.
    Embedded,
    /// A directory given with `--web-dir`.
    Directory(PathBuf),
}

/// What every request handler shares.
struct Shared {
    /// The start design, as JSON text: it lives as long as the server, so
    /// that every answer borrows it.
    design: &'static str,
    /// The page's files.
    page: Page,
}

/// Runs `monge explore`: serves until the process is stopped.
pub fn run(args: &ExploreArgs) -> anyhow::Result<Outcome> {
    let design = match &args.design {
        Some(path) => {
            let design = monge_io::read_design(path)?;
            let text = serde_json::to_string_pretty(&design)
                .context("cannot encode the design as JSON")?;
            // Served until the process ends: kept once rather than copied per answer.
            &*text.leak()
        }
        None => DEFAULT_DESIGN,
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
    if let Some(warning) = beyond_loopback_warning(address) {
        eprint(&warning);
    }
    print(&format!(
        "monge explore: open http://{}/ (Ctrl-C to stop)\n",
        local_address(address)
    ))?;
    let shared = Shared { design, page };
    http::serve(listener, LIMITS, move |request| answer(request, &shared))
        .with_context(|| format!("the server on {address} stopped"))?;
    Ok(Outcome::Success)
}

/// The address to open on this machine: `address`, or its family's loopback
/// address when it listens on every interface (0.0.0.0 or ::), which is no
/// address a browser reaches (the server answers only the address reached).
fn local_address(address: SocketAddr) -> SocketAddr {
    match address.ip() {
        IpAddr::V4(ip) if ip.is_unspecified() => {
            SocketAddr::new(Ipv4Addr::LOCALHOST.into(), address.port())
        }
        IpAddr::V6(ip) if ip.is_unspecified() => {
            SocketAddr::new(Ipv6Addr::LOCALHOST.into(), address.port())
        }
        _ => address,
    }
}

/// The warning printed when the server listens beyond this machine (any
/// address but a loopback one), or `None`.
fn beyond_loopback_warning(address: SocketAddr) -> Option<String> {
    if address.ip().to_canonical().is_loopback() {
        return None;
    }
    Some(format!(
        "warning: listening on {address}, beyond this machine: anyone who can reach it on the \
         network can open the explorer and read its start design (no password, no encryption). \
         Stop it (Ctrl-C) and leave out --host (or give --host 127.0.0.1) to keep it to this \
         machine.\n"
    ))
}

/// A TCP listener on `address` whose connections send without delay.
///
/// Answers are written in one piece, but small answers still go out at once
/// with `TCP_NODELAY` (measured with Nagle's algorithm and separate writes:
/// 44 ms for every small answer in Chromium). Linux passes `TCP_NODELAY`
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

/// Answers one request, once [`guard`] lets it through.
fn answer(request: &http::Request, shared: &Shared) -> http::Response {
    if let Err(refusal) = guard(request) {
        return refusal;
    }
    let target = &request.target;
    let path = target.split_once('?').map_or(target.as_str(), |(p, _)| p);
    match path {
        "/api/design" => file(
            "application/json",
            http::Body::Bytes(shared.design.as_bytes().into()),
        ),
        _ => static_file(&shared.page, path),
    }
}

/// A `200` answer of `body`.
fn file(content_type: &'static str, body: http::Body) -> http::Response {
    http::Response {
        status: 200,
        content_type,
        headers: Vec::new(),
        body,
        head_only: false,
    }
}

/// Only the explorer's own page may use the server. A request whose `Host` is
/// not this server, by the IP address the connection reached (or `localhost`
/// when that is a loopback address) and its port, is refused with 403: a page
/// of another site whose name was made to resolve to this machine (DNS
/// rebinding) names that site. So is a request whose `Origin`, when it has one,
/// is not exactly the origin it was sent to, `http://` and its `Host` (scheme,
/// host and port): a page of another site or of another address. A request
/// without `Origin` (not from a browser, or a same-origin `GET`) passes.
fn guard(request: &http::Request) -> Result<(), http::Response> {
    let header = |name| {
        request
            .header(name)
            .map_err(|m| http::Response::error(400, &m))
    };
    let served = SocketAddr::new(request.local.ip().to_canonical(), request.local.port());
    let host = header("host")?.unwrap_or("");
    if !names_this_server(host, served) {
        return Err(http::Response::error(
            403,
            &format!("Host `{host}` is not this server: open http://{served}/ itself"),
        ));
    }
    if let Some(origin) = header("origin")? {
        let own = origin
            .strip_prefix("http://")
            .is_some_and(|authority| authority.eq_ignore_ascii_case(host));
        if !own {
            return Err(http::Response::error(
                403,
                &format!(
                    "a page of `{origin}` may not use this server: only the explorer's own page \
                     at http://{host}/ may"
                ),
            ));
        }
    }
    Ok(())
}

/// Whether `host` (a `Host` header, `NAME:PORT`) names `served`, the address a
/// connection reached: that address with its port, as a browser writes it
/// (`127.0.0.1:8642`, `[::1]:8642`), or `localhost` with the port when it is a
/// loopback address. A name other than `localhost` can be made to resolve to
/// any address; an IP address cannot.
fn names_this_server(host: &str, served: SocketAddr) -> bool {
    let localhost = format!("localhost:{}", served.port());
    host.eq_ignore_ascii_case(&served.to_string())
        || (served.ip().is_loopback() && host.eq_ignore_ascii_case(&localhost))
}

/// `GET /<file>`: a file of the page, by a path of plain names only.
fn static_file(page: &Page, path: &str) -> http::Response {
    let relative = match path.trim_start_matches('/') {
        "" => "index.html",
        p => p,
    };
    let relative = Path::new(relative);
    let plain = relative
        .components()
        .all(|c| matches!(c, Component::Normal(_)));
    if plain && relative == Path::new("index.html") {
        let html = match page {
            Page::Embedded => EMBEDDED_PAGE
                .get_file(relative)
                .map(|f| f.contents().to_vec()),
            Page::Directory(dir) => fs::read(dir.join(relative)).ok(),
        };
        if let Some(html) = html {
            return file(
                content_type(relative),
                http::Body::Bytes(marked(&html).into()),
            );
        }
    }
    let body = match page {
        _ if !plain => None,
        Page::Embedded => EMBEDDED_PAGE
            .get_file(relative)
            .map(|f| http::Body::Bytes(Cow::Borrowed(f.contents()))),
        // Sent as the client takes it, never read whole.
        Page::Directory(dir) => fs::File::open(dir.join(relative))
            .and_then(|f| Ok((f.metadata()?, f)))
            .ok()
            .filter(|(meta, _)| meta.is_file())
            .map(|(meta, f)| http::Body::File(f, meta.len())),
    };
    match body {
        Some(body) => file(content_type(relative), body),
        None => http::Response::error(404, &format!("no file {path}")),
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
    fn static_paths_stay_in_the_web_directory() {
        let dir = std::env::temp_dir().join("monge-explore-static-test");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("index.html"), "<p>hi</p>").unwrap();
        fs::create_dir_all(dir.join("sub")).unwrap();
        for page in [Page::Directory(dir), Page::Embedded] {
            let index = static_file(&page, "/");
            assert_eq!(
                (index.status, index.content_type),
                (200, "text/html; charset=utf-8")
            );
            assert_eq!(static_file(&page, "/../Cargo.toml").status, 404);
            assert_eq!(static_file(&page, "/missing.js").status, 404);
            assert_eq!(static_file(&page, "/sub").status, 404);
        }
    }

    #[test]
    fn hosts_name_the_address_reached() {
        let loopback: SocketAddr = "127.0.0.1:8642".parse().unwrap();
        let v6: SocketAddr = "[::1]:8642".parse().unwrap();
        let lan: SocketAddr = "192.168.1.5:8642".parse().unwrap();
        for (host, served) in [
            ("127.0.0.1:8642", loopback),
            ("localhost:8642", loopback),
            ("LocalHost:8642", loopback),
            ("[::1]:8642", v6),
            ("localhost:8642", v6),
            ("192.168.1.5:8642", lan),
        ] {
            assert!(names_this_server(host, served), "{host} names {served}");
        }
        for (host, served) in [
            ("10.0.0.1:8642", loopback),
            ("127.0.0.1:8643", loopback),
            ("127.0.0.1", loopback),
            ("127.0.0.1:08642", loopback),
            ("::1:8642", v6),
            ("localhost:8642", lan),
            ("127.0.0.1:8642", lan),
            ("evil.example:8642", loopback),
        ] {
            assert!(!names_this_server(host, served), "{host} is not {served}");
        }
    }

    #[test]
    fn the_address_to_open_is_one_a_browser_reaches() {
        for (listening, open) in [
            ("0.0.0.0:8642", "127.0.0.1:8642"),
            ("[::]:8642", "[::1]:8642"),
            ("127.0.0.1:8642", "127.0.0.1:8642"),
            ("192.168.1.5:8642", "192.168.1.5:8642"),
        ] {
            let open: SocketAddr = open.parse().unwrap();
            assert_eq!(
                local_address(listening.parse().unwrap()),
                open,
                "{listening}"
            );
        }
    }

    #[test]
    fn only_a_loopback_address_listens_without_a_warning() {
        for quiet in [
            "127.0.0.1:1",
            "127.1.2.3:1",
            "[::1]:1",
            "[::ffff:127.0.0.1]:1",
        ] {
            assert_eq!(
                beyond_loopback_warning(quiet.parse().unwrap()),
                None,
                "{quiet}"
            );
        }
        for loud in ["0.0.0.0:1", "[::]:1", "192.168.1.5:1"] {
            let warning = beyond_loopback_warning(loud.parse().unwrap()).unwrap();
            assert!(
                warning.contains("anyone who can reach it"),
                "{loud}: {warning}"
            );
        }
    }
}
