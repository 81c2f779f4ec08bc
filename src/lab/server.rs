//! The lab's local web server: loopback only, every request carrying the session's random
//! token, none from another origin. The page and its script are served from the binary;
//! `/api/start` is the session the page opens with and `/api/bats` every bat's of the file
//! it was started with; `/api/evaluate` answers a session (`answer::evaluate`); `/api/save` writes its study
//! (and the bat's profile) into the one directory the user named.
//!
//! Edits that arrive while one is being computed are coalesced: the evaluator keeps only
//! the newest waiting session and answers the older ones `409` (superseded), so a flood of
//! drags costs one computation at a time and never a queue.

use super::{answer, balls, save, session, species};
use serde_json::{json, Value};
use std::io::Read;
use std::path::PathBuf;
use std::sync::{Arc, Condvar, Mutex};
use tiny_http::{Header, Method, Request, Response, Server};

/// The page and its script.
const PAGE: &str = include_str!("page.html");
const SCRIPT: &str = include_str!("lab.js");

/// Largest request body read, bytes (a session is a few kB).
const MAX_BODY: u64 = 1 << 20;

/// What the server is started with.
pub struct LabSettings {
    /// The sessions the page may open, one per bat of the study or results file it was
    /// started with (labelled as `/bat` labels them); the page opens the first.
    pub starts: Vec<(String, Value)>,
    /// Where `/api/save` may write.
    pub out_dir: PathBuf,
    /// Port on 127.0.0.1 (0: any free one).
    pub port: u16,
    /// Threads the evaluation may use.
    pub threads: usize,
}

/// A started server: its address and token.
pub struct Lab {
    server: Arc<Server>,
    pub port: u16,
    pub token: String,
    settings: LabSettings,
}

