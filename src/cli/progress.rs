//! What a run shows on a terminal, as an observer of the run: the phase (preparing bats,
//! simulating, writing), a bar with the points done, a rate in whole points per second and
//! an ETA once the rate means something (`run::progress`'s texts). Nothing is drawn when
//! stderr is not a terminal; notes go to stderr above the bar.

use crate::run::progress::{eta_text, rate_text};
use crate::run::{Observer, Phase};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Duration;

/// The command line's observer: a spinner or a bar per phase, or nothing (`--quiet`, or
/// stderr not a terminal).
pub(crate) struct TerminalBar {
    drawn: bool,
    /// What is counted (`points`, `candidates`).
    unit: &'static str,
    bar: Mutex<ProgressBar>,
}

impl TerminalBar {
    pub(crate) fn new(enabled: bool, unit: &'static str) -> Self {
        TerminalBar {
            drawn: enabled && std::io::stderr().is_terminal(),
            unit,
            bar: Mutex::new(ProgressBar::hidden()),
        }
    }

    fn replace(&self, next: ProgressBar) {
        let mut bar = self.bar.lock().unwrap_or_else(|p| p.into_inner());
        bar.finish_and_clear();
        *bar = next;
    }
}

impl Drop for TerminalBar {
    fn drop(&mut self) {
        self.replace(ProgressBar::hidden());
    }
}

impl Observer for TerminalBar {
    fn phase(&self, phase: Phase) {
        if !self.drawn {
            return;
        }
        match phase {
            Phase::Preparing { bats } => self.replace(spinner(format!(
                "preparing {bats} bat{}",
                if bats == 1 { "" } else { "s" }
            ))),
            Phase::Simulating { total } => self.replace(counted_bar(total as u64, self.unit)),
            Phase::Done => self.replace(ProgressBar::hidden()),
            Phase::Writing => self
                .bar
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .set_message("writing"),
        }
    }

    fn progress(&self, done: usize, total: usize) {
        if self.drawn {
            let bar = self.bar.lock().unwrap_or_else(|p| p.into_inner());
            if bar.length() != Some(total as u64) {
                bar.set_length(total as u64);
            }
            bar.set_position(done as u64);
        }
    }

    fn note(&self, text: &str) {
        let bar = self.bar.lock().unwrap_or_else(|p| p.into_inner());
        bar.suspend(|| eprintln!("{text}"));
    }
}

/// A spinner for a phase without a count (`preparing 14 bats`).
fn spinner(message: String) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template("{spinner} {msg}  {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    pb.set_message(message);
    pb.enable_steady_tick(Duration::from_millis(120));
    pb
}

/// The bar of the simulating phase; `set_message("writing")` names the last phase.
fn counted_bar(total: u64, unit: &str) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let template = format!(
        "{{msg:11}} {{elapsed:>4}} [{{wide_bar}}] {{pos}}/{{len}} {unit}  {{rate}}  {{eta_warm}}"
    );
    pb.set_style(
        ProgressStyle::with_template(&template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .with_key("rate", |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{}", rate_text(s.pos(), s.elapsed()));
            })
            .with_key(
                "eta_warm",
                |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(
                        w,
                        "{}",
                        eta_text(s.pos(), s.len().unwrap_or(0), s.elapsed())
                    );
                },
            ),
    );
    pb.set_message(if unit == "points" {
        "simulating"
    } else {
        "searching"
    });
    pb
}
