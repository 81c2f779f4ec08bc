//! The batted ball's flight (`model::flight`, docs/physics.md "Flight").
//!
//! References:
//! - Closed form: a projectile in a vacuum from height z₀ lands after
//!   T = (v_z + √(v_z² + 2g z₀))/g at v_h·T and peaks at z₀ + v_z²/(2g); from z₀ = 0 it
//!   lands at twice its apex time; with no drag mechanical energy is conserved, and the Magnus
//!   force (K·C_L·|v|·ω̂ × v, perpendicular to v) does no work, so lift alone conserves it too.
//! - Convergence: classical RK4 is fourth order: halving the step divides the error by 16.
//! - A. M. Nathan's trajectory calculator, TrajectoryCalculator-new-3D.xlsx
//!   (baseball.physics.illinois.edu), whose constants were fitted to about 80,000 Statcast
//!   batted balls of 2015 (Nathan, "Going deep on goin' deep", The Hardball Times, 6 April
//!   2016). Its output table for 103 mph, 27.5°, 2500 rpm backspin is published as the data
//!   set `Fly_ball` of the R package mosaicCalc (ProjectMOSAIC/mosaicCalc,
//!   inst/data_raw/Fly_ball/TrajectoryCalculator-new-3D.rds; documented in R/Fly_ball.R).
//! - Statcast "barrel" definition (MLB.com glossary): at 100 mph of exit velocity the barrel
//!   window is 24–33° of launch angle, widening with speed from 26–30° at 98 mph.
//! - Distance per mph: about 5 ft per mph at the best angle; HitTrax's algorithm gives
//!   5 ft 7 in per mph (Bat Digest, "How does exit speed affect distance", 3 July 2020).
//! - Coors Field: "most estimates [cite] an increase of 5 to 10% in distance"
//!   (P. Hamlington, CU Boulder, quoted by KDVR Denver); Chambers, Page & Zaidins,
//!   "Atmosphere, weather, and baseball: how much farther do baseballs really fly at Denver's
//!   Coors Field?", The Professional Geographer 55 (2003): about 6 % over the other National
//!   League parks, measured; R. K. Adair (quoted by
//!   the Hartford Courant, 15 Nov 1992): "about 10 percent farther".
//!
//! Each band was set from its source before the model's number was looked at.

use batstudy::model::flight::{
    fahrenheit_to_kelvin, fly, Atmosphere, Flight, FlightError, FlightOptions, Launch, NathanAero,
    DEFAULT_STEP_S, FOOT, GRAVITY, MPH, RPM,
};

fn deg(d: f64) -> f64 {
    d.to_radians()
}

fn vacuum_options(step_s: f64) -> FlightOptions {
    FlightOptions {
        aero: NathanAero::vacuum(),
        step_s,
        record_trajectory: true,
        ..FlightOptions::default()
    }
}

