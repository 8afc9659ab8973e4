//! The preview server's request parser (src/commands/preview/request.rs, included as it stands):
//! requests as browsers and curl send them, the refusals that keep a request small, and a
//! deterministic fuzz run that mutates the real requests of tests/fuzz/corpus/http_request/ and
//! checks that no input panics, allocates past the bounds or reads differently in pieces.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

#[path = "../src/commands/preview/request.rs"]
mod request;

#[path = "fuzz/mutate.rs"]
mod mutate;

use mutate::{Mutator, Runner};
use request::{parse, Parsed, Refusal, Request, MAX_BODY, MAX_HEAD, MAX_HEADERS};
use std::time::Duration;

fn complete(input: &[u8]) -> Request {
    match parse(input) {
        Ok(Parsed::Complete(request)) => request,
        other => panic!("{:?}: {other:?}", String::from_utf8_lossy(input)),
    }
}

fn refused(input: &[u8]) -> u16 {
    match parse(input) {
        Err(Refusal { status, reason }) => {
            assert!(!reason.is_empty());
            status
        }
        other => panic!("{:?}: {other:?}", String::from_utf8_lossy(input)),
    }
}

fn corpus() -> Vec<(String, Vec<u8>)> {
    let seeds: Vec<_> = mutate::corpus("http_request", &["http"]).into_iter().map(|s| (s.name, s.bytes)).collect();
    assert!(seeds.len() >= 5, "the corpus is in {}", mutate::corpus_dir("http_request").display());
    seeds
}

#[test]
fn the_corpus_reads_as_browsers_and_curl_meant_it() {
    let seeds = corpus();
    let seed = |name: &str| &seeds.iter().find(|(n, _)| n == name).unwrap().1;

    let state = complete(seed("chrome_get_state.http"));
    assert_eq!((state.method.as_str(), state.target.as_str()), ("GET", "/state"));
    assert_eq!(state.host.as_deref(), Some("127.0.0.1:8765"));
    assert!(!state.close && state.body.is_empty());
    assert_eq!(state.length, seed("chrome_get_state.http").len());

    let view = complete(seed("chrome_post_view.http"));
    assert_eq!(view.content_type.as_deref(), Some("application/json"));
    assert!(view.body.starts_with(b"{\"position\""), "{view:?}");

    // curl waits for 100 Continue before it sends the body.
    let curl = seed("curl_save_view_expect.http");
    let body_start = curl.windows(4).position(|w| w == b"\r\n\r\n").unwrap() + 4;
    assert_eq!(parse(&curl[..body_start]), Ok(Parsed::Incomplete { until: Some(curl.len()), send_continue: true }));
    assert_eq!(complete(curl).body, &curl[body_start..]);

    // Two requests in one read: the first, and where the second begins.
    let both = seed("pipelined_frames.http");
    let first = complete(both);
    assert!(!first.close);
    let second = complete(&both[first.length..]);
    assert!(second.close);
    assert_eq!(first.length + second.length, both.len());

    let old = complete(seed("http10_state.http"));
    assert!(old.close, "HTTP/1.0 is answered and closed");
    assert_eq!(old.host.as_deref(), Some("[::1]:8765"));

    assert_eq!(refused(seed("huge_content_length.http")), 413);
}

