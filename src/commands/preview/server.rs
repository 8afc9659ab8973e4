//! The preview's requests and answers: the page, the state, the frames, and the page's changes.
//! The server ([`super::http`]) listens on 127.0.0.1 only; this answers only requests that name
//! it in `Host` (so that a web page elsewhere cannot reach it through DNS rebinding); changes
//! must be `application/json` POSTs (which a page of another origin cannot send without a
//! preflight this server never grants). Every request is checked: unknown paths, query strings,
//! unknown JSON fields and out-of-range numbers are answered 4xx with the reason, never a panic.

use super::full_render;
use super::http::Reply;
use super::request::Request;
use super::save_view::{self, SaveError};
use super::source::Source;
use super::state::Shared;
use super::view::{Eye, Overrides, SettingsRequest};
use crate::commands::provenance;
use crate::commands::render::DEFAULT_SCENE;
use serde::de::DeserializeOwned;
use std::sync::{Arc, Mutex, PoisonError};

const PAGE: &str = include_str!("page.html");
const SCRIPT: &str = include_str!("page.js");

/// What the handlers share.
pub struct App {
    pub shared: Arc<Shared>,
    pub source: Source,
    /// The port the server listens on, for the `Host` check.
    pub port: u16,
    /// Held while the scene file is read, edited and replaced, so that two saves at once cannot
    /// both read the old file and each drop the other's view.
    pub writing: Mutex<()>,
}

/// The answer to `request`.
pub fn handle(app: &App, request: &Request) -> Reply {
    if !host_is_ours(request, app.port) {
        return text(403, "the Host header must name this server (127.0.0.1 or localhost and its port)");
    }
    route(app, request)
}

fn host_is_ours(request: &Request, port: u16) -> bool {
    request.host.as_ref().is_some_and(|h| {
        [format!("127.0.0.1:{port}"), format!("localhost:{port}"), format!("[::1]:{port}")].contains(h)
    })
}

fn text(status: u16, message: &str) -> Reply {
    Reply::text(status, message)
}

fn json(value: &serde_json::Value) -> Reply {
    Reply::new(200, "application/json", value.to_string().into_bytes())
}

/// A 200 with `message`, or a 400 with the error.
fn outcome(result: Result<String, String>) -> Reply {
    match result {
        Ok(message) => json(&serde_json::json!({ "message": message })),
        Err(e) => text(400, &e),
    }
}

fn route(app: &App, request: &Request) -> Reply {
    let (path, query) = request.target.split_once('?').unwrap_or((&request.target, ""));
    if !query.is_empty() {
        return text(400, "this server takes no query parameters");
    }
    let get = request.method == "GET";
    match path {
        "/" | "/page.js" | "/state" | "/frame.png" if !get => text(405, "use GET"),
        "/" => Reply::new(200, "text/html; charset=utf-8", PAGE.as_bytes().to_vec()),
        "/page.js" => Reply::new(200, "text/javascript; charset=utf-8", SCRIPT.as_bytes().to_vec()),
        "/state" => json(&app.shared.report(&app.source.name())),
        "/frame.png" => frame(app),
        "/view" | "/settings" | "/reset" | "/save-view" | "/render" => match body(request) {
            Err(reply) => reply,
            Ok(body) => post(app, path, body),
        },
        _ => text(404, "no such page"),
    }
}

/// The latest frame, with its version and samples in headers; 204 before the first.
fn frame(app: &App) -> Reply {
    let Some(frame) = app.shared.lock().frame.clone() else {
        return Reply::new(204, "image/png", Vec::new());
    };
    Reply::new(200, "image/png", frame.png.to_vec())
        .with_header("X-Frame-Version", frame.version.to_string())
        .with_header("X-Frame-Generation", frame.generation.to_string())
        .with_header("X-Frame-Spp", frame.spp.to_string())
        .with_header("X-Frame-Done", if frame.done { "1" } else { "0" }.to_string())
}