fn carry_ft(speed_mph: f64, angle_deg: f64, spin_rpm: f64, atm: &Atmosphere) -> f64 {
    let launch = Launch::new(speed_mph * MPH, deg(angle_deg), spin_rpm * RPM);
    fly(launch, atm, &FlightOptions::default()).unwrap().carry_m / FOOT
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

// ---------------------------------------------------------------- 1. vacuum

/// Closed-form projectile: carry, apex and hang time to 1e-9 relative, from 3 ft and from
/// the ground, for launch angles from −10° to 80°.
#[test]
fn vacuum_flight_matches_the_closed_form_projectile() {
    for (angle, height) in [
        (-10.0, 1.0),
        (5.0, 0.9144),
        (28.0, 0.9144),
        (45.0, 0.0),
        (80.0, 2.0),
    ] {
        let launch = Launch {
            height_m: height,
            ..Launch::new(45.0, deg(angle), 200.0)
        };
        let f = fly(launch, &Atmosphere::default(), &vacuum_options(0.05)).unwrap();
        let [_, vh, vz] = launch.velocity();
        let hang = (vz + (vz * vz + 2.0 * GRAVITY * height).sqrt()) / GRAVITY;
        let apex = if vz > 0.0 {
            height + vz * vz / (2.0 * GRAVITY)
        } else {
            height
        };
        assert!(
            relative(f.hang_time_s, hang) < 1e-9,
            "{angle}°: {} vs {hang}",
            f.hang_time_s
        );
        assert!(
            relative(f.carry_m, vh * hang) < 1e-9,
            "{angle}°: {} vs {}",
            f.carry_m,
            vh * hang
        );
        assert!(
            relative(f.apex_m, apex) < 1e-9,
            "{angle}°: {} vs {apex}",
            f.apex_m
        );
    }
}

/// Zero air density (no pressure, dry air) is a vacuum too, whatever the coefficients.
#[test]
fn zero_density_is_a_vacuum() {
    let atm = Atmosphere {
        sea_level_pressure_pa: 0.0,
        relative_humidity: 0.0,
        ..Atmosphere::default()
    };
    let launch = Launch::new(45.0, deg(30.0), 250.0);
    let f = fly(launch, &atm, &FlightOptions::default()).unwrap();
    let [_, vh, vz] = launch.velocity();
    let z0 = launch.height_m;
    let hang = (vz + (vz * vz + 2.0 * GRAVITY * z0).sqrt()) / GRAVITY;
    assert!(relative(f.carry_m, vh * hang) < 1e-9);
}

// ---------------------------------------------------------------- 2. convergence

/// Full drag + lift + spin decay: the carry error falls by about 16 per halving of the step
/// (RK4's fourth order), and at the default step (0.1 s) it is below 0.1 mm across exit
/// speeds 90–115 mph, launch angles 10–60° and spins 0–3000 rpm: why that is the default.
#[test]
fn rk4_carry_converges_at_fourth_order_and_the_default_step_is_within_a_tenth_of_a_millimetre() {
    let atm = Atmosphere::default();
    let carry_at = |launch: Launch, step_s: f64| {
        let opts = FlightOptions {
            step_s,
            ..FlightOptions::default()
        };
        fly(launch, &atm, &opts).unwrap().carry_m
    };
    let launch = Launch::new(103.0 * MPH, deg(28.0), 2500.0 * RPM);
    let reference = carry_at(launch, 0.2 / 64.0);
    let errors: Vec<f64> = [0.2, 0.1, 0.05]
        .iter()
        .map(|h| (carry_at(launch, *h) - reference).abs())
        .collect();
    println!("carry errors at 0.2, 0.1, 0.05 s: {errors:?} m");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!(
            (11.0..23.0).contains(&ratio),
            "errors {errors:?}: ratio {ratio}"
        );
    }
    for speed in [90.0, 100.0, 115.0] {
        for angle in [10.0, 25.0, 40.0, 60.0] {
            for spin in [0.0, 1500.0, 3000.0] {
                let launch = Launch::new(speed * MPH, deg(angle), spin * RPM);
                let error =
                    carry_at(launch, DEFAULT_STEP_S) - carry_at(launch, DEFAULT_STEP_S / 32.0);
                assert!(
                    error.abs() < 1e-4,
                    "{speed} mph {angle}° {spin} rpm: {error} m"
                );
            }
        }
    }
}

// ---------------------------------------------------------------- 3. published facts

