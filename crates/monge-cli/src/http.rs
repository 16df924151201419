//! A small, bounded HTTP/1.1 file server for `monge explore`.
//!
//! It answers `GET` and `HEAD` only (any other method gets `405` at once, its
//! body unread) and takes no request body (`400`). One thread per connection,
//! at most [`Limits::max_connections`] of them (a connection beyond that gets
//! `503` at once). Every request must arrive whole within
//! [`Limits::request_timeout`] of the moment the server starts waiting for it
//! (the connection's opening, or the end of the previous answer on a kept-alive
//! connection): a client that sends nothing is closed without a word, one that
//! sends part of a request (one byte a second, say) gets `408` and is closed.
//! Every answer must be taken whole within [`Limits::write_timeout`]: the
//! deadline bounds the whole answer, not each write, so a client that reads a
//! few bytes now and then is closed too; an answer being sent holds no copy of
//! bytes that live as long as the server and reads a file a piece at a time
//! ([`Body`]). Headers are at most [`Limits::max_header`] bytes (`431`). A
//! panicking handler gives `500`.

use std::borrow::Cow;
use std::fs::File;
use std::io::{self, IoSlice, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The bounds of the server.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Open connections at a time.
    pub max_connections: usize,
    /// Time a request may take to arrive whole, from the moment the server
    /// waits for it (the connection's opening, or the previous answer's end).
    pub request_timeout: Duration,
    /// Time an answer may take to be taken whole by the client.
    pub write_timeout: Duration,
    /// Bytes of the request line and headers.
    pub max_header: usize,
}

/// A request read whole (it has no body: the server refuses bodies).
#[derive(Debug)]
pub struct Request {
    /// `GET` or `HEAD`.
    pub method: String,
    /// The request target: path and query.
    pub target: String,
    /// Headers in order, names in lower case.
    pub headers: Vec<(String, String)>,
    /// HTTP/1.1 (else 1.0): keeps the connection alive unless told not to.
    pub http11: bool,
    /// The address on this machine that the connection reached.
    pub local: SocketAddr,
}

impl Request {
    /// The value of the header `name` (lower case), if it was sent once; a
    /// repeated header counts as absent only if all copies agree (else `Err`).
    pub fn header(&self, name: &str) -> Result<Option<&str>, String> {
        header(&self.headers, name)
    }
}

/// The value of the header `name` (lower case) among `headers`: see [`Request::header`].
fn header<'a>(headers: &'a [(String, String)], name: &str) -> Result<Option<&'a str>, String> {
    let mut values = headers
        .iter()
        .filter(|(n, _)| n == name)
        .map(|(_, v)| v.as_str());
    let first = values.next();
    match values.find(|v| Some(*v) != first) {
        Some(_) => Err(format!(
            "the header `{name}` is sent twice with different values"
        )),
        None => Ok(first),
    }
}

