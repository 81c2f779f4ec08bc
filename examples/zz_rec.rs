// scratch: one thread, the bench's modal study: compute with and without the history
use batstudy::bench::{curve_study_text, load_study, MODAL_HISTORY_BLOCK};
use batstudy::model::{prepare_bat, simulate_with_diagnostics};
use std::time::Instant;
fn main() {
    let m = load_study(
        &curve_study_text("bench-history-modal", 40, MODAL_HISTORY_BLOCK),
        "history-modal",
    )
    .unwrap();
    let p0 = m.plan.point(0).unwrap().spec;
    let bat = prepare_bat(&p0.bat, &p0.numerics).unwrap();
    let req = m.history_request(1.0).unwrap();
    let specs: Vec<_> = (0..m.plan.n_points())
        .map(|i| m.plan.point(i).unwrap().spec)
        .collect();
    let (mut steps, mut modes, mut dt) = (0usize, 0usize, 0.0);
    for (i, s) in specs.iter().enumerate() {
        let (_, d) = simulate_with_diagnostics(s, &bat, None).unwrap();
        steps += d.steps;
        modes += d.modes;
        dt = d.dt;
        if i % 400 == 0 {
            println!(
                "point {i}: steps {} modes {} dt {:.3e}",
                d.steps, d.modes, d.dt
            );
        }
    }
    let n = specs.len();
    println!(
        "mean steps {:.0}, modes {:.1}, dt {dt:.3e}",
        steps as f64 / n as f64,
        modes as f64 / n as f64
    );
    for _ in 0..3 {
        let t = Instant::now();
        for s in &specs {
            simulate_with_diagnostics(s, &bat, None).unwrap();
        }
        let a = t.elapsed().as_secs_f64() / n as f64 * 1e6;
        let t = Instant::now();
        let mut hs = 0usize;
        for s in &specs {
            let (o, d) = simulate_with_diagnostics(s, &bat, Some(&req)).unwrap();
            hs += d.steps;
            std::hint::black_box(o);
        }
        let b = t.elapsed().as_secs_f64() / n as f64 * 1e6;
        println!(
            "summary {a:.1} us/pt, with history {b:.1} us/pt (steps {:.0})",
            hs as f64 / n as f64
        );
    }
}
