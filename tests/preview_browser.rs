//! `nullpath preview` in a real browser: headless Chromium driven over the DevTools protocol.
//! The page loads, a frame arrives, a mouse drag moves the camera and the new frame differs, the
//! mass slider (clicked with the mouse) makes the shadow grow, editing the scene file reloads it,
//! a broken scene file shows its error on the page exactly as the command line prints it (and
//! does not squeeze the sidebar), and tabs closed mid-frame leave the server serving.
//!
//! In a room round a spinning hole: a drag keeps the camera in the room and an Alt-drag leaves
//! it, which the page explains; the wheel takes it into the hole's shadow and then to the
//! horizon, both explained; the spin slider offers no more than the mass, a refused spin leaves
//! thumb and label at the server's value; a slider's value survives Save view (the view renders
//! it) and Render (the image's metadata has it), whose "rendering to …" gives way to the result.
//!
//! Needs Debian's `chromium` (or `NULLPATH_CHROMIUM=/path/to/chrome`). Without it the test
//! prints SKIPPED and passes, unless `NULLPATH_REQUIRE_BROWSER=1` (as .ci/run sets after
//! installing it), which makes a missing browser a failure.

#![allow(clippy::unwrap_used)] // A panic is a failed test.

mod preview_server;

use preview_server::{temp_dir, Preview, SCENE};
use render::film::read_metadata;
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
        self.mouse_with(kind, (x, y), buttons, 0);
    }

    /// A mouse event with `modifiers` held (1: Alt).
    fn mouse_with(&mut self, kind: &str, (x, y): (f64, f64), buttons: u32, modifiers: u32) {
        let button = if kind == "mouseMoved" && buttons == 0 { "none" } else { "left" };
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": kind, "x": x, "y": y, "button": button, "buttons": buttons, "clickCount": 1,
                "modifiers": modifiers }),
        );
    }

    /// A drag on the picture from (300, 200) by `steps` moves of (`dx`, 0), with `modifiers` held.
    fn drag(&mut self, steps: u32, dx: f64, modifiers: u32) {
        let (x, y) = (300.0, 200.0);
        self.mouse_with("mouseMoved", (x, y), 0, modifiers);
        self.mouse_with("mousePressed", (x, y), 1, modifiers);
        for step in 1..=steps {
            self.mouse_with("mouseMoved", (x + dx * f64::from(step), y), 1, modifiers);
        }
        self.mouse_with("mouseReleased", (x + dx * f64::from(steps), y), 1, modifiers);
    }

    /// One turn of the wheel over the picture (negative: closer).
    fn wheel(&mut self, delta: f64) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": "mouseWheel", "x": 300, "y": 200, "deltaX": 0, "deltaY": delta }),
        );
    }

    /// Clicks the element `id` (a button) with the mouse, at its centre.
    fn click(&mut self, id: &str) {
        let at: Vec<f64> = serde_json::from_value(self.eval(&format!(
            "(() => {{ const r = document.getElementById('{id}').getBoundingClientRect(); \
             return [r.left + r.width / 2, r.top + r.height / 2]; }})()"
        )))
        .unwrap();
        self.mouse("mouseMoved", (at[0], at[1]), 0);
        self.mouse("mousePressed", (at[0], at[1]), 1);
        self.mouse("mouseReleased", (at[0], at[1]), 1);
    }

    /// The text of the element `id`.
    fn text(&mut self, id: &str) -> String {
        self.eval(&format!("document.getElementById('{id}').textContent")).as_str().unwrap().to_string()
    }

    /// The width of the sidebar, CSS pixels.
    fn sidebar_width(&mut self) -> f64 {
        self.eval("document.querySelector('aside').getBoundingClientRect().width").as_f64().unwrap()
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

/// The browser, or `None` (and the test passes as SKIPPED) where none is installed and none is
/// required.
fn chromium_or_skip() -> Option<PathBuf> {
    let found = find_chromium();
    if found.is_none() {
        assert!(
            std::env::var_os("NULLPATH_REQUIRE_BROWSER").is_none(),
            "NULLPATH_REQUIRE_BROWSER is set but chromium is not installed"
        );
        eprintln!("SKIPPED preview_browser: chromium not found (apt-get install chromium, or set NULLPATH_CHROMIUM)");
    }
    found
}

#[test]
fn the_page_previews_a_scene_live() {
    let Some(chromium) = chromium_or_skip() else { return };
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

    // A broken file shows its error on the page, as `nullpath render` prints it, beside the
    // sidebar rather than over it.
    let sidebar = page.sidebar_width();
    std::fs::write(&scene, SCENE.replace("mass = 0.3", "mass = \"heavy\"")).unwrap();
    let expected = cli_error(&scene);
    assert!(expected.contains(":4:8: spacetime.mass: expected a number"), "{expected}");
    page.wait("the error", "getComputedStyle(document.getElementById('error')).display !== 'none'");
    assert_eq!(page.eval("document.getElementById('error').textContent"), expected);
    assert_eq!(page.sidebar_width(), sidebar, "the error box does not squeeze the sidebar");
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

/// A room x ∈ [−2, 2], y ∈ [−1.5, 1.5], z ∈ [−3, 3] of glowing walls (each its own colour, seen
/// only from inside) round a Kerr hole of mass 0.1 and spin 0.05; the camera 2.8 from the hole
/// (its shadow some 10° across the 40° view), so that a quarter turn about it would take it
/// through the side walls.
const ROOM: &str = r#"# preview test room
[spacetime]
type = "kerr"
mass = 0.1
spin = 0.05

[camera]
position = [0, 0.2, 2.8]
look_at = [0, 0, 0]
fov = 40

[render]
width = 64
height = 48
spp = 2
max_depth = 1
integrator = "brute-force"

[materials.black]
type = "diffuse"
reflectance = [0, 0, 0]

[[objects]]   # back
shape = { type = "rectangle", corner = [-2, -1.5, -3], edge_u = [4, 0, 0], edge_v = [0, 3, 0] }
material = "black"
emission = { radiance = [0.9, 0.9, 0.9] }
[[objects]]   # front
shape = { type = "rectangle", corner = [2, -1.5, 3], edge_u = [-4, 0, 0], edge_v = [0, 3, 0] }
material = "black"
emission = { radiance = [0.2, 0.2, 0.9] }
[[objects]]   # left
shape = { type = "rectangle", corner = [-2, -1.5, 3], edge_u = [0, 0, -6], edge_v = [0, 3, 0] }
material = "black"
emission = { radiance = [0.9, 0.3, 0.2] }
[[objects]]   # right
shape = { type = "rectangle", corner = [2, -1.5, -3], edge_u = [0, 0, 6], edge_v = [0, 3, 0] }
material = "black"
emission = { radiance = [0.2, 0.9, 0.3] }
[[objects]]   # floor
shape = { type = "rectangle", corner = [-2, -1.5, 3], edge_u = [4, 0, 0], edge_v = [0, 0, -6] }
material = "black"
emission = { radiance = [0.5, 0.5, 0.4] }
[[objects]]   # ceiling
shape = { type = "rectangle", corner = [-2, 1.5, -3], edge_u = [4, 0, 0], edge_v = [0, 0, 6] }
material = "black"
emission = { radiance = [0.6, 0.6, 0.6] }
"#;

/// Whether `p` is in the room of [`ROOM`].
fn in_room(p: [f64; 3]) -> bool {
    p[0].abs() < 2.0 && p[1].abs() < 1.5 && p[2].abs() < 3.0
}

fn parameter(page: &mut Cdp, name: &str) -> f64 {
    page.eval(&format!("preview.state.parameters.find((p) => p.name === '{name}').value")).as_f64().unwrap()
}

#[test]
fn the_page_explains_empty_views_and_keeps_the_sliders_honest() {
    let Some(chromium) = chromium_or_skip() else { return };
    let dir = temp_dir("browser-room");
    let scene = dir.join("room.toml");
    std::fs::write(&scene, ROOM).unwrap();
    let preview = Preview::start(&scene);
    let mut browser = Browser::start(&chromium, &dir.join("profile"));
    let (_, mut page) = browser.open(&preview.url());
    page.wait("the first frame", "window.preview && preview.framesShown > 0");
    page.settled("the room", 0);
    let notice_shown = "getComputedStyle(document.getElementById('notice')).display !== 'none'";
    assert_eq!(page.eval(notice_shown), json!(false), "nothing to explain: {}", page.text("notice"));

    // A drag with Alt held orbits the camera through a side wall, out of the room, and the page
    // says where it is.
    let generation = page.generation();
    page.drag(30, 6.0, 1);
    page.settled("the frame after the Alt-drag", generation);
    let outside = camera_position(&mut page);
    assert!(!in_room(outside), "the camera left the room: {outside:?}");
    page.wait("the notice", notice_shown);
    let notice = page.text("notice");
    assert!(notice.contains("outside the room") && notice.contains("Reset"), "{notice}");

    // Reset brings it back.
    let generation = page.generation();
    page.click("reset");
    page.settled("the file's view", generation);
    assert_eq!(page.eval(notice_shown), json!(false), "{}", page.text("notice"));

    // Without Alt, the same drag keeps it in the room.
    let generation = page.generation();
    page.drag(30, 6.0, 0);
    page.settled("the frame after the drag", generation);
    let kept = camera_position(&mut page);
    assert!(in_room(kept) && (kept[2] - 2.8).abs() > 0.5, "the camera turned and stayed inside: {kept:?}");
    assert_eq!(page.eval(notice_shown), json!(false), "{}", page.text("notice"));

    // The wheel takes it towards the hole until its shadow fills the view, which the page says,
    // and then refuses to take it into the horizon.
    // Each turn brings it to 0.74 of its distance: 0.63 after five, where the shadow's edge is
    // 43° from its centre, beyond the view's corners.
    for _ in 0..5 {
        let generation = page.generation();
        page.wheel(-300.0);
        page.settled("the frame after the wheel", generation);
    }
    page.wait("the shadow's notice", notice_shown);
    let notice = page.text("notice");
    assert!(notice.contains("inside the black hole's shadow"), "{notice}");
    for _ in 0..6 {
        page.wheel(-300.0);
        std::thread::sleep(Duration::from_millis(300));
    }
    page.wait("the refusal", "document.getElementById('notice').textContent.includes('cannot go there')");
    let notice = page.text("notice");
    assert!(notice.contains("horizon"), "{notice}");
    let generation = page.generation();
    page.click("reset");
    page.settled("the file's view again", generation);

    // The spin slider offers no more than the mass, nor the mass less than the spin.
    let range = |page: &mut Cdp, id: &str| -> (f64, f64) {
        serde_json::from_value(page.eval(&format!(
            "(() => {{ const s = document.getElementById('{id}'); return [Number(s.min), Number(s.max)]; }})()"
        )))
        .unwrap()
    };
    assert_eq!(range(&mut page, "param-spin"), (-0.1, 0.1));
    assert_eq!(range(&mut page, "param-mass"), (0.05, 1.0));

    // A spin the server refuses (as from a range gone stale) leaves thumb and label at its value.
    page.eval(
        "(() => { const s = document.getElementById('param-spin'); s.max = 0.9; s.value = 0.9; \
         s.dispatchEvent(new Event('input')); s.dispatchEvent(new Event('change')); })()",
    );
    page.wait("the refusal", "document.getElementById('message').textContent.includes('spin 0.9 refused')");
    page.wait(
        "the slider back at the server's spin",
        "Number(document.getElementById('param-spin').value) === 0.05 \
         && document.getElementById('param-spin-value').textContent === '0.05000'",
    );
    assert_eq!(range(&mut page, "param-spin"), (-0.1, 0.1), "the range is the server's again");
    assert_eq!(parameter(&mut page, "spin"), 0.05);

    // Clicking the mass slider at 15 % of its track sets about 0.05 + 0.15 × 0.95; the spin's
    // range follows.
    let track: Vec<f64> = serde_json::from_value(page.eval(
        "(() => { const r = document.getElementById('param-mass').getBoundingClientRect(); \
         return [r.left, r.top, r.width, r.height]; })()",
    ))
    .unwrap();
    let generation = page.generation();
    let at = (track[0] + 0.15 * track[2], track[1] + 0.5 * track[3]);
    page.mouse("mouseMoved", at, 0);
    page.mouse("mousePressed", at, 1);
    page.mouse("mouseReleased", at, 1);
    page.wait("the new mass", "preview.state.parameters[0].value > 0.12");
    page.settled("the heavier hole", generation);
    let mass = parameter(&mut page, "mass");
    assert!((0.15..0.25).contains(&mass), "mass {mass}");
    page.wait("the spin's new range", &format!("Number(document.getElementById('param-spin').max) === {mass}"));

    // Save view keeps the mass with the view, and the view renders in it.
    page.eval("document.getElementById('view-name').value = 'heavy'");
    page.click("save-view");
    page.wait("the save", "document.getElementById('message').textContent.startsWith('saved [views.heavy]')");
    let saved = std::fs::read_to_string(&scene).unwrap();
    assert!(saved.contains(&format!("[views.heavy.spacetime]\nmass = {mass}\nspin = 0.05\n")), "{saved}");

    // Render writes the image with the mass in its metadata; "rendering to …" gives way to the
    // result, and the long name does not squeeze the sidebar.
    let sidebar = page.sidebar_width();
    let name = format!("heavy-{}.png", "x".repeat(100));
    page.eval(&format!("document.getElementById('output-name').value = '{name}'"));
    page.click("render");
    page.wait("the render to end", "document.getElementById('message').textContent.startsWith('wrote ')");
    let message = page.text("message");
    assert!(message.contains(&name) && !message.contains("rendering to"), "{message}");
    assert!(!page.text("status").contains("rendering"), "{}", page.text("status"));
    assert_eq!(page.sidebar_width(), sidebar, "a long message does not squeeze the sidebar");
    // Nor does a long status line or error without a place to break (the next poll puts back
    // the server's).
    let squeezed = page.eval(
        "(() => { document.getElementById('status').textContent = 'x'.repeat(400); \
         const e = document.getElementById('error'); e.textContent = '/a/long/path'.repeat(40); \
         e.style.display = 'block'; return document.querySelector('aside').getBoundingClientRect().width; })()",
    );
    assert_eq!(squeezed.as_f64(), Some(sidebar), "a long status line and error leave the sidebar as it was");
    let image = dir.join(&name);
    let metadata = read_metadata(&image).unwrap();
    let spacetime: Value = serde_json::from_str(&metadata["spacetime"]).unwrap();
    assert_eq!(spacetime, json!({ "type": "kerr", "mass": mass, "spin": 0.05 }), "the spacetime rendered");

    // `nullpath render --view heavy` makes the image Render made (but for the saved pose's
    // rounding to 6 digits).
    let cli = dir.join("cli.png");
    let out = Command::new(env!("CARGO_BIN_EXE_nullpath"))
        .args(["render", scene.to_str().unwrap(), "--view", "heavy", "--quiet", "-o", cli.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let [a, b] = [&image, &cli].map(|p| image::open(p).unwrap().to_rgb8());
    let mean = a.as_raw().iter().zip(b.as_raw()).map(|(x, y)| f64::from(x.abs_diff(*y))).sum::<f64>()
        / a.as_raw().len() as f64;
    assert!(mean < 0.5, "the view renders what Render wrote: mean difference {mean} levels");
}