/// An answer.
#[derive(Debug)]
pub struct Response {
    /// The status code.
    pub status: u16,
    /// `Content-Type`.
    pub content_type: &'static str,
    /// Further headers.
    pub headers: Vec<(&'static str, String)>,
    /// The body.
    pub body: Body,
    /// Whether only the headers are sent (an answer to `HEAD`).
    pub head_only: bool,
}

impl Response {
    /// An error answer, `{"error": message}` as every error of the explorer.
    pub fn error(status: u16, message: &str) -> Response {
        Response {
            status,
            content_type: "application/json",
            headers: Vec::new(),
            body: Body::Bytes(
                serde_json::json!({ "error": message })
                    .to_string()
                    .into_bytes()
                    .into(),
            ),
            head_only: false,
        }
    }
}

/// The body of an answer: an answer being sent holds at most
/// [`FILE_CHUNK`] bytes of a file, and no copy of bytes that live as long as
/// the server.
#[derive(Debug)]
pub enum Body {
    /// Bytes in memory, borrowed when they live as long as the server (the
    /// embedded page).
    Bytes(Cow<'static, [u8]>),
    /// A file of this many bytes, read a piece at a time as the client takes it.
    File(File, u64),
}

impl Body {
    /// The body's length in bytes.
    fn len(&self) -> u64 {
        match self {
            Body::Bytes(bytes) => bytes.len() as u64,
            Body::File(_, len) => *len,
        }
    }
}

/// The piece of a file read and sent at a time.
const FILE_CHUNK: usize = 64 << 10;

/// Time to write the `503` of a connection beyond [`Limits::max_connections`]
/// (the accepting thread writes it: a few hundred bytes, which the socket's
/// buffer takes at once).
const BUSY_WRITE_TIMEOUT: Duration = Duration::from_secs(1);

/// Serves `listener` forever, answering every request with `handler`.
pub fn serve<H>(listener: TcpListener, limits: Limits, handler: H) -> io::Result<()>
where
    H: Fn(&Request) -> Response + Send + Sync + 'static,
{
    let handler = Arc::new(handler);
    let open = Arc::new(AtomicUsize::new(0));
    loop {
        let (mut stream, _) = match listener.accept() {
            Ok(accepted) => accepted,
            // Out of file descriptors, a connection reset before accept, …: go on.
            Err(_) => continue,
        };
        if open.load(Ordering::SeqCst) >= limits.max_connections {
            let busy = Response::error(
                503,
                &format!(
                    "the explorer already has {} connections open: close some, then retry",
                    limits.max_connections
                ),
            );
            let _ = write_response(
                &mut stream,
                &busy,
                false,
                Instant::now() + BUSY_WRITE_TIMEOUT,
            );
            continue;
        }
        open.fetch_add(1, Ordering::SeqCst);
        let (count, handler) = (Arc::clone(&open), Arc::clone(&handler));
        let spawned = std::thread::Builder::new()
            .name("monge-http".into())
            .spawn(move || {
                let _open = Open(count);
                connection(stream, &limits, &*handler);
            });
        if spawned.is_err() {
            // No thread for it: the stream was dropped (closed) with the closure.
            open.fetch_sub(1, Ordering::SeqCst);
        }
    }
}

/// One open connection, counted until dropped (even by a panic).
struct Open(Arc<AtomicUsize>);

impl Drop for Open {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Answers the requests of one connection until it closes, times out or errs.
fn connection<H>(mut stream: TcpStream, limits: &Limits, handler: &H)
where
    H: Fn(&Request) -> Response,
{
    let Ok(local) = stream.local_addr() else {
        return;
    };
    let mut pending = Vec::new();
    loop {
        let deadline = Instant::now() + limits.request_timeout;
        let request = match read_request(&mut stream, &mut pending, local, deadline, limits) {
            Ok(Some(request)) => request,
            Ok(None) => return,
            Err(Refusal::Answer(response)) => {
                let deadline = Instant::now() + limits.write_timeout;
                let _ = write_response(&mut stream, &response, false, deadline);
                return;
            }
            Err(Refusal::Close) => return,
        };
        let keep_alive = keep_alive(&request);
        let mut response =
            catch_unwind(AssertUnwindSafe(|| handler(&request))).unwrap_or_else(|_| {
                Response::error(
                    500,
                    "internal error while answering the request (see the server's log)",
                )
            });
        if request.method == "HEAD" {
            // The headers of the GET, Content-Length included, without the body.
            response.head_only = true;
        }
        let deadline = Instant::now() + limits.write_timeout;
        if write_response(&mut stream, &response, keep_alive, deadline).is_err() || !keep_alive {
            return;
        }
    }
}

/// Why a request is not answered by the handler.
enum Refusal {
    /// Answer this, then close.
    Answer(Response),
    /// Close without a word (the client left, or the connection failed).
    Close,
}

/// Reads one request before `deadline`, `pending` holding bytes already
/// received; `Ok(None)` when the client closed, or sent nothing, before it.
fn read_request(
    stream: &mut TcpStream,
    pending: &mut Vec<u8>,
    local: SocketAddr,
    deadline: Instant,
    limits: &Limits,
) -> Result<Option<Request>, Refusal> {
    let refuse = |status, message: String| Refusal::Answer(Response::error(status, &message));
    let too_long = || {
        refuse(
            431,
            format!(
                "the request's headers are longer than {} bytes",
                limits.max_header
            ),
        )
    };
    let end = loop {
        if let Some(p) = pending.windows(4).position(|w| w == b"\r\n\r\n") {
            break p;
        }
        if pending.len() > limits.max_header {
            return Err(too_long());
        }
        match read_before(stream, pending, deadline) {
            Ok(0) if pending.is_empty() => return Ok(None),
            Ok(0) => return Err(Refusal::Close),
            Ok(_) => {}
            Err(e) if is_timeout(&e) && pending.is_empty() => return Ok(None),
            Err(e) if is_timeout(&e) => {
                return Err(refuse(
                    408,
                    format!(
                        "the request did not arrive whole within {} s",
                        limits.request_timeout.as_secs_f64()
                    ),
                ))
            }
            Err(_) => return Err(Refusal::Close),
        }
    };
    if end > limits.max_header {
        return Err(too_long());
    }
    let head = String::from_utf8(pending[..end].to_vec())
        .map_err(|_| refuse(400, "the request's headers are not UTF-8 text".into()))?;
    pending.drain(..end + 4);
    let (method, target, headers, http11) = parse_head(&head).map_err(|m| refuse(400, m))?;
    if method != "GET" && method != "HEAD" {
        let mut response = Response::error(
            405,
            &format!("{method} is not allowed: this server serves files, by GET and HEAD only"),
        );
        response.headers.push(("Allow", "GET, HEAD".into()));
        return Err(Refusal::Answer(response));
    }
    let length = header(&headers, "content-length").map_err(|m| refuse(400, m))?;
    let chunked = header(&headers, "transfer-encoding").map_err(|m| refuse(400, m))?;
    if chunked.is_some() || length.is_some_and(|l| l != "0") {
        return Err(refuse(
            400,
            format!("a {method} request has no body: send it without one"),
        ));
    }
    Ok(Some(Request {
        method,
        target,
        headers,
        http11,
        local,
    }))
}

/// The request line and headers: method, target, headers (names lower case), HTTP/1.1.
type Head = (String, String, Vec<(String, String)>, bool);

/// Parses the request line and headers (without the blank line).
fn parse_head(head: &str) -> Result<Head, String> {
    let mut lines = head.split("\r\n");
    let line = lines.next().unwrap_or_default();
    let mut parts = line.split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(format!("malformed request line `{line}`"));
    };
    if !matches!(version, "HTTP/1.1" | "HTTP/1.0") || method.is_empty() || !target.starts_with('/')
    {
        return Err(format!(
            "malformed request line `{line}`: expected `METHOD /path HTTP/1.1`"
        ));
    }
    let headers = lines
        .map(|l| {
            l.split_once(':')
                .map(|(n, v)| (n.trim().to_ascii_lowercase(), v.trim().to_owned()))
                .ok_or_else(|| format!("malformed header line `{l}`"))
        })
        .collect::<Result<_, _>>()?;
    Ok((
        method.to_owned(),
        target.to_owned(),
        headers,
        version == "HTTP/1.1",
    ))
}

/// Whether the connection stays open after this request.
fn keep_alive(request: &Request) -> bool {
    let connection = request
        .headers
        .iter()
        .find(|(n, _)| n == "connection")
        .map(|(_, v)| v.to_ascii_lowercase());
    match connection.as_deref() {
        Some("close") => false,
        Some("keep-alive") => true,
        _ => request.http11,
    }
}

/// Reads what is there into `buf`, waiting until `deadline` at most (a timeout
/// error once it has passed).
fn read_before(stream: &mut TcpStream, buf: &mut Vec<u8>, deadline: Instant) -> io::Result<usize> {
    stream.set_read_timeout(Some(time_left(deadline)?))?;
    let mut chunk = [0u8; 8192];
    let n = stream.read(&mut chunk)?;
    buf.extend_from_slice(&chunk[..n]);
    Ok(n)
}

/// The time until `deadline`; a timeout error once it has passed.
fn time_left(deadline: Instant) -> io::Result<Duration> {
    let left = deadline.saturating_duration_since(Instant::now());
    if left.is_zero() {
        return Err(io::ErrorKind::TimedOut.into());
    }
    Ok(left)
}

fn is_timeout(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
    )
}

/// Writes `response` whole before `deadline`, the headers in one piece with
/// the body's first bytes (no delayed-ACK wait between them), or fails.
fn write_response(
    stream: &mut TcpStream,
    response: &Response,
    keep_alive: bool,
    deadline: Instant,
) -> io::Result<()> {
    let mut head = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n",
        response.status,
        reason(response.status),
        response.content_type,
        response.body.len()
    );
    for (name, value) in &response.headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    if !keep_alive {
        head.push_str("Connection: close\r\n");
    }
    head.push_str("\r\n");
    match &response.body {
        _ if response.head_only => write_before(stream, [head.as_bytes(), &[]], deadline)?,
        Body::Bytes(bytes) => write_before(stream, [head.as_bytes(), bytes], deadline)?,
        Body::File(file, len) => {
            let mut chunk = vec![0; FILE_CHUNK];
            let (mut head, mut left) = (head.as_bytes(), *len);
            while left > 0 {
                let want = usize::try_from(left).map_or(FILE_CHUNK, |l| l.min(FILE_CHUNK));
                let n = match (&*file).read(&mut chunk[..want]) {
                    // The file shrank since the answer's length was taken.
                    Ok(0) => return Err(io::ErrorKind::UnexpectedEof.into()),
                    Ok(n) => n,
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                    Err(e) => return Err(e),
                };
                write_before(stream, [head, &chunk[..n]], deadline)?;
                head = &[];
                left -= n as u64;
            }
        }
    }
    if !keep_alive {
        // Let the client read the answer before the close (no reset).
        let _ = stream.shutdown(std::net::Shutdown::Write);
    }
    Ok(())
}

