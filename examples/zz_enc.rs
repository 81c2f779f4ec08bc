// scratch: encode the bench's modal histories alone, one thread
use batstudy::bench::{curve_study_text, load_study, MODAL_HISTORY_BLOCK};
use batstudy::model::{prepare_bat, simulate};
use batstudy::store::chunks::{filtered_coordinates, filtered_whole};
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
    let hs: Vec<_> = (0..m.plan.n_points())
        .step_by(3)
        .map(|i| {
            simulate(&m.plan.point(i).unwrap().spec, &bat, Some(&req))
                .unwrap()
                .history
                .unwrap()
        })
        .collect();
    let n = hs.len() as f64;
    for _ in 0..3 {
        let t = Instant::now();
        let mut bytes = 0;
        for h in &hs {
            let q = &h.modal.coordinate;
            let modes = h.modal.modes;
            let ns = q.len() / modes;
            bytes += filtered_coordinates(q, modes, ns, 0..modes, 32, 1).len();
        }
        let a = t.elapsed().as_secs_f64() / n * 1e6;
        let t = Instant::now();
        let mut b2 = 0;
        for h in &hs {
            for v in [
                &h.force,
                &h.compression,
                &h.ball_velocity,
                &h.rigid_translation,
                &h.rigid_rotation,
            ] {
                let f: Vec<f32> = v.iter().map(|&x| x as f32).collect();
                b2 += filtered_whole(&f, 1).len();
            }
            b2 += filtered_whole(&h.modal.bat_load, 1).len();
        }
        let b = t.elapsed().as_secs_f64() / n * 1e6;
        println!(
            "coordinates {a:.1} us/pt ({:.0} B), scalars {b:.1} us/pt ({:.0} B)",
            bytes as f64 / n,
            b2 as f64 / n
        );
    }
}
