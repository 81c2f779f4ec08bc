//! The measuring tools: CPU-time clocks, the peak-resident-memory mark, the median of
//! repeats, and the error text of a case that could not run.

pub(super) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// CPU seconds of a POSIX CPU-time clock (NaN if it cannot be read).
pub(super) fn cpu_clock_seconds(clock: libc::clockid_t) -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a valid pointer.
    if unsafe { libc::clock_gettime(clock, &mut t) } != 0 {
        return f64::NAN;
    }
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// CPU seconds this thread has run (ns resolution). On a shared machine a thread waits for a
/// core part of the wall time; its CPU time does not. A clock call, not a /proc read: the
/// store's calls are timed one by one, and reading /proc for each cost ~15 µs, more than a
/// journal write, and would inflate the measured store share.
pub fn thread_cpu_seconds() -> f64 {
    cpu_clock_seconds(libc::CLOCK_THREAD_CPUTIME_ID)
}

pub(super) fn proc_status_kib(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    s.lines()
        .find(|l| l.starts_with(key))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}

/// Reset the peak-RSS mark (Linux ≥ 4.0); returns the current RSS in bytes.
pub(super) fn reset_peak() -> Option<u64> {
    std::fs::write("/proc/self/clear_refs", "5").ok()?;
    proc_status_kib("VmRSS:").map(|k| k * 1024)
}

pub(super) fn peak_rss() -> Option<u64> {
    proc_status_kib("VmHWM:").map(|k| k * 1024)
}

pub(super) fn err<E: std::fmt::Display>(what: &str) -> impl FnOnce(E) -> String + '_ {
    move |e| format!("{what}: {e}")
}

/// CPU seconds (user + system) of this process so far, all threads (ns resolution).
pub(super) fn process_cpu_seconds() -> f64 {
    cpu_clock_seconds(libc::CLOCK_PROCESS_CPUTIME_ID)
}

/// What `/proc/stat` says of the time the host has taken from this machine's CPUs so far.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stolen {
    /// CPU seconds of every CPU together: the "steal" time, when a virtual CPU was ready to
    /// run and its host ran something else (other guests, or its own work for this one, such
    /// as emulating its disk).
    pub seconds: f64,
    /// The CPUs whose time that sums (the `cpuN` lines).
    pub cpus: usize,
}

/// The host's time so far, from one read of `/proc/stat`; None where it cannot be read or
/// has no steal field.
pub(super) fn machine_stolen() -> Option<Stolen> {
    let stat = std::fs::read_to_string("/proc/stat").ok()?;
    let ticks = stolen_ticks(stat.lines().next()?)?;
    // SAFETY: sysconf reads a constant of the system
    let hz = unsafe { libc::sysconf(libc::_SC_CLK_TCK) };
    let cpus = stat
        .lines()
        .filter(|l| l.starts_with("cpu") && l.as_bytes().get(3).is_some_and(u8::is_ascii_digit))
        .count();
    (hz > 0 && cpus > 0).then(|| Stolen {
        seconds: ticks as f64 / hz as f64,
        cpus,
    })
}

/// The steal field of `/proc/stat`'s first line (`cpu  user nice system idle iowait irq
/// softirq steal …`, in clock ticks, every CPU summed; proc(5)).
pub(super) fn stolen_ticks(line: &str) -> Option<u64> {
    let mut fields = line.split_whitespace();
    (fields.next()? == "cpu").then_some(())?;
    fields.nth(7)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    // proc(5): the aggregate line's eighth value is the steal time; older kernels without
    // it (before 2.6.11) give None, as does any other line
    #[test]
    fn steal_is_the_eighth_value_of_the_cpu_line() {
        let line = "cpu  10132153 290696 3084719 46828483 16683 0 25195 17453 0 0";
        assert_eq!(stolen_ticks(line), Some(17453));
        assert_eq!(stolen_ticks("cpu  1 2 3 4 5 6 7"), None);
        assert_eq!(stolen_ticks("cpu0 1 2 3 4 5 6 7 8 9"), None);
        assert_eq!(stolen_ticks("intr 1 2 3 4 5 6 7 8 9"), None);
    }
}