/// Writes `parts` in order before `deadline`: each write may wait only for the
/// time left, so a client that takes a few bytes now and then cannot stretch it.
fn write_before(
    stream: &mut TcpStream,
    mut parts: [&[u8]; 2],
    deadline: Instant,
) -> io::Result<()> {
    while parts.iter().any(|p| !p.is_empty()) {
        stream.set_write_timeout(Some(time_left(deadline)?))?;
        let mut written = match stream.write_vectored(&parts.map(IoSlice::new)) {
            Ok(0) => return Err(io::ErrorKind::WriteZero.into()),
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        for part in &mut parts {
            let n = written.min(part.len());
            *part = &part[n..];
            written -= n;
        }
    }
    Ok(())
}

/// The reason phrase of the statuses this server sends.
fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        431 => "Request Header Fields Too Large",
        500 => "Internal Server Error",
        503 => "Service Unavailable",
        _ => "",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heads_are_parsed_and_refused() {
        let (m, t, h, http11) =
            parse_head("GET /api/design?x=1 HTTP/1.1\r\nHost: a:1\r\nX-Y:  z ").unwrap();
        assert!(http11);
        assert_eq!((m.as_str(), t.as_str()), ("GET", "/api/design?x=1"));
        assert_eq!(
            h,
            vec![("host".into(), "a:1".into()), ("x-y".into(), "z".into())]
        );
        for bad in [
            "GET / HTTP/2",
            "GET",
            "GET  / HTTP/1.1",
            "GET x HTTP/1.1",
            "GET / HTTP/1.1\r\nnocolon",
        ] {
            assert!(parse_head(bad).is_err(), "{bad}");
        }
    }
}
