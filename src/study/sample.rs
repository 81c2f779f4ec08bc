//! The `sample` block: parameters drawn from distributions instead of a grid,
//! one dimension (`sample`) whose coordinates are the drawn values.
//!
//! The design is quasi-random: Owen-scrambled Sobol points (Burley 2020, the `sobol_burley`
//! crate), seeded, one Sobol dimension per parameter. Each point's uniform coordinates are
//! taken to normal scores, correlated through the Cholesky factor of the correlation matrix
//! (a Gaussian copula: `rho` is the correlation of the normal scores, the Pearson correlation
//! for two normal parameters, that of the logarithms for two lognormal ones), and taken back
//! to each parameter's distribution by its quantile function. Without correlations the
//! points are the Sobol points themselves, mapped one coordinate at a time.
//!
//! `method: saltelli` is Saltelli's design for first- and total-order Sobol indices
//! (Saltelli 2002; Saltelli et al. 2010, Comput. Phys. Commun. 181, 259): two matrices A and
//! B of n points each from 2d Sobol dimensions, and for each point i the rows A_i, A_i with
//! its k-th coordinate from B_i (k = 1 … d), then B_i: n(d + 2) points, in the order SALib's
//! `sobol.analyze` reads them (second-order terms left out). Its estimators need independent
//! inputs: no correlations.

use super::source::{keys, Seg};
use indexmap::IndexMap;
use schemars::JsonSchema;
use serde::Deserialize;

/// Most points a `sample` block may draw (the Sobol sequence's length, 2^16).
pub const MAX_SAMPLES: usize = 1 << 16;
/// Most parameters a `sample` block may draw (the Sobol sequence's dimensions).
pub const MAX_SAMPLE_PARAMS: usize = sobol_burley::NUM_DIMENSIONS as usize;

/// Parameters drawn from distributions: one dimension (default name `sample`) of `n`
/// points, each parameter's drawn values its coordinates.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SampleBlock {
    /// Dimension name. Default `sample`.
    #[serde(default)]
    pub name: Option<String>,
    /// Number of points, 1 to 65536 (a power of 2 keeps the Sobol design balanced); with
    /// `method: saltelli` the number of base points, the dimension then holding n(d + 2)
    /// for d parameters.
    pub n: usize,
    /// The design: `sobol` (Owen-scrambled Sobol points, the default), or `saltelli`
    /// (Saltelli's design for total-order indices, `batstudy.sobol_indices(order="total")`).
    #[serde(default)]
    pub method: SampleMethod,
    /// Seed of the scrambling (0 to 2^32 − 1): another seed, another independent design.
    /// Default 0.
    #[serde(default)]
    pub seed: u32,
    /// Dotted parameter path → its distribution. Default: none (then `ball_spread` must
    /// draw).
    #[serde(default, deserialize_with = "via_json")]
    pub params: IndexMap<String, Distribution>,
    /// Draw the base ball as measured balls spread about its preset (`base.ball.preset:
    /// mlb`): `ball` for one ball (COR SD 0.005, dynamic stiffness 3.2 %: ball to ball, lots
    /// included), `lot` for a lot's mean (0.0032 and 1.0 %: a certification's mean of several
    /// hits). It adds `ball.law.cor_shift` and `ball.law.k1` to the drawn parameters,
    /// correlated as measured (the rigid model, which uses the COR alone, draws only the
    /// shift; docs/physics.md, "The ball's measured spread"). Default: none.
    #[serde(default)]
    pub ball_spread: Option<BallSpread>,
    /// Correlated pairs: `{between: [path, path], rho: r}` (−1 < r < 1), the correlation of
    /// the two parameters' normal scores (a Gaussian copula). Default: independent.
    #[serde(default)]
    pub correlation: Vec<Correlation>,
}

/// The quasi-random design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SampleMethod {
    /// Owen-scrambled Sobol points (Burley 2020), seeded by `seed`.
    #[default]
    Sobol,
    /// Saltelli's design from the same points: A, the d rows of A with one column of B, B
    /// for each base point (n(d + 2) points); independent parameters only.
    Saltelli,
}

/// Which measured spread of the preset ball `sample.ball_spread` draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BallSpread {
    /// One ball: the spread of single balls about the preset, lots included.
    Ball,
    /// A lot's mean: the spread of lots' means about the preset.
    Lot,
}

