//! A lab session: one bat met by one ball along a range of the barrel. The page edits it
//! as JSON (a study's `base` block, the model and the impact range); the server writes it
//! as the study file that `batstudy run` reproduces bit for bit, and evaluates that text.

use crate::model::bat::section::BatGeometry;
use crate::model::spec::{CollisionSpec, ProfileSpec};
use crate::study::{self, LoadOptions};
use serde_json::{json, Value};
use std::path::Path;

/// Most impact positions a session sweeps (a live curve, not a study).
pub const MAX_POSITIONS: usize = 120;

/// The session the lab opens with when it is given nothing: the R161 wood bat with its
/// profile as knots, the calibrated MLB ball, a 90-mph pitch, a 70-mph swing 28 in from the
/// knob with the batter's law (the `batter` study's), its flight, every centimetre of the
/// barrel from 50 cm.
pub fn default_session() -> Result<Value, String> {
    let base = json!({
        "bat": {"preset": "r161"},
        "ball": {"preset": "mlb"},
        "batter": {"bat_speed": 31.3, "bat_speed_at": 0.7112, "reference_moi": 0.3342,
                   "exponent": 0.27},
        "pitch": {"speed": 40.2},
        "flight": {}
    });
    with_knots(json!({"model": "wave", "base": base, "impact": [0.50, 0.83, 0.01]}))
}

/// Points looked through for the study's bats (a bat that first appears later is not
/// offered).
const MAX_POINTS_SEARCHED: usize = 100_000;

/// One session per bat of a study, labelled as the results file's `/bat` labels them: the
/// session of the first point that uses the bat (its ball, swing and pitch; the study's
/// other axes dropped), along the barrel from 50 cm to 3 cm short of the end. The study's
/// first point's bat comes first.
pub fn sessions_of_study(text: &str, path: &Path) -> Result<Vec<(String, Value)>, String> {
    let loaded = study::load_str(text, path, &LoadOptions::default()).map_err(|e| e.to_string())?;
    let plan = &loaded.plan;
    let mut found: Vec<Option<Value>> = vec![None; plan.bats().len()];
    let mut order = Vec::new();
    for flat in 0..plan.n_points().min(MAX_POINTS_SEARCHED) {
        let point = plan.point(flat).map_err(|e| e.message)?;
        let slot = &mut found[point.bat as usize];
        if slot.is_none() {
            let tree = plan.value_at(&plan.shape().unravel(flat));
            *slot = Some(session_of_point(&tree, &point.spec)?);
            order.push(point.bat as usize);
        }
        if order.len() == found.len() {
            break;
        }
    }
    Ok(order
        .into_iter()
        .filter_map(|b| Some((plan.bats()[b].label.clone(), found[b].take()?)))
        .collect())
}

/// The session of one point: its parameters as the study wrote them (`tree`, so that what
/// the study left to its presets stays theirs), a profile read from a CSV written out as the
/// knots it resolved to (`spec`), without its impact position.
fn session_of_point<T: serde::Serialize>(tree: &T, spec: &CollisionSpec) -> Result<Value, String> {
    let mut base = serde_json::to_value(tree).map_err(|e| e.to_string())?;
    let model = serde_json::to_value(spec.model).map_err(|e| e.to_string())?;
    if let Some(m) = base.as_object_mut() {
        m.remove("model");
        m.remove("impact");
        if spec.impact.offset != 0.0 {
            m.insert("impact".into(), json!({"offset": spec.impact.offset}));
        }
    }
    if base["bat"]["profile"].get("csv").is_some() {
        base["bat"]["profile"] =
            serde_json::to_value(&spec.bat.profile).map_err(|e| e.to_string())?;
        if let Some(shell) = &spec.bat.shell {
            base["bat"]["shell"] = serde_json::to_value(shell).map_err(|e| e.to_string())?;
        }
    }
    let length = BatGeometry::resolve(&spec.bat).map_or(0.84, |g| g.length);
    let end = (length - 0.03).max(0.51);
    with_knots(json!({"model": model, "base": base, "impact": [0.50, round_cm(end), 0.01]}))
}

fn round_cm(x: f64) -> f64 {
    (x * 100.0).floor() / 100.0
}