/// A random token: 128 bits from the kernel's generator, as hex.
fn random_token() -> Result<String, String> {
    let mut bytes = [0u8; 16];
    std::fs::File::open("/dev/urandom")
        .and_then(|mut f| f.read_exact(&mut bytes))
        .map_err(|e| format!("cannot read /dev/urandom for the access token: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

impl Lab {
    /// Bind 127.0.0.1 and make the token.
    pub fn bind(settings: LabSettings) -> Result<Lab, String> {
        let server = Server::http(("127.0.0.1", settings.port))
            .map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", settings.port))?;
        let port = server
            .server_addr()
            .to_ip()
            .map(|a| a.port())
            .ok_or("the server has no IP address")?;
        Ok(Lab {
            server: Arc::new(server),
            port,
            token: random_token()?,
            settings,
        })
    }

    /// The URL to open, token included.
    pub fn url(&self) -> String {
        format!("http://127.0.0.1:{}/?token={}", self.port, self.token)
    }

    /// Serve until the process ends.
    pub fn serve(self) -> Result<(), String> {
        let pool = crate::run::build_pool(self.settings.threads).map_err(|e| e.to_string())?;
        let mailbox = Arc::new(Mailbox::default());
        let evaluator = {
            let mailbox = Arc::clone(&mailbox);
            std::thread::Builder::new()
                .name("batstudy-lab-evaluator".into())
                .spawn(move || loop {
                    let (session, request) = mailbox.take();
                    let answer = answer::evaluate(&session, &pool);
                    respond_json(request, 200, &answer);
                })
                .map_err(|e| e.to_string())?
        };
        let shared = Arc::new(Shared {
            guard: Guard {
                port: self.port,
                token: self.token.clone(),
            },
            settings: self.settings,
            mailbox,
        });
        // each request on a thread of its own: a client that sends its body slowly, or
        // never, holds up no one else
        for request in self.server.incoming_requests() {
            let shared = Arc::clone(&shared);
            let spawned = std::thread::Builder::new()
                .name("batstudy-lab-request".into())
                .spawn(move || shared.route(request));
            if spawned.is_err() {
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
        }
        drop(evaluator);
        Ok(())
    }
}

/// What every request's thread shares.
struct Shared {
    guard: Guard,
    settings: LabSettings,
    mailbox: Arc<Mailbox>,
}

impl Shared {
    fn route(&self, mut request: Request) {
        let (guard, mailbox) = (&self.guard, &self.mailbox);
        if let Err(status) = guard.check(&request) {
            let text = match status {
                403 => "refused: a cross-origin request, or a host other than this lab's",
                _ => "refused: this lab needs the access token its URL carries",
            };
            return respond_json(request, status, &json!({ "error": text }));
        }
        let path = request.url().split('?').next().unwrap_or("").to_string();
        match (request.method(), path.as_str()) {
            (Method::Get, "/") => {
                let page = PAGE.replace("__TOKEN__", &guard.token);
                respond(request, 200, &page, "text/html; charset=utf-8")
            }
            (Method::Get, "/lab.js") => {
                respond(request, 200, SCRIPT, "text/javascript; charset=utf-8")
            }
            (Method::Get, "/api/start") => respond_json(request, 200, &self.settings.starts[0].1),
            (Method::Get, "/api/species") => respond_json(request, 200, &species::species()),
            (Method::Get, "/api/balls") => respond_json(request, 200, &balls::balls()),
            (Method::Get, "/api/materials") => {
                respond_json(request, 200, &species::layer_materials())
            }
            (Method::Get, "/api/bats") => {
                let bats: Vec<Value> = self
                    .settings
                    .starts
                    .iter()
                    .map(|(label, session)| json!({"label": label, "session": session}))
                    .collect();
                respond_json(request, 200, &Value::Array(bats))
            }
            (Method::Post, "/api/evaluate") => match body_json(&mut request) {
                Ok(s) => mailbox.put(s, request),
                Err(e) => respond_json(request, 400, &json!({ "error": e })),
            },
            (Method::Post, "/api/save") => {
                let reply =
                    body_json(&mut request).and_then(|b| save::save(&b, &self.settings.out_dir));
                match reply {
                    Ok(saved) => respond_json(request, 200, &saved),
                    Err(e) => respond_json(request, 400, &json!({ "error": e })),
                }
            }
            _ => respond_json(request, 404, &json!({"error": "not found"})),
        }
    }
}

/// The checks every request passes: the token, this server's host, no other origin.
struct Guard {
    port: u16,
    token: String,
}

impl Guard {
    fn check(&self, r: &Request) -> Result<(), u16> {
        let header = |name: &'static str| {
            r.headers()
                .iter()
                .find(|h| h.field.equiv(name))
                .map(|h| h.value.as_str().to_string())
        };
        let hosts = [
            format!("127.0.0.1:{}", self.port),
            format!("localhost:{}", self.port),
        ];
        // a page of another site (or a DNS name rebound to 127.0.0.1) names its own host
        if !header("Host").is_some_and(|h| hosts.contains(&h)) {
            return Err(403);
        }
        if let Some(origin) = header("Origin") {
            if !hosts.iter().any(|h| origin == format!("http://{h}")) {
                return Err(403);
            }
        }
        let query_token = r
            .url()
            .split_once('?')
            .and_then(|(_, q)| q.split('&').find_map(|kv| kv.strip_prefix("token=")))
            .map(str::to_string);
        let token = header("X-Batstudy-Token").or(query_token);
        match token {
            Some(t) if constant_time_eq(t.as_bytes(), self.token.as_bytes()) => Ok(()),
            _ => Err(401),
        }
    }
}

/// Equality whose time does not depend on where two equal-length strings differ.
fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// The newest session waiting for the evaluator, with the request to answer.
#[derive(Default)]
struct Mailbox {
    slot: Mutex<Option<(Value, Request)>>,
    ready: Condvar,
}

impl Mailbox {
    /// Leave a session; the one it replaces is answered as superseded.
    fn put(&self, session: Value, request: Request) {
        let mut slot = self.slot.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, older)) = slot.replace((session, request)) {
            respond_json(older, 409, &json!({"superseded": true}));
        }
        self.ready.notify_one();
    }

    /// Wait for a session.
    fn take(&self) -> (Value, Request) {
        let mut slot = self.slot.lock().unwrap_or_else(|p| p.into_inner());
        loop {
            if let Some(next) = slot.take() {
                return next;
            }
            slot = self.ready.wait(slot).unwrap_or_else(|p| p.into_inner());
        }
    }
}

fn body_json(request: &mut Request) -> Result<Value, String> {
    let mut body = Vec::new();
    request
        .as_reader()
        .take(MAX_BODY + 1)
        .read_to_end(&mut body)
        .map_err(|e| format!("cannot read the request: {e}"))?;
    if body.len() as u64 > MAX_BODY {
        return Err(format!("the request is larger than {MAX_BODY} bytes"));
    }
    session::parse(&body)
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid header")
}

/// Answer with the headers every response carries: no caching, no sniffing, no referrer
/// (the token is in the page's URL), and a page that runs only its own script.
fn respond(request: Request, status: u16, body: &str, content_type: &str) {
    let response = Response::from_string(body)
        .with_status_code(status)
        .with_header(header("Content-Type", content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
        .with_header(header("Referrer-Policy", "no-referrer"))
        .with_header(header(
            "Content-Security-Policy",
            "default-src 'none'; script-src 'self'; connect-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:; frame-ancestors 'none'",
        ));
    // a client that has gone (a closed tab) is no error of the server's
    let _ = request.respond(response);
}

fn respond_json(request: Request, status: u16, body: &Value) {
    respond(request, status, &body.to_string(), "application/json");
}
