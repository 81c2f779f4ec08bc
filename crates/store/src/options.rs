//! What the caller hands the store and what it gets back: [`StoreOptions`] (with
//! [`RunMeta`], the facts about the run stored as root attributes) and [`Summary`].

use std::time::Duration;

/// Facts about the run, stored as root attributes.
#[derive(Debug, Clone, PartialEq)]
pub struct RunMeta {
    pub command_line: String,
    pub threads: usize,
    pub git_commit: String,
    pub git_dirty: bool,
    pub host: String,
    pub batstudy_version: String,
    /// ISO 8601 UTC.
    pub created: String,
    /// `Some("I/N")` for a shard file.
    pub shard: Option<String>,
    /// A shard's block of flat indices `[start, stop)` (root attributes `shard_start`,
    /// `shard_stop`): the points it covers.
    pub shard_range: Option<(usize, usize)>,
}

/// The git commit this build was made from (crates/store/build.rs), if it was made in a
/// checkout.
pub const BUILD_COMMIT: Option<&str> = option_env!("BATSTUDY_GIT_COMMIT");

impl Default for RunMeta {
    /// This process: its command line, host, the time now, crate version; git commit from the
    /// build environment (`BATSTUDY_GIT_COMMIT`, `BATSTUDY_GIT_DIRTY`) or "unknown".
    fn default() -> Self {
        let host = std::env::var("HOSTNAME")
            .ok()
            .or_else(|| std::fs::read_to_string("/etc/hostname").ok())
            .map(|s| s.trim().to_string())
            .unwrap_or_default();
        RunMeta {
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            git_commit: BUILD_COMMIT.unwrap_or("unknown").to_string(),
            git_dirty: option_env!("BATSTUDY_GIT_DIRTY") == Some("1"),
            host,
            batstudy_version: env!("CARGO_PKG_VERSION").to_string(),
            created: iso8601_now(),
            shard: None,
            shard_range: None,
        }
    }
}

/// The current UTC time as `YYYY-MM-DDTHH:MM:SSZ`.
pub fn iso8601_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86400), secs.rem_euclid(86400));
    // civil from days (H. Hinnant)
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// How to open the output.
#[derive(Debug, Clone)]
pub struct StoreOptions {
    /// Continue an interrupted run of the same study (journal or finished file).
    pub resume: bool,
    /// Overwrite an existing output (and discard its journal) when not resuming.
    pub force: bool,
    pub run_meta: RunMeta,
    /// Hand records to the OS at least this often (protects against the process being killed).
    pub flush_interval: Duration,
    /// fsync the journal at least this often (protects against power loss).
    pub sync_interval: Duration,
    /// Bytes of summary values the final file's build holds at once (default 64 MiB, about
    /// 380 000 points). A larger study is built window by window (its journal first split
    /// into one spill file per window), so the store's memory does not grow with the study.
    pub build_memory: usize,
    /// Bytes of history records the placer holds ahead of its cursor before it gives up and
    /// leaves the rest to the finish (default 64 MiB; `store::placer`).
    pub history_hold: usize,
}

impl Default for StoreOptions {
    fn default() -> Self {
        StoreOptions {
            resume: false,
            force: false,
            run_meta: RunMeta::default(),
            flush_interval: Duration::from_millis(50),
            sync_interval: Duration::from_secs(1),
            build_memory: 64 << 20,
            history_hold: super::placer::HELD_BYTES,
        }
    }
}

/// What [`Session::finish`](super::Session::finish) wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Summary {
    /// Points of the study.
    pub n_points: usize,
    /// Points present in the file (ok or failed).
    pub n_done: usize,
    pub n_failed: usize,
}
