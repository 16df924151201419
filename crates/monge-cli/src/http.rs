//! A small, bounded HTTP/1.1 server for `monge explore`.
//!
//! One thread per connection, at most [`Limits::max_connections`] of them (a
//! connection beyond that gets `503` at once); a request must arrive whole
//! within [`Limits::request_timeout`] of its first byte (a client sending one
//! byte a second gets `408` and is closed), an idle keep-alive connection is
//! closed after [`Limits::idle_timeout`]; headers are at most
//! [`Limits::max_header`] bytes (`431`), bodies at most [`Limits::max_body`]
//! (`413`), and at most [`Limits::workers`] requests are computed at a time,
//! so slow or many clients hold connection threads, never the computation.
//! Bodies need `Content-Length` (chunked ones get `501`); `Expect:
//! 100-continue` is answered. A panicking handler gives `500`.

use std::io::{self, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// The bounds of the server.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Open connections at a time.
    pub max_connections: usize,
    /// Requests computed at a time.
    pub workers: usize,
    /// Time from a request's first byte to its last.
    pub request_timeout: Duration,
    /// Time a kept-alive connection may wait for its next request.
    pub idle_timeout: Duration,
    /// Time to write an answer (a client that does not read is closed).
    pub write_timeout: Duration,
    /// Bytes of the request line and headers.
    pub max_header: usize,
    /// Bytes of a body.
    pub max_body: usize,
}

/// A request read whole.
#[derive(Debug)]
pub struct Request {
    /// `GET`, `POST`, …
    pub method: String,
    /// The request target: path and query.
    pub target: String,
    /// Headers in order, names in lower case.
    pub headers: Vec<(String, String)>,
    /// The body (`Content-Length` bytes).
    pub body: Vec<u8>,
    /// HTTP/1.1 (else 1.0): keeps the connection alive unless told not to.
    pub http11: bool,
}