/// A parameter's distribution.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Distribution {
    /// `{normal: {mean, sd, min, max}}`: normal, optionally truncated to [min, max].
    Normal {
        mean: f64,
        /// Standard deviation (> 0).
        sd: f64,
        #[serde(default)]
        min: Option<f64>,
        #[serde(default)]
        max: Option<f64>,
    },
    /// `{lognormal: {mean, cov, min, max}}`: lognormal with this mean and coefficient of
    /// variation (sd / mean, > 0), optionally truncated to [min, max].
    Lognormal {
        /// Mean (> 0).
        mean: f64,
        /// Coefficient of variation (> 0).
        cov: f64,
        #[serde(default)]
        min: Option<f64>,
        #[serde(default)]
        max: Option<f64>,
    },
    /// `{uniform: {min, max}}`.
    Uniform { min: f64, max: f64 },
}

/// A correlated pair of parameters.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Correlation {
    /// The two parameter paths (both in `params`).
    pub between: [String; 2],
    /// Correlation of their normal scores, −1 < rho < 1.
    pub rho: f64,
}

/// A bad `sample` block: where, the field, the value and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleError {
    pub at: Vec<Seg>,
    pub message: String,
    pub field: String,
    pub value: String,
    pub allowed: String,
}

pub(super) fn err(
    at: Vec<Seg>,
    message: String,
    field: &str,
    value: String,
    allowed: &str,
) -> SampleError {
    SampleError {
        at,
        message,
        field: field.to_string(),
        value,
        allowed: allowed.to_string(),
    }
}

/// Deserialize through JSON: yaml_serde's `Value` reads an enum with data only from a YAML
/// tag, while a study writes `{normal: {mean: 1, sd: 2}}`.
pub(crate) fn via_json<'de, D, T>(d: D) -> Result<T, D::Error>
where
    D: serde::Deserializer<'de>,
    T: serde::de::DeserializeOwned,
{
    let v = serde_json::Value::deserialize(d)?;
    serde_json::from_value(v).map_err(serde::de::Error::custom)
}

/// The score at probability `p` of a standard normal truncated to [za, zb] (za ≤ 0 or the
/// interval mirrored so that it is: its CDF values then keep their digits).
fn truncated_score(za: f64, zb: f64, p: f64) -> f64 {
    let (a, b) = (normal_cdf(za), normal_cdf(zb));
    normal_quantile(a + p * (b - a))
}

/// The standard normal CDF.
pub fn normal_cdf(z: f64) -> f64 {
    0.5 * statrs::function::erf::erfc(-z / std::f64::consts::SQRT_2)
}

/// The standard normal quantile (0 < p < 1).
pub fn normal_quantile(p: f64) -> f64 {
    -std::f64::consts::SQRT_2 * statrs::function::erf::erfc_inv(2.0 * p)
}

impl Distribution {
    /// The location and scale of the normal behind it, and its truncation in those terms.
    fn normal_form(&self) -> (f64, f64, Option<f64>, Option<f64>, bool) {
        match *self {
            Distribution::Normal { mean, sd, min, max } => (mean, sd, min, max, false),
            Distribution::Lognormal {
                mean,
                cov,
                min,
                max,
            } => {
                let s2 = (1.0 + cov * cov).ln();
                (mean.ln() - s2 / 2.0, s2.sqrt(), min, max, true)
            }
            Distribution::Uniform { min, max } => (min, max, None, None, false),
        }
    }

