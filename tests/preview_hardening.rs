//! `nullpath preview` against what the security review (issue 38) found: requests that say they
//! are huge, slow or too many clients, parallel and failing "Save view"s, "Render" onto an
//! existing file or onto a full disk, and a render whose film does not fit in memory. Each test
//! checks that the server answers, keeps serving, and leaves the user's files as they were.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod preview_server;

use preview_server::{temp_dir, Preview, SCENE};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The server's `MAX_CONNECTIONS`.
const MAX_CONNECTIONS: usize = 128;
/// The server's `REQUEST_TIME`, seconds.
const REQUEST_TIME: u64 = 10;

fn started(name: &str) -> (PathBuf, Preview) {
    let dir = temp_dir(name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let preview = Preview::start(&scene);
    (scene, preview)
}

/// Sends `bytes` on a new connection and returns all that comes back until the server closes it.
fn exchange(preview: &Preview, bytes: &[u8]) -> String {
    let mut stream = TcpStream::connect(("127.0.0.1", preview.port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    stream.write_all(bytes).unwrap();
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).unwrap();
    String::from_utf8_lossy(&answer).to_string()
}

fn status_of(answer: &str) -> u16 {
    answer.strip_prefix("HTTP/1.1 ").and_then(|s| s.get(..3)).and_then(|s| s.parse().ok()).unwrap_or(0)
}

/// The files in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect();
    names.sort();
    names
}

#[test]
fn a_huge_content_length_is_answered_413_and_the_preview_keeps_serving() {
    let (_, mut preview) = started("huge-length");
    let port = preview.port;
    let requests = [
        // The request of the review: refused for its Host, and tiny_http then aborted on its length.
        "GET /state HTTP/1.1\r\nHost: evil.example\r\nContent-Length: 99999999999\r\n\r\n".to_string(),
        format!(
            "POST /view HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n\
             Content-Length: 99999999999\r\n\r\n{{\"position\": "
        ),
        format!("POST /view HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 18446744073709551616\r\n\r\n"),
    ];
    for request in &requests {
        let answer = exchange(&preview, request.as_bytes());
        assert_eq!(status_of(&answer), 413, "{request}\n→ {answer}");
        assert!(answer.contains("Connection: close"), "{answer}");
        assert!(preview.alive(), "the preview died of {request}");
    }
    // Heads too large, framing it does not take, bytes that are not HTTP: refused, one by one.
    let many_fields: String = (0..40).map(|i| format!("X-{i}: y\r\n")).collect();
    let refusals = [
        (format!("GET /state HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX: {}\r\n\r\n", "a".repeat(9000)), 431),
        (format!("GET /state HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n{many_fields}\r\n"), 431),
        (format!("POST /view HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n"), 501),
        ("\u{16}\u{3}\u{1} not HTTP at all\r\n\r\n".to_string(), 400),
    ];
    for (request, expected) in &refusals {
        let answer = exchange(&preview, request.as_bytes());
        assert_eq!(status_of(&answer), *expected, "{}\n→ {answer}", &request[..request.len().min(80)]);
    }
    assert!(preview.alive());
    assert_eq!(preview.state()["error"], serde_json::Value::Null);
    assert_eq!(preview.post("/settings", r#"{"spp": 2}"#).0, 200);
}

#[test]
fn connections_are_kept_alive_pipelined_and_continued() {
    let (_, preview) = started("keep-alive");
    let port = preview.port;
    // Three requests in one write: each answered in order, the connection closed after the last.
    let get = |close: &str| format!("GET /state HTTP/1.1\r\nHost: localhost:{port}\r\n{close}\r\n");
    let answer = exchange(&preview, format!("{}{}{}", get(""), get(""), get("Connection: close\r\n")).as_bytes());
    assert_eq!(answer.matches("HTTP/1.1 200 OK\r\n").count(), 3, "{answer}");
    assert_eq!(answer.matches("Connection: keep-alive\r\n").count(), 2, "{answer}");
    assert!(answer.contains("Cache-Control: no-store\r\n") && answer.contains("X-Content-Type-Options: nosniff\r\n"));

    // curl's Expect: 100-continue: the body is sent once the server asks for it.
    let body = br#"{"spp": 2}"#;
    let mut stream = TcpStream::connect(("127.0.0.1", port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let head = format!(
        "POST /settings HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nExpect: 100-continue\r\nConnection: close\r\n\r\n",
        body.len()
    );
    stream.write_all(head.as_bytes()).unwrap();
    let mut continued = [0u8; 25];
    stream.read_exact(&mut continued).unwrap();
    assert_eq!(&continued, b"HTTP/1.1 100 Continue\r\n\r\n");
    stream.write_all(body).unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    assert_eq!(status_of(&answer), 200, "{answer}");
}

#[test]
fn slow_and_surplus_clients_are_bounded() {
    let (_, mut preview) = started("slow");
    let port = preview.port;
    // A client that starts a request and then says nothing is answered 408 after REQUEST_TIME,
    // and meanwhile the others are served.
    let started = Instant::now();
    let mut slow = TcpStream::connect(("127.0.0.1", port)).unwrap();
    slow.set_read_timeout(Some(Duration::from_secs(REQUEST_TIME + 20))).unwrap();
    slow.write_all(format!("POST /view HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Len").as_bytes()).unwrap();

    // Connections past MAX_CONNECTIONS are answered 503 at once; the held ones are not dropped.
    let held: Vec<TcpStream> =
        (0..MAX_CONNECTIONS - 1).map(|_| TcpStream::connect(("127.0.0.1", port)).unwrap()).collect();
    let mut surplus = TcpStream::connect(("127.0.0.1", port)).unwrap();
    surplus.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let mut answer = String::new();
    surplus.read_to_string(&mut answer).unwrap();
    assert_eq!(status_of(&answer), 503, "{answer}");
    // Closing them gives their threads back: requests are served again.
    drop(held);
    let deadline = Instant::now() + Duration::from_secs(30);
    while preview.request("GET", "/state", None, b"").0 != 200 {
        assert!(Instant::now() < deadline, "the held connections' slots were never given back");
        std::thread::sleep(Duration::from_millis(50));
    }

    let mut answer = String::new();
    slow.read_to_string(&mut answer).unwrap();
    let waited = started.elapsed();
    assert_eq!(status_of(&answer), 408, "{answer}");
    assert!(waited >= Duration::from_secs(REQUEST_TIME - 1), "answered after {waited:?}");
    assert!(waited < Duration::from_secs(REQUEST_TIME + 15), "answered after {waited:?}");
    assert!(preview.alive());
}

#[test]
fn sixty_parallel_saves_keep_all_sixty_views_and_the_file_mode() {
    let (scene, preview) = started("parallel-saves");
    std::fs::set_permissions(&scene, std::fs::Permissions::from_mode(0o640)).unwrap();
    let answers: Vec<(u16, String)> = std::thread::scope(|scope| {
        let preview = &preview;
        let saves: Vec<_> = (0..60)
            .map(|i| scope.spawn(move || preview.post("/save-view", &format!(r#"{{"name": "v{i}"}}"#))))
            .collect();
        saves.into_iter().map(|s| s.join().unwrap()).collect()
    });
    for (i, (status, answer)) in answers.iter().enumerate() {
        assert_eq!(*status, 200, "save v{i}: {answer}");
    }
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.starts_with(SCENE), "the user's text is kept:\n{text}");
    let mut names = scene::view_names(&text);
    names.sort();
    let mut expected: Vec<String> = (0..60).map(|i| format!("v{i}")).collect();
    expected.sort();
    assert_eq!(names, expected);
    let mode = std::fs::metadata(&scene).unwrap().permissions().mode();
    assert_eq!(mode & 0o777, 0o640, "the file keeps its permissions");
    assert_eq!(listing(scene.parent().unwrap()), ["scene.toml"], "no temporary is left");
}

/// A scene file larger than the file size limit of [`full_disk`], so that any write of it fails.
fn large_scene() -> String {
    format!("{}\n{SCENE}", "# a long comment, to make the file larger than the limit\n".repeat(40))
}

/// A preview whose writes fail past 512 bytes (`ulimit -f 1`), as on a full disk.
fn full_disk(name: &str) -> (PathBuf, Preview) {
    let dir = temp_dir(name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, large_scene()).unwrap();
    let preview = Preview::start_under(&scene, "ulimit -f 1");
    (scene, preview)
}

#[test]
fn a_failed_save_leaves_the_scene_file_as_it_was() {
    let (scene, mut preview) = full_disk("full-disk-save");
    let before = std::fs::read(&scene).unwrap();
    let (status, answer) = preview.post("/save-view", r#"{"name": "corner"}"#);
    assert_eq!(status, 500, "{answer}");
    assert!(answer.contains("cannot write") && answer.contains("left as it was"), "{answer}");
    assert_eq!(std::fs::read(&scene).unwrap(), before, "the scene file is byte for byte as it was");
    assert_eq!(listing(scene.parent().unwrap()), ["scene.toml"], "no temporary is left");
    assert!(preview.alive());
    assert_eq!(preview.state()["error"], serde_json::Value::Null, "the scene still loads");
}

#[test]
fn render_never_replaces_a_file_unless_asked() {
    let (scene, preview) = started("render-overwrite");
    let dir = scene.parent().unwrap().to_path_buf();
    let texture = dir.join("texture.png");
    std::fs::write(&texture, b"the user's texture").unwrap();
    let (status, answer) = preview.post("/render", r#"{"output": "texture.png"}"#);
    assert_eq!(status, 400, "{answer}");
    assert!(answer.contains("already exists") && answer.contains("overwrite"), "{answer}");
    // A link counts as a file too, even one that leads nowhere.
    std::os::unix::fs::symlink(dir.join("nowhere"), dir.join("link.png")).unwrap();
    assert_eq!(preview.post("/render", r#"{"output": "link.png"}"#).0, 400);
    assert_eq!(std::fs::read(&texture).unwrap(), b"the user's texture");
    assert_eq!(preview.state()["render"], serde_json::Value::Null, "nothing started");

    let done = |preview: &Preview| {
        let state = preview.wait_for("the render", |s| s["render"]["state"] != "running");
        assert_eq!(state["render"]["state"], "done", "{state}");
    };
    assert_eq!(preview.post("/render", r#"{"output": "new.png"}"#).0, 200);
    done(&preview);
    assert_eq!(preview.post("/render", r#"{"output": "new.png"}"#).0, 400, "not twice");

    let (status, answer) = preview.post("/render", r#"{"output": "texture.png", "overwrite": true}"#);
    assert_eq!(status, 200, "{answer}");
    done(&preview);
    let image = image::open(&texture).unwrap();
    assert_eq!((image.width(), image.height()), (96, 72));
    let mode = std::fs::metadata(&texture).unwrap().permissions().mode();
    assert_eq!(mode & 0o044, 0o044, "an image others can read, as `nullpath render` writes it");
    assert_eq!(listing(&dir), ["link.png", "new.png", "scene.toml", "texture.png"], "no temporary is left");
}

#[test]
fn a_render_that_cannot_be_written_fails_visibly_and_leaves_the_file() {
    let (scene, preview) = full_disk("full-disk-render");
    let dir = scene.parent().unwrap().to_path_buf();
    let texture = dir.join("texture.png");
    std::fs::write(&texture, b"the user's texture").unwrap();
    let (status, answer) = preview.post("/render", r#"{"output": "texture.png", "overwrite": true}"#);
    assert_eq!(status, 200, "{answer}");
    let state = preview.wait_for("the render", |s| s["render"]["state"] != "running");
    assert_eq!(state["render"]["state"], "failed", "{state}");
    let message = state["render"]["message"].as_str().unwrap();
    assert!(message.contains("texture.png") && message.contains("File too large"), "{message}");
    assert!(!message.contains(".nullpath-render-"), "the temporary's name is not the user's business: {message}");
    assert_eq!(std::fs::read(&texture).unwrap(), b"the user's texture");
    assert_eq!(listing(&dir), ["scene.toml", "texture.png"], "no temporary is left");
}

#[test]
fn a_render_whose_film_does_not_fit_fails_and_the_next_may_start() {
    let dir = temp_dir("film-too-large");
    let scene = dir.join("scene.toml");
    // 16384² pixels need well over the 4 GiB of address space the preview gets.
    std::fs::write(&scene, SCENE.replace("width = 96\nheight = 72", "width = 16384\nheight = 16384")).unwrap();
    let mut preview = Preview::start_under(&scene, "ulimit -v 4194304");
    preview.wait_for_done_frame();
    for attempt in 0..2 {
        let (status, answer) = preview.post("/render", r#"{"output": "big.png"}"#);
        assert_eq!(status, 200, "attempt {attempt}: {answer}");
        let state = preview.wait_for("the render", |s| s["render"]["state"] != "running");
        assert_eq!(state["render"]["state"], "failed", "{state}");
        let message = state["render"]["message"].as_str().unwrap();
        assert!(message.contains("16384x16384") && message.contains("cannot be allocated"), "{message}");
        assert!(!message.contains("panicked") && !message.contains(".rs:"), "no Rust panic text: {message}");
    }
    assert!(!dir.join("big.png").exists());
    assert!(preview.alive());
}
