//! Physical checks of a spec without heavy work: every error names the field by its dotted
//! path and the allowed range.

use crate::bat::section::BatGeometry;
use crate::error::{out_of_range, ModelError};
use crate::outcome::HistoryRequest;
use crate::spec::CollisionSpec;

/// Lowest and highest hoop frequency accepted, Hz.
pub const HOOP_FREQUENCY_RANGE: (f64, f64) = (1.0, 1.0e5);
/// Largest hoop mass, in ball masses.
pub const HOOP_MASS_MAX_BALL_MASSES: f64 = 10.0;

fn check(path: &str, v: f64, ok: bool, allowed: &str) -> Result<(), ModelError> {
    if ok && v.is_finite() {
        Ok(())
    } else {
        Err(out_of_range(path, v, allowed))
    }
}

/// Check a collision spec: positive quantities, 0 < cor ≤ 1, shell thinner than the radius
/// wherever it applies, impact inside the bat, hoop in a sane range, numerics sane.
pub fn validate_spec(spec: &CollisionSpec) -> Result<(), ModelError> {
    let wall = spec.bat.preset.is_rigid_target();
    check_cylinder(&spec.bat)?;
    // A wall has no geometry: nothing to hit off the bat, no length to bound the approach.
    let geometry = if wall {
        None
    } else {
        Some(BatGeometry::resolve(&spec.bat)?)
    };
    let length = geometry.as_ref().map_or(0.0, |g| g.length);
    check_ball(&spec.ball)?;
    check("swing.omega", spec.swing.omega, true, "finite rad/s")?;
    check("swing.cm_speed", spec.swing.cm_speed, true, "finite m/s")?;
    check_oblique(spec, wall)?;
    if let Some(g) = &geometry {
        crate::collision::oblique::check_reach(spec, g)?;
    }
    check_batter(spec, wall)?;
    if spec.pitch.is_some() && spec.batter.is_none() {
        return Err(ModelError::Unsupported(
            "a pitch block without a batter block (the batter's swing meets the pitch)",
        ));
    }
    if let Some(flight) = &spec.flight {
        check_flight(flight)?;
    }
    if let Some(hoop) = &spec.hoop {
        check_hoop(hoop, spec.ball.mass)?;
    }
    if spec.model == crate::spec::ModelKind::Rigid && spec.bat.grip.is_some() {
        return Err(ModelError::Unsupported(
            "bat.grip with the rigid model (it is a free bat)",
        ));
    }
    if !wall {
        check(
            "impact.z",
            spec.impact.z,
            crate::bat::on_bat(spec.impact.z, length),
            &format!("on the bat: 0 <= z <= {length} m"),
        )?;
    }
    check_numerics(&spec.numerics)?;
    check_step_budget(spec, length)
}

/// `bat.radius` is the cylinder's, and only the cylinder's.
fn check_cylinder(bat: &crate::spec::BatSpec) -> Result<(), ModelError> {
    let cylinder = bat.preset == crate::spec::BatPreset::Cylinder;
    match (cylinder, bat.radius) {
        (true, Some(r)) => check("bat.radius", r, r > 0.0, "a radius > 0 m"),
        (true, None) => Err(ModelError::Unsupported(
            "bat.preset: cylinder without bat.radius (the cylinder's radius, m)",
        )),
        (false, Some(r)) => check("bat.radius", r, false, "unset: only bat.preset cylinder has a radius of its own (a bat's comes from its profile)"),
        (false, None) => Ok(()),
    }
}

