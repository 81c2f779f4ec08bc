//! A table of batted-ball flights as CSV on standard output, for the comparison with the
//! Python package pybaseball's port of Nathan's trajectory calculator
//! (tests/python/test_flight_reference.py runs `cargo run --example flight_table`).
//!
//! Grid: exit speed 90, 100, 110, 115 mph; launch angle 10, 20, 25, 30, 40°; backspin 1,
//! 1000, 2000, 3000 rpm (1 rpm stands for none: pybaseball divides the Magnus force by the
//! spin rate). Everything else is the default: sea level, 70 °F, 50 % RH, 29.92 inHg, no
//! wind, contact 3 ft up, spin decay τ = 30 s. Speeds are converted as the calculator and
//! pybaseball do, 1.467 ft/s per mph, so both start from the same velocity; the `speed_m_s`
//! column is the speed actually flown.

use batstudy::model::flight::{fly, Atmosphere, FlightOptions, Launch, FOOT, RPM};

/// The calculator's (and pybaseball's) mph to ft/s factor.
const CALCULATOR_FT_S_PER_MPH: f64 = 1.467;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let atm = Atmosphere::default();
    let opts = FlightOptions::default();
    println!("speed_m_s,launch_deg,backspin_rpm,spin_decay_tau_s,carry_m,apex_m,hang_time_s");
    for speed_mph in [90.0, 100.0, 110.0, 115.0] {
        for angle_deg in [10.0, 20.0, 25.0, 30.0, 40.0] {
            for spin_rpm in [1.0, 1000.0, 2000.0, 3000.0] {
                let speed = speed_mph * CALCULATOR_FT_S_PER_MPH * FOOT;
                let launch = Launch::new(speed, f64::to_radians(angle_deg), spin_rpm * RPM);
                let f = fly(launch, &atm, &opts)?;
                println!(
                    "{speed:.17e},{angle_deg},{spin_rpm},{},{:.17e},{:.17e},{:.17e}",
                    opts.aero.spin_decay_tau_s, f.carry_m, f.apex_m, f.hang_time_s
                );
            }
        }
    }
    Ok(())
}