/// The session with its bat's profile written out as knots (`[[z, R], ...]`, m) where it
/// was the preset's, so that the page can drag them; and a hollow preset's wall along the
/// bat as its thickness knots (`bat.shell.thickness_knots`, m) and its plies
/// (`bat.shell.layers`), so that the page can edit them.
pub fn with_knots(mut session: Value) -> Result<Value, String> {
    let bat = session["base"]["bat"].clone();
    let spec: crate::model::spec::BatSpec =
        serde_json::from_value(bat).map_err(|e| format!("bat: {e}"))?;
    let expanded = crate::model::bat::hollow_presets::expand(&spec);
    let own_wall = spec
        .shell
        .as_ref()
        .is_some_and(|s| s.thickness.is_some() || s.thickness_knots.is_some());
    let own_layers = spec.shell.as_ref().is_some_and(|s| s.layers.is_some());
    let preset_shell = expanded.shell.as_ref();
    let knots = preset_shell
        .and_then(|s| s.thickness_knots.clone())
        .filter(|_| !own_wall);
    let layers = preset_shell
        .and_then(|s| s.layers.clone())
        .filter(|_| !own_layers);
    if knots.is_some() || layers.is_some() {
        let shell = &mut session["base"]["bat"]["shell"];
        if !shell.is_object() {
            *shell = json!({});
        }
        if let Some(k) = knots {
            shell["thickness_knots"] = json!(k);
        }
        if let Some(mut l) = layers {
            // written beside the knots, the stack is the wall where it is thickest (every
            // layer scales with the local thickness: the same wall)
            let thickest = shell["thickness_knots"]
                .as_array()
                .map(|k| k.iter().filter_map(|p| p[1].as_f64()).fold(0.0, f64::max))
                .unwrap_or(0.0);
            let total: f64 = l.iter().map(|p| p.thickness).sum();
            if thickest > 0.0 && total > 0.0 {
                l.iter_mut().for_each(|p| p.thickness *= thickest / total);
            }
            shell["layers"] = serde_json::to_value(l).map_err(|e| e.to_string())?;
        }
    }
    if spec.profile.is_none() {
        let g = BatGeometry::resolve(&spec).map_err(|e| e.to_string())?;
        let knots: Vec<[f64; 2]> = g
            .profile
            .knots_z()
            .iter()
            .map(|&z| [z, g.profile.radius(z)])
            .collect();
        session["base"]["bat"]["profile"] =
            serde_json::to_value(ProfileSpec::Knots(knots)).map_err(|e| e.to_string())?;
    }
    Ok(session)
}

/// The study file a session stands for: its base block, its model, and the impact range
/// as the grid's one axis.
pub fn study_text(session: &Value) -> Result<String, String> {
    let obj = session.as_object().ok_or("the session is not an object")?;
    let model = obj
        .get("model")
        .and_then(Value::as_str)
        .ok_or("session.model: a string (wave or rigid) is needed")?;
    if !matches!(model, "wave" | "rigid") {
        return Err(format!(
            "session.model: {model:?} is not one of wave, rigid"
        ));
    }
    let base = obj
        .get("base")
        .and_then(Value::as_object)
        .ok_or("session.base: an object (a study's base block) is needed")?;
    let range = impact_range(obj.get("impact"))?;
    let base_yaml =
        yaml_serde::to_string(&Value::Object(base.clone())).map_err(|e| e.to_string())?;
    let mut text = String::from(
        "# A batstudy lab session: `batstudy run` on this file computes what the lab showed.\n\
         name: lab\n",
    );
    text.push_str(&format!("model: {model}\nbase:\n"));
    for line in base_yaml.lines() {
        text.push_str("  ");
        text.push_str(line);
        text.push('\n');
    }
    text.push_str(&format!(
        "grid:\n  impact.z: {{range: [{}, {}, {}]}}\n",
        range[0], range[1], range[2]
    ));
    Ok(text)
}

/// `[from, to, step]`, m: finite, rising, at most [`MAX_POSITIONS`] positions.
fn impact_range(v: Option<&Value>) -> Result<[f64; 3], String> {
    let allowed = "session.impact: [from, to, step] in m, from < to, step > 0";
    let a: Vec<f64> = v
        .and_then(Value::as_array)
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default();
    let [from, to, step] = <[f64; 3]>::try_from(a).map_err(|_| allowed.to_string())?;
    if !(from.is_finite() && to.is_finite() && step.is_finite() && from < to && step > 0.0) {
        return Err(format!("{allowed}; got [{from}, {to}, {step}]"));
    }
    let n = ((to - from) / step).floor() + 1.0;
    if n > MAX_POSITIONS as f64 {
        return Err(format!(
            "session.impact: {n} positions; the lab sweeps at most {MAX_POSITIONS} (a larger step)"
        ));
    }
    Ok([from, to, step])
}

/// A session's JSON object from the page's bytes.
pub fn parse(body: &[u8]) -> Result<Value, String> {
    let v: Value =
        serde_json::from_slice(body).map_err(|e| format!("the session is not JSON: {e}"))?;
    match v {
        Value::Object(_) => Ok(v),
        _ => Err("the session is not a JSON object".into()),
    }
}
