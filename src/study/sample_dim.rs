//! The `sample` block as a dimension of the plan: its values drawn, the base ball's measured
//! spread added where the block asks for it.

use super::error::StudyError;
use super::locate::Ctx;
use super::plan::{DimOrigin, PlanDim};
use super::sample::{draw, err, BallSpread, Correlation, Distribution, SampleBlock, SampleError};
use super::source::keys;
use super::syntax::check_path;
use super::types::StudyFile;
use yaml_serde::Value;

/// The `sample` block's dimension (after every other block's), its values drawn.
pub(super) fn sample_dim(cx: &Ctx, file: &StudyFile) -> Result<Option<PlanDim>, StudyError> {
    let Some(block) = &file.sample else {
        return Ok(None);
    };
    let rigid = file.model == Some(crate::model::spec::ModelKind::Rigid)
        || file.base.get("model").and_then(|m| m.as_str()) == Some("rigid");
    let block = &with_ball_spread(block, &file.base, !rigid).map_err(|e| {
        cx.err(&e.at, e.message)
            .field(e.field)
            .value(e.value)
            .allowed(e.allowed)
    })?;
    for path in block.params.keys().filter(|p| !block.spread_path(p)) {
        check_path(cx, path, &keys(&["sample", "params", path]))?;
    }
    let size = super::sample::points(block);
    let values = draw(block).map_err(|e| {
        cx.err(&e.at, e.message)
            .field(e.field)
            .value(e.value)
            .allowed(e.allowed)
    })?;
    let params = block
        .params
        .keys()
        .zip(values)
        .map(|(p, v)| {
            (
                p.clone(),
                v.into_iter().map(yaml_serde::Value::from).collect(),
            )
        })
        .collect();
    Ok(Some(PlanDim {
        name: block.name.clone().unwrap_or_else(|| "sample".into()),
        size,
        params,
        origin: DimOrigin::Sample,
    }))
}

const COR_SHIFT: &str = "ball.law.cor_shift";
const K1: &str = "ball.law.k1";

impl SampleBlock {
    /// Whether `ball_spread`, not the file, draws this path.
    fn spread_path(&self, path: &str) -> bool {
        self.ball_spread.is_some() && (path == COR_SHIFT || path == K1)
    }
}

/// The block with the base ball's measured spread among its parameters, if it asks for it:
/// the COR curve's shift a truncated normal, k₁ a truncated lognormal about the preset's
/// (its median), both cut at 3 SD, their normal scores correlated as the balls' are.
/// `stiffness_used`: whether the study's model uses k₁ (the wave model does, the rigid one not).
fn with_ball_spread(
    block: &SampleBlock,
    base: &Value,
    stiffness_used: bool,
) -> Result<SampleBlock, SampleError> {
    let Some(unit) = block.ball_spread else {
        return Ok(block.clone());
    };
    let ball = base.get("ball");
    let preset = ball.and_then(|b| b.get("preset")).and_then(|p| p.as_str());
    let fail = |message: String, value: String, allowed: &str| {
        Err(err(
            keys(&["sample", "ball_spread"]),
            message,
            "sample.ball_spread",
            value,
            allowed,
        ))
    };
    if preset != Some("mlb") {
        let value = preset.map_or("no preset".into(), |p| format!("ball.preset {p}"));
        return fail(
            "`sample.ball_spread` draws a preset ball's measured spread; the base ball has none"
                .into(),
            value,
            "`base.ball.preset: mlb` (the preset calibrated on measured balls)",
        );
    }
    let law = ball.and_then(|b| b.get("law"));
    let path_set = |p: &str| {
        let field = p.rsplit('.').next().unwrap_or(p);
        block.params.contains_key(p) || law.and_then(|l| l.get(field)).is_some()
    };
    if let Some(p) = [COR_SHIFT, K1].into_iter().find(|p| path_set(p)) {
        return fail(
            format!("`{p}` is drawn by `sample.ball_spread` and also set in the study"),
            p.to_string(),
            "the spread's parameters left to it (remove them from `sample.params` and `base.ball.law`)",
        );
    }
    let spread = crate::model::ball::mlb_spread(unit == BallSpread::Lot);
    let (sd, sig, k1) = (
        spread.cor_sd,
        spread.k1_log_sd,
        crate::model::ball::mlb_k1(),
    );
    let mut out = block.clone();
    out.params.insert(
        COR_SHIFT.into(),
        Distribution::Normal {
            mean: 0.0,
            sd,
            min: Some(-3.0 * sd),
            max: Some(3.0 * sd),
        },
    );
    if !stiffness_used {
        // the rigid model uses the ball's COR alone
        return Ok(out);
    }
    out.params.insert(
        K1.into(),
        Distribution::Lognormal {
            mean: k1 * (0.5 * sig * sig).exp(),
            cov: (sig * sig).exp_m1().sqrt(),
            min: Some(k1 * (-3.0 * sig).exp()),
            max: Some(k1 * (3.0 * sig).exp()),
        },
    );
    out.correlation.push(Correlation {
        between: [COR_SHIFT.into(), K1.into()],
        rho: spread.rho,
    });
    Ok(out)
}