    /// The value at probability `p` (0 < p < 1).
    pub fn quantile(&self, p: f64) -> f64 {
        if let Distribution::Uniform { min, max } = *self {
            return min + p * (max - min);
        }
        let (mu, sigma, lo, hi, log) = self.normal_form();
        let (za, zb) = self.scores();
        // In the upper tail the CDF rounds to 1 (at 9 sd, 1 − 1e-19), so the interval is
        // mirrored into the lower tail, where erfc keeps its digits down to 1e-308.
        let z = match za > 0.0 {
            true => -truncated_score(-zb, -za, 1.0 - p),
            false => truncated_score(za, zb, p),
        };
        let x = mu + sigma * z;
        let x = if log { x.exp() } else { x };
        // rounding may step over a bound by an ulp
        x.clamp(lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY))
    }

    /// The truncation's bounds as scores of the normal behind it (±∞ where open).
    fn scores(&self) -> (f64, f64) {
        let (mu, sigma, lo, hi, log) = self.normal_form();
        let score = |x: Option<f64>, inf: f64| match x {
            Some(x) if log => (x.ln() - mu) / sigma,
            Some(x) => (x - mu) / sigma,
            None => inf,
        };
        (score(lo, f64::NEG_INFINITY), score(hi, f64::INFINITY))
    }

    /// The probability the truncation keeps, computed in the tail it lies in (0 when the
    /// interval lies too far out to be drawn in floating point).
    fn kept(&self) -> f64 {
        let (za, zb) = self.scores();
        match za > 0.0 {
            true => normal_cdf(-za) - normal_cdf(-zb),
            false => normal_cdf(zb) - normal_cdf(za),
        }
    }

    /// Why its parameters are not a distribution, if they are not: (field, value, allowed).
    fn problem(&self) -> Option<(&'static str, f64, &'static str)> {
        let bounds = |min: Option<f64>, max: Option<f64>| match (min, max) {
            (Some(a), Some(b)) if a >= b => Some(("max", b, "greater than `min`")),
            _ => None,
        };
        match *self {
            Distribution::Normal { sd, .. } if sd <= 0.0 => {
                Some(("sd", sd, "a standard deviation > 0"))
            }
            Distribution::Normal { min, max, .. } => {
                bounds(min, max).or_else(|| self.unreachable_tail())
            }
            Distribution::Lognormal { mean, .. } if mean <= 0.0 => {
                Some(("mean", mean, "a mean > 0"))
            }
            Distribution::Lognormal { cov, .. } if cov <= 0.0 => {
                Some(("cov", cov, "a coefficient of variation > 0"))
            }
            Distribution::Lognormal { min: Some(m), .. } if m <= 0.0 => Some((
                "min",
                m,
                "a lower bound > 0 (lognormal values are positive)",
            )),
            Distribution::Lognormal { min, max, .. } => {
                bounds(min, max).or_else(|| self.unreachable_tail())
            }
            Distribution::Uniform { min, max } if min >= max => {
                Some(("max", max, "greater than `min`"))
            }
            Distribution::Uniform { .. } => None,
        }
    }

    /// A truncation so far in a tail that no double can draw from it (about 37 standard
    /// deviations out): it would draw ±∞.
    fn unreachable_tail(&self) -> Option<(&'static str, f64, &'static str)> {
        if self.kept() > 0.0 {
            return None;
        }
        let (za, _) = self.scores();
        let (_, _, lo, hi, _) = self.normal_form();
        let (field, value) = match za > 0.0 {
            true => ("min", lo.unwrap_or(f64::NAN)),
            false => ("max", hi.unwrap_or(f64::NAN)),
        };
        Some((
            field,
            value,
            "bounds that keep some of the distribution: within about 37 standard deviations of the mean (further out no value can be drawn)",
        ))
    }

    fn kind(&self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::Lognormal { .. } => "lognormal",
            Distribution::Uniform { .. } => "uniform",
        }
    }
}

/// The block's drawn values: for each parameter (in `params` order), its `n` values.
pub fn draw(block: &SampleBlock) -> Result<Vec<Vec<f64>>, SampleError> {
    check(block)?;
    let d = block.params.len();
    let l = cholesky(&correlation_matrix(block)?).ok_or_else(|| {
        err(
            keys(&["sample", "correlation"]),
            "the correlations are not those of any set of parameters (the matrix is not positive definite)".into(),
            "sample.correlation",
            format!("{} pairs", block.correlation.len()),
            "correlations that can hold together, e.g. smaller |rho|",
        )
    })?;
    let dists: Vec<&Distribution> = block.params.values().collect();
    let rows = points(block);
    let mut out = vec![Vec::with_capacity(rows); d];
    let mut z = vec![0.0; d];
    for i in 0..rows {
        for (k, zk) in z.iter_mut().enumerate() {
            *zk = normal_quantile(design_uniform(block, i, k));
        }
        for k in 0..d {
            // the correlated score: row k of L times z (L lower triangular)
            let s: f64 = (0..=k).map(|j| l[k * d + j] * z[j]).sum();
            // a parameter correlated with none before it keeps its Sobol coordinate itself
            let p = if (0..k).all(|j| l[k * d + j] == 0.0) {
                design_uniform(block, i, k)
            } else {
                normal_cdf(s)
            };
            out[k].push(dists[k].quantile(p));
        }
    }
    Ok(out)
}

