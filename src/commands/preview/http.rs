//! The preview's HTTP/1.1 server: a blocking accept loop on a `TcpListener`, one thread per
//! connection, requests read by [`request::parse`]. Everything a client can make it spend is
//! bounded: at most [`MAX_CONNECTIONS`] connection threads (more are answered 503), at most
//! [`MAX_HEAD`] + [`MAX_BODY`] bytes buffered a connection (a larger `Content-Length` is answered
//! 413 before its body is read), and [`REQUEST_TIME`] for a request to arrive (so that a slow or
//! silent client gives its thread back).

use super::request::{self, Parsed, Request, MAX_BODY, MAX_HEAD};
use std::io::{ErrorKind, Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Most connections served at once. A browser opens at most six; the rest is room for scripts.
pub const MAX_CONNECTIONS: usize = 128;
/// How long a request may take to arrive, from the moment the connection is ready for it
/// (a kept-alive connection that stays silent that long is closed).
pub const REQUEST_TIME: Duration = Duration::from_secs(10);
/// How long a response may take to be taken by the client.
const WRITE_TIME: Duration = Duration::from_secs(10);
/// After a refusal, how long and how much of what the client still sends is read and dropped
/// before the connection closes, so that the client reads the answer rather than a reset.
const LINGER_TIME: Duration = Duration::from_secs(2);
const LINGER_BYTES: usize = 1 << 20;

/// A response.
pub struct Reply {
    status: u16,
    headers: Vec<(&'static str, String)>,
    body: Vec<u8>,
}

impl Reply {
    /// A response of `content_type`, never cached, never sniffed as another type.
    pub fn new(status: u16, content_type: &str, body: Vec<u8>) -> Self {
        let headers = vec![
            ("Content-Type", content_type.to_string()),
            ("Cache-Control", "no-store".to_string()),
            ("X-Content-Type-Options", "nosniff".to_string()),
        ];
        Self { status, headers, body }
    }

    /// A plain-text response: `message` and a newline.
    pub fn text(status: u16, message: &str) -> Self {
        Self::new(status, "text/plain; charset=utf-8", format!("{message}\n").into_bytes())
    }

    /// The response with the header `name: value` added; `value` comes from this program, never
    /// from a request, so it cannot break the head.
    pub fn with_header(mut self, name: &'static str, value: String) -> Self {
        self.headers.push((name, value));
        self
    }

    /// The response as sent, with `Connection: close` if `close`.
    fn bytes(&self, close: bool) -> Vec<u8> {
        let mut head = format!("HTTP/1.1 {} {}\r\n", self.status, reason(self.status));
        for (name, value) in &self.headers {
            head.push_str(&format!("{name}: {value}\r\n"));
        }
        // A 204 has no body, and says nothing of its length.
        if self.status != 204 {
            head.push_str(&format!("Content-Length: {}\r\n", self.body.len()));
        }
        head.push_str(if close { "Connection: close\r\n\r\n" } else { "Connection: keep-alive\r\n\r\n" });
        let mut bytes = head.into_bytes();
        bytes.extend_from_slice(&self.body);
        bytes
    }
}

/// The reason phrase of the statuses this server sends.
fn reason(status: u16) -> &'static str {
    match status {
        100 => "Continue",
        200 => "OK",
        204 => "No Content",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        413 => "Content Too Large",
        415 => "Unsupported Media Type",
        417 => "Expectation Failed",
        431 => "Request Header Fields Too Large",
        500 => "Internal Server Error",
        501 => "Not Implemented",
        503 => "Service Unavailable",
        505 => "HTTP Version Not Supported",
        _ => "",
    }
}

/// Answers connections on `listener` forever, each on its own thread, each request by `handle`.
pub fn serve(listener: &TcpListener, handle: Arc<dyn Fn(&Request) -> Reply + Send + Sync>) {
    let open = Arc::new(AtomicUsize::new(0));
    for stream in listener.incoming() {
        let Ok(stream) = stream else {
            // Out of file descriptors, most likely: wait for connections to end rather than spin.
            std::thread::sleep(Duration::from_millis(50));
            continue;
        };
        let Some(slot) = Slot::take(&open) else {
            busy(stream);
            continue;
        };
        let handle = Arc::clone(&handle);
        // If no thread can be started, the closure and its slot are dropped and so is the
        // connection: the client sees it closed.
        let _ = std::thread::Builder::new().name("preview-connection".into()).spawn(move || {
            let _slot = slot;
            connection(stream, &*handle);
        });
    }
}

/// One of the [`MAX_CONNECTIONS`] connection threads; given back when dropped, panic or not.
struct Slot(Arc<AtomicUsize>);

impl Slot {
    fn take(open: &Arc<AtomicUsize>) -> Option<Slot> {
        open.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < MAX_CONNECTIONS).then_some(n + 1))
            .ok()
            .map(|_| Slot(Arc::clone(open)))
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Answers a connection over the limit 503, from the accepting thread: the answer is small
/// enough for the socket's buffer, and the write timeout bounds it anyway.
fn busy(mut stream: TcpStream) {
    let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
    let reply = Reply::text(503, "the preview has too many connections open; try again");
    let _ = stream.write_all(&reply.bytes(true));
}

/// Serves the requests of one connection until it closes, fails or times out.
fn connection(mut stream: TcpStream, handle: &dyn Fn(&Request) -> Reply) {
    // The listener is on 127.0.0.1 only, so this holds; it is checked all the same, so that a
    // change of address could not open the preview to other machines.
    if !stream.peer_addr().is_ok_and(|a| a.ip().is_loopback()) {
        refuse(stream, Reply::text(403, "only connections from this machine's loopback interface are served"));
        return;
    }
    if stream.set_write_timeout(Some(WRITE_TIME)).is_err() {
        return;
    }
    let mut buffer = Vec::new();
    loop {
        let request = match next_request(&mut stream, &mut buffer) {
            Ok(Some(request)) => request,
            // The client closed the connection, went silent or failed: nobody to answer.
            Ok(None) => return,
            Err(reply) => return refuse(stream, reply),
        };
        buffer.drain(..request.length);
        let reply = handle(&request);
        // A client that closed the connection (a tab closed mid-frame) cannot be answered;
        // there is nobody to tell.
        if stream.write_all(&reply.bytes(request.close)).is_err() || request.close {
            return;
        }
    }
}

/// Reads the connection's next request into `buffer` (which may hold its beginning already);
/// `None` when the connection ends before one begins, or fails.
fn next_request(stream: &mut TcpStream, buffer: &mut Vec<u8>) -> Result<Option<Request>, Reply> {
    let deadline = Instant::now() + REQUEST_TIME;
    let mut continued = false;
    let mut until = None;
    loop {
        if until.is_none_or(|n| buffer.len() >= n) {
            match request::parse(buffer) {
                Ok(Parsed::Complete(request)) => return Ok(Some(request)),
                Ok(Parsed::Incomplete { until: u, send_continue }) => {
                    until = u;
                    if send_continue && !continued {
                        continued = true;
                        if stream.write_all(b"HTTP/1.1 100 Continue\r\n\r\n").is_err() {
                            return Ok(None);
                        }
                    }
                }
                Err(refusal) => return Err(Reply::text(refusal.status, refusal.reason)),
            }
        }
        match read_more(stream, buffer, deadline) {
            Ok(0) => return Ok(None),
            Ok(_) => {}
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                return if buffer.is_empty() {
                    Ok(None)
                } else {
                    Err(Reply::text(408, "the request took too long to arrive"))
                };
            }
            Err(_) => return Ok(None),
        }
    }
}

