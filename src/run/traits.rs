//! The two seams of the driver: the physics (`Simulator`) and the results file (`Sink`).
//! The real implementations live in `model` and `store`; tests use fakes.

use crate::model::measures::metrics::BbcorShot;
use crate::model::outcome::{BatProperties, HistoryRequest, Outcome};
use crate::model::spec::{BatSpec, CollisionSpec, NumericsSpec};
use crate::results::{PointGroups, PointRecord, ShapeSource};
use std::sync::Arc;

/// Simulates collisions. Shared by all worker threads.
pub trait Simulator: Sync {
    /// A prepared bat (discretisation, modal basis…), shared read-only by every point
    /// that uses it.
    type Bat: Send + Sync;
    /// Prepare one bat (called once per distinct bat + numerics); its BBCOR with `shot`.
    fn prepare(
        &self,
        bat: &BatSpec,
        numerics: &NumericsSpec,
        shot: &BbcorShot,
    ) -> Result<(BatProperties, Self::Bat), String>;
    /// The bat's mode shapes, for the modal form of its displacement histories (None: it
    /// has none to store).
    fn shapes(&self, _bat: &Arc<Self::Bat>) -> Option<ShapeSource> {
        None
    }
    /// Simulate one collision with a prepared bat.
    fn simulate(
        &self,
        bat: &Self::Bat,
        spec: &CollisionSpec,
        history: Option<&HistoryRequest>,
    ) -> Result<Outcome, String>;
}

/// Prepares finished points for a sink on the worker that computed them: the part of
/// storing a point that can run in parallel (the store serialises and compresses histories
/// here, so its one writer thread only appends bytes).
pub trait Encode: Sync {
    /// What the sink's writer takes.
    type Record: Send;
    fn encode(&self, rec: PointRecord) -> Self::Record;
    /// The points of one group ([`Sink::groups`], in flat-index order) as the records the
    /// writer takes: one each, unless the sink stores a group as one.
    fn encode_group(&self, recs: Vec<PointRecord>) -> Vec<Self::Record> {
        recs.into_iter().map(|r| self.encode(r)).collect()
    }
}

/// For sinks that take points as they come.
pub struct AsIs;

impl Encode for AsIs {
    type Record = PointRecord;
    fn encode(&self, rec: PointRecord) -> PointRecord {
        rec
    }
}

/// Receives finished points; owned by the single writer thread (the driver asks it which
/// points are done, and for its encoder, before the run starts).
pub trait Sink: Send {
    /// Run on the workers on each finished point before it is sent to [`Self::write`].
    type Encoder: Encode;
    /// The encoder the workers share.
    fn encoder(&self) -> Self::Encoder;
    /// How the sink groups points (each on its own unless it says otherwise): the driver
    /// computes a group's points on one worker, one after the other, and hands them to
    /// [`Encode::encode_group`] together. A sink that groups reports a group's points done
    /// all or none ([`Self::is_done`]).
    fn groups(&self) -> PointGroups {
        PointGroups::single()
    }
    /// Is the point at this flat index already in the output (resume)? The driver asks for
    /// every point of its range once, before the workers start, and skips those points
    /// without resolving them.
    fn is_done(&self, index: usize) -> bool;
    /// Store one finished point, as the encoder made it (arrival order is arbitrary).
    fn write(&mut self, rec: <Self::Encoder as Encode>::Record) -> Result<(), String>;
    /// Called when no point has arrived for a while: a chance to flush what is buffered,
    /// so that a run killed during a long point loses nothing already finished.
    fn idle(&mut self) -> Result<(), String> {
        Ok(())
    }
    /// Flush and close. Called once, after the last `write`.
    fn finish(&mut self) -> Result<(), String>;
}