#[test]
fn what_a_request_says_cannot_make_it_large() {
    let head = |fields: &str| format!("POST /view HTTP/1.1\r\nHost: 127.0.0.1:1\r\n{fields}\r\n").into_bytes();
    // The length that aborted tiny_http, wherever it is, with or without a body behind it.
    assert_eq!(refused(&head("Content-Length: 99999999999\r\n")), 413);
    assert_eq!(refused(&head("Content-Length: 18446744073709551616\r\n")), 413);
    assert_eq!(refused(&head(&format!("Content-Length: {}\r\n", "9".repeat(4000)))), 413);
    assert_eq!(refused(&head(&format!("Content-Length: {}\r\n", MAX_BODY + 1))), 413);
    let at_most = head(&format!("Content-Length: {MAX_BODY}\r\n"));
    assert_eq!(parse(&at_most), Ok(Parsed::Incomplete { until: Some(at_most.len() + MAX_BODY), send_continue: false }));
    assert_eq!(complete(&[head("Content-Length: 0002\r\n"), b"{}".to_vec()].concat()).body, b"{}", "leading zeros");
    for bad in ["-1", "1 2", "0x10", "", "+5", "1e3"] {
        assert_eq!(refused(&head(&format!("Content-Length: {bad}\r\n"))), 400, "{bad:?}");
    }
    assert_eq!(refused(&head("Content-Length: 2\r\nContent-Length: 3\r\n")), 400, "smuggling");
    assert_eq!(complete(&[head("Content-Length: 2\r\nContent-Length: 2\r\n"), b"{}".to_vec()].concat()).body, b"{}");
    assert_eq!(refused(&head("Transfer-Encoding: chunked\r\n")), 501);

    // Heads: at most MAX_HEAD bytes and MAX_HEADERS fields, finished or not.
    let fields: String = (0..=MAX_HEADERS).map(|i| format!("X-{i}: y\r\n")).collect();
    assert_eq!(refused(&head(&fields)), 431);
    let long = format!("GET /state HTTP/1.1\r\nHost: 127.0.0.1:1\r\nX: {}", "a".repeat(MAX_HEAD));
    assert_eq!(refused(long.as_bytes()), 431, "an unfinished head past the bound");
    assert_eq!(parse(&long.as_bytes()[..MAX_HEAD - 1]), Ok(Parsed::Incomplete { until: None, send_continue: false }));

    assert_eq!(refused(b"GET /state HTTP/2.0\r\n\r\n"), 505);
    assert_eq!(refused(b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03"), 400, "TLS to a plain port");
    assert_eq!(refused(&head("Host: 127.0.0.1:2\r\n")), 400, "two Hosts");
    assert_eq!(refused(&head("Expect: 200-ok\r\n")), 417);
    assert_eq!(refused(b"GET /state HTTP/1.1\r\nHost: \xff\xfe\r\n\r\n"), 400, "a Host that is not text");
    assert!(complete(&head("Connection: keep-alive, Close\r\n")).close);
}

/// Pieces that steer a mutation to the parser's edges.
const TOKENS: &[&[u8]] = &[
    b"\r\n",
    b"\r\n\r\n",
    b"\n",
    b": ",
    b"Content-Length: 99999999999\r\n",
    b"Content-Length: 65536\r\n",
    b"Content-Length: 65537\r\n",
    b"Content-Length: 4\r\n",
    b"Content-Length: -1\r\n",
    b"Transfer-Encoding: chunked\r\n",
    b"Host: 127.0.0.1:8765\r\n",
    b"Expect: 100-continue\r\n",
    b"Connection: close\r\n",
    b"HTTP/1.0",
    b"HTTP/9.9",
    b"\x00",
    b"\xff",
    b" ",
    b"\t",
];

/// The largest input a run makes: past every bound of the parser.
const MAX_INPUT: usize = 2 * (MAX_HEAD + MAX_BODY);

/// What must hold of `parse(input)`, whatever the input.
fn check(input: &[u8]) -> mutate::Verdict {
    let shown = || String::from_utf8_lossy(&input[..input.len().min(400)]).to_string();
    match parse(input) {
        Ok(Parsed::Complete(request)) => {
            assert!(request.length <= input.len() && request.length <= MAX_HEAD + MAX_BODY, "{}", shown());
            assert!(request.body.len() <= MAX_BODY, "{}", shown());
            assert!(request.method.len() + request.target.len() < MAX_HEAD, "{}", shown());
            // The request alone reads the same; every proper beginning of it asks for more.
            assert_eq!(parse(&input[..request.length]), Ok(Parsed::Complete(request.clone())), "{}", shown());
            // A beginning of the input's own choosing, so that the check is the same every time.
            let cut = input.iter().fold(input.len(), |h, &b| h.wrapping_mul(31).wrapping_add(usize::from(b)))
                % request.length;
            assert!(
                matches!(parse(&input[..cut]), Ok(Parsed::Incomplete { .. })),
                "a beginning of {} read as {:?}",
                shown(),
                parse(&input[..cut])
            );
        }
        Ok(Parsed::Incomplete { until: Some(until), .. }) => {
            assert!(input.len() < until && until <= MAX_HEAD + MAX_BODY, "{}", shown());
            // The bytes it waits for make it whole, whatever they are.
            let mut whole = input.to_vec();
            whole.resize(until, b'x');
            assert!(matches!(parse(&whole), Ok(Parsed::Complete(r)) if r.length == until), "{}", shown());
        }
        Ok(Parsed::Incomplete { until: None, .. }) => assert!(input.len() < MAX_HEAD, "{}", shown()),
        Err(Refusal { status, reason }) => {
            assert!([400, 413, 417, 431, 501, 505].contains(&status), "{status} for {}", shown());
            assert!(!reason.is_empty());
        }
    }
    Ok(match parse(input) {
        Ok(Parsed::Complete(_)) => "complete",
        Ok(Parsed::Incomplete { .. }) => "incomplete",
        Err(Refusal { status: 400, .. }) => "400",
        Err(Refusal { status: 413, .. }) => "413",
        Err(Refusal { status: 431, .. }) => "431",
        Err(Refusal { status: 501, .. }) => "501",
        Err(_) => "other refusals",
    })
}

#[test]
fn fuzzed_requests_never_panic_and_stay_bounded() {
    let seeds = mutate::corpus("http_request", &["http"]);
    let mut random = mutate::random(0x6e75_6c6c_7061_7468);
    let mutator = Mutator::new(TOKENS, &[], MAX_INPUT);
    // Parsing is microseconds; one taking a second is a hang.
    let mut runner = Runner::inline("http_request", Duration::from_secs(1), check);
    // Mutants of the corpus itself (none kept): the thresholds below were set for them.
    let stats = mutate::drive(
        &mut runner,
        &seeds,
        &mut random,
        mutate::iterations(200_000),
        |random, input, other| mutator.mutate(random, input, other),
        |_| false,
    );
    // A run that only ever refuses (or only accepts) tests little: every outcome is reached.
    // Complete, incomplete, and each status refused with.
    for outcome in ["complete", "incomplete", "400", "413", "431", "501"] {
        assert!(stats.outcomes.get(outcome).is_some_and(|&n| n >= 10), "{outcome} too rare: {:?}", stats.outcomes);
    }
}
