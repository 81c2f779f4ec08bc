//! Sampling time histories on the request's grid t = k·interval from integrator steps,
//! by linear interpolation between the states at the ends of each step.

use super::modal_precision::ModalRounding;
use crate::error::ModelError;
use crate::outcome::{History, HistoryDisplacement, HistoryField, HistoryRequest};

/// The recordable quantities at one instant.
#[derive(Debug, Clone, Default)]
pub(crate) struct Sample {
    pub force: f64,
    pub compression: f64,
    pub ball_velocity: f64,
    pub hoop_displacement: f64,
    pub rigid_translation: f64,
    pub rigid_rotation: f64,
    /// Bat displacement at the requested z (NaN beyond the bat), when the integrator
    /// computes it at every state it records.
    pub displacement: Vec<f64>,
    /// Or the modal coordinates and the force on the bat, from which the recorder's
    /// [`Projector`] computes the displacement of each emitted sample only: half the
    /// states, and no interpolation of every z (interpolating the displacement at every z
    /// of every state took a fifth of a history point's time); or which it records as they
    /// are (the modal form).
    pub modal: Vec<f64>,
    pub modal_force: f64,
}

/// Bat displacement at the requested z from modal coordinates and the force on the bat,
/// appended to the output (`(q, p, out)`).
pub(crate) type Projector = Box<dyn Fn(&[f64], f64, &mut Vec<f64>)>;

/// Collects samples as the integrator advances.
pub(crate) struct Recorder<'r> {
    request: &'r HistoryRequest,
    next: usize,
    /// The two states an emitted sample lies between: the one recorded last (`latest`: its
    /// slot and time) and the one being recorded, in the other slot. Filled in place, their
    /// buffers kept from state to state: a history records hundreds of states, and building
    /// and moving a sample for each made recording a modal history 39 µs a point where
    /// filling them in place takes 28.
    states: [Sample; 2],
    latest: Option<(usize, f64)>,
    history: History,
    pub wants_displacement: bool,
    pub wants_rigid: bool,
    /// Samples carry modal coordinates ([`Sample::modal`]).
    pub wants_modal: bool,
    projector: Option<Projector>,
    /// The modal form's scale: coordinates are recorded divided by it (`bat::shapes`).
    modal_scale: f64,
    /// The modal form's stored precision (f32: `modal_precision`; f64: none).
    rounding: Option<ModalRounding>,
    /// The interpolated coordinates handed to the projector.
    scratch: Vec<f64>,
}

impl<'r> Recorder<'r> {
    /// A recorder with every requested series reserved at its final length (grown by
    /// doubling, the displacement was copied about twice over). The memory is reserved
    /// fallibly: a request the machine cannot hold is an error of the point, not an abort
    /// of the process (the study layer bounds a point's history beforehand).
    pub fn new(request: &'r HistoryRequest) -> Result<Self, ModelError> {
        let has = |f: HistoryField| request.fields.contains(&f);
        let room = |f: HistoryField, per_sample: usize| -> Result<Vec<f64>, ModelError> {
            let n = if has(f) {
                request.n_samples.saturating_mul(per_sample)
            } else {
                0
            };
            let mut v = Vec::new();
            v.try_reserve_exact(n)
                .map_err(|_| ModelError::OutOfMemory {
                    what: "the time histories",
                    bytes: n as f64 * 8.0,
                })?;
            Ok(v)
        };
        let history = History {
            force: room(HistoryField::Force, 1)?,
            compression: room(HistoryField::Compression, 1)?,
            ball_velocity: room(HistoryField::BallVelocity, 1)?,
            displacement: match request.displacement {
                HistoryDisplacement::Grid => room(HistoryField::Displacement, request.z.len())?,
                HistoryDisplacement::Modal => Vec::new(),
            },
            rigid_translation: room(HistoryField::RigidMotion, 1)?,
            rigid_rotation: room(HistoryField::RigidMotion, 1)?,
            hoop_displacement: room(HistoryField::HoopDisplacement, 1)?,
            ..History::default()
        };
        Ok(Self {
            request,
            next: 0,
            states: Default::default(),
            latest: None,
            history,
            wants_displacement: has(HistoryField::Displacement),
            wants_rigid: has(HistoryField::RigidMotion),
            wants_modal: false,
            projector: None,
            modal_scale: 1.0,
            rounding: None,
            scratch: Vec::new(),
        })
    }

    /// Whether the displacement is recorded in modal form (`history.displacement: modal`).
    pub fn modal_form(&self) -> bool {
        self.wants_displacement && self.request.displacement == HistoryDisplacement::Modal
    }

