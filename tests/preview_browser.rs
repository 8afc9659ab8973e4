//! `nullpath preview` in a real browser: headless Chromium driven over the DevTools protocol.
//! The page loads, a frame arrives, a mouse drag moves the camera and the new frame differs, the
//! mass slider (clicked with the mouse) makes the shadow grow, editing the scene file reloads it,
//! a broken scene file shows its error on the page exactly as the command line prints it, and
//! tabs closed mid-frame leave the server serving.
//!
//! Needs Debian's `chromium` (or `NULLPATH_CHROMIUM=/path/to/chrome`). Without it the test
//! prints SKIPPED and passes, unless `NULLPATH_REQUIRE_BROWSER=1` (as .ci/run sets after
//! installing it), which makes a missing browser a failure.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod preview_server;

use preview_server::{temp_dir, Preview, SCENE};
use serde_json::{json, Value};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// How long any one wait may take.
const PATIENCE: Duration = Duration::from_secs(90);

fn find_chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("NULLPATH_CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    let path = std::env::var_os("PATH")?;
    let names = ["chromium", "chromium-browser", "google-chrome", "google-chrome-stable"];
    std::env::split_paths(&path).flat_map(|dir| names.map(|n| dir.join(n))).find(|p| p.is_file())
}

/// A headless Chromium with remote debugging; killed when dropped.
struct Browser {
    child: Child,
    port: u16,
    cdp: Cdp,
}

impl Browser {
    fn start(executable: &Path, profile: &Path) -> Browser {
        let child = Command::new(executable)
            .args(["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--no-default-browser-check"])
            .args(["--disable-background-timer-throttling", "--disable-renderer-backgrounding"])
            .arg("--window-size=1280,900")
            .arg("--remote-debugging-port=0")
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {}: {e}", executable.display()));
        // Chromium writes its port and the browser's DevTools path here once it listens.
        let active = profile.join("DevToolsActivePort");
        let start = Instant::now();
        let (port, path) = loop {
            if let Some((port, path)) = std::fs::read_to_string(&active)
                .ok()
                .and_then(|t| t.lines().next().zip(t.lines().nth(1)).map(|(a, b)| (a.to_string(), b.to_string())))
                .and_then(|(port, path)| port.parse::<u16>().ok().map(|p| (p, path)))
            {
                break (port, path);
            }
            assert!(start.elapsed() < PATIENCE, "chromium did not start listening");
            std::thread::sleep(Duration::from_millis(100));
        };
        let cdp = Cdp::connect(&format!("ws://127.0.0.1:{port}{path}"));
        Browser { child, port, cdp }
    }

    /// Opens `url` in a new tab; returns its target id and a connection to it.
    fn open(&mut self, url: &str) -> (String, Cdp) {
        let target = self.cdp.call("Target.createTarget", json!({ "url": url }));
        let id = target["targetId"].as_str().unwrap().to_string();
        let page = Cdp::connect(&format!("ws://127.0.0.1:{}/devtools/page/{id}", self.port));
        (id, page)
    }

