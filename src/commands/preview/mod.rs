//! `nullpath preview`: a local web page that shows a scene refining progressively while the view
//! holds still and restarting at low resolution when it moves, with orbit and fly controls,
//! sliders for the spacetime's parameters and the samples per pixel, buttons that save the view
//! into the scene file (`[views.NAME]`) and write a full-quality render, and the scene reloaded
//! whenever its file changes (its error shown on the page while it is broken).
//!
//! Threads: the server ([`http`]) answers each connection on its own thread, as [`server`] says;
//! one thread renders ([`refine`]) and one watches the file ([`source`]); they meet in
//! [`state::Shared`].

mod full_render;
mod http;
mod notices;
mod parameters;
mod refine;
mod request;
mod save_view;
mod server;
mod source;
mod state;
mod view;

pub use refine::{encode_png, low_resolution};

use clap::Parser;
use server::App;
use source::Source;
use state::Shared;
use std::io::Write as _;
use std::net::TcpListener;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

#[derive(Parser, Debug)]
#[command(after_help = "Open the printed http://127.0.0.1:PORT/ in a browser on this machine. Drag to orbit, \
    shift-drag or right-drag to look around, wheel to move closer, W A S D Q E to fly.")]
pub struct Args {
    /// Scene file (TOML); the default scene (scenes/room-black-hole.toml, built in) when omitted.
    scene: Option<PathBuf>,
    /// Port to listen on (127.0.0.1 only); 0 picks a free one.
    #[arg(long, default_value_t = 8765)]
    port: u16,
}

pub fn run(args: &Args) -> Result<(), String> {
    let source = Source { path: args.scene.clone() };
    let loaded = source.load();
    if let Err(e) = &loaded {
        eprintln!("nullpath preview: {e} (the page shows it until the file is fixed)");
    }
    let listener = TcpListener::bind(("127.0.0.1", args.port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", args.port))?;
    let port = listener.local_addr().map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", args.port))?.port();
    let app = Arc::new(App { shared: Arc::new(Shared::new(loaded)), source, port, writing: Mutex::new(()) });
    eprintln!("nullpath preview: {} — open this page (Ctrl-C stops):", app.source.name());
    println!("http://127.0.0.1:{port}/");
    // The URL is how scripts find the port: get it out now, not when the buffer fills.
    std::io::stdout().flush().map_err(|e| e.to_string())?;
    let renderer = Arc::clone(&app.shared);
    std::thread::spawn(move || refine::refine_forever(&renderer));
    let watcher = Arc::clone(&app);
    std::thread::spawn(move || watcher.source.watch(&watcher.shared));
    http::serve(&listener, Arc::new(move |request: &request::Request| server::handle(&app, request)));
    Ok(())
}