    /// Samples carry modal coordinates ([`Sample::modal`]); `p` turns each emitted one
    /// into displacements.
    pub fn project_with(&mut self, p: Projector) {
        self.projector = Some(p);
        self.wants_modal = true;
    }

    /// Samples carry the coordinates of `modes` modes, recorded divided by `scale` with
    /// the force on the bat; `static_shape` (m/N at the bat's shape points) is the static
    /// response of the modes not stepped (the modal form), and `rounding` the precision
    /// they are kept to when the history is finished.
    pub fn record_modes(
        &mut self,
        modes: usize,
        scale: f64,
        static_shape: Vec<f64>,
        rounding: Option<ModalRounding>,
    ) -> Result<(), ModelError> {
        let n = self.request.n_samples.saturating_mul(modes);
        let m = &mut self.history.modal;
        for (v, len) in [
            (&mut m.coordinate, n),
            (&mut m.bat_load, self.request.n_samples),
        ] {
            v.try_reserve_exact(len)
                .map_err(|_| ModelError::OutOfMemory {
                    what: "the time histories",
                    bytes: len as f64 * 8.0,
                })?;
        }
        m.modes = modes;
        m.static_shape = static_shape;
        self.modal_scale = scale;
        self.rounding = rounding;
        self.wants_modal = true;
        Ok(())
    }

