//! CMA-ES, the covariance matrix adaptation evolution strategy, as Hansen's tutorial states
//! it (N. Hansen, "The CMA Evolution Strategy: A Tutorial", arXiv:1604.00772, 2016; the
//! (μ/μ_w, λ) strategy of its Fig. 6 with the default parameters of its Table 1 and positive
//! recombination weights). Each generation samples λ designs about the mean, ranks them, and
//! moves the mean, the step size and the covariance toward what ranked best: a search for
//! rugged or noisy objectives, where a simplex stalls, at the price of more evaluations.
//!
//! Why our own: the strategy is 150 lines over nalgebra's symmetric eigensolver, and its
//! random numbers are a seeded generator of ours, so a search asks for the same designs in
//! the same order on every run and machine (its record replays as Nelder–Mead's does). No
//! maintained CMA-ES crate offered both.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

/// The strategy's state in the scaled design space ([0, 1] per variable inside the bounds).
pub struct Cmaes {
    mean: DVector<f64>,
    sigma: f64,
    cov: DMatrix<f64>,
    /// B and D of C = B D² Bᵀ.
    basis: DMatrix<f64>,
    scales: DVector<f64>,
    path_sigma: DVector<f64>,
    path_cov: DVector<f64>,
    p: Parameters,
    rng: Normal,
    generation: usize,
}

/// Table 1's defaults for dimension n.
struct Parameters {
    lambda: usize,
    weights: Vec<f64>,
    mu_eff: f64,
    c_sigma: f64,
    d_sigma: f64,
    c_c: f64,
    c_1: f64,
    c_mu: f64,
    /// E‖N(0, I)‖.
    chi_n: f64,
}

impl Parameters {
    fn new(n: usize) -> Self {
        let nf = n as f64;
        let lambda = 4 + (3.0 * nf.ln()).floor() as usize;
        let mu = lambda / 2;
        let raw: Vec<f64> = (1..=mu)
            .map(|i| ((lambda as f64 + 1.0) / 2.0).ln() - (i as f64).ln())
            .collect();
        let sum: f64 = raw.iter().sum();
        let weights: Vec<f64> = raw.iter().map(|w| w / sum).collect();
        let mu_eff = 1.0 / weights.iter().map(|w| w * w).sum::<f64>();
        let c_sigma = (mu_eff + 2.0) / (nf + mu_eff + 5.0);
        let d_sigma = 1.0 + 2.0 * (((mu_eff - 1.0) / (nf + 1.0)).sqrt() - 1.0).max(0.0) + c_sigma;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let c_1 = 2.0 / ((nf + 1.3).powi(2) + mu_eff);
        let c_mu =
            (1.0 - c_1).min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0).powi(2) + mu_eff));
        let chi_n = nf.sqrt() * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
        Parameters {
            lambda,
            weights,
            mu_eff,
            c_sigma,
            d_sigma,
            c_c,
            c_1,
            c_mu,
            chi_n,
        }
    }
}

/// Standard normal numbers from a seeded SplitMix64 (Steele, Lea & Flood 2014) by the
/// Box–Muller transform: the same sequence on every machine.
struct Normal {
    state: u64,
    spare: Option<f64>,
}

impl Normal {
    fn uniform(&mut self) -> f64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        // in (0, 1]: the logarithm below never sees 0
        ((z >> 11) + 1) as f64 / (1u64 << 53) as f64
    }

    fn next(&mut self) -> f64 {
        if let Some(x) = self.spare.take() {
            return x;
        }
        let (u1, u2) = (self.uniform(), self.uniform());
        let r = (-2.0 * u1.ln()).sqrt();
        let t = std::f64::consts::TAU * u2;
        self.spare = Some(r * t.sin());
        r * t.cos()
    }
}

impl Cmaes {
    /// A strategy about `start` with step size `sigma` (in the scaled space), seeded.
    pub fn new(start: &[f64], sigma: f64, seed: u64) -> Self {
        let n = start.len();
        Cmaes {
            mean: DVector::from_column_slice(start),
            sigma,
            cov: DMatrix::identity(n, n),
            basis: DMatrix::identity(n, n),
            scales: DVector::from_element(n, 1.0),
            path_sigma: DVector::zeros(n),
            path_cov: DVector::zeros(n),
            p: Parameters::new(n),
            rng: Normal {
                state: seed,
                spare: None,
            },
            generation: 0,
        }
    }

    /// Designs per generation (λ).
    pub fn population(&self) -> usize {
        self.p.lambda
    }

    /// The step size times the largest axis of the covariance: how far the search still
    /// looks (in the scaled space).
    pub fn spread(&self) -> f64 {
        self.sigma * self.scales.max()
    }

    /// The next generation's λ designs: m + σ B D z, z ~ N(0, I).
    pub fn ask(&mut self) -> Vec<Vec<f64>> {
        (0..self.p.lambda)
            .map(|_| {
                let z = DVector::from_fn(self.mean.len(), |_, _| self.rng.next());
                let y = &self.basis * self.scales.component_mul(&z);
                (&self.mean + self.sigma * y).iter().copied().collect()
            })
            .collect()
    }

