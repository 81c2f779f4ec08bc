//! Fixed-step classical Runge–Kutta (RK4) for the ball's position and velocity, with the
//! apex and the landing found inside their steps by Newton's method on partial RK4 steps:
//! the events are then exactly as accurate as the steps themselves (fourth order), and a
//! vacuum flight, whose solution is a quadratic that RK4 reproduces exactly, comes out exact
//! to rounding.

use super::aero::Forces;
use super::error::FlightError;
use super::Sample;

/// Time, position (m) and velocity (m/s) of the ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct State {
    pub t: f64,
    pub p: [f64; 3],
    pub v: [f64; 3],
}

/// Newton's method stops when its correction is below this, s (a landing-point error of
/// about 1e-11 m at 100 m/s).
const EVENT_TOLERANCE_S: f64 = 1e-13;
/// Newton iterations at most (it needs 2–4; bisection takes over if it strays).
const EVENT_ITERATIONS: usize = 40;

/// `base + h·k`, component-wise.
#[inline]
fn axpy(base: [f64; 3], h: f64, k: [f64; 3]) -> [f64; 3] {
    [base[0] + h * k[0], base[1] + h * k[1], base[2] + h * k[2]]
}

/// One classical RK4 step of length `h` from `s`.
#[inline]
pub(crate) fn rk4(forces: &Forces, s: &State, h: f64) -> State {
    let half = 0.5 * h;
    let a1 = forces.acceleration(s.t, s.v);
    let v2 = axpy(s.v, half, a1);
    let a2 = forces.acceleration(s.t + half, v2);
    let v3 = axpy(s.v, half, a2);
    let a3 = forces.acceleration(s.t + half, v3);
    let v4 = axpy(s.v, h, a3);
    let a4 = forces.acceleration(s.t + h, v4);
    let sixth = h / 6.0;
    let mut p = s.p;
    let mut v = s.v;
    for i in 0..3 {
        // dp/dt = v: the stage slopes of the position are the stage velocities.
        p[i] += sixth * (s.v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
        v[i] += sixth * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
    }
    State { t: s.t + h, p, v }
}

/// The state where z = 0 inside the step `from` → `to` (z(from) > 0 ≥ z(to)): Newton on the
/// partial step length, dz/ds = v_z, from the Hermite interpolant's root.
pub(crate) fn landing_in_step(forces: &Forces, from: &State, to: &State) -> State {
    let first = hermite_root(from, to);
    root_in_step(forces, from, to, first, |st| st.p[2], |st| st.v[2])
}

/// The state where v_z = 0 inside the step `from` → `to` (v_z(from) > 0 ≥ v_z(to)): Newton
/// with dv_z/ds = a_z, from the straight line's root.
pub(crate) fn apex_in_step(forces: &Forces, from: &State, to: &State) -> State {
    let first = (to.t - from.t) * from.v[2] / (from.v[2] - to.v[2]);
    let slope = |st: &State| forces.acceleration(st.t, st.v)[2];
    root_in_step(forces, from, to, first, |st| st.v[2], slope)
}

/// The state inside the step `from` → `to` where `value` (positive at `from`, not at `to`)
/// crosses zero: Newton on the partial step length s with d value/ds = `slope`, from
/// `first`, kept inside the bracket by bisection.
fn root_in_step(
    forces: &Forces,
    from: &State,
    to: &State,
    first: f64,
    value: impl Fn(&State) -> f64,
    slope: impl Fn(&State) -> f64,
) -> State {
    let (mut lo, mut hi) = (0.0, to.t - from.t);
    let mut s = first;
    let mut state = *to;
    for _ in 0..EVENT_ITERATIONS {
        state = rk4(forces, from, s);
        let y = value(&state);
        if y > 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let mut next = s - y / slope(&state);
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - s).abs() <= EVENT_TOLERANCE_S {
            break;
        }
        s = next;
    }
    state
}

/// The cubic Hermite through values `y0`, `y1` and slopes `d0`, `d1` (per unit τ) at the
/// ends of τ ∈ [0, 1], as its coefficients: y(τ) = c0 + c1 τ + c2 τ² + c3 τ³.
pub(crate) fn hermite_cubic(y0: f64, y1: f64, d0: f64, d1: f64) -> [f64; 4] {
    [
        y0,
        d0,
        3.0 * (y1 - y0) - 2.0 * d0 - d1,
        2.0 * (y0 - y1) + d0 + d1,
    ]
}

/// First guess of the landing: the root of the cubic Hermite interpolant of z through the
/// step's ends (heights and vertical speeds), by Newton from the straight-line root.
fn hermite_root(from: &State, to: &State) -> f64 {
    let h = to.t - from.t;
    let (z0, z1) = (from.p[2], to.p[2]);
    let d0 = h * from.v[2];
    let [_, _, c2, c3] = hermite_cubic(z0, z1, d0, h * to.v[2]);
    let mut tau = if z0 > z1 { z0 / (z0 - z1) } else { 1.0 };
    for _ in 0..4 {
        let value = z0 + tau * (d0 + tau * (c2 + tau * c3));
        let slope = d0 + tau * (2.0 * c2 + 3.0 * tau * c3);
        let next = tau - value / slope;
        if !(0.0..=1.0).contains(&next) {
            break;
        }
        tau = next;
    }
    tau * h
}

/// What a flight integration finds.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Events {
    pub landing: State,
    pub apex_m: f64,
    pub apex_time_s: f64,
}

/// Steps from `start` (z ≥ 0) until the ball comes back to z = 0. `record`, when given,
/// receives every step's position and the landing.
pub(crate) fn integrate(
    forces: &Forces,
    start: State,
    step: f64,
    max_time: f64,
    mut record: Option<&mut Vec<Sample>>,
) -> Result<Events, FlightError> {
    let mut current = start;
    // The highest point: the start unless the ball rises.
    let mut apex = start;
    if let Some(samples) = record.as_deref_mut() {
        samples.push(Sample::from_state(&start));
    }
    loop {
        if current.t >= max_time {
            return Err(FlightError::NoLanding {
                max_time_s: max_time,
            });
        }
        let next = rk4(forces, &current, step);
        if current.v[2] > 0.0 && next.v[2] <= 0.0 {
            let top = apex_in_step(forces, &current, &next);
            if top.p[2] > apex.p[2] {
                apex = top;
            }
        }
        if next.p[2] <= 0.0 {
            let landing = landing_in_step(forces, &current, &next);
            if let Some(samples) = record.as_deref_mut() {
                samples.push(Sample::from_state(&landing));
            }
            return Ok(Events {
                landing,
                apex_m: apex.p[2],
                apex_time_s: apex.t,
            });
        }
        if let Some(samples) = record.as_deref_mut() {
            samples.push(Sample::from_state(&next));
        }
        current = next;
    }
}