    fn close(&mut self, id: &str) {
        self.cdp.call("Target.closeTarget", json!({ "targetId": id }));
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One DevTools protocol connection (to the browser or to a page).
struct Cdp {
    socket: WebSocket<MaybeTlsStream<TcpStream>>,
    next_id: u64,
}

impl Cdp {
    fn connect(url: &str) -> Cdp {
        let (socket, _) = tungstenite::connect(url).unwrap_or_else(|e| panic!("DevTools at {url}: {e}"));
        if let MaybeTlsStream::Plain(stream) = socket.get_ref() {
            stream.set_read_timeout(Some(PATIENCE)).unwrap();
        }
        Cdp { socket, next_id: 1 }
    }

    /// Calls `method` and returns its result (events that arrive meanwhile are skipped).
    fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let message = json!({ "id": id, "method": method, "params": params }).to_string();
        self.socket.send(Message::text(message)).unwrap();
        loop {
            let Message::Text(text) = self.socket.read().unwrap() else { continue };
            let reply: Value = serde_json::from_str(&text).unwrap();
            if reply["id"] == id {
                assert!(reply["error"].is_null(), "{method}: {}", reply["error"]);
                return reply["result"].clone();
            }
        }
    }

    /// The value of the JavaScript expression `expression` in the page (promises awaited).
    fn eval(&mut self, expression: &str) -> Value {
        let params = json!({ "expression": expression, "returnByValue": true, "awaitPromise": true });
        let result = self.call("Runtime.evaluate", params);
        assert!(result["exceptionDetails"].is_null(), "{expression}: {}", result["exceptionDetails"]);
        result["result"]["value"].clone()
    }

    /// Waits until `condition` (JavaScript) is true in the page.
    fn wait(&mut self, what: &str, condition: &str) {
        let start = Instant::now();
        while self.eval(&format!("Boolean({condition})")) != json!(true) {
            let shown = self.eval(
                "JSON.stringify({ frame: window.preview && preview.frame, state: window.preview && preview.state })",
            );
            assert!(start.elapsed() < PATIENCE, "timed out waiting for {what}: {shown}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// The generation of the state the page last read.
    fn generation(&mut self) -> u64 {
        self.eval("preview.state ? preview.state.generation : 0").as_u64().unwrap()
    }

    /// Waits until the page shows the finished frame of the server's current generation, a
    /// later one than `after`, and returns a summary of the canvas.
    fn settled(&mut self, what: &str, after: u64) -> Summary {
        self.wait(
            what,
            &format!(
                "preview.state && preview.frame && !preview.state.error && preview.frame.done \
                 && preview.frame.generation === preview.state.generation && preview.state.generation > {after}"
            ),
        );
        Summary::of(self)
    }

    fn mouse(&mut self, kind: &str, (x, y): (f64, f64), buttons: u32) {
        let button = if kind == "mouseMoved" && buttons == 0 { "none" } else { "left" };
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": kind, "x": x, "y": y, "button": button, "buttons": buttons, "clickCount": 1 }),
        );
    }
}

/// What the canvas shows: how many pixels are dark (luma < 25 of 255) and a 16 × 12 thumbnail
/// of mean luma.
#[derive(Debug)]
struct Summary {
    dark: u64,
    thumbnail: Vec<f64>,
}

const SUMMARY_JS: &str = r#"(() => {
  const c = document.getElementById("view");
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  const W = 16, H = 12, sums = new Array(W * H).fill(0), counts = new Array(W * H).fill(0);
  let dark = 0;
  for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) {
    const i = 4 * (y * c.width + x), luma = 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2];
    if (luma < 25) dark++;
    const cell = Math.floor((y * H) / c.height) * W + Math.floor((x * W) / c.width);
    sums[cell] += luma; counts[cell]++;
  }
  return { dark, thumbnail: sums.map((s, i) => s / counts[i]) };
})()"#;