/// The ball and its force law.
fn check_ball(ball: &crate::spec::BallSpec) -> Result<(), ModelError> {
    check(
        "ball.mass",
        ball.mass,
        ball.mass > 0.0,
        "a finite number > 0 kg",
    )?;
    check(
        "ball.speed",
        ball.speed,
        ball.speed > 0.0,
        "a finite number > 0 m/s",
    )?;
    let law = &ball.law;
    let stiffness = law.stiffness;
    check(
        "ball.law.stiffness",
        stiffness,
        stiffness > 0.0,
        "a finite number > 0 N/m",
    )?;
    check(
        "ball.law.cor",
        law.cor,
        law.cor > 0.0 && law.cor <= 1.0,
        "(0, 1]",
    )?;
    check(
        "ball.law.k1",
        law.k1,
        law.k1 > 0.0,
        "a finite number > 0 N/m^α",
    )?;
    if let Some(v) = law.reference_speed {
        check(
            "ball.law.reference_speed",
            v,
            v > 0.0,
            "a finite number > 0 m/s",
        )?;
    }
    if let Some(slope) = law.cor_slope {
        check(
            "ball.law.cor_slope",
            slope,
            true,
            "a finite number, 1/(m/s)",
        )?;
    }
    if let Some(gamma) = law.cor_exponent {
        let allowed = if law.cor_slope.is_some() {
            "unset when ball.law.cor_slope is given (the COR is a line or a power curve, not both)"
        } else {
            "a finite number in [0, 1)"
        };
        check(
            "ball.law.cor_exponent",
            gamma,
            law.cor_slope.is_none() && (0.0..1.0).contains(&gamma),
            allowed,
        )?;
    }
    check_rest_curve(law)?;
    check(
        "ball.law.alpha",
        law.alpha,
        law.alpha > 0.0,
        "a finite number > 0",
    )?;
    Ok(())
}

/// `cor_at_rest` and `cor_power`: given together, alone among the COR's forms, the curve
/// falling from its value at rest through `cor` (so `cor_at_rest` ≥ `cor`).
fn check_rest_curve(law: &crate::spec::BallLaw) -> Result<(), ModelError> {
    let other_form = law.cor_slope.is_some() || law.cor_exponent.is_some();
    let alone =
        "unset when ball.law.cor_slope or ball.law.cor_exponent is given (the COR has one form)";
    let pair = "given together with the other of ball.law.cor_at_rest and ball.law.cor_power";
    if let Some(e0) = law.cor_at_rest {
        let (ok, allowed) = match (other_form, law.cor_power.is_some()) {
            (true, _) => (false, alone),
            (false, false) => (false, pair),
            (false, true) => (e0 >= law.cor && e0 <= 1.0, "a COR in [ball.law.cor, 1]"),
        };
        check("ball.law.cor_at_rest", e0, ok, allowed)?;
    }
    if let Some(q) = law.cor_power {
        let (ok, allowed) = match (other_form, law.cor_at_rest.is_some()) {
            (true, _) => (false, alone),
            (false, false) => (false, pair),
            (false, true) => (q > 0.0 && q <= 4.0, "a finite number in (0, 4]"),
        };
        check("ball.law.cor_power", q, ok, allowed)?;
    }
    Ok(())
}

/// An oblique impact, a spinning ball and the swing's angles.
fn check_oblique(spec: &CollisionSpec, wall: bool) -> Result<(), ModelError> {
    let offset = spec.impact.offset;
    let flat = "0 against the wall (a flat target has no offset)";
    check(
        "impact.offset",
        offset,
        !wall || offset == 0.0,
        if wall { flat } else { "finite m" },
    )?;
    check("ball.spin", spec.ball.spin, true, "finite rad/s")?;
    if let Some(r) = spec.ball.radius {
        check("ball.radius", r, r > 0.0, "a finite number > 0 m")?;
    }
    if let Some(k) = spec.ball.inertia_factor {
        // a thin shell's 2/3 is the most a sphere can have
        check(
            "ball.inertia_factor",
            k,
            k > 0.0 && k <= 2.0 / 3.0,
            "(0, 2/3]",
        )?;
    }
    if let Some(mu) = spec.ball.law.friction {
        check("ball.law.friction", mu, mu >= 0.0, "a finite number >= 0")?;
    }
    if let Some(k) = spec.ball.law.tangential_ratio {
        check(
            "ball.law.tangential_ratio",
            k,
            k > 0.0,
            "a finite number > 0",
        )?;
    }
    let right_angle = std::f64::consts::FRAC_PI_2;
    for (path, angle) in [
        ("swing.attack_angle", spec.swing.attack_angle),
        ("swing.attack_direction", spec.swing.attack_direction),
        ("swing.tilt", spec.swing.tilt),
    ] {
        check(path, angle, angle.abs() < right_angle, "(-pi/2, pi/2) rad")?;
    }
    Ok(())
}

