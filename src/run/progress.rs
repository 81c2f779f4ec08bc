//! A run's pace as text: a rate in whole points per second, an ETA that appears only once
//! the rate means something, and durations (the report and the command line's bar use them).

use std::time::Duration;

/// The ETA is shown from this much running time on (the first points pay for cold caches
/// and threads waking; an ETA from them overstates a short study many times over).
const WARM_UP: Duration = Duration::from_secs(2);
/// … and from this share of the points done.
const WARM_UP_SHARE: f64 = 0.02;

/// `1234 points/s` (mean since the start; whole numbers, or one decimal below 10).
pub fn rate_text(done: u64, elapsed: Duration) -> String {
    let secs = elapsed.as_secs_f64();
    if done == 0 || secs <= 0.0 {
        return "– points/s".into();
    }
    let rate = done as f64 / secs;
    if rate < 10.0 {
        format!("{rate:.1} points/s")
    } else {
        format!("{rate:.0} points/s")
    }
}

/// `ETA 12s` from the mean rate, once warmed up; `ETA …` before.
pub fn eta_text(done: u64, total: u64, elapsed: Duration) -> String {
    let warm = elapsed >= WARM_UP && done as f64 >= WARM_UP_SHARE * total as f64 && done > 0;
    if !warm {
        return "ETA …".into();
    }
    let left = elapsed.as_secs_f64() * (total.saturating_sub(done)) as f64 / done as f64;
    format!("ETA {}", duration_text(left))
}

/// `850ms`, `12s`, `3m05s`, `2h04m`.
pub fn duration_text(secs: f64) -> String {
    if secs < 1.0 {
        format!("{:.0}ms", secs * 1e3)
    } else if secs < 60.0 {
        format!("{secs:.0}s")
    } else if secs < 3600.0 {
        let s = secs.round() as u64;
        format!("{}m{:02}s", s / 60, s % 60)
    } else {
        let m = (secs / 60.0).round() as u64;
        format!("{}h{:02}m", m / 60, m % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_eta_during_the_warm_up() {
        let total = 10_000;
        assert_eq!(eta_text(5, total, Duration::from_millis(500)), "ETA …");
        assert_eq!(eta_text(5000, total, Duration::from_secs(1)), "ETA …");
        assert_eq!(eta_text(100, total, Duration::from_secs(5)), "ETA …");
        // 4000 of 10 000 in 8 s: 6000 more at 500/s.
        assert_eq!(eta_text(4000, total, Duration::from_secs(8)), "ETA 12s");
    }

    #[test]
    fn rates_without_decimals() {
        assert_eq!(rate_text(2047, Duration::from_secs(1)), "2047 points/s");
        assert_eq!(rate_text(15, Duration::from_secs(2)), "7.5 points/s");
        assert_eq!(duration_text(185.0), "3m05s");
    }
}