/// The number of points the block draws: n, or n(d + 2) for Saltelli's design.
pub fn points(block: &SampleBlock) -> usize {
    match block.method {
        SampleMethod::Sobol => block.n,
        SampleMethod::Saltelli => block.n.saturating_mul(block.params.len() + 2),
    }
}

/// Coordinate `k` of the design's point `i` on [0, 1): a Sobol point's, or for Saltelli's
/// design A's or B's (B's are the Sobol dimensions d … 2d − 1 of the same base point).
fn design_uniform(block: &SampleBlock, i: usize, k: usize) -> f64 {
    match block.method {
        SampleMethod::Sobol => uniform(i, k, block.seed),
        SampleMethod::Saltelli => {
            let d = block.params.len();
            let (base, row) = (i / (d + 2), i % (d + 2));
            let from_b = row == d + 1 || row == k + 1;
            uniform(base, if from_b { d + k } else { k }, block.seed)
        }
    }
}

/// The Sobol coordinate `k` of point `i`, moved to the middle of its f32 cell so that it is
/// never 0 (whose normal score is −∞).
fn uniform(i: usize, k: usize, seed: u32) -> f64 {
    let u = sobol_burley::sample(i as u32, k as u32, seed) as f64;
    u + 0.5 / (1u64 << 24) as f64
}

fn check(block: &SampleBlock) -> Result<(), SampleError> {
    if block.method == SampleMethod::Saltelli {
        check_saltelli(block)?;
    }
    if block.n == 0 || block.n > MAX_SAMPLES {
        return Err(err(
            keys(&["sample", "n"]),
            "`sample.n` out of range".into(),
            "sample.n",
            block.n.to_string(),
            "1 to 65536 points (the Sobol sequence's length)",
        ));
    }
    if block.params.is_empty() || block.params.len() > MAX_SAMPLE_PARAMS {
        return Err(err(
            keys(&["sample", "params"]),
            "`sample.params` must name 1 to 256 parameters".into(),
            "sample.params",
            format!("{} parameters", block.params.len()),
            "1 to 256 dotted parameter paths, each with a distribution (or `ball_spread`)",
        ));
    }
    for (path, dist) in &block.params {
        if let Some((field, value, allowed)) = dist.problem() {
            return Err(err(
                keys(&["sample", "params", path, dist.kind(), field]),
                format!(
                    "the {} distribution of `{path}` has a bad `{field}`",
                    dist.kind()
                ),
                &format!("sample.params.{path}.{}.{field}", dist.kind()),
                value.to_string(),
                allowed,
            ));
        }
    }
    Ok(())
}

/// Saltelli's design: independent parameters (its estimators assume them), 2d Sobol
/// dimensions and at most 65536 points in all.
fn check_saltelli(block: &SampleBlock) -> Result<(), SampleError> {
    let d = block.params.len();
    if !block.correlation.is_empty() || block.ball_spread.is_some() {
        let what = if block.ball_spread.is_some() {
            "ball_spread"
        } else {
            "correlation"
        };
        return Err(err(
            keys(&["sample", what]),
            format!("`sample.method: saltelli` needs independent parameters; `sample.{what}` correlates them"),
            "sample.method",
            "saltelli".into(),
            "`sobol` with correlated parameters, or `saltelli` with independent ones",
        ));
    }
    let total = block.n.saturating_mul(d + 2);
    if 2 * d > MAX_SAMPLE_PARAMS || total > MAX_SAMPLES {
        return Err(err(
            keys(&["sample", "n"]),
            "Saltelli's design is too large".into(),
            "sample.n",
            format!("{} base points × ({d} parameters + 2) = {total}", block.n),
            "n(d + 2) ≤ 65536 points and 2d ≤ 256 parameters",
        ));
    }
    Ok(())
}