impl Summary {
    fn of(page: &mut Cdp) -> Summary {
        let v = page.eval(SUMMARY_JS);
        let thumbnail = v["thumbnail"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        Summary { dark: v["dark"].as_u64().unwrap(), thumbnail }
    }

    /// Mean absolute difference of the thumbnails, in luma levels.
    fn difference(&self, other: &Summary) -> f64 {
        let n = self.thumbnail.len() as f64;
        self.thumbnail.iter().zip(&other.thumbnail).map(|(a, b)| (a - b).abs()).sum::<f64>() / n
    }
}

/// The message `nullpath render` prints for the scene file at `path` (which must be broken).
fn cli_error(path: &Path) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_nullpath"))
        .args(["render", path.to_str().unwrap(), "-o", path.with_extension("png").to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    stderr.trim().strip_prefix("nullpath: error: ").unwrap_or_else(|| panic!("{stderr}")).to_string()
}

fn camera_position(page: &mut Cdp) -> [f64; 3] {
    serde_json::from_value(page.eval("preview.camera.position")).unwrap()
}

#[test]
fn the_page_previews_a_scene_live() {
    let Some(chromium) = find_chromium() else {
        assert!(
            std::env::var_os("NULLPATH_REQUIRE_BROWSER").is_none(),
            "NULLPATH_REQUIRE_BROWSER is set but chromium is not installed"
        );
        eprintln!("SKIPPED preview_browser: chromium not found (apt-get install chromium, or set NULLPATH_CHROMIUM)");
        return;
    };
    let dir = temp_dir("browser");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let mut preview = Preview::start(&scene);
    let mut browser = Browser::start(&chromium, &dir.join("profile"));

    // The page loads and a frame arrives.
    let opened = Instant::now();
    let (_, mut page) = browser.open(&preview.url());
    page.wait("the first frame", "window.preview && preview.framesShown > 0");
    eprintln!(
        "first frame on the page {} ms after it began loading, {:.0} ms after the tab was asked for",
        page.eval("preview.firstFrameMs"),
        opened.elapsed().as_secs_f64() * 1e3
    );
    assert_eq!(page.eval("document.title"), "nullpath preview");
    assert_eq!(page.eval("document.getElementById('scene').textContent"), scene.display().to_string());
    let before = page.settled("the refined frame", 0);
    assert!(before.dark > 500, "the hole's shadow is dark: {before:?}");

    // A mouse drag orbits the camera; the new frame differs.
    let start = camera_position(&mut page);
    let generation = page.generation();
    page.mouse("mouseMoved", (300.0, 200.0), 0);
    page.mouse("mousePressed", (300.0, 200.0), 1);
    for step in 1..=10 {
        page.mouse("mouseMoved", (300.0 + 8.0 * f64::from(step), 200.0 + 2.0 * f64::from(step)), 1);
    }
    page.mouse("mouseReleased", (380.0, 220.0), 1);
    let dragged = page.settled("the frame after the drag", generation);
    let moved = camera_position(&mut page);
    let distance = start.iter().zip(moved).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
    assert!(distance > 0.5, "the camera moved from {start:?} to {moved:?}");
    assert!(dragged.difference(&before) > 3.0, "the frame changed: {}", dragged.difference(&before));

    // Clicking the mass slider at 60 % of its track (0 to 1) doubles the mass: the shadow grows.
    let track: Vec<f64> = serde_json::from_value(page.eval(
        "(() => { const r = document.getElementById('param-mass').getBoundingClientRect(); \
         return [r.left, r.top, r.width, r.height]; })()",
    ))
    .unwrap();
    let generation = page.generation();
    let at = (track[0] + 0.6 * track[2], track[1] + 0.5 * track[3]);
    page.mouse("mouseMoved", at, 0);
    page.mouse("mousePressed", at, 1);
    std::thread::sleep(Duration::from_millis(50));
    page.mouse("mouseReleased", at, 1);
    let slider = page.eval("[document.getElementById('param-mass').value, document.activeElement.id]");
    eprintln!("slider after the click: {slider} (track {track:?})");
    page.wait("the new mass", "preview.state.parameters[0].value > 0.5");
    let heavier = page.settled("the frame with more mass", generation);
    let mass = page.eval("preview.state.parameters[0].value").as_f64().unwrap();
    assert!((0.5..0.7).contains(&mass), "mass {mass}");
    eprintln!("mass 0.3 → {mass}: the shadow grows from {} to {} dark pixels", dragged.dark, heavier.dark);
    assert!(heavier.dark > 2 * dragged.dark, "the shadow grows: {} → {} dark pixels", dragged.dark, heavier.dark);

    // Editing the file reloads it: a red sky.
    let generation = page.generation();
    std::fs::write(&scene, SCENE.replace("zenith = [0.3, 0.3, 0.35]", "zenith = [0.4, 0.02, 0.02]")).unwrap();
    page.wait("the reload", "preview.state.reloads >= 1");
    let red = page.settled("the frame of the edited file", generation);
    let shown = page.eval("JSON.stringify([preview.frame, preview.state])");
    assert!(
        red.difference(&heavier) > 3.0,
        "the frame changed: {} {red:?} {heavier:?} {shown}",
        red.difference(&heavier)
    );

    // A broken file shows its error on the page, as `nullpath render` prints it.
    std::fs::write(&scene, SCENE.replace("mass = 0.3", "mass = \"heavy\"")).unwrap();
    let expected = cli_error(&scene);
    assert!(expected.contains(":4:8: spacetime.mass: expected a number"), "{expected}");
    page.wait("the error", "getComputedStyle(document.getElementById('error')).display !== 'none'");
    assert_eq!(page.eval("document.getElementById('error').textContent"), expected);
    assert!(preview.alive());
    let generation = page.generation();
    std::fs::write(&scene, SCENE).unwrap();
    page.wait("the error to go", "!preview.state.error");
    page.settled("the frame of the fixed file", generation);

    // Tabs closed while they load and fetch frames leave the server serving.
    for delay in [0, 30, 80, 150, 300] {
        let (id, _tab) = browser.open(&preview.url());
        std::thread::sleep(Duration::from_millis(delay));
        browser.close(&id);
    }
    let generation = page.generation();
    assert_eq!(preview.post("/settings", r#"{"spp": 8}"#).0, 200);
    page.settled("a frame after the closed tabs", generation);
    assert_eq!(page.eval("preview.frame.spp"), 8);
    assert!(preview.alive());
}