/// Nathan's calculator's own output (mosaicCalc `Fly_ball`): 103 mph (its table starts at
/// 151.101 ft/s), 27.5°, 2500 rpm of pure backspin, from 3 ft, 2 ft in front of the plate;
/// 70 °F, 50 % RH, 29.92 inHg, 15 ft of elevation; τ = 30 s. Its table crosses z = 0 at
/// 421.49 ft from the plate (419.49 ft from contact) after 5.520 s and peaks at 92.04 ft.
/// Band, set beforehand: ±1 % on each. The equations are the same; what differs is the
/// workbook's first-order step of 0.01 s and its drag/lift factor K, 0.3 % larger than ρA/2m
/// (it converts kg/m³ to lb/ft³ with 0.06261 instead of 0.06243): each about a foot.
#[test]
fn nathan_calculator_fly_ball_103_mph_27_5_degrees_2500_rpm() {
    let atm = Atmosphere {
        temperature_k: fahrenheit_to_kelvin(70.0),
        sea_level_pressure_pa: 29.92 * 3386.389,
        elevation_m: 15.0 * FOOT,
        relative_humidity: 0.5,
        wind_m_s: [0.0; 3],
    };
    let launch = Launch::new(151.101 * FOOT, deg(27.5), 2500.0 * RPM);
    let f = fly(launch, &atm, &FlightOptions::default()).unwrap();
    let (carry, apex) = (f.carry_m / FOOT, f.apex_m / FOOT);
    println!(
        "carry {carry:.2} ft, hang {:.4} s, apex {apex:.2} ft",
        f.hang_time_s
    );
    assert!(
        relative(carry, 419.49) < 0.01,
        "carry {carry} ft vs 419.49 ft"
    );
    assert!(
        relative(f.hang_time_s, 5.520) < 0.01,
        "hang {} s vs 5.520 s",
        f.hang_time_s
    );
    assert!(relative(apex, 92.04) < 0.01, "apex {apex} ft vs 92.04 ft");
}

