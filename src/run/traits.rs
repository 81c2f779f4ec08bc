//! The two seams of the driver: the physics (`Simulator`) and the results file (`Sink`).
//! The real implementations live in `model` and `store`; tests use fakes.

use crate::model::outcome::{BatProperties, HistoryRequest, Outcome};
use crate::model::spec::{BatSpec, CollisionSpec, NumericsSpec};
use crate::results::PointRecord;

/// Simulates collisions. Shared by all worker threads.
pub trait Simulator: Sync {
    /// A prepared bat (discretisation, modal basis…), shared read-only by every point
    /// that uses it.
    type Bat: Send + Sync;
    /// Prepare one bat (called once per distinct bat + numerics).
    fn prepare(
        &self,
        bat: &BatSpec,
        numerics: &NumericsSpec,
    ) -> Result<(BatProperties, Self::Bat), String>;
    /// Simulate one collision with a prepared bat.
    fn simulate(
        &self,
        bat: &Self::Bat,
        spec: &CollisionSpec,
        history: Option<&HistoryRequest>,
    ) -> Result<Outcome, String>;
}

/// Receives finished points; owned by the single writer thread (the driver asks it which
/// points are done before the run starts).
pub trait Sink: Send {
    /// Is the point at this flat index already in the output (resume)? The driver asks for
    /// every point of its range once, before the workers start, and skips those points
    /// without resolving them.
    fn is_done(&self, index: usize) -> bool;
    /// Store one finished point (at `rec.index`; arrival order is arbitrary).
    fn write(&mut self, rec: PointRecord) -> Result<(), String>;
    /// Called when no point has arrived for a while: a chance to flush what is buffered,
    /// so that a run killed during a long point loses nothing already finished.
    fn idle(&mut self) -> Result<(), String> {
        Ok(())
    }
    /// Flush and close. Called once, after the last `write`.
    fn finish(&mut self) -> Result<(), String>;
}