/// The JSON body of a POST (the server has bounded its size).
fn body(request: &Request) -> Result<&str, Reply> {
    if request.method != "POST" {
        return Err(text(405, "use POST"));
    }
    if !request.content_type.as_ref().is_some_and(|t| t.starts_with("application/json")) {
        return Err(text(415, "send the request as Content-Type: application/json"));
    }
    std::str::from_utf8(&request.body).map_err(|_| text(400, "the request body is not UTF-8"))
}

fn parse<T: DeserializeOwned>(body: &str) -> Result<T, String> {
    serde_json::from_str(body).map_err(|e| format!("bad request: {e}"))
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Nothing {}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SaveView {
    name: String,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderRequest {
    output: String,
    /// Replace the file if it exists; without it an existing file is never touched.
    #[serde(default)]
    overwrite: bool,
}

fn post(app: &App, path: &str, body: &str) -> Reply {
    let shared = &app.shared;
    outcome(match path {
        "/view" => parse::<Eye>(body).and_then(|eye| {
            eye.keyframe()?;
            shared.change(|o, _| Ok(Overrides { eye: Some(eye), ..o.clone() }))?;
            Ok("moved".into())
        }),
        "/settings" => parse::<SettingsRequest>(body).and_then(|request| {
            shared.change(|o, scene| request.apply_to(o, scene))?;
            Ok("changed".into())
        }),
        "/reset" => parse::<Nothing>(body).and_then(|_| {
            shared.change(|_, _| Ok(Overrides::default()))?;
            Ok("back to the scene file's camera and parameters".into())
        }),
        "/save-view" => {
            return match parse::<SaveView>(body).map_err(SaveError::Refused).and_then(|r| save(app, &r.name)) {
                Ok(message) => outcome(Ok(message)),
                Err(SaveError::Refused(e)) => text(400, &e),
                // Not the request's fault: the disk is full, the folder read-only.
                Err(SaveError::Io(e)) => text(500, &e),
            };
        }
        _ => {
            return match parse::<RenderRequest>(body).and_then(|r| start_render(app, &r.output, r.overwrite)) {
                Ok((message, job)) => json(&serde_json::json!({ "message": message, "job": job })),
                Err(e) => text(400, &e),
            };
        }
    })
}

fn save(app: &App, name: &str) -> Result<String, SaveError> {
    let refused = |e: &str| SaveError::Refused(e.to_string());
    let path = app.source.path.as_ref().ok_or_else(|| {
        refused("the built-in default scene has no file to save a view into: start the preview with a scene file")
    })?;
    let (current, file) = {
        let inner = app.shared.lock();
        (inner.current.clone().map_err(SaveError::Refused)?, inner.loaded.clone().map_err(SaveError::Refused)?)
    };
    let eye = Eye::of(&current).ok_or_else(|| refused("the scene has no camera pose"))?;
    let _writing = app.writing.lock().unwrap_or_else(PoisonError::into_inner);
    save_view::save(path, name, &eye, &current, &file.spacetime)?;
    let with = if current.spacetime == file.spacetime { "" } else { " with the sliders' spacetime" };
    Ok(format!("saved [views.{name}]{with} in {}: nullpath render {} --view {name}", path.display(), path.display()))
}

/// Starts the render; returns what to tell the page and the job's id.
fn start_render(app: &App, output: &str, overwrite: bool) -> Result<(String, u64), String> {
    let path = full_render::output_path(app.source.directory(), output)?;
    let current = app.shared.lock().current.clone()?;
    let text = match &app.source.path {
        Some(p) => std::fs::read_to_string(p).unwrap_or_default(),
        None => DEFAULT_SCENE.to_string(),
    };
    let source = provenance::Source { name: app.source.name(), text, view: None, time: 0.0 };
    let job = full_render::start(&app.shared, (*current).clone(), source, path.clone(), overwrite)?;
    Ok((format!("rendering to {}", path.display()), job))
}