impl Request {
    /// The value of the header `name` (lower case), if it was sent once; a
    /// repeated header counts as absent only if all copies agree (else `Err`).
    pub fn header(&self, name: &str) -> Result<Option<&str>, String> {
        let mut values = self
            .headers
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
    pub body: Vec<u8>,
    /// Whether only the headers are sent (an answer to `HEAD`).
    pub head_only: bool,
}

impl Response {
    /// An error answer, `{"error": message}` as every error of the explorer's API.
    pub fn error(status: u16, message: &str) -> Response {
        Response {
            status,
            content_type: "application/json",
            headers: Vec::new(),
            body: serde_json::json!({ "error": message })
                .to_string()
                .into_bytes(),
            head_only: false,
        }
    }
}

/// Serves `listener` forever, answering every request with `handler`.
pub fn serve<H>(listener: TcpListener, limits: Limits, handler: H) -> io::Result<()>
where
    H: Fn(&Request) -> Response + Send + Sync + 'static,
{
    let handler = Arc::new(handler);
    let open = Arc::new(AtomicUsize::new(0));
    let workers = Arc::new(Semaphore::new(limits.workers));
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
            let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
            let _ = write_response(&mut stream, busy, false);
            continue;
        }
        open.fetch_add(1, Ordering::SeqCst);
        let (count, workers, handler) = (
            Arc::clone(&open),
            Arc::clone(&workers),
            Arc::clone(&handler),
        );
        let spawned = std::thread::Builder::new()
            .name("monge-http".into())
            .spawn(move || {
                let _open = Open(count);
                connection(stream, &limits, &workers, &*handler);
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
fn connection<H>(mut stream: TcpStream, limits: &Limits, workers: &Semaphore, handler: &H)
where
    H: Fn(&Request) -> Response,
{
    let _ = stream.set_write_timeout(Some(limits.write_timeout));
    let mut pending = Vec::new();
    loop {
        let request = match read_request(&mut stream, &mut pending, limits) {
            Ok(Some(request)) => request,
            Ok(None) => return,
            Err(Refusal::Answer(response)) => {
                let _ = write_response(&mut stream, response, false);
                return;
            }
            Err(Refusal::Close) => return,
        };
        let keep_alive = keep_alive(&request);
        let head = request.method == "HEAD";
        let mut response = {
            let _permit = workers.acquire();
            catch_unwind(AssertUnwindSafe(|| handler(&request))).unwrap_or_else(|_| {
                Response::error(
                    500,
                    "internal error while answering the request (see the server's log)",
                )
            })
        };
        if head {
            // The headers of the GET, Content-Length included, without the body.
            response.head_only = true;
        }
        if write_response(&mut stream, response, keep_alive).is_err() || !keep_alive {
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

/// Reads one request, `pending` holding bytes already received; `Ok(None)`
/// when the client closed or stayed idle between requests.
fn read_request(
    stream: &mut TcpStream,
    pending: &mut Vec<u8>,
    limits: &Limits,
) -> Result<Option<Request>, Refusal> {
    let refuse = |status, message: String| Refusal::Answer(Response::error(status, &message));
    let timeout = || {
        refuse(
            408,
            format!(
                "the request did not arrive whole within {} s",
                limits.request_timeout.as_secs_f64()
            ),
        )
    };
    // The first byte may wait for the idle timeout; the rest must follow within the request timeout.
    if pending.is_empty() {
        match read_some(stream, pending, limits.idle_timeout) {
            Ok(0) | Err(_) => return Ok(None),
            Ok(_) => {}
        }
    }
    let deadline = Instant::now() + limits.request_timeout;
    let end = loop {
        if let Some(p) = pending.windows(4).position(|w| w == b"\r\n\r\n") {
            break p;
        }
        if pending.len() > limits.max_header {
            return Err(refuse(
                431,
                format!(
                    "the request's headers are longer than {} bytes",
                    limits.max_header
                ),
            ));
        }
        match read_before(stream, pending, deadline) {
            Ok(0) => return Err(Refusal::Close),
            Ok(_) => {}
            Err(e) if is_timeout(&e) => return Err(timeout()),
            Err(_) => return Err(Refusal::Close),
        }
    };
    if end > limits.max_header {
        return Err(refuse(
            431,
            format!(
                "the request's headers are longer than {} bytes",
                limits.max_header
            ),
        ));
    }
    let head = String::from_utf8(pending[..end].to_vec())
        .map_err(|_| refuse(400, "the request's headers are not UTF-8 text".into()))?;
    pending.drain(..end + 4);
    let (method, target, headers, http11) = parse_head(&head).map_err(|m| refuse(400, m))?;
    let mut request = Request {
        method,
        target,
        headers,
        body: Vec::new(),
        http11,
    };
    if request
        .header("transfer-encoding")
        .map_err(|m| refuse(400, m))?
        .is_some()
    {
        return Err(refuse(
            501,
            "chunked request bodies are not accepted: send Content-Length".into(),
        ));
    }
    let length = match request
        .header("content-length")
        .map_err(|m| refuse(400, m))?
    {
        None => 0,
        Some(v) => v
            .parse::<usize>()
            .ok()
            .filter(|_| v.bytes().all(|b| b.is_ascii_digit()))
            .ok_or_else(|| refuse(400, format!("Content-Length `{v}` is not a whole number")))?,
    };
    if length > limits.max_body {
        return Err(refuse(
            413,
            format!(
                "the request body is {length} bytes, larger than {} bytes: designs are small, send one design",
                limits.max_body
            ),
        ));
    }
    let expects = request.header("expect").map_err(|m| refuse(400, m))?;
    if expects.is_some_and(|e| e.eq_ignore_ascii_case("100-continue")) && pending.len() < length {
        stream
            .write_all(b"HTTP/1.1 100 Continue\r\n\r\n")
            .map_err(|_| Refusal::Close)?;
    }
    while pending.len() < length {
        match read_before(stream, pending, deadline) {
            Ok(0) => return Err(Refusal::Close),
            Ok(_) => {}
            Err(e) if is_timeout(&e) => return Err(timeout()),
            Err(_) => return Err(Refusal::Close),
        }
    }
    request.body = pending.drain(..length).collect();
    Ok(Some(request))
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

/// Reads what is there into `buf`, waiting at most `timeout`.
fn read_some(stream: &mut TcpStream, buf: &mut Vec<u8>, timeout: Duration) -> io::Result<usize> {
    stream.set_read_timeout(Some(timeout))?;
    let mut chunk = [0u8; 8192];
    let n = stream.read(&mut chunk)?;
    buf.extend_from_slice(&chunk[..n]);
    Ok(n)
}

/// [`read_some`] until `deadline` (a timeout error once it has passed).
fn read_before(stream: &mut TcpStream, buf: &mut Vec<u8>, deadline: Instant) -> io::Result<usize> {
    let left = deadline.saturating_duration_since(Instant::now());
    if left.is_zero() {
        return Err(io::ErrorKind::TimedOut.into());
    }
    read_some(stream, buf, left)
}

fn is_timeout(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
    )
}

/// Writes `response` in one piece (no delayed-ACK wait between headers and body).
fn write_response(stream: &mut TcpStream, response: Response, keep_alive: bool) -> io::Result<()> {
    let mut out = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n",
        response.status,
        reason(response.status),
        response.content_type,
        response.body.len()
    );
    for (name, value) in &response.headers {
        out.push_str(&format!("{name}: {value}\r\n"));
    }
    if !keep_alive {
        out.push_str("Connection: close\r\n");
    }
    out.push_str("\r\n");
    let mut bytes = out.into_bytes();
    if !response.head_only {
        bytes.extend_from_slice(&response.body);
    }
    stream.write_all(&bytes)?;
    stream.flush()?;
    if !keep_alive {
        // Let the client read the answer before the close (no reset).
        let _ = stream.shutdown(std::net::Shutdown::Write);
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
        413 => "Payload Too Large",
        422 => "Unprocessable Entity",
        431 => "Request Header Fields Too Large",
        500 => "Internal Server Error",
        501 => "Not Implemented",
        503 => "Service Unavailable",
        _ => "",
    }
}

/// A counting semaphore: the requests computed at a time.
struct Semaphore {
    free: Mutex<usize>,
    freed: Condvar,
}

/// A permit of a [`Semaphore`], given back when dropped.
struct Permit<'a>(&'a Semaphore);

impl Semaphore {
    fn new(permits: usize) -> Semaphore {
        Semaphore {
            free: Mutex::new(permits.max(1)),
            freed: Condvar::new(),
        }
    }

    fn acquire(&self) -> Permit<'_> {
        let mut free = self.free.lock().unwrap_or_else(PoisonError::into_inner);
        while *free == 0 {
            free = self
                .freed
                .wait(free)
                .unwrap_or_else(PoisonError::into_inner);
        }
        *free -= 1;
        Permit(self)
    }
}

impl Drop for Permit<'_> {
    fn drop(&mut self) {
        *self.0.free.lock().unwrap_or_else(PoisonError::into_inner) += 1;
        self.0.freed.notify_one();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heads_are_parsed_and_refused() {
        let (m, t, h, http11) =
            parse_head("POST /api/generate?x=1 HTTP/1.1\r\nHost: a:1\r\nX-Y:  z ").unwrap();
        assert!(http11);
        assert_eq!((m.as_str(), t.as_str()), ("POST", "/api/generate?x=1"));
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
