//! The preview's HTTP server (`tiny_http`): the page, the state, the frames, and the page's
//! changes. It listens on 127.0.0.1 only and answers only loopback peers that name it in `Host`
//! (so that a web page elsewhere cannot reach it through DNS rebinding); changes must be
//! `application/json` POSTs (which a page of another origin cannot send without a preflight this
//! server never grants). Every request is checked: unknown paths, query strings, unknown JSON
//! fields and out-of-range numbers are answered 4xx with the reason, never a panic. A client that
//! goes away mid-response costs only its own request's thread.

use super::full_render;
use super::save_view;
use super::source::Source;
use super::state::Shared;
use super::view::{Eye, Overrides, SettingsRequest};
use crate::commands::provenance;
use crate::commands::render::DEFAULT_SCENE;
use serde::de::DeserializeOwned;
use std::io::{Cursor, Read};
use std::sync::Arc;
use tiny_http::{Header, Method, Request, Response, StatusCode};

const PAGE: &str = include_str!("page.html");
const SCRIPT: &str = include_str!("page.js");
/// Largest request body, bytes.
const MAX_BODY: u64 = 64 * 1024;

type Reply = Response<Cursor<Vec<u8>>>;

/// What the handlers share.
pub struct App {
    pub shared: Arc<Shared>,
    pub source: Source,
    /// The port the server listens on, for the `Host` check.
    pub port: u16,
}

/// Answers requests until the server is dropped, each on its own thread.
pub fn serve(server: &tiny_http::Server, app: &Arc<App>) {
    for request in server.incoming_requests() {
        let app = Arc::clone(app);
        std::thread::spawn(move || handle(&app, request));
    }
}

fn handle(app: &App, mut request: Request) {
    let reply = if !request.remote_addr().is_some_and(|a| a.ip().is_loopback()) {
        text(403, "only connections from this machine's loopback interface are served")
            .with_header(header("Connection", "close"))
    } else if !host_is_ours(&request, app.port) {
        text(403, "the Host header must name this server (127.0.0.1 or localhost and its port)")
    } else {
        route(app, &mut request)
    };
    // A client that closed the connection (a tab closed mid-frame) cannot be answered; there is
    // nobody to tell.
    let _ = request.respond(reply);
}

fn host_is_ours(request: &Request, port: u16) -> bool {
    let host = request.headers().iter().find(|h| h.field.equiv("Host")).map(|h| h.value.as_str());
    host.is_some_and(|h| {
        [format!("127.0.0.1:{port}"), format!("localhost:{port}"), format!("[::1]:{port}")].contains(&h.to_string())
    })
}

fn header(name: &str, value: &str) -> Header {
    // Names and values here are fixed ASCII.
    Header::from_bytes(name.as_bytes(), value.as_bytes()).unwrap_or_else(|()| unreachable!("ASCII header"))
}

fn reply(status: u16, content_type: &str, body: Vec<u8>) -> Reply {
    Response::from_data(body)
        .with_status_code(StatusCode(status))
        .with_header(header("Content-Type", content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
}

fn text(status: u16, message: &str) -> Reply {
    reply(status, "text/plain; charset=utf-8", format!("{message}\n").into_bytes())
}

fn json(value: &serde_json::Value) -> Reply {
    reply(200, "application/json", value.to_string().into_bytes())
}

/// A 200 with `message`, or a 400 with the error.
fn outcome(result: Result<String, String>) -> Reply {
    match result {
        Ok(message) => json(&serde_json::json!({ "message": message })),
        Err(e) => text(400, &e),
    }
}

fn route(app: &App, request: &mut Request) -> Reply {
    let url = request.url().to_string();
    let (path, query) = url.split_once('?').unwrap_or((&url, ""));
    if !query.is_empty() {
        return text(400, "this server takes no query parameters");
    }
    let get = *request.method() == Method::Get;
    match path {
        "/" | "/page.js" | "/state" | "/frame.png" if !get => text(405, "use GET"),
        "/" => reply(200, "text/html; charset=utf-8", PAGE.as_bytes().to_vec()),
        "/page.js" => reply(200, "text/javascript; charset=utf-8", SCRIPT.as_bytes().to_vec()),
        "/state" => json(&app.shared.report(&app.source.name())),
        "/frame.png" => frame(app),
        "/view" | "/settings" | "/reset" | "/save-view" | "/render" => match body(request) {
            Err(reply) => reply,
            Ok(body) => post(app, path, &body),
        },
        _ => text(404, "no such page"),
    }
}

/// The latest frame, with its version and samples in headers; 204 before the first.
fn frame(app: &App) -> Reply {
    let Some(frame) = app.shared.lock().frame.clone() else {
        return reply(204, "image/png", Vec::new());
    };
    reply(200, "image/png", frame.png.to_vec())
        .with_header(header("X-Frame-Version", &frame.version.to_string()))
        .with_header(header("X-Frame-Generation", &frame.generation.to_string()))
        .with_header(header("X-Frame-Spp", &frame.spp.to_string()))
        .with_header(header("X-Frame-Done", if frame.done { "1" } else { "0" }))
}

/// The JSON body of a POST, at most [`MAX_BODY`] bytes.
fn body(request: &mut Request) -> Result<String, Reply> {
    if *request.method() != Method::Post {
        return Err(text(405, "use POST"));
    }
    let is_json = request
        .headers()
        .iter()
        .any(|h| h.field.equiv("Content-Type") && h.value.as_str().starts_with("application/json"));
    if !is_json {
        return Err(text(415, "send the request as Content-Type: application/json"));
    }
    if request.body_length().is_some_and(|n| n as u64 > MAX_BODY) {
        return Err(text(413, "the request is too large"));
    }
    let mut body = String::new();
    let read = request.as_reader().take(MAX_BODY + 1).read_to_string(&mut body);
    match read {
        Ok(n) if n as u64 <= MAX_BODY => Ok(body),
        Ok(_) => Err(text(413, "the request is too large")),
        Err(e) => Err(text(400, &format!("cannot read the request: {e}"))),
    }
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
        "/save-view" => parse::<SaveView>(body).and_then(|request| save(app, &request.name)),
        _ => parse::<RenderRequest>(body).and_then(|request| start_render(app, &request.output)),
    })
}

fn save(app: &App, name: &str) -> Result<String, String> {
    let path = app
        .source
        .path
        .as_ref()
        .ok_or("the built-in default scene has no file to save a view into: start the preview with a scene file")?;
    let current = app.shared.lock().current.clone()?;
    let eye = Eye::of(&current).ok_or("the scene has no camera pose")?;
    save_view::save(path, name, &eye, &current)?;
    Ok(format!("saved [views.{name}] in {}: nullpath render {} --view {name}", path.display(), path.display()))
}

fn start_render(app: &App, output: &str) -> Result<String, String> {
    let path = full_render::output_path(app.source.directory(), output)?;
    let current = app.shared.lock().current.clone()?;
    let text = match &app.source.path {
        Some(p) => std::fs::read_to_string(p).unwrap_or_default(),
        None => DEFAULT_SCENE.to_string(),
    };
    let source = provenance::Source { name: app.source.name(), text, view: None, time: 0.0 };
    full_render::start(&app.shared, (*current).clone(), source, path.clone())?;
    Ok(format!("rendering to {}", path.display()))
}
