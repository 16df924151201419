//! Tests of `monge explore`'s server, without a browser: the server is the
//! real binary on a free port, spoken to over plain TCP.

use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;
use tempfile::{NamedTempFile, TempDir};

use crate::common;
use common::example;

/// What `monge explore` adds after the `<head>` of the page it serves.
const MARK: &str = "\n  <meta name=\"monge-design\" content=\"api/design\">";

/// The page's files, as committed (what the binary embeds).
fn web_dist() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("web-dist")
}

/// A running `monge explore`, stopped when dropped.
struct Server {
    child: Child,
    /// `127.0.0.1:PORT`.
    address: String,
    /// The line it printed first.
    printed: String,
    /// What it wrote on stderr.
    stderr: NamedTempFile,
    /// Its web directory (holds a tiny page), or the binary's copy.
    dir: TempDir,
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
        let stderr = NamedTempFile::new().unwrap();
        let spawn = || {
            Command::new(binary)
                .args(["explore", "--port", "0"])
                .args(args)
                .stdout(Stdio::piped())
                .stderr(stderr.reopen().unwrap())
                .spawn()
        };
        // A binary just copied may be "busy" for a moment: a process another
        // test thread forked meanwhile holds the copy's file open until it
        // execs. Try again then.
        let mut tries = 0;
        let mut child = loop {
            match spawn() {
                Err(e) if e.kind() == std::io::ErrorKind::ExecutableFileBusy && tries < 100 => {
                    tries += 1;
                    std::thread::sleep(Duration::from_millis(20));
                }
                started => break started.unwrap(),
            }
        };
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let port = line
            .split("http://")
            .nth(1)
            .and_then(|rest| rest.split('/').next())
            .and_then(|address| address.rsplit(':').next())
            .unwrap_or_else(|| panic!("no address in {line:?}"));
        Server {
            child,
            // Reached through the loopback interface, whatever address it listens on.
            address: format!("127.0.0.1:{port}"),
            printed: line.clone(),
            stderr,
            dir,
        }
    }

    /// What the server wrote on stderr so far.
    fn stderr(&self) -> String {
        std::fs::read_to_string(self.stderr.path()).unwrap()
    }

    /// Sends one HTTP/1.0 request (the server closes after it); returns the
    /// status and the body.
    fn request(&self, method: &str, path: &str) -> (u16, Vec<u8>) {
        self.raw(&format!(
            "{method} {path} HTTP/1.0\r\nHost: {}",
            self.address
        ))
    }

    /// Sends `head` (request line and headers, no blank line) over a new
    /// connection and reads the answer to its end: status and body.
    fn raw(&self, head: &str) -> (u16, Vec<u8>) {
        let mut stream = TcpStream::connect(&self.address).unwrap();
        write!(stream, "{head}\r\n\r\n").unwrap();
        let mut answer = Vec::new();
        stream.read_to_end(&mut answer).unwrap();
        split_answer(&answer)
    }

    /// The server's threads (Linux): one, plus one for each open connection.
    fn threads(&self) -> u64 {
        self.status("Threads:")
    }

    /// The server's resident memory, in kB (Linux).
    fn rss_kb(&self) -> u64 {
        self.status("VmRSS:")
    }

    /// The first number of a line of `/proc/PID/status`.
    fn status(&self, key: &str) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).unwrap();
        let line = status.lines().find(|l| l.starts_with(key)).unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
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