    pub fn request(&self) -> &'r HistoryRequest {
        self.request
    }

    pub fn done(&self) -> bool {
        self.next >= self.request.n_samples
    }

    /// The time of the next sample to emit (past the last one when [`Self::done`]).
    pub fn next_time(&self) -> f64 {
        self.sample_time(self.next)
    }

    /// Sample `k`'s time, k·interval: computed here alone, so that a state recorded at it
    /// ([`Self::commit`]) is that sample exactly.
    fn sample_time(&self, k: usize) -> f64 {
        k as f64 * self.request.interval
    }

    /// Whether the state at step time `t` (steps of length `h`) is needed: a sample time falls
    /// in this step or in the next one (the state is then the start of the interpolation).
    /// States not needed are never computed (sampling every step costs more than the
    /// collision); the emitted samples are the same, since a sample only ever interpolates
    /// between the two steps around it. The margin of 10⁻⁶ h keeps the step before a sample
    /// time that falls on a step; a window of 1.5 h records a quarter more states than
    /// needed.
    pub fn wants(&self, t: f64, h: f64) -> bool {
        !self.done() && self.sample_time(self.next) <= t + h * (1.0 + 1e-6)
    }

    /// Record the state at time `t` (non-decreasing); emits every sample time up to `t`.
    pub fn push(&mut self, t: f64, sample: Sample) {
        *self.state() = sample;
        self.commit(t);
    }

    /// The state to record next, to be filled in place (its buffers hold the values of a
    /// state recorded before: clear them) and then [`Self::commit`]ted.
    pub fn state(&mut self) -> &mut Sample {
        &mut self.states[self.free_slot()]
    }

    fn free_slot(&self) -> usize {
        self.latest.map_or(0, |(slot, _)| 1 - slot)
    }

    /// The state filled in [`Self::state`] is the one at time `t` (non-decreasing): emits
    /// every sample time up to `t`.
    pub fn commit(&mut self, t: f64) {
        let slot = self.free_slot();
        while !self.done() {
            let ts = self.sample_time(self.next);
            if ts > t * (1.0 + 1e-12) {
                break;
            }
            // a state at the sample's time is the sample (x + 1·(y − x) need not be y)
            let w = match self.latest {
                Some((_, t0)) if t > t0 && ts != t => Some(((ts - t0) / (t - t0)).clamp(0.0, 1.0)),
                _ => None,
            };
            self.emit(slot, w);
            self.next += 1;
        }
        self.latest = Some((slot, t));
    }

    /// Emit the sample at weight `w` between the latest state and the one in `slot` (None:
    /// that one itself), each value interpolated as x + w (y − x).
    fn emit(&mut self, slot: usize, w: Option<f64>) {
        let Recorder {
            request,
            states,
            history: h,
            projector,
            modal_scale,
            scratch,
            ..
        } = self;
        let s = &states[slot];
        let prev = Some(&states[1 - slot]).filter(|_| w.is_some());
        let w = w.unwrap_or(0.0);
        let l = |x: f64, y: f64| x + w * (y - x);
        let at = |f: fn(&Sample) -> f64| prev.map_or(f(s), |a| l(f(a), f(s)));
        let each = |out: &mut Vec<f64>, f: fn(&Sample) -> &[f64], scale: f64| match prev {
            Some(a) => out.extend(f(a).iter().zip(f(s)).map(|(x, y)| l(*x, *y) * scale)),
            None => out.extend(f(s).iter().map(|x| x * scale)),
        };
        for field in &request.fields {
            match field {
                HistoryField::Force => h.force.push(at(|s| s.force)),
                HistoryField::Compression => h.compression.push(at(|s| s.compression)),
                HistoryField::BallVelocity => h.ball_velocity.push(at(|s| s.ball_velocity)),
                HistoryField::Displacement
                    if request.displacement == HistoryDisplacement::Modal =>
                {
                    let m = &mut h.modal;
                    each(&mut m.coordinate, |s| &s.modal, 1.0 / *modal_scale);
                    m.bat_load.push(at(|s| s.modal_force));
                }
                HistoryField::Displacement => match projector {
                    Some(p) => {
                        scratch.clear();
                        each(scratch, |s| &s.modal, 1.0);
                        p(scratch, at(|s| s.modal_force), &mut h.displacement)
                    }
                    None => each(&mut h.displacement, |s| &s.displacement, 1.0),
                },
                HistoryField::RigidMotion => {
                    h.rigid_translation.push(at(|s| s.rigid_translation));
                    h.rigid_rotation.push(at(|s| s.rigid_rotation));
                }
                HistoryField::HoopDisplacement => {
                    h.hoop_displacement.push(at(|s| s.hoop_displacement))
                }
                // the flight's, after the collision (`collision::simulate`)
                HistoryField::Trajectory => {}
            }
        }
    }

    /// The history recorded, the modal form at its stored precision.
    pub fn finish(mut self) -> History {
        if let Some(r) = &self.rounding {
            r.round(&mut self.history.modal);
        }
        self.history
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcome::{HistoryCompression, HistoryPrecision};

    fn request(interval: f64, n_samples: usize) -> HistoryRequest {
        HistoryRequest {
            fields: vec![HistoryField::Force, HistoryField::Displacement],
            interval,
            n_samples,
            z: Vec::new(),
            precision: HistoryPrecision::F64,
            compression: HistoryCompression::default(),
            displacement: HistoryDisplacement::Modal,
        }
    }

    /// States of a signal linear in time, f(t) = 3 + 2·10⁴ t and q_j(t) = j − 5·10³ t,
    /// recorded at uneven times with both ways of recording (in place, and whole samples);
    /// linear interpolation between any two of them gives the signal at every sample time
    /// (to rounding), whatever the steps: several samples in one step, a sample on a step,
    /// steps with no sample.
    #[test]
    fn linear_signals_are_sampled_exactly() {
        let f = |t: f64| 3.0 + 2e4 * t;
        let q = |t: f64, j: usize| j as f64 - 5e3 * t;
        // steps of 0.3 to 2.7 sample intervals (interval 10 µs), in tenths of an interval:
        // every tenth state or so falls on a sample time
        let mut tenths = 0;
        let mut times = vec![0.0];
        for k in 0..200 {
            tenths += 3 + 6 * (k % 5);
            times.push(tenths as f64 * 1e-6);
        }
        let req = request(1e-5, 150);
        for in_place in [true, false] {
            let mut rec = Recorder::new(&req).unwrap();
            rec.record_modes(3, 1.0, Vec::new(), None).unwrap();
            for &t in &times {
                let modal: Vec<f64> = (0..3).map(|j| q(t, j)).collect();
                match in_place {
                    true => {
                        let s = rec.state();
                        s.force = f(t);
                        s.modal.clear();
                        s.modal.extend_from_slice(&modal);
                        rec.commit(t);
                    }
                    false => rec.push(
                        t,
                        Sample {
                            force: f(t),
                            modal,
                            ..Sample::default()
                        },
                    ),
                }
            }
            assert!(rec.done());
            let h = rec.finish();
            assert_eq!(h.force.len(), 150);
            for (k, &got) in h.force.iter().enumerate() {
                let ts = k as f64 * 1e-5;
                assert!((got - f(ts)).abs() <= 1e-12 * f(ts), "{in_place} force {k}");
                for j in 0..3 {
                    let want = q(ts, j);
                    let got = h.modal.coordinate[3 * k + j];
                    assert!((got - want).abs() <= 1e-12, "{in_place} q{j} at {k}");
                }
            }
        }
    }
}
