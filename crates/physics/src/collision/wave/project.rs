//! Displacements from modal coordinates: y_i = Σ_j q_j ψ_j(z_i) for every requested z at
//! once, the inner loop of a history's displacement samples.
//!
//! Each y_i is summed in the order of j, one add after one multiply, as a plain loop would:
//! the lanes of a vector register hold different z, never parts of one sum, so the width of
//! the registers (SSE2 everywhere, AVX where the CPU has it) does not change a bit of the
//! result. No fused multiply-add is used, for the same reason.

/// `y[i] = start + Σ_j q[j] · shape_by_mode[j · y.len() + i]`, summed in the order of j.
pub(super) fn project(q: &[f64], shape_by_mode: &[f64], y: &mut [f64], start: f64) {
    debug_assert_eq!(shape_by_mode.len(), q.len() * y.len());
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU has AVX (checked just above).
        unsafe { project_avx(q, shape_by_mode, y, start) };
        return;
    }
    project_blocks::<16>(q, shape_by_mode, y, start);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn project_avx(q: &[f64], shape_by_mode: &[f64], y: &mut [f64], start: f64) {
    project_blocks::<32>(q, shape_by_mode, y, start);
}

/// Blocks of `B` positions whose sums stay in registers over all the modes: enough
/// independent sums to hide the adds' latency (one block of 8 was latency-bound).
#[inline(always)]
fn project_blocks<const B: usize>(q: &[f64], shape_by_mode: &[f64], y: &mut [f64], start: f64) {
    let nz = y.len();
    for (b, yb) in y.chunks_mut(B).enumerate() {
        let i0 = b * B;
        if yb.len() == B {
            let mut acc = [start; B];
            for (j, &qj) in q.iter().enumerate() {
                let row = &shape_by_mode[j * nz + i0..j * nz + i0 + B];
                for (a, &psi) in acc.iter_mut().zip(row) {
                    *a += psi * qj;
                }
            }
            yb.copy_from_slice(&acc);
        } else {
            yb.fill(start);
            for (j, &qj) in q.iter().enumerate() {
                let row = &shape_by_mode[j * nz + i0..j * nz + i0 + yb.len()];
                for (a, &psi) in yb.iter_mut().zip(row) {
                    *a += psi * qj;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Every position's sum is the plain left-to-right sum, to the bit, whatever the block
    // and register width (IEEE 754: the same operations in the same order).
    #[test]
    fn sums_are_the_plain_ordered_sums() {
        for (modes, nz) in [(21, 85), (3, 7), (40, 33), (1, 64)] {
            let q: Vec<f64> = (0..modes)
                .map(|j| ((j * 7 + 3) as f64).sin() * 1e-3)
                .collect();
            let shapes: Vec<f64> = (0..modes * nz)
                .map(|k| ((k * 13 + 1) as f64).cos() / (1.0 + k as f64))
                .collect();
            let plain: Vec<f64> = (0..nz)
                .map(|i| (0..modes).map(|j| q[j] * shapes[j * nz + i]).sum())
                .collect();
            let start: f64 = std::iter::empty::<f64>().sum();
            let mut y = vec![f64::NAN; nz];
            project(&q, &shapes, &mut y, start);
            assert_eq!(
                y.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                plain.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
            let mut y16 = vec![f64::NAN; nz];
            project_blocks::<16>(&q, &shapes, &mut y16, start);
            assert_eq!(y16, y);
        }
    }
}