/// The correlation matrix (row-major, d × d) of the block's parameters.
fn correlation_matrix(block: &SampleBlock) -> Result<Vec<f64>, SampleError> {
    let d = block.params.len();
    let mut c = vec![0.0; d * d];
    for k in 0..d {
        c[k * d + k] = 1.0;
    }
    for (i, pair) in block.correlation.iter().enumerate() {
        let at = |f: &str| {
            let mut s = keys(&["sample", "correlation"]);
            s.push(Seg::Index(i));
            s.push(Seg::Key(f.into()));
            s
        };
        let idx: Vec<Option<usize>> = pair
            .between
            .iter()
            .map(|p| block.params.get_index_of(p))
            .collect();
        let (Some(a), Some(b)) = (idx[0], idx[1]) else {
            let bad = pair.between.iter().find(|p| !block.params.contains_key(*p));
            return Err(err(
                at("between"),
                "a correlated parameter is not drawn by the sample".into(),
                "sample.correlation.between",
                bad.cloned().unwrap_or_default(),
                "two of the paths under `sample.params`",
            ));
        };
        if a == b || !(pair.rho > -1.0 && pair.rho < 1.0) || c[a * d + b] != 0.0 {
            let (value, allowed) = match a == b {
                true => (pair.between[0].clone(), "two different paths"),
                false if c[a * d + b] != 0.0 => (pair.between.join(", "), "each pair once"),
                false => (pair.rho.to_string(), "-1 < rho < 1"),
            };
            return Err(err(
                at(if a == b || c[a * d + b] != 0.0 {
                    "between"
                } else {
                    "rho"
                }),
                "bad correlated pair".into(),
                "sample.correlation",
                value,
                allowed,
            ));
        }
        c[a * d + b] = pair.rho;
        c[b * d + a] = pair.rho;
    }
    Ok(c)
}

