//! The preview server's reading of a request: the bytes a client has sent so far in, a request,
//! a call for more bytes, or the status that refuses it out. Pure (no I/O, no clock) and bounded:
//! whatever the bytes say, a request holds at most [`MAX_HEAD`] bytes of head and [`MAX_BODY`] of
//! body, so that a `Content-Length: 99999999999` is answered 413 before anything is read or
//! allocated. It depends on `httparse` and `std` alone, so that a fuzzer can include this file
//! as it stands (tests/preview_http_request.rs does, and mutates real requests through it).

use httparse::{Error, Status, EMPTY_HEADER};

/// Longest request head (request line and header fields), bytes.
pub const MAX_HEAD: usize = 8 * 1024;
/// Most header fields in a request.
pub const MAX_HEADERS: usize = 32;
/// Largest request body, bytes.
pub const MAX_BODY: usize = 64 * 1024;

/// A whole request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Request {
    pub method: String,
    /// The request target as sent: a path, perhaps with a query.
    pub target: String,
    /// The `Host` field, if it has one.
    pub host: Option<String>,
    /// The `Content-Type` field, if it has one.
    pub content_type: Option<String>,
    pub body: Vec<u8>,
    /// The connection ends after the response: the client said `Connection: close`, or speaks
    /// HTTP/1.0 (whose keep-alive this server does not offer).
    pub close: bool,
    /// Bytes of the input this request took; what follows is the next request's.
    pub length: usize,
}

/// What the bytes so far make.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Parsed {
    /// More bytes are needed. Once the head is complete, `until` says how many the request has
    /// in all (so that the body need not be parsed again at every read), and `send_continue`
    /// that the client waits for `100 Continue` before it sends the body.
    Incomplete {
        until: Option<usize>,
        send_continue: bool,
    },
    Complete(Request),
}

/// A request refused: the status to answer, and why (for the answer's text).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub status: u16,
    pub reason: &'static str,
}

const fn refusal(status: u16, reason: &'static str) -> Refusal {
    Refusal { status, reason }
}

const MALFORMED: Refusal = refusal(400, "the request is not well-formed HTTP/1.1");
const HEAD_TOO_LARGE: Refusal = refusal(431, "the request's header fields are too large (at most 8 KiB and 32 fields)");
const BODY_TOO_LARGE: Refusal = refusal(413, "the request is too large (at most 64 KiB)");

/// Reads `input`, the bytes a client has sent on a connection so far (from the start of a
/// request).
pub fn parse(input: &[u8]) -> Result<Parsed, Refusal> {
    let window = &input[..input.len().min(MAX_HEAD)];
    let mut fields = [EMPTY_HEADER; MAX_HEADERS];
    let mut head = httparse::Request::new(&mut fields);
    let head_length = match head.parse(window) {
        Ok(Status::Complete(n)) => n,
        Ok(Status::Partial) if window.len() < MAX_HEAD => {
            return Ok(Parsed::Incomplete { until: None, send_continue: false })
        }
        Ok(Status::Partial) | Err(Error::TooManyHeaders) => return Err(HEAD_TOO_LARGE),
        Err(Error::Version) => return Err(refusal(505, "this server speaks HTTP/1.0 and HTTP/1.1 only")),
        Err(_) => return Err(MALFORMED),
    };
    // A complete head has all three.
    let (Some(method), Some(target), Some(version)) = (head.method, head.path, head.version) else {
        return Err(MALFORMED);
    };
    let mut fields = Fields::default();
    for field in head.headers.iter() {
        fields.add(field.name, field.value)?;
    }
    let body_length = fields.content_length.unwrap_or(0);
    let until = head_length + body_length;
    if input.len() < until {
        return Ok(Parsed::Incomplete { until: Some(until), send_continue: fields.expects_continue });
    }
    Ok(Parsed::Complete(Request {
        method: method.to_string(),
        target: target.to_string(),
        host: fields.host,
        content_type: fields.content_type,
        body: input[head_length..until].to_vec(),
        close: version == 0 || fields.close,
        length: until,
    }))
}

/// The header fields the server reads.
#[derive(Default)]
struct Fields {
    host: Option<String>,
    content_type: Option<String>,
    content_length: Option<usize>,
    close: bool,
    expects_continue: bool,
}

impl Fields {
    fn add(&mut self, name: &str, value: &[u8]) -> Result<(), Refusal> {
        let text = || std::str::from_utf8(value).map(str::trim).map_err(|_| MALFORMED);
        if name.eq_ignore_ascii_case("Content-Length") {
            let length = content_length(value)?;
            // Two different lengths are how request smuggling starts; equal ones are harmless.
            if self.content_length.is_some_and(|l| l != length) {
                return Err(refusal(400, "the request has two different Content-Length fields"));
            }
            self.content_length = Some(length);
        } else if name.eq_ignore_ascii_case("Transfer-Encoding") {
            // Browsers send a page's JSON with a Content-Length; a chunked body is the one way
            // around the length check, so it is not taken at all.
            return Err(refusal(501, "this server takes no Transfer-Encoding: send a Content-Length"));
        } else if name.eq_ignore_ascii_case("Host") {
            if self.host.is_some() {
                return Err(refusal(400, "the request has two Host fields"));
            }
            self.host = Some(text()?.to_string());
        } else if name.eq_ignore_ascii_case("Content-Type") {
            if self.content_type.is_none() {
                self.content_type = Some(text()?.to_string());
            }
        } else if name.eq_ignore_ascii_case("Connection") {
            self.close |= text()?.split(',').any(|option| option.trim().eq_ignore_ascii_case("close"));
        } else if name.eq_ignore_ascii_case("Expect") {
            if !text()?.eq_ignore_ascii_case("100-continue") {
                return Err(refusal(417, "the only expectation this server meets is 100-continue"));
            }
            self.expects_continue = true;
        }
        Ok(())
    }
}

/// A `Content-Length` value: digits, at most [`MAX_BODY`].
fn content_length(value: &[u8]) -> Result<usize, Refusal> {
    let digits = value.trim_ascii();
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return Err(refusal(400, "the Content-Length is not a number"));
    }
    // Stops at the first digit that takes the length past MAX_BODY, however many follow: no
    // number that could overflow is ever formed.
    let length = digits.iter().try_fold(0usize, |n, &d| {
        let n = n * 10 + usize::from(d - b'0');
        (n <= MAX_BODY).then_some(n)
    });
    length.ok_or(BODY_TOO_LARGE)
}
