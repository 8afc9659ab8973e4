//! A `nullpath preview` process for tests, and a minimal HTTP/1.1 client to talk to it (one
//! request per connection), so that the tests see exactly the bytes the server sends.

#![allow(dead_code)] // Each test file uses its own share of this.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A scene for the preview tests: a black hole (mass 0.3) in front of a bright gradient sky,
/// with a lamp-lit sphere off to one side so that turning the camera changes the picture. The
/// sky is never dark (nor so bright that the tone map saturates it), so dark pixels are the hole's shadow.
pub const SCENE: &str = r#"# preview test scene
[spacetime]
type = "schwarzschild"
mass = 0.3   # the slider's value

[camera]
position = [0, 0, 6]
look_at = [0, 0, 0]
fov = 60

[render]
width = 96
height = 72
spp = 4
max_depth = 2

[sky]
type = "gradient"
zenith = [0.3, 0.3, 0.35]
horizon = [0.2, 0.25, 0.3]
nadir = [0.25, 0.2, 0.15]

[[objects]]
shape = { type = "sphere", center = [2.2, 0.6, 0], radius = 0.5 }
material = { type = "diffuse", reflectance = [0.2, 0.2, 0.2] }
emission = { radiance = [4.0, 3.0, 0.5] }
"#;

/// A temporary directory for one test.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nullpath-preview-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

/// A running `nullpath preview`; killed when dropped.
pub struct Preview {
    child: Child,
    pub port: u16,
}

impl Preview {
    /// Starts `nullpath preview SCENE --port 0` and reads the URL it prints.
    pub fn start(scene: &Path) -> Preview {
        let mut command = Command::new(env!("CARGO_BIN_EXE_nullpath"));
        command.args(["preview", scene.to_str().expect("UTF-8 path"), "--port", "0"]);
        Self::spawn(command)
    }

    /// [`Preview::start`] under the limits the shell commands `limits` set (`ulimit -f 1`, say),
    /// with SIGXFSZ ignored so that a write past the file size limit fails (EFBIG) rather than
    /// kills the process.
    pub fn start_under(scene: &Path, limits: &str) -> Preview {
        let mut command = Command::new("sh");
        command
            // Its messages go to /dev/null: a file size limit also binds the test's own stderr
            // when that is a log file already past the limit, and a failed write there would end
            // the preview before it prints its address.
            .args(["-c", &format!("trap '' XFSZ; {limits}\nexec \"$0\" \"$@\" 2>/dev/null")])
            .arg(env!("CARGO_BIN_EXE_nullpath"))
            .args(["preview", scene.to_str().expect("UTF-8 path"), "--port", "0"]);
        Self::spawn(command)
    }

    fn spawn(mut command: Command) -> Preview {
        let mut child =
            command.stdout(Stdio::piped()).stderr(Stdio::inherit()).spawn().expect("nullpath preview starts");
        let mut line = String::new();
        let stdout = child.stdout.take().expect("stdout");
        BufReader::new(stdout).read_line(&mut line).expect("the URL");
        let port = line
            .trim()
            .strip_prefix("http://127.0.0.1:")
            .and_then(|rest| rest.strip_suffix('/'))
            .and_then(|p| p.parse().ok())
            .unwrap_or_else(|| panic!("expected http://127.0.0.1:PORT/, got {line:?}"));
        Preview { child, port }
    }

    pub fn url(&self) -> String {
        format!("http://127.0.0.1:{}/", self.port)
    }

    /// Whether the process is still running.
    pub fn alive(&mut self) -> bool {
        self.child.try_wait().expect("try_wait").is_none()
    }

    /// One request; returns the status and the body.
    pub fn request(&self, method: &str, path: &str, content_type: Option<&str>, body: &[u8]) -> (u16, Vec<u8>) {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).expect("connects");
        stream.set_read_timeout(Some(Duration::from_secs(30))).expect("timeout");
        let mut head = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\nContent-Length: {}\r\n",
            self.port,
            body.len()
        );
        if let Some(t) = content_type {
            head.push_str(&format!("Content-Type: {t}\r\n"));
        }
        head.push_str("\r\n");
        stream.write_all(head.as_bytes()).expect("sends");
        stream.write_all(body).expect("sends");
        let mut response = Vec::new();
        stream.read_to_end(&mut response).expect("reads");
        let split = response.windows(4).position(|w| w == b"\r\n\r\n").expect("a header");
        let status_line = String::from_utf8_lossy(&response[..split]).to_string();
        let status = status_line.split_whitespace().nth(1).and_then(|s| s.parse().ok()).expect("a status");
        (status, response[split + 4..].to_vec())
    }

    pub fn get(&self, path: &str) -> (u16, Vec<u8>) {
        self.request("GET", path, None, b"")
    }

    pub fn post(&self, path: &str, json: &str) -> (u16, String) {
        let (status, body) = self.request("POST", path, Some("application/json"), json.as_bytes());
        (status, String::from_utf8_lossy(&body).to_string())
    }

    pub fn state(&self) -> serde_json::Value {
        let (status, body) = self.get("/state");
        assert_eq!(status, 200);
        serde_json::from_slice(&body).expect("JSON state")
    }

    /// Waits (up to a minute) until `ready` holds for the state, and returns it.
    pub fn wait_for(&self, what: &str, ready: impl Fn(&serde_json::Value) -> bool) -> serde_json::Value {
        let start = Instant::now();
        loop {
            let state = self.state();
            if ready(&state) {
                return state;
            }
            assert!(start.elapsed() < Duration::from_secs(60), "timed out waiting for {what}; state {state}");
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Waits until the current generation's last frame is published.
    pub fn wait_for_done_frame(&self) -> serde_json::Value {
        self.wait_for("a finished frame", |s| s["frame"]["done"] == true && s["frame"]["generation"] == s["generation"])
    }
}

impl Drop for Preview {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
