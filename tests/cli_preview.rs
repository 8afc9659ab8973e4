//! `nullpath preview`'s server without a browser: untrusted requests are refused with 4xx (and
//! the server keeps serving), it listens on loopback only, clients that vanish mid-frame do no
//! harm, "Save view" writes a `[views.NAME]` that `nullpath render --view` uses, and "Render"
//! writes the full-quality image. The page itself is tested in a browser by preview_browser.rs.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod preview_server;

use preview_server::{temp_dir, Preview, SCENE};
use std::io::{Read, Write};
use std::net::{IpAddr, SocketAddr, TcpStream, UdpSocket};
use std::time::Duration;

fn started(name: &str) -> (std::path::PathBuf, Preview) {
    let dir = temp_dir(name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let preview = Preview::start(&scene);
    (scene, preview)
}

#[test]
fn untrusted_requests_are_refused_and_the_server_keeps_serving() {
    let (_, preview) = started("requests");
    let json = Some("application/json");
    let cases: &[(&str, &str, Option<&str>, &str, u16)] = &[
        ("GET", "/nothing", None, "", 404),
        ("GET", "/state?x=1", None, "", 400),
        ("POST", "/state", json, "{}", 405),
        ("GET", "/view", None, "", 405),
        ("POST", "/view", Some("text/plain"), "{}", 415),
        ("POST", "/view", json, "not json", 400),
        ("POST", "/view", json, r#"{"position": [0, 0, 6], "look_at": [0, 0, 0], "up": [0, 1, 0]}"#, 400),
        (
            "POST",
            "/view",
            json,
            r#"{"position": [0, 0, 6], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40, "zoom": 2}"#,
            400,
        ),
        (
            "POST",
            "/view",
            json,
            r#"{"position": [0, 0, 1e300], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40}"#,
            400,
        ),
        ("POST", "/view", json, r#"{"position": [0, 0, 6], "look_at": [0, 0, 6], "up": [0, 1, 0], "fov": 40}"#, 400),
        ("POST", "/view", json, r#"{"position": [0, 0, 6], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 400}"#, 400),
        ("POST", "/view", json, r#"{"position": ["a", 0, 6], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40}"#, 400),
        ("POST", "/settings", json, r#"{"parameters": {"mass": -1}}"#, 400),
        ("POST", "/settings", json, r#"{"parameters": {"mass": 1e999}}"#, 400),
        ("POST", "/settings", json, r#"{"parameters": {"mass": NaN}}"#, 400),
        ("POST", "/settings", json, r#"{"parameters": {"throat": 1}}"#, 400),
        ("POST", "/settings", json, r#"{"spp": 0}"#, 400),
        ("POST", "/settings", json, r#"{"spp": 100000}"#, 400),
        ("POST", "/settings", json, r#"{"spp": 2.5}"#, 400),
        ("POST", "/settings", json, r#"{"exposure": 2}"#, 400),
        ("POST", "/reset", json, r#"{"all": true}"#, 400),
        ("POST", "/save-view", json, r#"{"name": "../evil"}"#, 400),
        ("POST", "/save-view", json, r#"{"name": "x]\n[camera"}"#, 400),
        ("POST", "/render", json, r#"{"output": "../../x.png"}"#, 400),
        ("POST", "/render", json, r#"{"output": "x.txt"}"#, 400),
    ];
    for &(method, path, content_type, body, expected) in cases {
        let (status, answer) = preview.request(method, path, content_type, body.as_bytes());
        let answer = String::from_utf8_lossy(&answer);
        assert_eq!(status, expected, "{method} {path} {body}: {answer}");
        assert!(expected == 404 || !answer.trim().is_empty(), "{method} {path} {body}: the reason is given");
    }
    let big = format!(r#"{{"name": "{}"}}"#, "v".repeat(100_000));
    assert_eq!(preview.post("/save-view", &big).0, 413);
    // Nothing above changed what is shown.
    let state = preview.state();
    assert_eq!(state["generation"], 1, "{state}");
    assert_eq!(state["error"], serde_json::Value::Null);
    assert_eq!(preview.post("/settings", r#"{"parameters": {"mass": 0.5}, "spp": 2}"#).0, 200);
    let state = preview.wait_for_done_frame();
    assert_eq!((state["parameters"][0]["value"].as_f64(), state["spp"].as_u64()), (Some(0.5), Some(2)));
}

/// The machine's IPv4 address on its default route, if it has one (a UDP "connection" sends
/// nothing; it only picks the interface).
fn non_loopback_address() -> Option<IpAddr> {
    let socket = UdpSocket::bind("0.0.0.0:0").ok()?;
    socket.connect("192.0.2.1:9").or_else(|_| socket.connect("10.255.255.255:9")).ok()?;
    let ip = socket.local_addr().ok()?.ip();
    (!ip.is_loopback() && !ip.is_unspecified()).then_some(ip)
}

#[test]
fn it_listens_on_loopback_only() {
    let (_, preview) = started("loopback");
    // The kernel's table of listening sockets: the port is bound to 127.0.0.1 (0100007F) alone.
    let table = std::fs::read_to_string("/proc/net/tcp").unwrap()
        + &std::fs::read_to_string("/proc/net/tcp6").unwrap_or_default();
    let port = format!(":{:04X} ", preview.port);
    let listening: Vec<&str> = table
        .lines()
        .filter(|l| l.split_whitespace().nth(1).is_some_and(|a| format!("{a} ").ends_with(&port)))
        .filter(|l| l.split_whitespace().nth(3) == Some("0A"))
        .filter_map(|l| l.split_whitespace().nth(1))
        .collect();
    assert_eq!(listening, [format!("0100007F{}", port.trim_end())], "listening sockets on the port");
    match non_loopback_address() {
        Some(ip) => {
            let refused = TcpStream::connect_timeout(&SocketAddr::new(ip, preview.port), Duration::from_secs(2));
            assert!(refused.is_err(), "a connection to {ip}:{} was accepted", preview.port);
        }
        None => eprintln!("SKIPPED the connection through a non-loopback address: this machine has none"),
    }
    // A Host header naming another server (DNS rebinding) is refused.
    let mut stream = TcpStream::connect(("127.0.0.1", preview.port)).unwrap();
    stream.write_all(b"GET /state HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n").unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 403"), "{answer}");
}

#[test]
fn clients_that_vanish_mid_frame_do_no_harm() {
    let (_, mut preview) = started("vanish");
    preview.wait_for_done_frame();
    let request = format!("GET /frame.png HTTP/1.1\r\nHost: 127.0.0.1:{}\r\n\r\n", preview.port);
    for i in 0..40 {
        let mut stream = TcpStream::connect(("127.0.0.1", preview.port)).unwrap();
        stream.write_all(request.as_bytes()).unwrap();
        if i % 2 == 0 {
            // Read the head and a little of the picture, then hang up.
            let mut some = [0u8; 300];
            let _ = stream.read(&mut some);
        }
        drop(stream);
    }
    // Changes still render and frames are still served.
    assert_eq!(preview.post("/settings", r#"{"spp": 8}"#).0, 200);
    let state = preview.wait_for_done_frame();
    assert_eq!(state["frame"]["spp"], 8);
    let (status, png) = preview.get("/frame.png");
    assert_eq!(status, 200);
    let frame = image::load_from_memory(&png).unwrap();
    assert_eq!((frame.width(), frame.height()), (96, 72));
    assert!(preview.alive());
}

#[test]
fn a_saved_view_renders_and_the_render_button_writes_the_image() {
    let (scene, preview) = started("save");
    let eye = r#"{"position": [1, 2, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 45}"#;
    assert_eq!(preview.post("/view", eye).0, 200);
    let (status, answer) = preview.post("/save-view", r#"{"name": "high"}"#);
    assert_eq!(status, 200, "{answer}");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.starts_with(SCENE), "the file is kept as written, the view appended:\n{text}");
    assert!(text.contains("[views.high]\nposition = [1.0, 2.0, 5.0]\n"), "{text}");
    let out = scene.with_file_name("high.png");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_nullpath"))
        .args(["render", scene.to_str().unwrap(), "--view", "high", "-o", out.to_str().unwrap()])
        .args(["--width", "8", "--height", "6", "--spp", "1", "--quiet"])
        .status()
        .unwrap();
    assert!(status.success());

    let (status, answer) = preview.post("/render", r#"{"output": "full.png"}"#);
    assert_eq!(status, 200, "{answer}");
    let state = preview.wait_for("the render", |s| s["render"]["state"] != "running");
    assert_eq!(state["render"]["state"], "done", "{state}");
    let full = image::open(scene.with_file_name("full.png")).unwrap();
    assert_eq!((full.width(), full.height()), (96, 72), "the scene file's size, not the preview's");
}
