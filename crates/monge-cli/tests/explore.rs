//! Tests of `monge explore`'s HTTP API, without a browser: the server is the
//! real binary on a free port, spoken to over plain TCP.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};

use serde_json::Value;
use tempfile::TempDir;

mod common;
use common::example;

/// A running `monge explore`, stopped when dropped.
struct Server {
    child: Child,
    /// `127.0.0.1:PORT`.
    address: String,
    /// Its web directory (holds a tiny page), or the binary's copy.
    _dir: TempDir,
}

impl Server {
    /// Starts `monge explore --port 0 --web-dir DIR ARGS…` (DIR holding a tiny
    /// page) and reads the address it prints.
    fn start(args: &[&str]) -> Server {
        let web = TempDir::new().unwrap();
        std::fs::write(web.path().join("index.html"), "<p>explorer</p>").unwrap();
        let dir = web.path().to_str().unwrap().to_owned();
        let mut all = vec!["--web-dir", dir.as_str()];
        all.extend_from_slice(args);
        Server::spawn(Path::new(env!("CARGO_BIN_EXE_monge")), &all, web)
    }

    /// Starts `BINARY explore --port 0 ARGS…`, keeping `dir` until dropped.
    fn spawn(binary: &Path, args: &[&str], dir: TempDir) -> Server {
        let mut child = Command::new(binary)
            .args(["explore", "--port", "0"])
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let address = line
            .split("http://")
            .nth(1)
            .and_then(|rest| rest.split('/').next())
            .unwrap_or_else(|| panic!("no address in {line:?}"))
            .to_owned();
        Server {
            child,
            address,
            _dir: dir,
        }
    }

    /// Sends one HTTP/1.0 request (the server closes after it); returns the
    /// status and the body.
    fn request(&self, method: &str, path: &str, body: &[u8]) -> (u16, Vec<u8>) {
        self.raw(
            &format!("{method} {path} HTTP/1.0\r\nHost: {}", self.address),
            body,
        )
    }

    /// Sends `head` (request line and headers, no blank line) with `body` over a
    /// new connection and reads the answer to its end: status and body.
    fn raw(&self, head: &str, body: &[u8]) -> (u16, Vec<u8>) {
        let mut stream = TcpStream::connect(&self.address).unwrap();
        write!(stream, "{head}\r\nContent-Length: {}\r\n\r\n", body.len()).unwrap();
        // A server that refuses early may close before reading everything.
        let _ = stream.write_all(body);
        let mut answer = Vec::new();
        stream.read_to_end(&mut answer).unwrap();
        split_answer(&answer)
    }

    /// The server's resident memory, in kB (Linux).
    fn rss_kb(&self) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).unwrap();
        let line = status.lines().find(|l| l.starts_with("VmRSS:")).unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    }

    /// POSTs `body` to `path` and parses the JSON answer.
    fn post_json(&self, path: &str, body: &[u8]) -> (u16, Value) {
        let (status, body) = self.request("POST", path, body);
        let value = serde_json::from_slice(&body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&body)));
        (status, value)
    }
}

