//! `/uncertainty`: what a `sample` dimension's scatter does to the answers —
//! quantiles, mean and standard deviation over the sample of the exit speed and BBCOR of
//! every point, of the sweet spot's position and exit speed, and of the bat's BBCOR (its
//! maximum along `impact_z`, parabola-refined) with the probability that it exceeds the
//! NCAA limit. Read back from the finished `/summary` and `/sweet_spot`, so it is the same
//! however the file was built (one run, a resume, a merge).

use super::vars::study_dims;
use crate::dimscale::{self as h5u, attr_num, describe, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout::{self as l, OwnedVarDef, VarDef};
use crate::results::{Dim, StudyInfo};
use batstudy_physics::measures::sweet::find_maximum;
use hdf5::{Dataset, File, Group};
use std::path::Path;

/// The group's name.
pub const GROUP_UNCERTAINTY: &str = "uncertainty";
/// The quantiles stored, as fractions of the sample (xarray's and NumPy's `quantile`).
pub const QUANTILES: [f64; 7] = [0.025, 0.05, 0.25, 0.5, 0.75, 0.95, 0.975];
/// The NCAA BBCOR limit the exceedance probability is counted against.
pub const BBCOR_LIMIT: f64 = 0.50;

pub use crate::results::UNCERTAINTY_NAMES;

/// Quantiles (linear between order statistics, NumPy's default), mean and sample
/// standard deviation of the finite values; NaN where there are none (std: fewer than 2).
pub fn statistics(values: &[f64]) -> ([f64; 7], f64, f64) {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    let n = v.len();
    if n == 0 {
        return ([f64::NAN; 7], f64::NAN, f64::NAN);
    }
    v.sort_by(f64::total_cmp);
    let pct = QUANTILES.map(|p| {
        let h = (n - 1) as f64 * p;
        let (lo, t) = (h.floor() as usize, h - h.floor());
        match lo + 1 < n {
            true => v[lo] + t * (v[lo + 1] - v[lo]),
            false => v[lo],
        }
    });
    let mean = v.iter().sum::<f64>() / n as f64;
    let std = match n {
        1 => f64::NAN,
        _ => (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt(),
    };
    (pct, mean, std)
}

/// An N-D row-major array reduced along `axis`: `f` of each line along it, in row-major
/// order of the other axes.
fn reduce<T>(data: &[f64], shape: &[usize], axis: usize, f: impl Fn(&[f64]) -> T) -> Vec<T> {
    let inner: usize = shape[axis + 1..].iter().product();
    let n = shape[axis];
    let outer: usize = shape[..axis].iter().product();
    let mut line = vec![0.0; n];
    let mut out = Vec::with_capacity(outer * inner);
    for o in 0..outer {
        for i in 0..inner {
            for (k, x) in line.iter_mut().enumerate() {
                *x = data[(o * n + k) * inner + i];
            }
            out.push(f(&line));
        }
    }
    out
}

fn without(v: &[usize], k: usize) -> Vec<usize> {
    v.iter()
        .enumerate()
        .filter(|&(i, _)| i != k)
        .map(|(_, &x)| x)
        .collect()
}

/// One reduced quantity: its name, units, long name and description, and its statistics.
struct Quantity {
    def: OwnedVarDef,
    stats: Vec<([f64; 7], f64, f64)>,
    /// Its dims, as indices into the summary's dims.
    dims: Vec<usize>,
}

fn read(f: &File, name: &str, out: &Path) -> Result<Vec<f64>, StoreError> {
    f.dataset(name)
        .and_then(|d| d.read_raw::<f64>())
        .ctx(out, &format!("read {name} back"))
}

/// Write `/uncertainty` for the sample dimension `sample` into the finished file `f`.
pub(super) fn write_uncertainty(
    f: &File,
    info: &StudyInfo,
    sample: &str,
    out: &Path,
) -> Result<(), StoreError> {
    let dims = &info.shape.dims;
    let Some(s) = dims.iter().position(|d| d.name == sample) else {
        return Ok(());
    };
    let shape: Vec<usize> = dims.iter().map(|d| d.size).collect();
    let all: Vec<usize> = (0..dims.len()).collect();
    let mut qs = Vec::new();
    for var in ["exit_speed", "bbcor"] {
        let def = l::SUMMARY_FLOATS
            .iter()
            .find(|d| d.name == var)
            .expect("a summary var");
        let data = read(f, &format!("{}/{var}", l::GROUP_SUMMARY), out)?;
        qs.push(Quantity {
            def: OwnedVarDef::from(*def),
            stats: reduce(&data, &shape, s, statistics),
            dims: without(&all, s),
        });
    }
    let mut above = None;
    if let Some(iz) = dims.iter().position(|d| d.name == l::IMPACT_Z) {
        qs.extend(sweet_quantities(f, dims, iz, s, out)?);
        let (q, p) = bbcor_max(f, dims, iz, s, out)?;
        qs.push(q);
        above = Some(p);
    }
    write_group(f, dims, s, &qs, above, out)
}

/// The sweet spot's position and exit speed over the sample.
fn sweet_quantities(
    f: &File,
    dims: &[Dim],
    iz: usize,
    s: usize,
    out: &Path,
) -> Result<Vec<Quantity>, StoreError> {
    let rest: Vec<usize> = without(&(0..dims.len()).collect::<Vec<_>>(), iz);
    let rshape: Vec<usize> = rest.iter().map(|&k| dims[k].size).collect();
    let rs = rest.iter().position(|&k| k == s).expect("the sample dim");
    let mut qs = Vec::new();
    for (var, name) in [
        ("position", "sweet_spot_position"),
        ("exit_speed", "sweet_spot_exit_speed"),
    ] {
        let def = l::SWEET_FLOATS
            .iter()
            .find(|d| d.name == var)
            .expect("a sweet var");
        let data = read(f, &format!("{}/{var}", l::GROUP_SWEET_SPOT), out)?;
        qs.push(Quantity {
            def: OwnedVarDef::new(
                name,
                def.units,
                &format!("sweet spot {}", def.long_name),
                def.description,
            ),
            stats: reduce(&data, &rshape, rs, statistics),
            dims: without(&rest, rs),
        });
    }
    Ok(qs)
}

/// The bat's BBCOR in each sample (the maximum of `bbcor` along `impact_z`), over the
/// sample; and the fraction of samples above [`BBCOR_LIMIT`].
fn bbcor_max(
    f: &File,
    dims: &[Dim],
    iz: usize,
    s: usize,
    out: &Path,
) -> Result<(Quantity, Vec<f64>), StoreError> {
    let shape: Vec<usize> = dims.iter().map(|d| d.size).collect();
    let z = match dims[iz].coords.iter().find(|c| c.name == l::IMPACT_Z) {
        Some(crate::results::Coord {
            values: crate::results::CoordValues::Numbers(z),
            ..
        }) => z.clone(),
        _ => vec![f64::NAN; shape[iz]],
    };
    let data = read(f, &format!("{}/bbcor", l::GROUP_SUMMARY), out)?;
    let peak = |line: &[f64]| find_maximum(&z, line).map_or(f64::NAN, |m| m.1);
    let maxima = reduce(&data, &shape, iz, peak);
    let rest = without(&(0..dims.len()).collect::<Vec<_>>(), iz);
    let rshape: Vec<usize> = rest.iter().map(|&k| dims[k].size).collect();
    let rs = rest.iter().position(|&k| k == s).expect("the sample dim");
    let above = reduce(&maxima, &rshape, rs, |v| {
        let finite: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
        let n = finite.iter().filter(|&&x| x > BBCOR_LIMIT).count();
        match finite.len() {
            0 => f64::NAN,
            k => n as f64 / k as f64,
        }
    });
    let q = Quantity {
        def: OwnedVarDef::new(
            "bbcor_max",
            "1",
            "BBCOR (maximum along the barrel)",
            "the largest bbcor along impact_z (parabola-refined): the bat's BBCOR",
        ),
        stats: reduce(&maxima, &rshape, rs, statistics),
        dims: without(&rest, rs),
    };
    Ok((q, above))
}

/// The group: the study's dims without the sample (coordinates and scales), `quantile`,
/// and each quantity's quantiles, mean and standard deviation.
fn write_group(
    f: &File,
    dims: &[Dim],
    s: usize,
    qs: &[Quantity],
    above: Option<Vec<f64>>,
    out: &Path,
) -> Result<(), StoreError> {
    let g = f
        .create_group(GROUP_UNCERTAINTY)
        .ctx(out, "create group uncertainty")?;
    let att = Attacher::default();
    let kept: Vec<usize> = (0..dims.len()).filter(|&k| k != s).collect();
    let kept_dims: Vec<Dim> = kept.iter().map(|&k| dims[k].clone()).collect();
    let (scales, aux) = study_dims(&g, &kept_dims, &att, out)?;
    let pdef = VarDef {
        name: "quantile",
        units: "1",
        long_name: "quantile",
        description: "quantile of the quantity over the sample dimension: the fraction of the sample at or below it",
    };
    let pscale = h5u::scale_coord(&g, "quantile", &QUANTILES, &pdef)
        .ctx(out, "write the quantile coordinate")?;
    let scale_of = |k: usize| &scales[kept.iter().position(|&j| j == k).expect("kept dim")];
    for q in qs {
        let qscales: Vec<&Dataset> = q.dims.iter().map(|&k| scale_of(k)).collect();
        let shape: Vec<usize> = q.dims.iter().map(|&k| dims[k].size).collect();
        let pct: Vec<f64> = q.stats.iter().flat_map(|t| t.0).collect();
        let mut with_p = qscales.clone();
        with_p.push(&pscale);
        let mut pshape = shape.clone();
        pshape.push(QUANTILES.len());
        let desc = |what: &str| format!("{what} of {} over the sample", q.def.name);
        let parts: [Part; 3] = [
            (
                OwnedVarDef {
                    description: desc("quantiles"),
                    ..q.def.clone()
                },
                &with_p,
                &pshape,
                pct,
            ),
            (
                named(&q.def, "mean", &desc("mean")),
                &qscales,
                &shape,
                q.stats.iter().map(|t| t.1).collect(),
            ),
            (
                named(&q.def, "std", &desc("sample standard deviation")),
                &qscales,
                &shape,
                q.stats.iter().map(|t| t.2).collect(),
            ),
        ];
        for (def, sc, sh, data) in parts {
            write_var(&g, &def.def(), sh, &data, (sc, &aux, &att), out)?;
        }
    }
    if let (Some(p), Some(q)) = (above, qs.iter().find(|q| q.def.name == "bbcor_max")) {
        let qscales: Vec<&Dataset> = q.dims.iter().map(|&k| scale_of(k)).collect();
        let shape: Vec<usize> = q.dims.iter().map(|&k| dims[k].size).collect();
        let def = VarDef {
            name: "bbcor_max_above_limit",
            units: "1",
            long_name: "P(BBCOR > 0.50)",
            description: "fraction of the sample whose bbcor_max exceeds the NCAA limit 0.50 (attribute `limit`)",
        };
        let ds = write_var(&g, &def, &shape, &p, (&qscales, &aux, &att), out)?;
        attr_num(&ds, "limit", BBCOR_LIMIT).ctx(out, "describe bbcor_max_above_limit")?;
    }
    att.write().ctx(out, "attach the dimension scales")
}

/// One variable to write: what it is, its scales, its shape and its data.
type Part<'a> = (OwnedVarDef, &'a [&'a Dataset], &'a [usize], Vec<f64>);

fn named(def: &OwnedVarDef, suffix: &str, description: &str) -> OwnedVarDef {
    OwnedVarDef::new(
        &format!("{}_{suffix}", def.name),
        &def.units,
        &format!("{} ({suffix})", def.long_name),
        description,
    )
}

fn write_var(
    g: &Group,
    def: &VarDef,
    shape: &[usize],
    data: &[f64],
    (scales, aux, att): (&[&Dataset], &[String], &Attacher),
    out: &Path,
) -> Result<Dataset, StoreError> {
    let what = format!("write uncertainty/{}", def.name);
    let ds = g
        .new_dataset::<f64>()
        .shape(shape.to_vec())
        .create(def.name)
        .ctx(out, &what)?;
    h5u::write_small(&ds, data).ctx(out, &what)?;
    describe(&ds, def).ctx(out, &what)?;
    if !aux.is_empty() {
        h5u::attr_str(&ds, "coordinates", &aux.join(" ")).ctx(out, &what)?;
    }
    att.add(&ds, scales);
    Ok(ds)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_as_numpy() {
        // numpy.quantile([1, 2, 3, 4, 10], [0.025, 0.05, 0.25, 0.5, 0.75, 0.95, 0.975])
        let (p, mean, std) = statistics(&[4.0, 1.0, f64::NAN, 10.0, 3.0, 2.0]);
        let want = [1.1, 1.2, 2.0, 3.0, 4.0, 8.8, 9.4];
        for (a, b) in p.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{p:?}");
        }
        assert_eq!(mean, 4.0);
        assert!((std - 12.5f64.sqrt()).abs() < 1e-12);
        assert!(statistics(&[f64::NAN]).1.is_nan());
    }

    #[test]
    fn reduce_along_the_middle_axis() {
        // shape [2, 3, 2]: the sums along axis 1
        let data: Vec<f64> = (0..12).map(f64::from).collect();
        let sums = reduce(&data, &[2, 3, 2], 1, |v| v.iter().sum::<f64>());
        assert_eq!(sums, vec![6.0, 9.0, 24.0, 27.0]);
    }
}