/// Appends what the client sends next to `buffer`, waiting until `deadline` at most; the buffer
/// never grows past a request's largest size.
fn read_more(stream: &mut TcpStream, buffer: &mut Vec<u8>, deadline: Instant) -> std::io::Result<usize> {
    let left = deadline.saturating_duration_since(Instant::now());
    if left.is_zero() {
        return Err(ErrorKind::TimedOut.into());
    }
    stream.set_read_timeout(Some(left))?;
    // `parse` answers before a buffer this full; the bound holds whatever it does.
    let room = (MAX_HEAD + MAX_BODY).saturating_sub(buffer.len());
    let mut chunk = [0u8; 8192];
    let n = stream.read(&mut chunk[..room.min(8192)])?;
    buffer.extend_from_slice(&chunk[..n]);
    Ok(n)
}

/// Sends `reply` and closes the connection, first reading (and dropping) a little of what the
/// client still sends: closing with unread bytes would reset the connection, and the client
/// could lose the answer.
fn refuse(mut stream: TcpStream, reply: Reply) {
    if stream.write_all(&reply.bytes(true)).is_err() || stream.shutdown(Shutdown::Write).is_err() {
        return;
    }
    let deadline = Instant::now() + LINGER_TIME;
    let mut chunk = [0u8; 4096];
    let mut dropped = 0;
    while dropped < LINGER_BYTES {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return;
        }
        match stream.read(&mut chunk) {
            Ok(0) | Err(_) => return,
            Ok(n) => dropped += n,
        }
    }
}
