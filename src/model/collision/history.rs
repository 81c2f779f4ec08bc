//! Sampling time histories on the request's grid t = k·interval from integrator steps,
//! by linear interpolation between the states at the ends of each step.

use crate::model::error::ModelError;
use crate::model::outcome::{History, HistoryDisplacement, HistoryField, HistoryRequest};

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
    /// states, and no interpolation of every z (issue 22: the displacement was a fifth of
    /// a history point's time); or which it records as they are (the modal form, issue 37).
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
    previous: Option<(f64, Sample)>,
    history: History,
    pub wants_displacement: bool,
    pub wants_rigid: bool,
    /// Samples carry modal coordinates ([`Sample::modal`]).
    pub wants_modal: bool,
    projector: Option<Projector>,
    /// The modal form's scale: coordinates are recorded divided by it (`bat::shapes`).
    modal_scale: f64,
}

impl<'r> Recorder<'r> {
    /// A recorder with every requested series reserved at its final length (grown by
    /// doubling, the displacement was copied about twice over). The memory is reserved
    /// fallibly: a request the machine cannot hold is an error of the point, not an abort
    /// of the process (issue 31; the study layer bounds a point's history beforehand).
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
            previous: None,
            history,
            wants_displacement: has(HistoryField::Displacement),
            wants_rigid: has(HistoryField::RigidMotion),
            wants_modal: false,
            projector: None,
            modal_scale: 1.0,
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
    /// response of the modes not stepped (the modal form).
    pub fn record_modes(
        &mut self,
        modes: usize,
        scale: f64,
        static_shape: Vec<f64>,
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
        self.wants_modal = true;
        Ok(())
    }

    pub fn request(&self) -> &'r HistoryRequest {
        self.request
    }

    pub fn done(&self) -> bool {
        self.next >= self.request.n_samples
    }

    /// Whether the state at step time `t` (steps of length `h`) is needed: a sample time falls
    /// in this step or in the next one (the state is then the start of the interpolation).
    /// States not needed are never computed (issue 7: sampling every step cost more than the
    /// collision); the emitted samples are the same, since a sample only ever interpolates
    /// between the two steps around it.
    pub fn wants(&self, t: f64, h: f64) -> bool {
        !self.done() && self.next as f64 * self.request.interval <= t + 1.5 * h
    }

    /// Record the state at time `t` (non-decreasing); emits every sample time up to `t`.
    pub fn push(&mut self, t: f64, sample: Sample) {
        while !self.done() {
            let ts = self.next as f64 * self.request.interval;
            if ts > t * (1.0 + 1e-12) {
                break;
            }
            let interpolated = match &self.previous {
                Some((t0, s0)) if t > *t0 => {
                    let w = ((ts - t0) / (t - t0)).clamp(0.0, 1.0);
                    lerp(s0, &sample, w)
                }
                _ => sample.clone(),
            };
            self.emit(&interpolated);
            self.next += 1;
        }
        self.previous = Some((t, sample));
    }

    fn emit(&mut self, s: &Sample) {
        let h = &mut self.history;
        for field in &self.request.fields {
            match field {
                HistoryField::Force => h.force.push(s.force),
                HistoryField::Compression => h.compression.push(s.compression),
                HistoryField::BallVelocity => h.ball_velocity.push(s.ball_velocity),
                HistoryField::Displacement
                    if self.request.displacement == HistoryDisplacement::Modal =>
                {
                    let scale = self.modal_scale;
                    let m = &mut h.modal;
                    m.coordinate.extend(s.modal.iter().map(|q| q / scale));
                    m.bat_load.push(s.modal_force);
                }
                HistoryField::Displacement => match &self.projector {
                    Some(p) => p(&s.modal, s.modal_force, &mut h.displacement),
                    None => h.displacement.extend_from_slice(&s.displacement),
                },
                HistoryField::RigidMotion => {
                    h.rigid_translation.push(s.rigid_translation);
                    h.rigid_rotation.push(s.rigid_rotation);
                }
                HistoryField::HoopDisplacement => h.hoop_displacement.push(s.hoop_displacement),
            }
        }
    }

    pub fn finish(self) -> History {
        self.history
    }
}

fn lerp(a: &Sample, b: &Sample, w: f64) -> Sample {
    let l = |x: f64, y: f64| x + w * (y - x);
    let lerp_each =
        |x: &[f64], y: &[f64]| -> Vec<f64> { x.iter().zip(y).map(|(x, y)| l(*x, *y)).collect() };
    Sample {
        force: l(a.force, b.force),
        compression: l(a.compression, b.compression),
        ball_velocity: l(a.ball_velocity, b.ball_velocity),
        hoop_displacement: l(a.hoop_displacement, b.hoop_displacement),
        rigid_translation: l(a.rigid_translation, b.rigid_translation),
        rigid_rotation: l(a.rigid_rotation, b.rigid_rotation),
        displacement: lerp_each(&a.displacement, &b.displacement),
        modal: lerp_each(&a.modal, &b.modal),
        modal_force: l(a.modal_force, b.modal_force),
    }
}