    /// Take the generation's designs and their costs (lower is better): move the mean, the
    /// evolution paths, the covariance and the step size (the tutorial's eqs. 41–47).
    pub fn tell(&mut self, designs: &[Vec<f64>], costs: &[f64]) {
        let n = self.mean.len() as f64;
        let mut order: Vec<usize> = (0..designs.len()).collect();
        order.sort_by(|&a, &b| costs[a].total_cmp(&costs[b]));
        let old = self.mean.clone();
        let steps: Vec<DVector<f64>> = order[..self.p.weights.len()]
            .iter()
            .map(|&i| (DVector::from_column_slice(&designs[i]) - &old) / self.sigma)
            .collect();
        let step = steps
            .iter()
            .zip(&self.p.weights)
            .fold(DVector::zeros(old.len()), |acc, (y, w)| acc + y * *w);
        self.mean = &old + self.sigma * &step;
        self.generation += 1;
        let h_sigma = self.update_paths(&step, n);
        self.update_covariance(&steps, h_sigma);
        self.sigma *= ((self.p.c_sigma / self.p.d_sigma)
            * (self.path_sigma.norm() / self.p.chi_n - 1.0))
            .exp();
        self.decompose();
    }

    /// The evolution paths p_σ (through C^(-1/2)) and p_c (stalled while p_σ is long: the
    /// returned h_σ is false then).
    fn update_paths(&mut self, step: &DVector<f64>, n: f64) -> bool {
        let p = &self.p;
        let inv_sqrt = &self.basis
            * DMatrix::from_diagonal(&self.scales.map(|d| 1.0 / d))
            * self.basis.transpose();
        self.path_sigma = (1.0 - p.c_sigma) * &self.path_sigma
            + (p.c_sigma * (2.0 - p.c_sigma) * p.mu_eff).sqrt() * inv_sqrt * step;
        let norm = self.path_sigma.norm()
            / (1.0 - (1.0 - p.c_sigma).powi(2 * self.generation as i32)).sqrt();
        let h_sigma = norm < (1.4 + 2.0 / (n + 1.0)) * p.chi_n;
        self.path_cov = (1.0 - p.c_c) * &self.path_cov
            + if h_sigma {
                (p.c_c * (2.0 - p.c_c) * p.mu_eff).sqrt() * step
            } else {
                DVector::zeros(step.len())
            };
        h_sigma
    }

    /// C ← (1 + c₁ δ(h_σ) − c₁ − c_μ) C + c₁ p_c p_cᵀ + c_μ Σ w_i y_i y_iᵀ, δ(h_σ) =
    /// (1 − h_σ) c_c (2 − c_c) making up for the stalled path's missing variance.
    fn update_covariance(&mut self, steps: &[DVector<f64>], h_sigma: bool) {
        let p = &self.p;
        let delta = if h_sigma { 0.0 } else { p.c_c * (2.0 - p.c_c) };
        let rank_one = &self.path_cov * self.path_cov.transpose();
        let rank_mu = steps.iter().zip(&p.weights).fold(
            DMatrix::zeros(self.cov.nrows(), self.cov.ncols()),
            |acc, (y, w)| acc + *w * y * y.transpose(),
        );
        self.cov = (1.0 + p.c_1 * delta - p.c_1 - p.c_mu) * &self.cov
            + p.c_1 * rank_one
            + p.c_mu * rank_mu;
    }

    /// B and D from C (made exactly symmetric first).
    fn decompose(&mut self) {
        let sym = 0.5 * (&self.cov + self.cov.transpose());
        let e = SymmetricEigen::new(sym.clone());
        self.cov = sym;
        self.basis = e.eigenvectors;
        self.scales = e.eigenvalues.map(|v| v.max(1e-300).sqrt());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the sphere and on an ill-conditioned ellipsoid (axes 1 to 1000) in 5 dimensions the
    /// strategy converges to the minimum (the tutorial's behaviour: the covariance learns
    /// the ellipsoid's axes; Hansen's reference runs solve both to 1e-10 in a few thousand
    /// evaluations).
    #[test]
    fn converges_on_the_sphere_and_an_ellipsoid() {
        for scale in [1.0f64, 1000.0] {
            let f = |x: &[f64]| {
                x.iter()
                    .enumerate()
                    .map(|(i, &xi)| scale.powf(i as f64 / 4.0) * (xi - 0.3).powi(2))
                    .sum::<f64>()
            };
            let mut es = Cmaes::new(&[0.8; 5], 0.3, 7);
            let mut evaluations = 0;
            while es.spread() > 1e-9 && evaluations < 20_000 {
                let xs = es.ask();
                let costs: Vec<f64> = xs.iter().map(|x| f(x)).collect();
                evaluations += xs.len();
                es.tell(&xs, &costs);
            }
            let best = es.mean.iter().map(|&m| (m - 0.3).abs()).fold(0.0, f64::max);
            assert!(best < 1e-6, "scale {scale}: {best} after {evaluations}");
            assert!(
                evaluations < 10_000,
                "scale {scale}: {evaluations} evaluations"
            );
        }
    }
}
