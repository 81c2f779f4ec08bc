//! The parameters a collision really uses: its spec with every field that a preset or a
//! default fills in set to that value (`bat.material.density` of the `r161` preset is 649,
//! not "unset"). The store labels its coordinates with these, so that a point that leaves
//! a field to its preset still shows the number it ran with.

use crate::ball::{DEFAULT_COR_SLOPE, DEFAULT_REFERENCE_SPEED};
use crate::bat::section::BatGeometry;
use crate::spec::{BallLawKind, CollisionSpec};
use serde_json::{json, Value};

/// The spec as a JSON tree, preset and default values filled in where the model defines
/// them. Fields that do not apply stay as they are (`null`: a solid bat's shell).
pub fn resolved_tree(spec: &CollisionSpec) -> Value {
    let mut tree = serde_json::to_value(spec).unwrap_or(Value::Null);
    if !spec.bat.preset.is_rigid_target() {
        if let (Ok(g), Some(bat)) = (BatGeometry::resolve(&spec.bat), tree.get_mut("bat")) {
            bat["length"] = json!(g.length);
            let m = &mut bat["material"];
            m["density"] = json!(g.density);
            m["youngs_modulus"] = json!(g.youngs_modulus);
            m["poisson_ratio"] = json!(g.poisson_ratio);
            m["shear_modulus"] = json!(g.shear_modulus);
            if let Some((thickness, from)) = g.shell {
                bat["shell"] = json!({"thickness": thickness, "from": from});
            }
            if g.fill_density > 0.0 && g.bore.is_none() {
                bat["fill"] = json!({"density": g.fill_density});
            }
        }
    }
    fill_contact_defaults(spec, &mut tree);
    if spec.ball.law.kind == BallLawKind::SpeedDependent {
        if let Some(law) = tree.pointer_mut("/ball/law") {
            law["reference_speed"] = json!(spec
                .ball
                .law
                .reference_speed
                .unwrap_or(DEFAULT_REFERENCE_SPEED));
            let curve = spec.ball.law.cor_exponent.or(spec.ball.law.cor_at_rest);
            if curve.is_none() {
                law["cor_slope"] = json!(spec.ball.law.cor_slope.unwrap_or(DEFAULT_COR_SLOPE));
            }
        }
    }
    tree
}

/// The oblique contact's and the swing's defaults (left out of the canonical spec when they
/// are zero or unset, so that the points that do not use them keep their ids).
fn fill_contact_defaults(spec: &CollisionSpec, tree: &mut Value) {
    let ball = crate::collision::oblique::BallContact::of(&spec.ball);
    let mut set = |pointer: &str, key: &str, value: f64| {
        if let Some(node) = tree.pointer_mut(pointer) {
            if node.get(key).is_none_or(Value::is_null) {
                node[key] = json!(value);
            }
        }
    };
    set("/impact", "offset", 0.0);
    set("/ball", "spin", 0.0);
    set("/ball", "radius", ball.radius);
    let factor = spec
        .ball
        .inertia_factor
        .unwrap_or(crate::ball::DEFAULT_INERTIA_FACTOR);
    set("/ball", "inertia_factor", factor);
    set("/ball/law", "friction", ball.friction);
    set("/ball/law", "tangential_ratio", ball.tangential_ratio);
    set("/swing", "attack_angle", 0.0);
    set("/swing", "attack_direction", 0.0);
    set("/swing", "tilt", 0.0);
}

/// The value at a dotted path (`bat.material.density`) of [`resolved_tree`]; `None` where
/// the path does not exist or is `null`.
pub fn resolved_value(tree: &Value, path: &str) -> Option<Value> {
    let mut v = tree;
    for key in path.split('.') {
        v = v.get(key)?;
    }
    (!v.is_null()).then(|| v.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bat::section::{ALUMINUM_DENSITY, WOOD_DENSITY};

    // The preset tables of model::bat::section (sources there: Nathan 2000; the paper).
    #[test]
    fn presets_fill_in_their_material() {
        let mut spec = CollisionSpec::base_case(0.7);
        let t = resolved_tree(&spec);
        assert_eq!(
            resolved_value(&t, "bat.material.density"),
            Some(json!(WOOD_DENSITY))
        );
        assert_eq!(resolved_value(&t, "bat.shell.thickness"), None);
        spec.bat.preset = crate::spec::BatPreset::Aluminum;
        let t = resolved_tree(&spec);
        assert_eq!(
            resolved_value(&t, "bat.material.density"),
            Some(json!(ALUMINUM_DENSITY))
        );
        assert_eq!(
            resolved_value(&t, "bat.shell.thickness"),
            Some(json!(0.003))
        );
        spec.bat.material.density = Some(2800.0);
        let t = resolved_tree(&spec);
        assert_eq!(
            resolved_value(&t, "bat.material.density"),
            Some(json!(2800.0))
        );
        assert_eq!(resolved_value(&t, "impact.z"), Some(json!(0.7)));
    }
}