/// The batter: speeds, the reference bat, the exponent, the pivot.
fn check_batter(spec: &CollisionSpec, wall: bool) -> Result<(), ModelError> {
    let Some(b) = &spec.batter else {
        return Ok(());
    };
    if wall {
        return Err(ModelError::Unsupported(
            "a batter with a rigid target (bat.preset wall or cylinder: it is not swung)",
        ));
    }
    if let Some(e) = crate::collision::batter::swing_conflict(spec) {
        return Err(e);
    }
    if let Some(speed) = b.pitch_speed {
        check(
            "batter.pitch_speed",
            speed,
            speed >= 0.0,
            "a finite number >= 0 m/s",
        )?;
    }
    check_pitch(spec)?;
    check(
        "batter.bat_speed",
        b.bat_speed,
        b.bat_speed > 0.0,
        "a finite number > 0 m/s",
    )?;
    check(
        "batter.pivot",
        b.pivot,
        b.pivot >= 0.0,
        "a finite number >= 0 m (from the knob)",
    )?;
    check(
        "batter.bat_speed_at",
        b.bat_speed_at,
        b.bat_speed_at - b.pivot >= MIN_SWING_ARM,
        &format!("at least {MIN_SWING_ARM} m beyond batter.pivot (the swing's rate is bat_speed over that distance)"),
    )?;
    check(
        "batter.reference_moi",
        b.reference_moi,
        b.reference_moi > 0.0,
        "a finite number > 0 kg m^2",
    )?;
    check(
        "batter.exponent",
        b.exponent,
        (0.0..=1.0).contains(&b.exponent),
        "[0, 1]",
    )
}

/// The shortest distance from the swing's pivot to where its speed is given, m: the rate
/// `bat_speed / (bat_speed_at - pivot)` of a shorter arm is beyond any swing.
pub const MIN_SWING_ARM: f64 = 0.05;

/// The pitch block: a speed and two angles of a path that reaches the bat, with exactly
/// one of it and `batter.pitch_speed` giving the pitch.
fn check_pitch(spec: &CollisionSpec) -> Result<(), ModelError> {
    if let Some(p) = &spec.pitch {
        check(
            "pitch.speed",
            p.speed,
            p.speed >= 0.0,
            "a finite number >= 0 m/s",
        )?;
        let right_angle = std::f64::consts::FRAC_PI_2;
        for (path, angle) in [
            ("pitch.descent_angle", p.descent_angle),
            ("pitch.horizontal_angle", p.horizontal_angle),
        ] {
            check(path, angle, angle.abs() < right_angle, "(-pi/2, pi/2) rad")?;
        }
    }
    crate::collision::batter::pitch_along(spec).map(|_| ())
}

/// The flight's air: the ranges the flight model accepts.
fn check_flight(f: &crate::spec::FlightSpec) -> Result<(), ModelError> {
    check(
        "flight.height",
        f.height,
        (0.0..=10.0).contains(&f.height),
        "[0, 10] m",
    )?;
    check(
        "flight.wind_direction",
        f.wind_direction,
        f.wind_direction.abs() <= std::f64::consts::PI,
        "[-pi, pi] rad",
    )?;
    check(
        "flight.wind_speed",
        f.wind_speed,
        f.wind_speed.abs() <= 100.0,
        "[-100, 100] m/s",
    )?;
    let atmosphere = crate::flight::Atmosphere {
        temperature_k: f.temperature,
        sea_level_pressure_pa: f.pressure,
        elevation_m: f.elevation,
        relative_humidity: f.humidity,
        wind_m_s: [0.0; 3],
    };
    // the air's density, not only each field: dry air less its water vapour can be
    // negative (a pressure near 0), which would fail every flight
    atmosphere.air_density().map_err(|e| flight_field(e, f))?;
    Ok(())
}