#[test]
fn the_compute_api_is_gone() {
    let server = Server::start(&[]);
    let design = std::fs::read(example("fig13-freeform.json")).unwrap();
    for path in [
        "/api/generate",
        "/api/export?format=obj",
        "/",
        "/api/design",
    ] {
        // Any method but GET and HEAD: 405 at once, the body unread.
        let mut stream = TcpStream::connect(&server.address).unwrap();
        write!(
            stream,
            "POST {path} HTTP/1.1\r\nHost: {}\r\nContent-Length: {}\r\n\r\n",
            server.address,
            design.len()
        )
        .unwrap();
        let _ = stream.write_all(&design);
        let mut answer = Vec::new();
        stream.read_to_end(&mut answer).unwrap();
        let text = String::from_utf8_lossy(&answer);
        assert!(text.starts_with("HTTP/1.1 405 "), "POST {path}: {text}");
        assert!(text.contains("\r\nAllow: GET, HEAD\r\n"), "{text}");
    }
    for method in ["PUT", "DELETE", "OPTIONS"] {
        assert_eq!(server.request(method, "/api/design").0, 405, "{method}");
    }
    assert_eq!(server.request("GET", "/api/generate").0, 404);
    assert_eq!(server.request("GET", "/api/export").0, 404);
    // A GET with a body is refused, not read as the next request.
    for body in ["Content-Length: 5", "Transfer-Encoding: chunked"] {
        let head = format!("GET / HTTP/1.1\r\nHost: {}\r\n{body}", server.address);
        assert_eq!(server.raw(&head).0, 400, "{body}");
    }
    assert_eq!(
        server
            .raw(&format!(
                "GET / HTTP/1.1\r\nHost: {}\r\nContent-Length: 0\r\nConnection: close",
                server.address
            ))
            .0,
        200
    );
}

