//! Errors of the physics layer. Each carries the offending numbers so that a study's
//! error report can say exactly what to change.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModelError {
    /// A parameter outside its physical range. `path` is the dotted spec path.
    #[error("{path} = {value} is outside the allowed range {allowed}")]
    OutOfRange {
        path: String,
        value: f64,
        allowed: String,
    },
    /// A parameter that must be given in this combination is missing.
    #[error("missing field `{}`: {allowed}", path.rsplit('.').next().unwrap_or(path))]
    Missing { path: String, allowed: String },
    /// A shell wall that would leave no hollow (or a negative inner radius).
    #[error(
        "bat.shell.thickness: shell thickness {thickness} m exceeds the outer radius {radius} m at z = {z} m"
    )]
    ShellTooThick { thickness: f64, radius: f64, z: f64 },
    /// A malformed profile (knots not increasing, radius not positive, ...).
    #[error("bat.profile: {0}")]
    Profile(String),
    /// A CSV profile must be loaded into knots by the study layer before it reaches the model.
    #[error("bat.profile: CSV profile {0:?} was not loaded into knots before simulation (the study layer must resolve it)")]
    UnresolvedCsvProfile(String),
    /// `bat.length` shorter than the profile.
    #[error("bat.length = {length} m is shorter than the profile ({profile_length} m); only extension is supported")]
    BatShorterThanProfile { length: f64, profile_length: f64 },
    /// A time step above the chosen integrator's stability (or resolution) limit.
    #[error("numerics.dt = {dt} s exceeds the {integrator} integrator's limit of {limit} s for this collision")]
    TimeStepTooLarge {
        dt: f64,
        limit: f64,
        integrator: &'static str,
    },
    /// The ball never reaches the bat (non-positive approach speed at the impact point).
    #[error("approach speed at the impact point is {approach_speed} m/s (ball.speed − swing.omega·(impact.z − z_cm)); it must be > 0 for a collision")]
    NoApproach { approach_speed: f64 },
    /// The ball was still in contact when the bounded simulation time ran out.
    #[error("ball still in contact after {t} s (simulation bound); the bat may be too soft for this ball")]
    NoSeparation { t: f64 },
    /// The collision needs more time steps than its budget (`numerics.max_steps`).
    #[error("this collision needs {}{steps:.0} time steps of {dt:.3e} s, more than its budget numerics.max_steps = {budget}{}",
        if *provable { "at least " } else { "" },
        if *provable { "" } else { ": it was stopped there" })]
    StepBudget {
        steps: f64,
        dt: f64,
        budget: u64,
        /// The field that sets the step: `numerics.dt` when given, else the ball's
        /// stiffness (`ball.law.stiffness` or `ball.law.k1`), or `numerics.max_steps`.
        cause: &'static str,
        /// Known before the run (true) or found when the budget ran out (false).
        provable: bool,
    },
    /// A name that is not in a list of known names (a layer's material).
    #[error("{path} = {name:?} is not known; allowed: {allowed}")]
    UnknownName {
        path: String,
        name: String,
        allowed: String,
    },
    /// A feature not available (yet).
    #[error("unsupported: {0}")]
    Unsupported(&'static str),
    /// Memory for the point could not be reserved.
    #[error("cannot reserve {bytes:.0} bytes for {what}: not enough memory")]
    OutOfMemory { what: &'static str, bytes: f64 },
    /// The batted ball's flight could not be computed (a launch outside the flight's
    /// ranges, or a ball that never lands).
    #[error("flight: {0}")]
    Flight(String),
}

impl ModelError {
    /// The offending parameter's dotted path, its value and what is allowed, for error
    /// reports that point at a study file (empty strings where the error has none).
    pub fn field_value_allowed(&self) -> (String, String, String) {
        let none = String::new;
        match self {
            ModelError::OutOfRange {
                path,
                value,
                allowed,
            } => (path.clone(), number_text(*value), allowed.clone()),
            ModelError::Missing { path, allowed } => {
                (path.clone(), "missing".into(), allowed.clone())
            }
            ModelError::ShellTooThick {
                thickness,
                radius,
                z,
            } => (
                "bat.shell.thickness".into(),
                thickness.to_string(),
                format!("< the bat's outer radius, {radius} m at z = {z} m"),
            ),
            ModelError::UnknownName {
                path,
                name,
                allowed,
            } => (path.clone(), name.clone(), allowed.clone()),
            ModelError::Profile(message) => ("bat.profile".into(), none(), message.clone()),
            ModelError::UnresolvedCsvProfile(path) => (
                "bat.profile.csv".into(),
                path.clone(),
                "a loaded CSV profile".into(),
            ),
            ModelError::BatShorterThanProfile {
                length,
                profile_length,
            } => (
                "bat.length".into(),
                length.to_string(),
                format!("at least the profile's length, {profile_length} m"),
            ),
            ModelError::TimeStepTooLarge { dt, limit, .. } => (
                "numerics.dt".into(),
                dt.to_string(),
                format!("at most {limit} s"),
            ),
            ModelError::NoApproach { approach_speed } => (
                "ball.speed".into(),
                approach_speed.to_string(),
                "a positive approach speed at the impact point".into(),
            ),
            ModelError::StepBudget {
                steps,
                dt,
                budget,
                cause,
                ..
            } => (
                cause.to_string(),
                none(),
                format!(
                    "at most {budget} steps (numerics.max_steps) for {steps:.0} steps of {dt:.3e} s: a softer ball.law, a larger numerics.dt, or a larger numerics.max_steps"
                ),
            ),
            ModelError::OutOfMemory { bytes, .. } => (
                "history".into(),
                format!("{bytes:.0} bytes"),
                "a smaller history (fewer samples, positions or fields)".into(),
            ),
            ModelError::Flight(message) => ("flight".into(), none(), message.clone()),
            ModelError::NoSeparation { .. } | ModelError::Unsupported(_) => {
                (none(), none(), self.to_string())
            }
        }
    }
}

/// Shorthand for an out-of-range error.
pub(crate) fn out_of_range(path: &str, value: f64, allowed: &str) -> ModelError {
    ModelError::OutOfRange {
        path: path.to_string(),
        value,
        allowed: allowed.to_string(),
    }
}

/// A value as a reader takes it in: plain decimals from 1e-6 to 1e9, else with an exponent
/// (1e-300 is not three hundred zeros).
pub fn number_text(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && a.is_finite() && !(1e-6..1e9).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}
