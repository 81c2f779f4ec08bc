//! The balls the lab offers beside the calibrated MLB ball's mean: single balls two of the
//! measured ball-to-ball standard deviations of COR above and below it (`ball::MLB_COR_SD`,
//! the spread `sample.ball_spread: ball` draws from), as `ball.law.cor_shift`. The
//! dynamic stiffness, which the sample draws correlated with the COR, stays the mean's.

use crate::model::ball::MLB_COR_SD;
use serde_json::{json, Value};

/// `[{name, cor_shift}]`: the mean ball, a lively one and a dead one.
pub fn balls() -> Value {
    json!([
        {"name": "the calibrated MLB ball (a mean ball)", "cor_shift": 0.0},
        {"name": "a lively ball (COR +2 SD of single balls)", "cor_shift": 2.0 * MLB_COR_SD},
        {"name": "a dead ball (COR −2 SD of single balls)", "cor_shift": -2.0 * MLB_COR_SD},
    ])
}
