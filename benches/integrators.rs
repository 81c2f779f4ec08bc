//! One collision of the base case (R161, linear-hysteresis ball, 40 m/s, z = 0.70 m, ω = 0)
//! on one thread: the modal integrator (the default) against plain velocity Verlet at
//! 0.9 × its stability limit. Their accuracy against a converged reference (modal, dt/16,
//! twice the segments) is printed first: the speed-up only counts at equal accuracy
//! (`tests/bench_quick.rs` asserts both within 1e-4).
//!
//!     cargo bench --bench integrators

use batstudy::bench::{base_spec, dev};
use batstudy::model::{prepare_bat, simulate, PreparedBat};
use divan::Bencher;

fn main() {
    if !std::env::args().any(|a| a == "--list") {
        print_accuracy();
    }
    divan::main();
}

fn print_accuracy() {
    let a = dev::integrator_accuracy().expect("the base case runs");
    println!(
        "reference (modal, dt {:.3} µs, {} segments): exit speed {:.7} m/s",
        a.reference_dt * 1e6,
        a.reference_segments,
        a.reference_exit_speed
    );
    for (name, f) in [("modal ", &a.modal), ("verlet", &a.verlet)] {
        println!(
            "{name}: exit speed {:.7} m/s, relative error {:.2e}, dt {:.3} µs, {} steps, {} \
             modes/nodes",
            f.exit_speed,
            f.rel_error,
            f.dt * 1e6,
            f.steps,
            f.modes
        );
    }
}

fn base_bat() -> PreparedBat {
    let spec = base_spec(0.70);
    prepare_bat(&spec.bat, &spec.numerics).expect("the base case's bat")
}

/// The default integrator: the beam's modes advanced exactly between contact steps.
#[divan::bench(sample_count = 1000)]
fn modal(bencher: Bencher) {
    let (spec, bat) = (base_spec(0.70), base_bat());
    bencher.bench_local(|| simulate(&spec, &bat, None).expect("modal").exit_speed);
}

/// Velocity Verlet on every node, its step set by the highest beam mode.
#[divan::bench(sample_count = 30)]
fn verlet(bencher: Bencher) {
    let (spec, bat) = (dev::verlet_spec(&base_spec(0.70)), base_bat());
    bencher.bench_local(|| simulate(&spec, &bat, None).expect("verlet").exit_speed);
}
