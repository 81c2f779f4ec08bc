//! The lowest eigenpairs of K x = λ M x for symmetric banded K (positive definite) and M
//! (positive semi-definite) by subspace iteration (Bathe & Wilson 1972; Bathe, "Finite
//! Element Procedures", 2nd ed. 2014, §11.6): K X̄ = M X, the Ritz problem of X̄, repeat.
//! The shell's matrices have a half-bandwidth of 11 and a few hundred rows; a band
//! Cholesky of K once, then a few dozen sweeps of O(n·b) each, where a dense solver is
//! O(n³). Pure sequential arithmetic: the same bits on every run.

use nalgebra::{DMatrix, SymmetricEigen};

use crate::error::ModelError;
use crate::xorshift;

/// A symmetric band matrix: row i holds a(i, i..=i + b).
#[derive(Debug, Clone)]
pub struct Band {
    pub n: usize,
    pub b: usize,
    data: Vec<f64>,
}

impl Band {
    pub fn zeros(n: usize, b: usize) -> Self {
        Band {
            n,
            b,
            data: vec![0.0; n * (b + 1)],
        }
    }

    /// Add v to a(i, j) (and so to a(j, i)); only one of the two is to be added.
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let (r, c) = if i <= j { (i, j) } else { (j, i) };
        debug_assert!(c - r <= self.b);
        self.data[r * (self.b + 1) + (c - r)] += v;
    }

    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (r, c) = if i <= j { (i, j) } else { (j, i) };
        if c - r > self.b {
            return 0.0;
        }
        self.data[r * (self.b + 1) + (c - r)]
    }

    fn set(&mut self, i: usize, j: usize, v: f64) {
        let (r, c) = if i <= j { (i, j) } else { (j, i) };
        self.data[r * (self.b + 1) + (c - r)] = v;
    }

    /// Remove dof i from the problem: its row and column cleared, the diagonal `diag`.
    pub fn hold(&mut self, i: usize, diag: f64) {
        let lo = i.saturating_sub(self.b);
        let hi = (i + self.b).min(self.n - 1);
        for j in lo..=hi {
            self.set(i, j, 0.0);
        }
        self.set(i, i, diag);
    }

    /// y = A x.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        let w = self.b + 1;
        y.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..self.n {
            let row = &self.data[i * w..i * w + w];
            let hi = (self.n - i).min(w);
            let mut acc = row[0] * x[i];
            for d in 1..hi {
                acc += row[d] * x[i + d];
                y[i + d] += row[d] * x[i];
            }
            y[i] += acc;
        }
    }

    /// Every entry times `factor`.
    pub fn scale(&mut self, factor: f64) {
        self.data.iter_mut().for_each(|v| *v *= factor);
    }

    /// Solve A x = f for a positive definite A (`None` if it is not): a band Cholesky and
    /// two triangular sweeps.
    pub fn solve_positive(&self, f: &[f64]) -> Option<Vec<f64>> {
        let u = self.cholesky()?;
        let mut x = f.to_vec();
        u.solve(&mut x);
        Some(x)
    }

    /// The band Cholesky factor of a positive definite matrix (`None` if it is not), for
    /// [`Self::solve_factored`].
    pub fn factor(&self) -> Option<Band> {
        self.cholesky()
    }

    /// Solve A x = f in place, `self` being A's [`Self::factor`].
    pub fn solve_factored(&self, x: &mut [f64]) {
        self.solve(x);
    }

    /// The dense matrix (tests, small problems).
    pub fn to_dense(&self) -> DMatrix<f64> {
        DMatrix::from_fn(self.n, self.n, |i, j| self.get(i, j))
    }

    /// The band Cholesky factor: row i of Lᵀ stored as row i (U = Lᵀ, upper band).
    fn cholesky(&self) -> Option<Band> {
        let mut u = self.clone();
        for i in 0..self.n {
            let hi = (i + self.b).min(self.n - 1);
            let mut d = u.get(i, i);
            for k in i.saturating_sub(self.b)..i {
                d -= u.get(k, i).powi(2);
            }
            if d.is_nan() || d <= 0.0 {
                return None;
            }
            let d = d.sqrt();
            u.set(i, i, d);
            for j in i + 1..=hi {
                let mut s = u.get(i, j);
                for k in j.saturating_sub(self.b)..i {
                    s -= u.get(k, i) * u.get(k, j);
                }
                u.set(i, j, s / d);
            }
        }
        Some(u)
    }

    /// Solve Uᵀ U x = y in place, U from `cholesky`.
    fn solve(&self, x: &mut [f64]) {
        let w = self.b + 1;
        // Uᵀ z = y: column i of U is row i of Uᵀ; push each solved z_i into the rest
        for i in 0..self.n {
            let row = &self.data[i * w..i * w + w];
            x[i] /= row[0];
            let xi = x[i];
            for d in 1..(self.n - i).min(w) {
                x[i + d] -= row[d] * xi;
            }
        }
        for i in (0..self.n).rev() {
            let row = &self.data[i * w..i * w + w];
            let mut s = x[i];
            for d in 1..(self.n - i).min(w) {
                s -= row[d] * x[i + d];
            }
            x[i] = s / row[0];
        }
    }
}