#[test]
fn routes_and_files() {
    let server = Server::start(&[]);
    assert!(
        server.stderr().is_empty(),
        "no warning on 127.0.0.1: {}",
        server.stderr()
    );
    // The page, marked as served by `monge explore` (it then asks for /api/design).
    let page = format!("{MARK}<p>explorer</p>");
    assert_eq!(server.request("GET", "/"), (200, page.clone().into_bytes()));
    assert_eq!(
        server.request("GET", "/index.html"),
        (200, page.clone().into_bytes())
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
    assert!(
        answer.contains(&format!("Content-Length: {}\r\n", page.len())),
        "{answer}"
    );
    assert!(answer.ends_with("\r\n\r\n"), "no body: {answer}");
    assert_eq!(server.request("HEAD", "/nothing.js").0, 404);
    assert_eq!(server.request("GET", "/nothing.js").0, 404);
    assert_eq!(server.request("GET", "/../Cargo.toml").0, 404);
    assert_eq!(server.request("GET", "/api/unknown").0, 404);
    // The start design: the page's own default, as committed.
    let (status, design) = server.request("GET", "/api/design?x=1");
    assert_eq!(status, 200);
    assert_eq!(
        design,
        std::fs::read(web_dist().join("default-design.json")).unwrap()
    );
}

#[test]
fn a_design_file_is_the_start_design() {
    let server = Server::start(&[example("fig10-arbitrary.json").to_str().unwrap()]);
    let (status, body) = server.request("GET", "/api/design");
    assert_eq!(status, 200);
    let design: Value = serde_json::from_slice(&body).unwrap();
    let file: Value =
        serde_json::from_str(&std::fs::read_to_string(example("fig10-arbitrary.json")).unwrap())
            .unwrap();
    assert_eq!(design["theta_deg"].as_f64(), file["theta_deg"].as_f64());
    assert_eq!(
        design["guide_u"]["bspline"]["samples"],
        file["guide_u"]["bspline"]["samples"]
    );
}

#[test]
fn a_copied_binary_serves_its_embedded_page() {
    // A copy of the binary far from the source tree, as `cargo install` leaves it.
    let dir = TempDir::new().unwrap();
    let binary = dir.path().join("monge");
    std::fs::copy(env!("CARGO_BIN_EXE_monge"), &binary).unwrap();
    let server = Server::spawn(&binary, &[], dir);
    let page = web_dist();
    let (status, index) = server.request("GET", "/");
    assert_eq!(status, 200);
    // As committed, with the mark after `<head>` that makes it ask for /api/design.
    let committed = std::fs::read_to_string(page.join("index.html")).unwrap();
    assert!(
        !committed.contains("monge-design"),
        "a static server's page asks for no api/design"
    );
    assert_eq!(
        String::from_utf8(index).unwrap(),
        committed.replacen("<head>", &format!("<head>{MARK}"), 1)
    );
    // Every file the page links to or loads, as committed (the icon is inline: no request).
    let linked: Vec<&str> = ["src=\"", "href=\""]
        .iter()
        .flat_map(|attr| committed.split(attr).skip(1))
        .filter_map(|rest| rest.split('"').next())
        .filter(|link| !link.starts_with("data:"))
        .collect();
    assert_eq!(linked.len(), 2, "app.js and style.css: {linked:?}");
    for file in linked
        .into_iter()
        .chain(["monge_wasm_bg.wasm", "worker.js", "default-design.json"])
    {
        let (status, body) = server.request("GET", &format!("/{file}"));
        assert_eq!(status, 200, "{file}");
        assert_eq!(body, std::fs::read(page.join(file)).unwrap(), "{file}");
    }
    assert_eq!(server.request("GET", "/missing.js").0, 404);
}

#[test]
fn a_web_dir_without_a_page_is_refused() {
    let empty = TempDir::new().unwrap();
    common::refuses(
        common::monge()
            .args(["explore", "--port", "0", "--web-dir"])
            .arg(empty.path()),
        &["has no index.html"],
        &[],
    );
}

#[test]
fn listening_beyond_this_machine_is_warned_of() {
    let server = Server::start(&["--host", "0.0.0.0"]);
    let port = server.address.rsplit(':').next().unwrap().to_owned();
    let stderr = server.stderr();
    assert!(
        stderr.starts_with(&format!(
            "warning: listening on 0.0.0.0:{port}, beyond this machine"
        )) && stderr.contains("anyone who can reach it on the network"),
        "{stderr}"
    );
    // The address to open is one a browser reaches: 127.0.0.1, not 0.0.0.0.
    assert!(
        server
            .printed
            .contains(&format!("open http://127.0.0.1:{port}/ ")),
        "{}",
        server.printed
    );
    // Reached through 127.0.0.1, it answers requests naming 127.0.0.1 (or
    // localhost), not another of the machine's names.
    assert_eq!(server.request("GET", "/").0, 200);
    let other = format!("GET / HTTP/1.0\r\nHost: 192.0.2.1:{port}");
    assert_eq!(server.raw(&other).0, 403);
}

#[test]
fn only_its_own_page_may_use_the_server() {
    let server = Server::start(&[]);
    let port = server.address.rsplit(':').next().unwrap().to_owned();
    // DNS rebinding: a page of evil.example whose name now resolves to
    // 127.0.0.1; another address or port than the one reached.
    for host in [
        format!("evil.example:{port}"),
        format!("10.0.0.1:{port}"),
        "127.0.0.1:1".into(),
        "127.0.0.1".into(),
        String::new(),
    ] {
        let (status, body) = server.raw(&format!("GET / HTTP/1.0\r\nHost: {host}"));
        assert_eq!(status, 403, "Host `{host}`");
        assert!(String::from_utf8_lossy(&body).contains("is not this server"));
    }
    for host in [format!("localhost:{port}"), server.address.clone()] {
        let (status, _) = server.raw(&format!("GET / HTTP/1.0\r\nHost: {host}"));
        assert_eq!(status, 200, "Host `{host}`");
    }
    // A request from a page of another origin: scheme, host and port must be
    // the ones the request was sent to, exactly.
    let from = |host: &str, origin: &str| {
        let head = format!("GET /api/design HTTP/1.0\r\nHost: {host}\r\nOrigin: {origin}");
        server.raw(&head)
    };
    let own = server.address.clone();
    for origin in [
        "https://evil.example".to_owned(),
        "null".into(),
        format!("http://evil.example:{port}"),
        format!("http://10.0.0.1:{port}"),
        format!("http://192.168.1.5:{port}"),
        format!("http://127.0.0.2:{port}"),
        format!("https://{own}"),
        "http://127.0.0.1:1".into(),
        format!("http://localhost:{port}"),
        format!("http://{own}/"),
    ] {
        let (status, body) = from(&own, &origin);
        assert_eq!(status, 403, "Origin `{origin}`");
        assert!(String::from_utf8_lossy(&body).contains("may not use this server"));
    }
    assert_eq!(from(&own, &format!("http://{own}")).0, 200);
    let localhost = format!("localhost:{port}");
    assert_eq!(from(&localhost, &format!("http://{localhost}")).0, 200);
    // Without Origin (curl, scripts, a same-origin GET): allowed.
    assert_eq!(server.request("GET", "/api/design").0, 200);
}

#[test]
fn silent_connections_are_closed_within_the_request_timeout() {
    let server = Server::start(&[]);
    // 255 connections that send nothing, and one kept alive after an answer.
    let mut silent: Vec<TcpStream> = (0..255)
        .map(|_| TcpStream::connect(&server.address).unwrap())
        .collect();
    let mut kept = Connection::open(&server.address);
    assert_eq!(kept.get("/").0, 200);
    silent.push(kept.0.into_inner());
    let start = Instant::now();
    // Every slot is held: a new connection is refused.
    let mut busy = TcpStream::connect(&server.address).unwrap();
    let _ = write!(busy, "GET / HTTP/1.0\r\nHost: {}\r\n\r\n", server.address);
    let mut refused = Vec::new();
    let _ = busy.read_to_end(&mut refused);
    assert_eq!(split_answer(&refused).0, 503);
    // The server closes them all after its request timeout (10 s), without a word.
    // (The bound is loose: a machine's load delays a timer by far less; the idle
    // timeout they used to get was 60 s.)
    for s in &mut silent {
        s.set_read_timeout(Some(Duration::from_secs(40))).unwrap();
        let mut rest = Vec::new();
        match s.read_to_end(&mut rest) {
            Ok(_) => assert!(rest.is_empty(), "{}", String::from_utf8_lossy(&rest)),
            Err(e) if e.kind() == ErrorKind::ConnectionReset => {}
            Err(e) => panic!("still open after {:?}: {e}", start.elapsed()),
        }
    }
    let closed_after = start.elapsed();
    assert!(
        closed_after < Duration::from_secs(30),
        "closed after {closed_after:?}"
    );
    assert_eq!(server.request("GET", "/").0, 200);
}

#[test]
fn a_slow_reader_is_let_go_within_the_write_timeout() {
    // 64 MB: no socket buffer holds it.
    let big = vec![7u8; 64 << 20];
    let server = Server::start(&[]);
    std::fs::write(server.dir.path().join("big.bin"), &big).unwrap();
    let (idle, rss) = (server.threads(), server.rss_kb());
    let mut stream = TcpStream::connect(&server.address).unwrap();
    write!(
        stream,
        "GET /big.bin HTTP/1.0\r\nHost: {}\r\n\r\n",
        server.address
    )
    .unwrap();
    // A reader that takes 16 kB every 100 ms (160 kB/s: 7 minutes for the
    // whole answer), so that no write of the server waits long. The server
    // holds the connection (and the file) in a thread of its own until it
    // lets go; what it had already written, the kernel still delivers.
    let start = Instant::now();
    let mut received = 0;
    let mut chunk = vec![0u8; 16 << 10];
    let (mut held, mut peak) = (true, rss);
    while held && start.elapsed() < Duration::from_secs(90) {
        match stream.read(&mut chunk) {
            Ok(n) if n > 0 => received += n,
            _ => break,
        }
        std::thread::sleep(Duration::from_millis(100));
        held = server.threads() > idle;
        peak = peak.max(server.rss_kb());
    }
    let elapsed = start.elapsed();
    eprintln!(
        "slow reader: let go after {elapsed:?}, {received} bytes received; \
         server RSS {rss} kB, at most {peak} kB meanwhile"
    );
    // The file is read a piece at a time, never whole (64 MB).
    assert!(peak < rss + 16 * 1024, "RSS {rss} kB → {peak} kB");
    assert!(
        !held,
        "still held after {elapsed:?}, {received} bytes received"
    );
    assert!(received < big.len(), "the whole answer: {received} bytes");
    // The write timeout is 30 s for the whole answer; the bound is loose.
    assert!(
        elapsed < Duration::from_secs(60),
        "let go after {elapsed:?}"
    );
    assert_eq!(server.request("GET", "/").0, 200);
}

#[test]
fn slow_clients_get_408_and_do_not_hold_the_page() {
    let server = Server::start(&[]);
    // 100 clients sending their request one byte a second (bounded: 20 s at most).
    let mut slow: Vec<TcpStream> = (0..100)
        .map(|_| TcpStream::connect(&server.address).unwrap())
        .collect();
    let line = b"GET /api/design HTTP/1.1\r\nHost: 127.0.0.1\r\n";
    let start = Instant::now();
    for s in &mut slow {
        s.write_all(&line[..1]).unwrap();
        s.set_read_timeout(Some(Duration::from_millis(1))).unwrap();
    }
    // Meanwhile the page is answered.
    for _ in 0..8 {
        assert_eq!(server.request("GET", "/").0, 200);
        assert_eq!(server.request("GET", "/api/design").0, 200);
    }
    let answered_after = start.elapsed();
    assert!(
        answered_after.as_secs() < 10,
        "answered only after {answered_after:?}"
    );
    let mut refused = vec![None; slow.len()];
    for second in 1..20 {
        std::thread::sleep(Duration::from_secs(1));
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
    // Every one refused within the loop's 20 s (the request timeout is 10 s),
    // however loaded the machine: no bound tighter than the loop's own.
    assert!(refused.iter().all(|r| *r == Some(408)), "{refused:?}");
    assert_eq!(server.request("GET", "/api/design").0, 200);
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
    assert_eq!(server.request("GET", "/api/design").0, 200);
}

/// A kept-alive HTTP/1.1 connection.
struct Connection(BufReader<TcpStream>);

impl Connection {
    fn open(address: &str) -> Connection {
        Connection(BufReader::new(TcpStream::connect(address).unwrap()))
    }

    /// Sends a GET and reads its answer (by Content-Length): status, body.
    fn get(&mut self, path: &str) -> (u16, Vec<u8>) {
        let s = self.0.get_mut();
        let head = format!(
            "GET {path} HTTP/1.1\r\nHost: {}\r\n\r\n",
            s.peer_addr().unwrap()
        );
        s.write_all(head.as_bytes()).unwrap();
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
fn memory_over_30000_requests() {
    let dir = TempDir::new().unwrap();
    let binary = dir.path().join("monge");
    std::fs::copy(env!("CARGO_BIN_EXE_monge"), &binary).unwrap();
    // The embedded page: its files are answered without a copy.
    let server = Server::spawn(&binary, &[], dir);
    let address = server.address.clone();
    let before = server.rss_kb();
    // 10 000 requests in all, then 20 000 more, 4 clients kept alive: the
    // start design, and the module every hundredth.
    let requests = |count: usize| {
        std::thread::scope(|scope| {
            for _ in 0..4 {
                scope.spawn(|| {
                    let mut c = Connection::open(&address);
                    for k in 0..count / 4 {
                        let (status, _) = match k % 100 {
                            0 => c.get("/monge_wasm_bg.wasm"),
                            _ => c.get("/api/design"),
                        };
                        assert_eq!(status, 200);
                    }
                });
            }
        });
        server.rss_kb()
    };
    let first = requests(10_000);
    let second = requests(20_000);
    eprintln!(
        "RSS before {before} kB, after 10 000 requests {first} kB, after 20 000 more {second} kB"
    );
    // No leak: a leak of 1 kB a request would add 20 MB over the last 20 000.
    assert!(first < before + 64 * 1024, "RSS {before} kB → {first} kB");
    assert!(second < first + 8 * 1024, "RSS {first} kB → {second} kB");
}