/// A flight error named by the study's field.
fn flight_field(e: crate::flight::FlightError, f: &crate::spec::FlightSpec) -> ModelError {
    use crate::flight::FlightError;
    match e {
        FlightError::OutOfRange {
            name,
            value,
            allowed,
        } => {
            let path = match name {
                "atmosphere.temperature_k" => "flight.temperature",
                "atmosphere.sea_level_pressure_pa" => "flight.pressure",
                "atmosphere.elevation_m" => "flight.elevation",
                "atmosphere.relative_humidity" => "flight.humidity",
                _ => "flight",
            };
            out_of_range(path, value, allowed)
        }
        // dry air less its water vapour below zero: the pressure is far too low (weather
        // reports' pressures always exceed the vapour term)
        other => out_of_range("flight.pressure", f.pressure, &other.to_string()),
    }
}

/// The hoop mode: given (frequency and mass), or derived from the geometry (neither).
fn check_hoop(hoop: &crate::spec::HoopSpec, ball_mass: f64) -> Result<(), ModelError> {
    if hoop.from_geometry {
        for (path, v) in [("hoop.frequency", hoop.frequency), ("hoop.mass", hoop.mass)] {
            if let Some(v) = v {
                check(path, v, false, "unset (hoop.from_geometry derives it)")?;
            }
        }
        if let Some(r) = hoop.patch_radius {
            check("hoop.patch_radius", r, r > 0.0 && r <= 0.05, "(0, 0.05] m")?;
        }
        if let Some(c) = hoop.footprint_ratio {
            check("hoop.footprint_ratio", c, c > 0.0 && c <= 1.0, "(0, 1]")?;
            if hoop.patch_radius.is_some() {
                check(
                    "hoop.footprint_ratio",
                    c,
                    false,
                    "unset with hoop.patch_radius (a fixed patch has no footprint to scale)",
                )?;
            }
        }
        return Ok(());
    }
    for (path, v) in [("hoop.frequency", hoop.frequency), ("hoop.mass", hoop.mass)] {
        if v.is_none() {
            return Err(ModelError::Missing {
                path: path.into(),
                allowed: "this field is required (hoop.frequency and hoop.mass are both needed unless hoop.from_geometry: true)".into(),
            });
        }
    }
    let (lo, hi) = HOOP_FREQUENCY_RANGE;
    let f = hoop.frequency.unwrap_or(f64::NAN);
    check(
        "hoop.frequency",
        f,
        f >= lo && f <= hi,
        &format!("{lo} to {hi} Hz (required unless hoop.from_geometry)"),
    )?;
    let max_mass = HOOP_MASS_MAX_BALL_MASSES * ball_mass;
    let m = hoop.mass.unwrap_or(f64::NAN);
    check(
        "hoop.mass",
        m,
        m > 0.0 && m < max_mass,
        &format!("> 0 and < {max_mass} kg (10 ball masses; required unless hoop.from_geometry)"),
    )
}

/// The numerics the study may set.
fn check_numerics(numerics: &crate::spec::NumericsSpec) -> Result<(), ModelError> {
    if let Some(n) = numerics.segments {
        let (lo, hi) = (crate::bat::MIN_SEGMENTS, crate::bat::MAX_SEGMENTS);
        check(
            "numerics.segments",
            n as f64,
            (lo..=hi).contains(&n),
            &format!("[{lo}, {hi}]"),
        )?;
    }
    if let Some(dt) = numerics.dt {
        check("numerics.dt", dt, dt > 0.0, "(0, stability limit] s")?;
    }
    if let Some(b) = numerics.max_steps {
        check(
            "numerics.max_steps",
            b as f64,
            b >= 1,
            "a whole number >= 1",
        )?;
    }
    check_shell_numerics(numerics)
}