/// The lower Cholesky factor of a symmetric matrix (row-major), None unless it is positive
/// definite.
fn cholesky(c: &[f64]) -> Option<Vec<f64>> {
    let d = (c.len() as f64).sqrt().round() as usize;
    let m = nalgebra::DMatrix::from_row_slice(d, d, c);
    let l = nalgebra::Cholesky::new(m)?.unpack();
    Some((0..d * d).map(|i| l[(i / d, i % d)]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(params: &[(&str, Distribution)], corr: Vec<Correlation>, n: usize) -> SampleBlock {
        SampleBlock {
            name: None,
            n,
            method: SampleMethod::Sobol,
            ball_spread: None,
            seed: 7,
            params: params
                .iter()
                .map(|(p, d)| (p.to_string(), d.clone()))
                .collect(),
            correlation: corr,
        }
    }

    // Saltelli's design (Saltelli et al. 2010, table 1's matrices): for every base point, A,
    // then A with one coordinate from B, then B; A and B the two halves of one Sobol point
    #[test]
    fn saltelli_rows_are_a_then_a_with_one_column_of_b_then_b() {
        let u = || Distribution::Uniform { min: 0.0, max: 1.0 };
        let mut b = block(&[("a", u()), ("b", u()), ("c", u())], vec![], 16);
        b.method = SampleMethod::Saltelli;
        let v = draw(&b).unwrap();
        let (d, n) = (3, 16);
        assert_eq!(v[0].len(), n * (d + 2));
        for i in 0..n {
            let row = |r: usize| {
                [
                    v[0][i * (d + 2) + r],
                    v[1][i * (d + 2) + r],
                    v[2][i * (d + 2) + r],
                ]
            };
            let (a, bb) = (row(0), row(d + 1));
            assert!((0..d).all(|k| a[k] != bb[k]), "A and B differ everywhere");
            for k in 0..d {
                let mut want = a;
                want[k] = bb[k];
                assert_eq!(row(k + 1), want, "point {i}, column {k}");
            }
        }
        // correlated parameters have no Saltelli estimator: refused, positioned
        let corr = vec![Correlation {
            between: ["a".into(), "b".into()],
            rho: 0.5,
        }];
        let mut c = block(&[("a", u()), ("b", u())], corr, 8);
        c.method = SampleMethod::Saltelli;
        let e = draw(&c).unwrap_err();
        assert_eq!(e.field, "sample.method");
    }

    #[test]
    fn quantiles_invert_the_cdf() {
        for p in [1e-6, 0.025, 0.3, 0.5, 0.9, 0.999] {
            assert!((normal_cdf(normal_quantile(p)) - p).abs() < 1e-9 * p, "{p}");
        }
        assert!((normal_quantile(0.975) - 1.959963984540054).abs() < 1e-12);
        let t = Distribution::Normal {
            mean: 0.0,
            sd: 1.0,
            min: Some(-0.5),
            max: Some(0.5),
        };
        assert!((t.quantile(0.5)).abs() < 1e-14);
        assert!(t.quantile(1e-9) > -0.5 && t.quantile(1.0 - 1e-9) < 0.5);
        // the lognormal's median is mean / sqrt(1 + cov^2)
        let ln = Distribution::Lognormal {
            mean: 2.0,
            cov: 0.5,
            min: None,
            max: None,
        };
        assert!((ln.quantile(0.5) - 2.0 / 1.25f64.sqrt()).abs() < 1e-12);
    }

    /// A normal truncated far in its upper tail (9 to 15 sd out, where the CDF rounds to
    /// 1) draws finite values inside its bounds; one beyond any double's reach is refused.
    #[test]
    fn truncations_far_in_a_tail_draw_inside_their_bounds() {
        let tail = |min: f64, max: f64| Distribution::Normal {
            mean: 649.0,
            sd: 10.0,
            min: Some(min),
            max: Some(max),
        };
        for d in [tail(740.0, 800.0), tail(498.0, 558.0)] {
            let v = draw(&block(&[("a", d.clone())], vec![], 64)).unwrap();
            let (lo, hi) = match d {
                Distribution::Normal { min, max, .. } => (min.unwrap(), max.unwrap()),
                _ => unreachable!(),
            };
            assert!(
                v[0].iter().all(|x| x.is_finite() && (lo..=hi).contains(x)),
                "{v:?}"
            );
            // the truncated normal piles up at the bound nearest the mean: the sample's
            // mean lies within one sd/z of it (the exponential tail's mean excess)
            let mean = v[0].iter().sum::<f64>() / 64.0;
            let near = if lo > 649.0 { lo } else { hi };
            assert!((mean - near).abs() < 10.0 / 9.0, "{mean}");
        }
        let e = draw(&block(&[("a", tail(1100.0, 1200.0))], vec![], 8)).unwrap_err();
        assert_eq!(e.field, "sample.params.a.normal.min");
        let e = draw(&block(&[("a", tail(100.0, 200.0))], vec![], 8)).unwrap_err();
        assert_eq!(e.field, "sample.params.a.normal.max");
    }

    #[test]
    fn correlated_normals_have_their_correlation() {
        let n = |m| Distribution::Normal {
            mean: m,
            sd: 1.0,
            min: None,
            max: None,
        };
        let corr = vec![Correlation {
            between: ["a".into(), "b".into()],
            rho: 0.7,
        }];
        let v = draw(&block(&[("a", n(0.0)), ("b", n(0.0))], corr, 4096)).unwrap();
        let r: f64 = v[0].iter().zip(&v[1]).map(|(x, y)| x * y).sum::<f64>() / 4096.0;
        assert!((r - 0.7).abs() < 0.01, "{r}");
        let mean: f64 = v[1].iter().sum::<f64>() / 4096.0;
        assert!(mean.abs() < 0.01, "{mean}");
    }

    #[test]
    fn bad_blocks_are_refused() {
        let bad = Distribution::Uniform { min: 1.0, max: 1.0 };
        let e = draw(&block(&[("a", bad)], vec![], 8)).unwrap_err();
        assert_eq!(e.field, "sample.params.a.uniform.max");
        let u = Distribution::Uniform { min: 0.0, max: 1.0 };
        let e = draw(&block(&[("a", u.clone())], vec![], 0)).unwrap_err();
        assert_eq!(e.field, "sample.n");
        let pairs = |r: f64, r2: f64| {
            vec![
                Correlation {
                    between: ["a".into(), "b".into()],
                    rho: r,
                },
                Correlation {
                    between: ["b".into(), "c".into()],
                    rho: r2,
                },
                Correlation {
                    between: ["a".into(), "c".into()],
                    rho: -0.99,
                },
            ]
        };
        let three = [("a", u.clone()), ("b", u.clone()), ("c", u.clone())];
        let e = draw(&block(&three, pairs(0.99, 0.99), 8)).unwrap_err();
        assert_eq!(e.field, "sample.correlation");
        let e = draw(&block(&three, pairs(1.0, 0.0), 8)).unwrap_err();
        assert_eq!(e.value, "1");
    }
}
