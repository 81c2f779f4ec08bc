//! The machine the benchmark ran on, as Linux describes it (`/proc`, `/etc/os-release`, the
//! cgroup's memory limit); what cannot be read is "unknown" or `None`.

use serde::Serialize;
use std::path::Path;

/// Facts about the machine and the run.
#[derive(Debug, Clone, Serialize)]
pub struct Machine {
    /// CPUs this process may run on (affinity and cgroup quota: what `--jobs` defaults to).
    pub nproc: usize,
    /// CPUs the kernel lists (`/proc/cpuinfo`), whether or not this process may use them.
    pub logical_cpus: usize,
    pub cpu_model: String,
    /// Physical memory (`MemTotal`), and the memory limit of this process's cgroup where
    /// there is one (a batch scheduler's allocation).
    pub memory_bytes: Option<u64>,
    pub memory_limit_bytes: Option<u64>,
    /// The distribution (`PRETTY_NAME`) and the kernel release.
    pub os: String,
    pub kernel: String,
    /// `/proc/loadavg` at the start and the end (other work on the cores makes timings noisy).
    pub loadavg_start: String,
    pub loadavg_end: String,
    /// Where the results files and the disk probe were written.
    pub dir: String,
    pub quick: bool,
    pub batstudy_version: String,
    pub git_commit: String,
}

fn read(path: &str) -> Option<String> {
    std::fs::read_to_string(path).ok()
}

/// The value of the first `key: value` line of `/proc/cpuinfo` with one of `keys`.
fn cpuinfo_value(cpuinfo: &str, keys: &[&str]) -> Option<String> {
    cpuinfo.lines().find_map(|l| {
        let (k, v) = l.split_once(':')?;
        keys.contains(&k.trim()).then(|| v.trim().to_string())
    })
}

fn meminfo_bytes(key: &str) -> Option<u64> {
    let line = read("/proc/meminfo")?
        .lines()
        .find(|l| l.starts_with(key))?
        .to_string();
    line.split_whitespace()
        .nth(1)?
        .parse::<u64>()
        .ok()
        .map(|k| k * 1024)
}

/// The cgroup v2 (`memory.max`) or v1 (`memory.limit_in_bytes`) limit, if it is below the
/// machine's memory.
fn cgroup_memory_limit(total: Option<u64>) -> Option<u64> {
    let limit = [
        "/sys/fs/cgroup/memory.max",
        "/sys/fs/cgroup/memory/memory.limit_in_bytes",
    ]
    .iter()
    .find_map(|p| read(p)?.trim().parse::<u64>().ok())?;
    (total.is_none_or(|t| limit < t)).then_some(limit)
}

fn os_name() -> String {
    read("/etc/os-release")
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("PRETTY_NAME="))
                .map(|v| v.trim_matches('"').to_string())
        })
        .unwrap_or_else(|| std::env::consts::OS.to_string())
}

pub(super) fn describe(quick: bool, dir: &Path) -> Machine {
    let cpuinfo = read("/proc/cpuinfo").unwrap_or_default();
    let memory = meminfo_bytes("MemTotal:");
    Machine {
        nproc: std::thread::available_parallelism().map_or(1, |n| n.get()),
        logical_cpus: cpuinfo
            .lines()
            .filter(|l| l.starts_with("processor"))
            .count(),
        cpu_model: cpuinfo_value(&cpuinfo, &["model name", "Model", "Hardware", "cpu"])
            .unwrap_or_else(|| "unknown".into()),
        memory_bytes: memory,
        memory_limit_bytes: cgroup_memory_limit(memory),
        os: os_name(),
        kernel: read("/proc/sys/kernel/osrelease")
            .map_or_else(|| "unknown".into(), |s| s.trim().to_string()),
        loadavg_start: loadavg(),
        loadavg_end: String::new(),
        dir: dir.display().to_string(),
        quick,
        batstudy_version: env!("CARGO_PKG_VERSION").to_string(),
        git_commit: crate::store::options::BUILD_COMMIT
            .unwrap_or("unknown")
            .to_string(),
    }
}

pub(super) fn loadavg() -> String {
    read("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}