/// The shell's resolution: bounded, so that a study cannot ask for a solve without end.
fn check_shell_numerics(numerics: &crate::spec::NumericsSpec) -> Result<(), ModelError> {
    use crate::bat::barrel::{MAX_ELEMENTS, MAX_MODES_PER_WAVE, MAX_WAVE_NUMBER};
    if let Some(n) = numerics.shell_elements {
        let ok = (4..=MAX_ELEMENTS).contains(&n);
        check(
            "numerics.shell_elements",
            n as f64,
            ok,
            &format!("4 to {MAX_ELEMENTS}"),
        )?;
    }
    if let Some(waves) = &numerics.shell_wave_numbers {
        let distinct = waves
            .iter()
            .enumerate()
            .all(|(i, w)| !waves[..i].contains(w));
        let bad = waves.iter().find(|&&w| !(2..=MAX_WAVE_NUMBER).contains(&w));
        if waves.is_empty() || !distinct || bad.is_some() {
            let value = bad.map_or(waves.len() as f64, |&w| f64::from(w));
            check(
                "numerics.shell_wave_numbers",
                value,
                false,
                &format!("distinct wave numbers from 2 to {MAX_WAVE_NUMBER}, at least one"),
            )?;
        }
    }
    if let Some(n) = numerics.shell_modes_per_wave {
        let ok = (1..=MAX_MODES_PER_WAVE).contains(&n);
        check(
            "numerics.shell_modes_per_wave",
            n as f64,
            ok,
            &format!("1 to {MAX_MODES_PER_WAVE}"),
        )?;
    }
    Ok(())
}

/// Refuse a collision that provably needs more steps than its budget, without preparing
/// the bat: every run lasts at least `COAST_TIME` after separation, and its step is at most
/// the user's `numerics.dt`, or the default fraction of 1/ω where ω² = k_t/m uses the ball's
/// stiffest tangent alone (the bat and a hoop only make the real ω larger, the step smaller).
fn check_step_budget(spec: &CollisionSpec, length: f64) -> Result<(), ModelError> {
    use crate::collision::wave::{checked_step_budget, MODAL_STEP_FRACTION, VERLET_STEP_FRACTION};
    use crate::spec::Integrator;
    let dt = match spec.numerics.dt {
        Some(dt) => dt,
        None => {
            // The approach speed is at least this wherever the centre of mass lies.
            let approach = spec.ball.speed - spec.swing.omega.abs() * length;
            if approach <= 0.0 {
                return Ok(()); // no bound; the run's own budget check still holds
            }
            // A speed-dependent loop is bounded by its loading branch alone (the COR at the
            // real speed is not known here): the tangent, and so ω, is a lower bound.
            let mut loading_only = spec.ball.law.clone();
            if loading_only.kind == crate::spec::BallLawKind::SpeedDependent {
                loading_only.cor = 1.0;
                loading_only.cor_slope = Some(0.0);
                loading_only.cor_exponent = None;
                // a curved target softens the loading: bound it by the thinnest bat
                // surface (a 3-mm handle) so that ω stays a lower bound
                let thinnest =
                    crate::plausible::range_of(crate::plausible::PROFILE_RADIUS).map(|r| r.min);
                loading_only =
                    crate::ball::on_target(&loading_only, approach, spec.ball_radius(), thinnest).0;
            }
            let law = crate::ball::ContactLaw::new(&loading_only, approach);
            let omega = (law.max_tangent(spec.ball.mass, approach) / spec.ball.mass).sqrt();
            let fraction = match spec.numerics.integrator {
                Integrator::Modal => MODAL_STEP_FRACTION,
                // Verlet's limit is 2/ω with ω at least the ball's alone.
                Integrator::Verlet => VERLET_STEP_FRACTION * 2.0,
            };
            fraction / omega
        }
    };
    let cause = match (spec.numerics.dt, spec.ball.law.kind) {
        (Some(_), _) => "numerics.dt",
        (None, crate::spec::BallLawKind::PowerLaw) => "ball.law.k1",
        (None, _) => "ball.law.stiffness",
    };
    checked_step_budget(spec, dt, cause)?;
    Ok(())
}

/// Check a history request: positive interval, a bounded number of samples.
pub fn validate_history(request: &HistoryRequest) -> Result<(), ModelError> {
    check(
        "history.interval",
        request.interval,
        request.interval > 0.0,
        "a finite number > 0 s",
    )?;
    let duration = request.interval * request.n_samples as f64;
    check(
        "history duration",
        duration,
        duration <= crate::collision::wave::MAX_TIME,
        &format!("[0, {}] s", crate::collision::wave::MAX_TIME),
    )
}