/// Sweeps allowed before giving up.
const MAX_SWEEPS: usize = 400;
/// Relative change of every wanted eigenvalue between sweeps that ends the iteration.
const TOLERANCE: f64 = 1e-13;

/// The `count` lowest eigenvalues, ascending, and their M-orthonormal vectors (columns).
pub fn lowest(k: &Band, m: &Band, count: usize) -> Result<(Vec<f64>, DMatrix<f64>), ModelError> {
    let n = k.n;
    let p = (2 * count).max(count + 8).min(n);
    let u = k.cholesky().ok_or(ModelError::Unsupported(
        "the shell's stiffness matrix is not positive definite",
    ))?;
    let mut x = start_vectors(k, m, p);
    let mut previous = vec![f64::INFINITY; count];
    let mut mx = vec![0.0; n];
    for _ in 0..MAX_SWEEPS {
        // K X̄ = M X, column by column
        let mut xb = DMatrix::zeros(n, p);
        let mut kx = DMatrix::zeros(n, p);
        for c in 0..p {
            let col: Vec<f64> = x.column(c).iter().copied().collect();
            m.mul(&col, &mut mx);
            kx.column_mut(c).copy_from_slice(&mx);
            u.solve(&mut mx);
            xb.column_mut(c).copy_from_slice(&mx);
        }
        let mut mxb = DMatrix::zeros(n, p);
        for c in 0..p {
            let col: Vec<f64> = xb.column(c).iter().copied().collect();
            m.mul(&col, &mut mx);
            mxb.column_mut(c).copy_from_slice(&mx);
        }
        // the Ritz problem: X̄ᵀ K X̄ = X̄ᵀ M X (as K X̄ = M X), X̄ᵀ M X̄
        let kr = xb.transpose() * &kx;
        let mr = xb.transpose() * &mxb;
        let (values, q) = ritz(kr, mr)?;
        x = &xb * q;
        let done = (0..count).all(|i| (values[i] - previous[i]).abs() <= TOLERANCE * values[i]);
        previous.copy_from_slice(&values[..count]);
        if done {
            return Ok((values[..count].to_vec(), x.columns(0, count).into_owned()));
        }
    }
    Err(ModelError::Unsupported(
        "the shell's modes did not converge (subspace iteration)",
    ))
}

/// Bathe's start: M's diagonal, unit vectors at the dofs of largest m_ii/k_ii, and one
/// pseudo-random vector.
fn start_vectors(k: &Band, m: &Band, p: usize) -> DMatrix<f64> {
    let n = k.n;
    let mut x = DMatrix::zeros(n, p);
    for i in 0..n {
        x[(i, 0)] = m.get(i, i);
    }
    let mut ratio: Vec<(f64, usize)> = (0..n).map(|i| (m.get(i, i) / k.get(i, i), i)).collect();
    ratio.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    for c in 1..p - 1 {
        x[(ratio[c - 1].1, c)] = 1.0;
    }
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    for i in 0..n {
        x[(i, p - 1)] = (xorshift::next(&mut state) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
    }
    x
}

/// The p×p problem K_r q = λ M_r q: eigenvalues ascending, M_r-orthonormal vectors.
fn ritz(kr: DMatrix<f64>, mr: DMatrix<f64>) -> Result<(Vec<f64>, DMatrix<f64>), ModelError> {
    let mr = (&mr + mr.transpose()) * 0.5;
    let chol = mr
        .cholesky()
        .ok_or(ModelError::Unsupported("the shell's Ritz basis lost rank"))?;
    let l = chol.l();
    let l_inv = l
        .clone()
        .try_inverse()
        .ok_or(ModelError::Unsupported("the shell's Ritz basis lost rank"))?;
    let a = &l_inv * kr * l_inv.transpose();
    let e = SymmetricEigen::new((&a + a.transpose()) * 0.5);
    let mut order: Vec<usize> = (0..e.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| e.eigenvalues[i].total_cmp(&e.eigenvalues[j]));
    let vectors = l_inv.transpose() * &e.eigenvectors;
    let q = DMatrix::from_fn(vectors.nrows(), order.len(), |r, c| vectors[(r, order[c])]);
    Ok((order.iter().map(|&i| e.eigenvalues[i]).collect(), q))
}
