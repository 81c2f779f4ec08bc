//! The real implementations of the driver's two seams: the physics (`model`) as a
//! `Simulator`, and a results file (`store::Session`) as a `Sink`.

use super::traits::{Encode, Simulator, Sink};
use crate::model::bat::shapes;
use crate::model::measures::metrics::{bat_metrics_mapped, BbcorShot};
use crate::model::outcome::{BatProperties, HistoryRequest, Outcome};
use crate::model::spec::{BatSpec, CollisionSpec, NumericsSpec};
use crate::model::{simulate_target, Target};
use crate::optimize::rules::parallel_scan;
use crate::results::{PointGroups, PointRecord, ShapeSource};
use crate::store::{EncodedRecord, RecordEncoder, Session};
use std::sync::Arc;

/// The collision models of `crate::model`.
pub struct ModelSimulator;

impl Simulator for ModelSimulator {
    type Bat = Target;

    fn prepare(
        &self,
        bat: &BatSpec,
        numerics: &NumericsSpec,
        shot: &BbcorShot,
    ) -> Result<(BatProperties, Target), String> {
        let target = Target::prepare(bat, numerics).map_err(|e| e.to_string())?;
        let mut properties = target.properties();
        if let Some(prepared) = target.bat() {
            // The BBCOR scan's collisions on every core of the pool (bats are prepared in
            // it): they are most of preparing a bat, and one after the other a one-bat study
            // would leave cores idle. Each value is computed alone: the same whatever the
            // threads.
            properties.metrics = bat_metrics_mapped(prepared, bat, numerics, shot, &parallel_scan)
                .map_err(|e| e.to_string())?;
            properties.rule_checks = crate::optimize::rules::rule_checks(&properties, bat);
        }
        Ok((properties, target))
    }

    fn shapes(&self, bat: &Arc<Target>) -> Option<ShapeSource> {
        let b = bat.bat()?;
        let target = Arc::clone(bat);
        Some(ShapeSource {
            z: shapes::shape_points(b),
            modes: shapes::n_modes(b),
            shapes: Arc::new(move |modes| match target.bat() {
                Some(b) => shapes::scaled_shapes(b, modes),
                None => Vec::new(),
            }),
        })
    }

    fn simulate(
        &self,
        bat: &Target,
        spec: &CollisionSpec,
        history: Option<&HistoryRequest>,
    ) -> Result<Outcome, String> {
        // The rigid model has no time histories.
        let history = history.filter(|_| spec.model == crate::model::spec::ModelKind::Wave);
        simulate_target(spec, bat, history).map_err(|e| e.to_string())
    }
}

/// A results file being written. `finish` consumes the session, so it is held in an Option.
pub struct StoreSink(Option<Session>);

impl StoreSink {
    pub fn new(session: Session) -> Self {
        StoreSink(Some(session))
    }
    fn session(&mut self) -> Result<&mut Session, String> {
        self.0
            .as_mut()
            .ok_or_else(|| "the results file was already finished".to_string())
    }
}

/// The store's encoder on the workers: a point that does not fit the study is an error the
/// writer reports.
pub struct StoreEncoder(Option<RecordEncoder>);

impl Encode for StoreEncoder {
    type Record = Result<EncodedRecord, String>;
    fn encode(&self, rec: PointRecord) -> Self::Record {
        match &self.0 {
            Some(e) => e.encode(rec).map_err(|e| e.to_string()),
            None => Err("the results file was already finished".to_string()),
        }
    }
    fn encode_group(&self, recs: Vec<PointRecord>) -> Vec<Self::Record> {
        vec![match &self.0 {
            Some(e) => e.encode_group(recs).map_err(|e| e.to_string()),
            None => Err("the results file was already finished".to_string()),
        }]
    }
}

impl Sink for StoreSink {
    type Encoder = StoreEncoder;
    fn encoder(&self) -> StoreEncoder {
        StoreEncoder(self.0.as_ref().map(Session::encoder))
    }
    fn groups(&self) -> PointGroups {
        self.0
            .as_ref()
            .map_or(PointGroups::single(), |s| s.encoder().groups())
    }
    fn is_done(&self, index: usize) -> bool {
        self.0.as_ref().is_some_and(|s| s.is_done(index))
    }
    fn write(&mut self, rec: Result<EncodedRecord, String>) -> Result<(), String> {
        let rec = rec?;
        self.session()?
            .write_encoded(rec)
            .map_err(|e| e.to_string())
    }
    fn idle(&mut self) -> Result<(), String> {
        self.session()?.idle().map_err(|e| e.to_string())
    }
    fn finish(&mut self) -> Result<(), String> {
        match self.0.take() {
            Some(s) => s.finish().map(|_| ()).map_err(|e| e.to_string()),
            None => Ok(()),
        }
    }
}
