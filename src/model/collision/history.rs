//! Sampling time histories on the request's grid t = k·interval from integrator steps,
//! by linear interpolation between the states at the ends of each step.

use super::modal_precision::ModalRounding;
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
    /// The modal form's stored precision (f32: `modal_precision`; f64: none).
    rounding: Option<ModalRounding>,
    /// The buffer of the last state dropped (for [`Self::modal_buffer`]), and the
    /// interpolated coordinates handed to the projector.
    spare: Vec<f64>,
    scratch: Vec<f64>,
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
            rounding: None,
            spare: Vec::new(),
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

    /// Whether the state at step time `t` (steps of length `h`) is needed: a sample time falls
    /// in this step or in the next one (the state is then the start of the interpolation).
    /// States not needed are never computed (issue 7: sampling every step cost more than the
    /// collision); the emitted samples are the same, since a sample only ever interpolates
    /// between the two steps around it. The margin of 10⁻⁶ h keeps the step before a sample
    /// time that falls on a step; a window of 1.5 h recorded a quarter more states than
    /// needed (issue 37).
    pub fn wants(&self, t: f64, h: f64) -> bool {
        !self.done() && self.next as f64 * self.request.interval <= t + h * (1.0 + 1e-6)
    }

    /// Record the state at time `t` (non-decreasing); emits every sample time up to `t`.
    pub fn push(&mut self, t: f64, sample: Sample) {
        while !self.done() {
            let ts = self.next as f64 * self.request.interval;
            if ts > t * (1.0 + 1e-12) {
                break;
            }
            let w = match &self.previous {
                Some((t0, _)) if t > *t0 => Some(((ts - t0) / (t - t0)).clamp(0.0, 1.0)),
                _ => None,
            };
            self.emit(&sample, w);
            self.next += 1;
        }
        if let Some((_, old)) = self.previous.replace((t, sample)) {
            self.spare = old.modal;
        }
    }

    /// An empty buffer for the next sample's modal coordinates: the one of the state the
    /// recorder no longer needs (a history records hundreds of states; allocating each
    /// one's coordinates was a tenth of a history point's time, issue 37).
    pub fn modal_buffer(&mut self) -> Vec<f64> {
        let mut v = std::mem::take(&mut self.spare);
        v.clear();
        v
    }

    /// Emit the sample at weight `w` between the previous state and `s` (None: `s` itself),
    /// each value interpolated as x + w (y − x).
    fn emit(&mut self, s: &Sample, w: Option<f64>) {
        let Recorder {
            request,
            previous,
            history: h,
            projector,
            modal_scale,
            scratch,
            ..
        } = self;
        let prev = previous.as_ref().map(|(_, a)| a).filter(|_| w.is_some());
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