/// Status and body of a whole HTTP answer.
fn split_answer(answer: &[u8]) -> (u16, Vec<u8>) {
    let split = answer
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("not an HTTP answer: {:?}", String::from_utf8_lossy(answer)));
    let head = String::from_utf8_lossy(&answer[..split]).into_owned();
    let status = head.split(' ').nth(1).unwrap().parse().unwrap();
    (status, answer[split + 4..].to_vec())
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `monge generate DESIGN -o -` as JSON.
fn generate(design: &Path) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_monge"))
        .arg("generate")
        .arg(design)
        .args(["-o", "-"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn generate_answers_the_mesh_of_monge_generate() {
    let server = Server::start(&[]);
    for name in [
        "fig13-freeform.json",
        "fig10-arbitrary.json",
        "fig13-conical.json",
    ] {
        let design = std::fs::read(example(name)).unwrap();
        let (status, mesh) = server.post_json("/api/generate", &design);
        assert_eq!(status, 200, "{name}: {mesh}");
        let cli = generate(&example(name));
        assert_eq!(mesh["rows"], cli["rows"], "{name}");
        assert_eq!(mesh["cols"], cli["cols"], "{name}");
        let cli_vertices: Vec<f64> = cli["vertices"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|v| v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect();
        let vertices: Vec<f64> = serde_json::from_value(mesh["vertices"].clone()).unwrap();
        assert_eq!(vertices, cli_vertices, "{name}: the same mesh, bit for bit");
        assert_eq!(mesh["report"], cli["report"], "{name}");
        assert_eq!(mesh["kind"], cli["kind"], "{name}");
        let metric = |key: &str| mesh["metrics"][key]["value"].as_f64().unwrap();
        assert!(metric("face_planarity") < 1e-9, "{name}");
        assert!(metric("row_planarity") < 1e-9, "{name}");
        let exact = if mesh["kind"] == "conical" {
            "conical"
        } else {
            "circularity"
        };
        assert!(metric(exact) < 1e-9, "{name}: {exact}");
        assert!(mesh["metrics"]["panel_area"]["min"].as_f64().unwrap() > 0.0);
        assert!(mesh["theta_range"]["text"].is_string());
    }
}

#[test]
fn the_page_gets_floats_after_a_json_header() {
    let server = Server::start(&[]);
    let (_, design) = server.request("GET", "/api/design", b"");
    let (status, body) = server.request("POST", "/api/generate?arrays=f32", &design);
    assert_eq!(status, 200);
    let length = u32::from_le_bytes(body[..4].try_into().unwrap()) as usize;
    let header: Value = serde_json::from_slice(&body[4..4 + length]).unwrap();
    assert_eq!(
        (header["rows"].as_u64(), header["cols"].as_u64()),
        (Some(101), Some(101))
    );
    let floats = [
        "vertices",
        "gauss.normals",
        "guides.u.points",
        "guides.v.points",
    ]
    .iter()
    .map(|path| {
        let v = path.split('.').fold(&header, |v, key| &v[key]);
        v["f32"].as_u64().unwrap() as usize
    })
    .sum::<usize>();
    assert_eq!(body.len(), 4 + length + 4 * floats);
    assert!(header["metrics"]["face_planarity"].is_object());
}

#[test]
fn metrics_can_wait_for_the_end_of_a_drag() {
    let server = Server::start(&[]);
    let (_, design) = server.request("GET", "/api/design", b"");
    let (status, later) = server.post_json("/api/generate?metrics=later", &design);
    assert_eq!(status, 200, "{later}");
    assert!(
        later["metrics"].is_null(),
        "no metrics: {}",
        later["metrics"]
    );
    let (_, full) = server.post_json("/api/generate", &design);
    assert!(full["metrics"]["circularity"].is_object());
    assert_eq!(later["vertices"], full["vertices"], "the same mesh");
    assert_eq!(later["gauss"], full["gauss"]);
    assert_eq!(later["report"], full["report"]);
}

#[test]
fn bad_designs_get_the_cli_message() {
    let server = Server::start(&[]);
    let dir = TempDir::new().unwrap();
    let cases = [
        ("syntax.json", "{\"theta_deg\": 30,"),
        ("unknown.json", "{\"theta_deg\": 30, \"thetadeg\": 1}"),
    ];
    for (name, text) in cases {
        std::fs::write(dir.path().join(name), text).unwrap();
        let (status, answer) =
            server.post_json(&format!("/api/generate?name={name}"), text.as_bytes());
        assert_eq!(status, 400, "{name}: {answer}");
        // The CLI names the file as given: run it where the file is.
        let cli = Command::new(env!("CARGO_BIN_EXE_monge"))
            .current_dir(dir.path())
            .args(["generate", name, "-o", "out.obj"])
            .output()
            .unwrap();
        assert_eq!(
            format!("error: {}\n", answer["error"].as_str().unwrap()),
            String::from_utf8(cli.stderr).unwrap(),
            "{name}"
        );
    }
    // An inadmissible θ: 422, the CLI's message, and the admissible range.
    let text = std::fs::read_to_string(example("fig10-arbitrary.json")).unwrap();
    let mut design: Value = serde_json::from_str(&text).unwrap();
    design["theta_deg"] = 5.0.into();
    std::fs::write(dir.path().join("theta.json"), design.to_string()).unwrap();
    let (status, answer) = server.post_json(
        "/api/generate?name=theta.json",
        design.to_string().as_bytes(),
    );
    assert_eq!(status, 422, "{answer}");
    let error = answer["error"].as_str().unwrap();
    assert!(
        error.starts_with("theta.json: theta_deg = 5° is not admissible"),
        "{error}"
    );
    assert!(answer["theta_range"]["min_deg"].as_f64().unwrap() > 5.0);
    // The server is still there.
    assert_eq!(server.request("GET", "/api/design", b"").0, 200);
}

#[test]
fn limits_are_enforced() {
    let server = Server::start(&["--max-vertices", "1000"]);
    let design = std::fs::read(example("fig13-freeform.json")).unwrap();
    let (status, answer) = server.post_json("/api/generate", &design);
    assert_eq!(status, 413, "61 × 41 vertices is over 1000: {answer}");
    assert!(answer["error"]
        .as_str()
        .unwrap()
        .contains("more than the limit of 1000"));
    let huge = vec![b' '; (1 << 20) + 1];
    let (status, answer) = server.post_json("/api/generate", &huge);
    assert_eq!(status, 413, "{answer}");
    let (status, _) = server.post_json("/api/generate?offset=abc", &design);
    assert_eq!(status, 400);
}

#[test]
fn routes_and_files() {
    let server = Server::start(&[]);
    assert!(
        server.address.starts_with("127.0.0.1:"),
        "binds 127.0.0.1 by default: {}",
        server.address
    );
    assert_eq!(
        server.request("GET", "/", b""),
        (200, b"<p>explorer</p>".to_vec())
    );
    // HEAD: the GET's status and headers, Content-Length included, no body.
    let mut stream = TcpStream::connect(&server.address).unwrap();
    write!(
        stream,
        "HEAD / HTTP/1.0\r\nHost: {}\r\n\r\n",
        server.address
    )
    .unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 200 "), "{answer}");
    assert!(answer.contains("Content-Length: 15\r\n"), "{answer}");
    assert!(answer.ends_with("\r\n\r\n"), "no body: {answer}");
    assert_eq!(server.request("HEAD", "/nothing.js", b"").0, 404);
    assert_eq!(server.request("GET", "/nothing.js", b"").0, 404);
    assert_eq!(server.request("GET", "/../Cargo.toml", b"").0, 404);
    assert_eq!(server.post_json("/api/unknown", b"{}").0, 404);
    assert_eq!(server.request("GET", "/api/generate", b"").0, 405);
    let design = std::fs::read(example("fig2-enneper.json")).unwrap();
    let (status, obj) = server.request("POST", "/api/export?format=obj", &design);
    assert_eq!(status, 200);
    let cli = Command::new(env!("CARGO_BIN_EXE_monge"))
        .arg("generate")
        .arg(example("fig2-enneper.json"))
        .args(["-o", "-", "--format", "obj"])
        .output()
        .unwrap();
    assert!(obj == cli.stdout, "the exported OBJ is monge generate's");
    assert_eq!(
        server.request("POST", "/api/export?format=stl", &design).0,
        400
    );
}

#[test]
fn a_design_file_is_the_start_design() {
    let server = Server::start(&[example("fig10-arbitrary.json").to_str().unwrap()]);
    let (status, body) = server.request("GET", "/api/design", b"");
    assert_eq!(status, 200);
    let design: Value = serde_json::from_slice(&body).unwrap();
    let file: Value =
        serde_json::from_str(&std::fs::read_to_string(example("fig10-arbitrary.json")).unwrap())
            .unwrap();
    assert_eq!(design["theta_deg"].as_f64(), file["theta_deg"].as_f64());
}

#[test]
fn a_copied_binary_serves_its_embedded_page() {
    // A copy of the binary far from the source tree, as `cargo install` leaves it.
    let dir = TempDir::new().unwrap();
    let binary = dir.path().join("monge");
    std::fs::copy(env!("CARGO_BIN_EXE_monge"), &binary).unwrap();
    let server = Server::spawn(&binary, &[], dir);
    let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("web-dist");
    let (status, index) = server.request("GET", "/", b"");
    assert_eq!(status, 200);
    assert_eq!(index, std::fs::read(page.join("index.html")).unwrap());
    // Every file the page links to, as committed.
    let html = String::from_utf8(index).unwrap();
    let linked: Vec<&str> = ["src=\"", "href=\""]
        .iter()
        .flat_map(|attr| html.split(attr).skip(1))
        .filter_map(|rest| rest.split('"').next())
        .collect();
    assert_eq!(linked.len(), 2, "app.js and style.css: {linked:?}");
    for file in linked {
        let (status, body) = server.request("GET", &format!("/{file}"), b"");
        assert_eq!(status, 200, "{file}");
        assert_eq!(body, std::fs::read(page.join(file)).unwrap(), "{file}");
    }
    assert_eq!(server.request("GET", "/missing.js", b"").0, 404);
}

#[test]
fn a_web_dir_without_a_page_is_refused() {
    let empty = TempDir::new().unwrap();
    common::monge()
        .args(["explore", "--port", "0", "--web-dir"])
        .arg(empty.path())
        .assert()
        .code(2)
        .stderr(predicates::str::contains("has no index.html"));
}

#[test]
fn only_its_own_page_may_use_the_server() {
    let server = Server::start(&[]);
    let port = server.address.rsplit(':').next().unwrap().to_owned();
    let design = std::fs::read(example("fig12-torus.json")).unwrap();
    // DNS rebinding: a page of evil.example whose name now resolves to 127.0.0.1.
    for host in [
        format!("evil.example:{port}"),
        "127.0.0.1:1".into(),
        String::new(),
    ] {
        let (status, body) = server.raw(&format!("GET / HTTP/1.0\r\nHost: {host}"), b"");
        assert_eq!(status, 403, "Host `{host}`");
        assert!(String::from_utf8_lossy(&body).contains("is not this server"));
    }
    for host in [format!("localhost:{port}"), server.address.clone()] {
        let (status, _) = server.raw(&format!("GET / HTTP/1.0\r\nHost: {host}"), b"");
        assert_eq!(status, 200, "Host `{host}`");
    }
    // A simple cross-origin POST from a page of another site.
    let post = |origin: &str| {
        let head = format!(
            "POST /api/generate HTTP/1.0\r\nHost: {}\r\nOrigin: {origin}\r\nContent-Type: text/plain",
            server.address
        );
        server.raw(&head, &design)
    };
    for origin in [
        "https://evil.example",
        "null",
        "http://evil.example:1",
        "https://127.0.0.1:1",
    ] {
        let (status, body) = post(origin);
        assert_eq!(status, 403, "Origin `{origin}`");
        assert!(String::from_utf8_lossy(&body).contains("may not use this server"));
    }
    for origin in [
        format!("http://localhost:{port}"),
        format!("http://{}", server.address),
    ] {
        assert_eq!(post(&origin).0, 200, "Origin `{origin}`");
    }
    // Without Origin (curl, scripts): allowed.
    assert_eq!(server.request("POST", "/api/generate", &design).0, 200);
}

#[test]
fn slow_clients_get_408_and_do_not_hold_the_workers() {
    let server = Server::start(&[]);
    // 100 clients sending their request one byte a second (bounded: 20 s at most).
    let mut slow: Vec<TcpStream> = (0..100)
        .map(|_| TcpStream::connect(&server.address).unwrap())
        .collect();
    let line = b"POST /api/generate HTTP/1.1\r\nHost: 127.0.0.1\r\n";
    let start = std::time::Instant::now();
    for s in &mut slow {
        s.write_all(&line[..1]).unwrap();
        s.set_read_timeout(Some(std::time::Duration::from_millis(1)))
            .unwrap();
    }
    // Meanwhile the page is answered.
    let design = std::fs::read(example("fig13-freeform.json")).unwrap();
    for _ in 0..8 {
        let (status, _) = server.request("POST", "/api/generate", &design);
        assert_eq!(status, 200);
    }
    let answered_after = start.elapsed();
    assert!(
        answered_after.as_secs() < 10,
        "answered only after {answered_after:?}"
    );
    let mut refused = vec![None; slow.len()];
    for second in 1..20 {
        std::thread::sleep(std::time::Duration::from_secs(1));
        for (k, s) in slow.iter_mut().enumerate() {
            if refused[k].is_some() {
                continue;
            }
            let mut answer = Vec::new();
            match s.read_to_end(&mut answer) {
                Ok(_) => refused[k] = Some(split_answer(&answer).0),
                Err(_) => {
                    let _ = s.write_all(&line[second..=second]);
                }
            }
        }
        if refused.iter().all(Option::is_some) {
            break;
        }
    }
    let elapsed = start.elapsed();
    assert!(refused.iter().all(|r| *r == Some(408)), "{refused:?}");
    assert!(elapsed.as_secs() <= 15, "closed after {elapsed:?}");
    assert_eq!(server.request("GET", "/api/design", b"").0, 200);
}

#[test]
fn a_thousand_concurrent_connections_are_answered_or_refused() {
    let server = Server::start(&[]);
    let head = format!(
        "GET /api/design HTTP/1.0\r\nHost: {}\r\n\r\n",
        server.address
    );
    let mut streams: Vec<TcpStream> = (0..1000)
        .map(|_| {
            let mut s = TcpStream::connect(&server.address).unwrap();
            // A refused connection may be closed already.
            let _ = s.write_all(head.as_bytes());
            s
        })
        .collect();
    let (mut ok, mut busy, mut reset) = (0, 0, 0);
    for s in &mut streams {
        let mut answer = Vec::new();
        match s.read_to_end(&mut answer) {
            Ok(_) if split_answer(&answer).0 == 200 => ok += 1,
            Ok(_) if split_answer(&answer).0 == 503 => busy += 1,
            Ok(_) => panic!("{}", String::from_utf8_lossy(&answer)),
            Err(_) => reset += 1,
        }
    }
    eprintln!("1000 concurrent connections: {ok} answered, {busy} refused with 503, {reset} reset");
    assert_eq!(ok + busy + reset, 1000);
    assert!(ok >= 256, "{ok} answered");
    assert_eq!(server.request("GET", "/api/design", b"").0, 200);
}

/// A kept-alive HTTP/1.1 connection.
struct Connection(BufReader<TcpStream>);

impl Connection {
    fn open(address: &str) -> Connection {
        Connection(BufReader::new(TcpStream::connect(address).unwrap()))
    }

    /// Sends a request and reads its answer (by Content-Length): status, body.
    fn send(&mut self, method: &str, path: &str, body: &[u8]) -> (u16, Vec<u8>) {
        let s = self.0.get_mut();
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: {}\r\nContent-Length: {}\r\n\r\n",
            s.peer_addr().unwrap(),
            body.len()
        );
        s.write_all(&[head.as_bytes(), body].concat()).unwrap();
        let (mut status, mut length, mut line) = (0, 0, String::new());
        loop {
            line.clear();
            self.0.read_line(&mut line).unwrap();
            let l = line.trim_end().to_ascii_lowercase();
            if l.is_empty() {
                break;
            } else if let Some(n) = l.strip_prefix("content-length:") {
                length = n.trim().parse().unwrap();
            } else if l.starts_with("http/1.1 ") {
                status = l[9..12].parse().unwrap();
            }
        }
        let mut body = vec![0; length];
        self.0.read_exact(&mut body).unwrap();
        (status, body)
    }
}

#[test]
fn latency_under_8_clients_and_memory_over_30000_requests() {
    let server = Server::start(&[]);
    let address = server.address.clone();
    let design = Connection::open(&address).send("GET", "/api/design", b"").1;
    // p50/p99 of the page's request at 100 × 100 faces, 8 clients at once.
    let before = server.rss_kb();
    let mut latencies: Vec<f64> = std::thread::scope(|scope| {
        let clients: Vec<_> = (0..8)
            .map(|_| {
                scope.spawn(|| {
                    let mut c = Connection::open(&address);
                    (0..25)
                        .map(|_| {
                            let t = std::time::Instant::now();
                            let (status, _) = c.send("POST", "/api/generate?arrays=f32", &design);
                            assert_eq!(status, 200);
                            t.elapsed().as_secs_f64() * 1e3
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        clients
            .into_iter()
            .flat_map(|c| c.join().unwrap())
            .collect()
    });
    latencies.sort_by(f64::total_cmp);
    let at = |q: f64| latencies[((latencies.len() - 1) as f64 * q).round() as usize];
    // 10 000 requests in all, then 20 000 more: the start design, and a small
    // design every tenth, 4 clients.
    let tiny = std::fs::read(example("fig12-torus.json")).unwrap();
    let requests = |count: usize| {
        std::thread::scope(|scope| {
            for _ in 0..4 {
                scope.spawn(|| {
                    let mut c = Connection::open(&address);
                    for k in 0..count / 4 {
                        let (status, _) = match k % 10 {
                            0 => c.send("POST", "/api/generate?metrics=later", &tiny),
                            _ => c.send("GET", "/api/design", b""),
                        };
                        assert_eq!(status, 200);
                    }
                });
            }
        });
        server.rss_kb()
    };
    let first = requests(10_000 - 200);
    let second = requests(20_000);
    eprintln!(
        "/api/generate at 100 × 100 faces, 8 clients × 25 requests: p50 {:.1} ms, p99 {:.1} ms; \
         RSS before {} kB, after 10 000 requests {} kB, after 20 000 more {} kB",
        at(0.5),
        at(0.99),
        before,
        first,
        second
    );
    // No leak: the allocator keeps what the first 10 000 requests needed (its
    // cache, ~50–110 MB depending on the machine) and reuses it for the next
    // 20 000, which add little (a leak of 1 kB a request would add 20 MB).
    assert!(first < before + 256 * 1024, "RSS {before} kB → {first} kB");
    assert!(second < first + 16 * 1024, "RSS {first} kB → {second} kB");
}
