//! What a run tells whoever started it while it goes on: the phase it is in, how many
//! points (or candidates) are done, and notes worth a user's attention. The run calls an
//! [`Observer`]; the front end decides what to show (the command line draws a bar, the
//! Python binding hands counts to its own bar, a server could push them to a page).

use std::sync::Arc;

/// A stage of a run, for what a front end shows while it lasts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// The bats are being prepared (`bats` of them), before any point runs.
    Preparing { bats: usize },
    /// Points are simulated; `total` in this run's range (a shard's, or every point).
    Simulating { total: usize },
    /// Every point is done; the results file is being finished.
    Writing,
    /// The stage is over: a front end clears what it drew.
    Done,
}

/// Called from the run's threads (the writer's and the workers'), so it must be cheap and
/// must not block for long. Every method has a default that does nothing.
pub trait Observer: Send + Sync {
    /// A new stage begins.
    fn phase(&self, _phase: Phase) {}
    /// `done` of `total` are finished (computed and stored, or found already done).
    fn progress(&self, _done: usize, _total: usize) {}
    /// A warning or a note for the user (one line, no trailing newline).
    fn note(&self, _text: &str) {}
}

/// An observer that shows nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Observer for Silent {}

/// A shared observer, as the options of a run hold it.
#[derive(Clone)]
pub struct SharedObserver(pub Arc<dyn Observer>);

impl SharedObserver {
    pub fn new(o: impl Observer + 'static) -> Self {
        SharedObserver(Arc::new(o))
    }
}

impl Default for SharedObserver {
    fn default() -> Self {
        SharedObserver(Arc::new(Silent))
    }
}

impl std::fmt::Debug for SharedObserver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SharedObserver")
    }
}

impl std::ops::Deref for SharedObserver {
    type Target = dyn Observer;
    fn deref(&self) -> &Self::Target {
        &*self.0
    }
}
