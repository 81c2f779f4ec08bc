//! The bat lab's server (`batstudy lab`), spoken to over raw HTTP: it answers only the
//! token's holder on its own host and origin, its answers are the library's (a saved
//! session run by `batstudy run` gives the same numbers), it refuses to overwrite or to
//! write outside its directory, and neither a flood of requests nor a client that goes away
//! mid-request stops it. (The page in a browser: tests/python/test_lab.py.)

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

struct Lab {
    child: Child,
    /// The server's stdout, kept open while it runs.
    _stdout: BufReader<std::process::ChildStdout>,
    port: u16,
    token: String,
}

impl Drop for Lab {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(out: &std::path::Path) -> Lab {
    let mut child = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .args(["lab", "--port", "0", "--jobs", "2", "--out"])
        .arg(out)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    stdout.read_line(&mut line).unwrap();
    let url = line.split("open ").nth(1).unwrap().trim().to_string();
    let port = url
        .split(':')
        .nth(2)
        .unwrap()
        .split('/')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let token = url.split("token=").nth(1).unwrap().to_string();
    Lab {
        child,
        _stdout: stdout,
        port,
        token,
    }
}

/// One request; (status, body).
fn request(
    lab: &Lab,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &str,
) -> (u16, String) {
    let mut s = TcpStream::connect(("127.0.0.1", lab.port)).unwrap();
    let mut text = format!(
        "{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    for (k, v) in headers {
        text.push_str(&format!("{k}: {v}\r\n"));
    }
    text.push_str("\r\n");
    text.push_str(body);
    s.write_all(text.as_bytes()).unwrap();
    let mut reply = String::new();
    s.read_to_string(&mut reply).unwrap();
    let status = reply.split(' ').nth(1).unwrap().parse().unwrap();
    let body = reply.split("\r\n\r\n").nth(1).unwrap_or("").to_string();
    (status, body)
}

fn host(lab: &Lab) -> String {
    format!("127.0.0.1:{}", lab.port)
}

fn api(lab: &Lab, method: &str, path: &str, body: &str) -> (u16, serde_json::Value) {
    let host = host(lab);
    let (status, text) = request(
        lab,
        method,
        path,
        &[("Host", &host), ("X-Batstudy-Token", &lab.token)],
        body,
    );
    (
        status,
        serde_json::from_str(&text).unwrap_or(serde_json::Value::Null),
    )
}

#[test]
fn only_the_tokens_holder_on_this_host_is_answered() {
    let dir = tempfile::tempdir().unwrap();
    let lab = start(dir.path());
    let host = host(&lab);
    let cases: [(&[(&str, &str)], u16); 5] = [
        (&[("Host", &host)], 401),
        (
            &[
                ("Host", &host),
                ("X-Batstudy-Token", "00000000000000000000000000000000"),
            ],
            401,
        ),
        (
            &[
                ("Host", "evil.example:80"),
                ("X-Batstudy-Token", &lab.token),
            ],
            403,
        ),
        (
            &[
                ("Host", &host),
                ("X-Batstudy-Token", &lab.token),
                ("Origin", "http://evil.example"),
            ],
            403,
        ),
        (
            &[
                ("Host", &host),
                ("X-Batstudy-Token", &lab.token),
                ("Origin", &format!("http://{host}")),
            ],
            200,
        ),
    ];
    for (headers, want) in cases {
        let (status, _) = request(&lab, "GET", "/api/start", headers, "");
        assert_eq!(status, want, "{headers:?}");
    }
    // the page itself wants the token in its URL
    assert_eq!(request(&lab, "GET", "/", &[("Host", &host)], "").0, 401);
    let (status, page) = request(
        &lab,
        "GET",
        &format!("/?token={}", lab.token),
        &[("Host", &host)],
        "",
    );
    assert_eq!(status, 200);
    assert!(page.contains(&format!("/lab.js?token={}", lab.token)));
}

#[test]
fn a_saved_session_run_by_batstudy_gives_the_labs_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let lab = start(dir.path());
    let (_, mut session) = api(&lab, "GET", "/api/start", "");
    // a hollow alloy bat with a thinner wall than its preset's, every 2 cm of the barrel
    session["base"]["bat"] =
        serde_json::json!({"preset": "alloy_bbcor", "shell": {"thickness": 0.0026}});
    session["impact"] = serde_json::json!([0.55, 0.81, 0.02]);
    let (status, answer) = api(&lab, "POST", "/api/evaluate", &session.to_string());
    assert_eq!(status, 200, "{answer}");
    assert!(answer.get("error").is_none(), "{answer}");
    let session = answer["session"].clone();
    let body = serde_json::json!({"name": "thin-wall", "session": session}).to_string();
    let (status, saved) = api(&lab, "POST", "/api/save", &body);
    assert_eq!(status, 200, "{saved}");
    let out = dir.path().join("thin-wall.h5");
    let run = Command::new(env!("CARGO_BIN_EXE_batstudy"))
        .arg("run")
        .arg(dir.path().join("thin-wall.yaml"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let f = hdf5::File::open(&out).unwrap();
    let read = |name: &str| f.dataset(name).unwrap().read_raw::<f64>().unwrap();
    let lab_speeds: Vec<f64> = answer["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["exit_speed_lab"].as_f64().unwrap())
        .collect();
    let run_speeds = read("summary/exit_speed_lab");
    assert_eq!(lab_speeds.len(), run_speeds.len());
    // JSON carries each number as its shortest round-trip decimal
    for (a, b) in lab_speeds.iter().zip(&run_speeds) {
        assert!((a - b).abs() <= f64::EPSILON * b.abs(), "{a} vs {b}");
    }
    for (key, name) in [
        ("mass", "bat/mass"),
        ("bbcor_max", "bat/bbcor_max"),
        ("barrel_compression", "bat/barrel_compression"),
    ] {
        let (a, b) = (answer["bat"][key].as_f64().unwrap(), read(name)[0]);
        assert!((a - b).abs() <= f64::EPSILON * b.abs(), "{key}: {a} vs {b}");
    }
    // the profile as the CSV a study reads back
    let csv = std::fs::read_to_string(dir.path().join("thin-wall_profile.csv")).unwrap();
    assert!(csv.lines().nth(1) == Some("z,radius"), "{csv}");
    // no overwriting, no path outside the directory
    let (status, again) = api(&lab, "POST", "/api/save", &body);
    assert_eq!(status, 400);
    assert!(
        again["error"].as_str().unwrap().contains("exists"),
        "{again}"
    );
    for name in ["../escape", "a/b", "", ".hidden"] {
        let body = serde_json::json!({"name": name, "session": session}).to_string();
        let (status, reply) = api(&lab, "POST", "/api/save", &body);
        assert_eq!(status, 400, "{name}: {reply}");
    }
    assert!(!dir.path().parent().unwrap().join("escape.yaml").exists());
}

/// The lathe's reading of the knots: a knot dragged 1 mm below its neighbour is the largest
/// fall between the handle and the barrel, where it is and by exactly that much, and it
/// bends the profile more sharply than anything in the R161's own smooth table (whose falls,
/// wiggles of its measured radii, are far below a tenth of a millimetre).
#[test]
fn the_lathe_reads_the_knots() {
    let dir = tempfile::tempdir().unwrap();
    let lab = start(dir.path());
    let (_, mut session) = api(&lab, "GET", "/api/start", "");
    let (_, answer) = api(&lab, "POST", "/api/evaluate", &session.to_string());
    let lathe = &answer["lathe"];
    let fall = lathe["largest_fall"]["by"].as_f64().unwrap_or(0.0);
    assert!(fall < 1e-4, "{lathe}");
    let bend = lathe["sharpest_bend"].as_f64().unwrap();
    let knots = session["base"]["bat"]["profile"]["knots"]
        .as_array_mut()
        .unwrap();
    let i = knots.len() - 23;
    let (z, before) = (
        knots[i][0].as_f64().unwrap(),
        knots[i - 1][1].as_f64().unwrap(),
    );
    knots[i][1] = serde_json::json!(before - 1e-3);
    let (_, answer) = api(&lab, "POST", "/api/evaluate", &session.to_string());
    let lathe = &answer["lathe"];
    assert_eq!(lathe["largest_fall"]["at"].as_f64(), Some(z), "{lathe}");
    assert!((lathe["largest_fall"]["by"].as_f64().unwrap() - 1e-3).abs() < 1e-12);
    assert!(
        lathe["sharpest_bend"].as_f64().unwrap() > 10.0 * bend,
        "{lathe}"
    );
}

#[test]
fn a_bad_value_gets_the_studys_positioned_message() {
    let dir = tempfile::tempdir().unwrap();
    let lab = start(dir.path());
    let (_, mut session) = api(&lab, "GET", "/api/start", "");
    session["base"]["bat"]["length"] = serde_json::json!(0.2);
    let (status, answer) = api(&lab, "POST", "/api/evaluate", &session.to_string());
    assert_eq!(status, 200);
    let e = answer["error"].as_str().unwrap();
    assert!(
        e.contains("lab-session.yaml:")
            && e.contains("bat.length")
            && e.contains("0.2")
            && e.contains("allowed"),
        "{e}"
    );
    session["impact"] = serde_json::json!([0.5, 0.84, 0.0001]);
    let (_, answer) = api(&lab, "POST", "/api/evaluate", &session.to_string());
    assert!(
        answer["error"].as_str().unwrap().contains("at most"),
        "{answer}"
    );
    let (status, answer) = api(&lab, "POST", "/api/evaluate", "not json");
    assert_eq!(status, 400, "{answer}");
}

#[test]
fn a_flood_and_a_vanished_client_do_not_stop_it() {
    let dir = tempfile::tempdir().unwrap();
    let lab = start(dir.path());
    let (_, session) = api(&lab, "GET", "/api/start", "");
    let body = session.to_string();
    // a client that sends half a request and goes away
    {
        let mut s = TcpStream::connect(("127.0.0.1", lab.port)).unwrap();
        s.write_all(b"POST /api/evaluate HTTP/1.1\r\nContent-Length: 100000\r\n\r\n{\"mo")
            .unwrap();
    }
    // twelve sessions at once: each answered, the superseded ones 409, never a queue
    let statuses: Vec<u16> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..12)
            .map(|_| s.spawn(|| api(&lab, "POST", "/api/evaluate", &body).0))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(
        statuses.iter().all(|&c| c == 200 || c == 409),
        "{statuses:?}"
    );
    assert!(statuses.contains(&200), "{statuses:?}");
    let (status, answer) = api(&lab, "POST", "/api/evaluate", &body);
    assert_eq!(status, 200);
    assert!(answer["points"].as_array().is_some_and(|p| !p.is_empty()));
}