/// The angle of greatest carry, to 0.25°, at `speed_mph` and `spin_rpm` at sea level.
fn best_angle(speed_mph: f64, spin_rpm: f64) -> f64 {
    let atm = Atmosphere::default();
    let angles = (0..=120).map(|k| 15.0 + 0.25 * k as f64);
    angles
        .map(|a| (a, carry_ft(speed_mph, a, spin_rpm, &atm)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(a, _)| a)
        .unwrap_or(f64::NAN)
}

/// Statcast's barrel window at 100 mph is 24–33°: a 100-mph ball with typical backspin
/// (2000–2500 rpm) carries farthest inside it.
#[test]
fn best_launch_angle_at_100_mph_is_inside_the_statcast_barrel_window() {
    for spin in [2000.0, 2500.0] {
        let best = best_angle(100.0, spin);
        println!("{spin} rpm: best angle {best}°");
        assert!(
            (24.0..=33.0).contains(&best),
            "{spin} rpm: best angle {best}°"
        );
    }
}

/// About 5 ft of carry per mph of exit speed near the best angle at 100 mph (HitTrax:
/// 5 ft 7 in per mph). Band, set beforehand: 4.0–6.5 ft per mph.
#[test]
fn about_five_feet_per_mph_near_the_best_angle_at_100_mph() {
    let atm = Atmosphere::default();
    let spin = 2200.0;
    let angle = best_angle(100.0, spin);
    let slope = (carry_ft(101.0, angle, spin, &atm) - carry_ft(99.0, angle, spin, &atm)) / 2.0;
    println!("{slope:.2} ft per mph at {angle}°");
    assert!(
        (4.0..=6.5).contains(&slope),
        "{slope} ft per mph at {angle}°"
    );
}

/// Coors Field (about 1600 m): the same 103-mph, 28°, 2200-rpm ball carries 5–10 % farther
/// than at sea level in the same weather (band from the estimates quoted above).
#[test]
fn coors_field_adds_five_to_ten_percent_of_carry() {
    let sea = Atmosphere::default();
    let coors = Atmosphere {
        elevation_m: 1600.0,
        ..sea
    };
    let gain = carry_ft(103.0, 28.0, 2200.0, &coors) / carry_ft(103.0, 28.0, 2200.0, &sea) - 1.0;
    println!("Coors gain {:.2} %", 100.0 * gain);
    assert!(
        (0.05..=0.10).contains(&gain),
        "Coors gain {:.2} %",
        100.0 * gain
    );
}

// ---------------------------------------------------------------- 5. conservation, symmetry

fn energy_per_mass(sample_v: [f64; 3], z: f64) -> f64 {
    0.5 * (sample_v[0] * sample_v[0] + sample_v[1] * sample_v[1] + sample_v[2] * sample_v[2])
        + GRAVITY * z
}

fn largest_energy_drift(f: &Flight) -> f64 {
    let e0 = energy_per_mass(f.trajectory[0].velocity_m_s, f.trajectory[0].z_m);
    f.trajectory
        .iter()
        .map(|s| relative(energy_per_mass(s.velocity_m_s, s.z_m), e0))
        .fold(0.0, f64::max)
}

/// No drag, no lift: energy is constant along the whole recorded trajectory (to rounding:
/// RK4 is exact for constant acceleration). Lift alone does no work either, so energy stays
/// constant to the integrator's accuracy, and that drift shrinks about 16-fold per halving.
#[test]
fn energy_is_conserved_without_drag_with_or_without_lift() {
    let launch = Launch::new(45.0, deg(30.0), 2500.0 * RPM);
    let vacuum = fly(launch, &Atmosphere::default(), &vacuum_options(0.05)).unwrap();
    assert!(largest_energy_drift(&vacuum) < 1e-12);
    let lift_only = |step_s: f64| FlightOptions {
        aero: NathanAero {
            drag_scale: 0.0,
            ..NathanAero::default()
        },
        step_s,
        record_trajectory: true,
        ..FlightOptions::default()
    };
    let coarse = fly(launch, &Atmosphere::default(), &lift_only(0.05)).unwrap();
    let fine = fly(launch, &Atmosphere::default(), &lift_only(0.025)).unwrap();
    let (d1, d2) = (largest_energy_drift(&coarse), largest_energy_drift(&fine));
    println!("lift-only energy drift {d1:.3e} at 0.05 s, {d2:.3e} at 0.025 s");
    assert!(d1 < 1e-6 && d2 < d1 / 8.0, "{d1} {d2}");
}

/// Drag always takes energy: it falls monotonically along the trajectory.
#[test]
fn drag_only_loses_energy_at_every_step() {
    let opts = FlightOptions {
        aero: NathanAero {
            lift_scale: 0.0,
            ..NathanAero::default()
        },
        record_trajectory: true,
        ..FlightOptions::default()
    };
    let f = fly(
        Launch::new(45.0, deg(30.0), 0.0),
        &Atmosphere::default(),
        &opts,
    )
    .unwrap();
    let energies: Vec<f64> = f
        .trajectory
        .iter()
        .map(|s| energy_per_mass(s.velocity_m_s, s.z_m))
        .collect();
    assert!(energies.windows(2).all(|w| w[1] < w[0]));
}

/// From the ground in a vacuum the flight is symmetric: it lands at twice its apex time.
#[test]
fn vacuum_flight_from_the_ground_lands_at_twice_its_apex_time() {
    let launch = Launch {
        height_m: 0.0,
        ..Launch::new(40.0, deg(35.0), 0.0)
    };
    let f = fly(launch, &Atmosphere::default(), &vacuum_options(0.05)).unwrap();
    assert!(relative(f.hang_time_s, 2.0 * f.apex_time_s) < 1e-12);
    // The last recorded sample is the landing, on the ground.
    let last = f.trajectory.last().unwrap();
    assert!(last.z_m.abs() < 1e-9 && last.t_s == f.hang_time_s);
}

// ---------------------------------------------------------------- frame, wind, inputs

/// Pure backspin to ±φ of spray lands at mirror-image points (x → −x).
#[test]
fn spray_angle_mirrors_without_sidespin() {
    let atm = Atmosphere::default();
    let opts = FlightOptions::default();
    let at = |phi: f64| {
        let launch = Launch {
            spray_angle_rad: deg(phi),
            ..Launch::new(45.0, deg(28.0), 2000.0 * RPM)
        };
        fly(launch, &atm, &opts).unwrap()
    };
    let (right, left) = (at(20.0), at(-20.0));
    assert!(right.landing_m[0] > 0.0);
    assert!((right.landing_m[0] + left.landing_m[0]).abs() < 1e-9);
    assert!((right.landing_m[1] - left.landing_m[1]).abs() < 1e-9);
    assert!((right.carry_m - at(0.0).carry_m).abs() < 1e-9);
}

/// Positive sidespin curves the ball toward the left-field side (−x), as in the calculator.
#[test]
fn positive_sidespin_curves_toward_left_field() {
    let launch = Launch {
        sidespin_rad_s: 1000.0 * RPM,
        ..Launch::new(45.0, deg(28.0), 2000.0 * RPM)
    };
    let f = fly(launch, &Atmosphere::default(), &FlightOptions::default()).unwrap();
    assert!(f.landing_m[0] < -1.0, "{:?}", f.landing_m);
}

/// A tail wind to centre field carries the ball farther, a head wind less.
#[test]
fn wind_to_centre_field_helps_and_from_it_hurts() {
    let with_wind = |w: f64| {
        let atm = Atmosphere {
            wind_m_s: [0.0, w, 0.0],
            ..Atmosphere::default()
        };
        fly(
            Launch::new(45.0, deg(28.0), 2000.0 * RPM),
            &atm,
            &FlightOptions::default(),
        )
        .unwrap()
        .carry_m
    };
    let calm = with_wind(0.0);
    assert!(with_wind(4.47) > calm + 3.0 && with_wind(-4.47) < calm - 3.0);
}

/// The same input gives the same bits; no trajectory is kept unless asked for.
#[test]
fn flights_are_deterministic_and_record_only_on_request() {
    let launch = Launch::new(46.0, deg(27.0), 230.0);
    let opts = FlightOptions::default();
    let a = fly(launch, &Atmosphere::default(), &opts).unwrap();
    let b = fly(launch, &Atmosphere::default(), &opts).unwrap();
    assert_eq!(a, b);
    assert!(a.trajectory.is_empty() && a.trajectory.capacity() == 0);
}

/// NaN and out-of-range inputs are errors that name the field; a ball on the ground going
/// down lands at once.
#[test]
fn invalid_inputs_are_named_errors() {
    let atm = Atmosphere::default();
    let opts = FlightOptions::default();
    let nan_speed = Launch::new(f64::NAN, 0.5, 0.0);
    assert!(matches!(
        fly(nan_speed, &atm, &opts),
        Err(FlightError::OutOfRange {
            name: "launch.speed_m_s",
            ..
        })
    ));
    let bad_tau = FlightOptions {
        aero: NathanAero {
            spin_decay_tau_s: 0.0,
            ..NathanAero::default()
        },
        ..opts
    };
    assert!(fly(Launch::new(40.0, 0.5, 0.0), &atm, &bad_tau).is_err());
    let updraft = Atmosphere {
        wind_m_s: [0.0, 0.0, 60.0],
        ..atm
    };
    assert!(matches!(
        fly(Launch::new(40.0, 0.5, 0.0), &updraft, &opts),
        Err(FlightError::NoLanding { .. })
    ));
    let grounder = Launch {
        height_m: 0.0,
        ..Launch::new(40.0, deg(-5.0), 0.0)
    };
    let f = fly(grounder, &atm, &opts).unwrap();
    assert_eq!((f.carry_m, f.hang_time_s), (0.0, 0.0));
}

// ---------------------------------------------------------------- cost

/// Cost per flight (not a timed assertion): `cargo test --release --test physics_flight --
/// --ignored --nocapture cost_per_flight`.
#[test]
#[ignore]
fn cost_per_flight() {
    let atm = Atmosphere::default();
    let opts = FlightOptions::default();
    let mut launches = Vec::new();
    for speed in [90.0, 95.0, 100.0, 105.0, 110.0, 115.0] {
        for angle in [10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0] {
            for spin in [0.0, 1000.0, 2000.0, 3000.0] {
                launches.push(Launch::new(speed * MPH, deg(angle), spin * RPM));
            }
        }
    }
    let rounds = 200;
    let start = std::time::Instant::now();
    let mut total = 0.0;
    for _ in 0..rounds {
        for launch in &launches {
            total += fly(*launch, &atm, &opts).unwrap().carry_m;
        }
    }
    let per_flight = start.elapsed().as_secs_f64() / (rounds * launches.len()) as f64;
    println!(
        "{:.2} µs per flight (checksum {total:.3})",
        per_flight * 1e6
    );
}
