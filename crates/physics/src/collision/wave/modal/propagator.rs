//! One exact step of a mode under a force linear in time: the propagator's constants.

/// Per-mode constants of one exact step of length h under a force linear in time.
pub(super) struct ModalStep {
    /// Free propagator [[cos, sin_over_omega], [minus_omega_sin, a22]] (damped if ζ > 0).
    pub(super) cos: Vec<f64>,
    pub(super) sin_over_omega: Vec<f64>,
    pub(super) minus_omega_sin: Vec<f64>,
    pub(super) a22: Vec<f64>,
    /// Position and velocity responses to the start/end force, times φ_n(z_impact).
    pub(super) q_start: Vec<f64>,
    pub(super) q_end: Vec<f64>,
    pub(super) v_start: Vec<f64>,
    pub(super) v_end: Vec<f64>,
}

/// (1 − cos ωh)/ω² and (h − sin(ωh)/ω)/(hω²), with series where ωh is small.
fn ramp_terms(omega: f64, h: f64) -> (f64, f64) {
    let x = omega * h;
    if x < 1e-2 {
        let x2 = x * x;
        (
            h * h * (0.5 - x2 / 24.0 + x2 * x2 / 720.0 - x2 * x2 * x2 / 40320.0),
            h * h * (1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0 - x2 * x2 * x2 / 362880.0),
        )
    } else {
        (
            (1.0 - x.cos()) / (omega * omega),
            (h - x.sin() / omega) / (h * omega * omega),
        )
    }
}

impl ModalStep {
    /// Exact step of q̈ + 2ζωq̇ + ω²q = φ f(t), f linear over the step; ζ applies to the
    /// flexible modes (ω > 0) only.
    pub(super) fn new(omega: &[f64], zeta: f64, phi: &[f64], h: f64) -> Self {
        Self::each(omega, &vec![zeta; omega.len()], phi, h)
    }

    /// [`Self::new`] with each mode's own damping ratio.
    pub(super) fn each(omega: &[f64], zetas: &[f64], phi: &[f64], h: f64) -> Self {
        let n = omega.len();
        let mut s = Self {
            cos: Vec::with_capacity(n),
            sin_over_omega: Vec::with_capacity(n),
            minus_omega_sin: Vec::with_capacity(n),
            a22: Vec::with_capacity(n),
            q_start: Vec::with_capacity(n),
            q_end: Vec::with_capacity(n),
            v_start: Vec::with_capacity(n),
            v_end: Vec::with_capacity(n),
        };
        for ((&w, &p), &zeta) in omega.iter().zip(phi).zip(zetas) {
            if zeta > 0.0 && w > 0.0 {
                // homogeneous: e^{−ζωt}(cos ω_d t, sin ω_d t); particular solution of the
                // ramp f0 + (f1 − f0) t/h: q_p = f(t)/ω² − 2ζ (f1 − f0)/(h ω³)
                let wd = w * (1.0 - zeta * zeta).sqrt();
                let e = (-zeta * w * h).exp();
                let (sn, cs) = (wd * h).sin_cos();
                let r = zeta * w / wd;
                let (a11, a12, a21, a22) = (
                    e * (cs + r * sn),
                    e * sn / wd,
                    -e * w * w / wd * sn,
                    e * (cs - r * sn),
                );
                let response = |qp0: f64, qph: f64, vp: f64| {
                    (qph - a11 * qp0 - a12 * vp, vp - a21 * qp0 - a22 * vp)
                };
                let c = 2.0 * zeta / (h * w * w * w);
                let (qs, vs) = response(1.0 / (w * w) + c, c, -1.0 / (h * w * w));
                let (qe, ve) = response(-c, 1.0 / (w * w) - c, 1.0 / (h * w * w));
                s.cos.push(a11);
                s.sin_over_omega.push(a12);
                s.minus_omega_sin.push(a21);
                s.a22.push(a22);
                s.q_start.push(qs * p);
                s.q_end.push(qe * p);
                s.v_start.push(vs * p);
                s.v_end.push(ve * p);
                continue;
            }
            let x = w * h;
            let sin_over_omega = if x < 1e-2 {
                let x2 = x * x;
                h * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
            } else {
                x.sin() / w
            };
            let (a, b) = ramp_terms(w, h);
            s.cos.push(x.cos());
            s.a22.push(x.cos());
            s.sin_over_omega.push(sin_over_omega);
            s.minus_omega_sin.push(-w * x.sin());
            s.q_start.push((a - b) * p);
            s.q_end.push(b * p);
            s.v_start.push((sin_over_omega - a / h) * p);
            s.v_end.push(a / h * p);
        }
        s
    }
}

impl ModalStep {
    /// Mode j's coordinate and velocity after the step from (x, ẋ) under a force that goes
    /// linearly from p0 to p1.
    #[inline]
    pub(super) fn advance(
        &self,
        j: usize,
        (x, xd): (f64, f64),
        (p0, p1): (f64, f64),
    ) -> (f64, f64) {
        (
            self.cos[j] * x
                + self.sin_over_omega[j] * xd
                + self.q_start[j] * p0
                + self.q_end[j] * p1,
            self.minus_omega_sin[j] * x
                + self.a22[j] * xd
                + self.v_start[j] * p0
                + self.v_end[j] * p1,
        )
    }
}

/// Dissipation rate of modal damping ζ, Σ 2ζω q̇², W (unit modal masses).
pub(super) fn damping_rate(omega: &[f64], zeta: f64, qd: &[f64]) -> f64 {
    qd.iter()
        .zip(omega)
        .map(|(v, w)| 2.0 * zeta * w * v * v)
        .sum()
}

/// [`damping_rate`] with each mode's own damping ratio.
pub(super) fn damping_rate_each(omega: &[f64], zetas: &[f64], qd: &[f64]) -> f64 {
    qd.iter()
        .zip(omega)
        .zip(zetas)
        .map(|((v, w), z)| 2.0 * z * w * v * v)
        .sum()
}
