//! Dotted parameter paths: which exist (taken from the `CollisionSpec` schema), how to set
//! one on a YAML value tree, and their units for the result coordinates.

use crate::model::spec::CollisionSpec;
use serde_json::Value as J;
use std::collections::BTreeMap;
use std::sync::OnceLock;
use yaml_serde::{Mapping, Value};

/// Kind of node a path names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathKind {
    /// A record with named fields (`bat`, `bat.material`, `hoop`, …).
    Record,
    /// A value (number, label, list).
    Leaf,
}

/// Every dotted path of `CollisionSpec` (records and leaves), from its JSON Schema.
pub fn known_paths() -> &'static BTreeMap<String, PathKind> {
    static PATHS: OnceLock<BTreeMap<String, PathKind>> = OnceLock::new();
    PATHS.get_or_init(|| {
        let schema = schemars::schema_for!(CollisionSpec);
        let root = schema.as_value().clone();
        let defs = root.get("$defs").cloned().unwrap_or(J::Null);
        let mut out = BTreeMap::new();
        walk(&root, &defs, "", &mut out, 0);
        out
    })
}

fn props_of<'a>(node: &'a J, defs: &'a J, acc: &mut Vec<(&'a String, &'a J)>, depth: usize) {
    if depth > 8 {
        return;
    }
    if let Some(r) = node.get("$ref").and_then(J::as_str) {
        if let Some(t) = r.strip_prefix("#/$defs/").and_then(|n| defs.get(n)) {
            props_of(t, defs, acc, depth + 1);
        }
    }
    for key in ["anyOf", "oneOf", "allOf"] {
        if let Some(arr) = node.get(key).and_then(J::as_array) {
            for b in arr {
                props_of(b, defs, acc, depth + 1);
            }
        }
    }
    if let Some(p) = node.get("properties").and_then(J::as_object) {
        acc.extend(p.iter());
    }
}

fn walk(node: &J, defs: &J, prefix: &str, out: &mut BTreeMap<String, PathKind>, depth: usize) {
    let mut props = Vec::new();
    props_of(node, defs, &mut props, 0);
    if !prefix.is_empty() {
        let kind = if props.is_empty() {
            PathKind::Leaf
        } else {
            PathKind::Record
        };
        out.insert(prefix.to_string(), kind);
    }
    if depth > 6 {
        return;
    }
    for (name, sub) in props {
        let p = if prefix.is_empty() {
            name.clone()
        } else {
            format!("{prefix}.{name}")
        };
        walk(sub, defs, &p, out, depth + 1);
    }
}

/// The fields directly under a record path (`""` for the top).
pub fn children(path: &str) -> Vec<&'static str> {
    let depth = if path.is_empty() {
        0
    } else {
        path.split('.').count()
    };
    known_paths()
        .keys()
        .filter(|k| {
            let segs = k.split('.').count();
            segs == depth + 1 && (path.is_empty() || k.starts_with(&format!("{path}.")))
        })
        .map(|k| k.rsplit('.').next().unwrap())
        .collect()
}

/// Set `path` (dotted) to `v` in `root`, creating intermediate records (a `null` record,
/// e.g. `hoop: null`, becomes one). Setting a field of `bat.profile` replaces the whole
/// profile (it is one of `knots` / `csv`).
pub fn set_path(root: &mut Value, path: &str, v: Value) -> Result<(), String> {
    let segs: Vec<&str> = path.split('.').collect();
    let mut cur = root;
    for (i, seg) in segs.iter().enumerate() {
        if cur.is_null() {
            *cur = Value::Mapping(Mapping::new());
        }
        let parent = segs[..i].join(".");
        let Value::Mapping(m) = cur else {
            return Err(format!("cannot set `{path}`: `{parent}` is not a record"));
        };
        if i + 1 == segs.len() {
            if parent == "bat.profile" {
                m.clear();
            }
            m.insert(Value::from(*seg), v);
            return Ok(());
        }
        let key = Value::from(*seg);
        if !m.contains_key(&key) {
            m.insert(key.clone(), Value::Null);
        }
        cur = m.get_mut(&key).unwrap();
    }
    *cur = v;
    Ok(())
}

/// The value at `path` in `root`, if any.
pub fn get_path<'a>(root: &'a Value, path: &str) -> Option<&'a Value> {
    if path.is_empty() {
        return Some(root);
    }
    path.split('.').try_fold(root, |cur, seg| cur.get(seg))
}

/// The result coordinate name of a path: `.` → `_`.
pub fn coord_name(path: &str) -> String {
    path.replace('.', "_")
}

/// What a coordinate of a parameter path says about itself.
#[derive(Debug, Clone, PartialEq)]
pub struct PathMeta {
    /// UDUNITS style; `1` dimensionless, empty for text.
    pub units: &'static str,
    /// Short, for a plot's axis label.
    pub long_name: String,
    /// The full sentence.
    pub description: String,
}

/// Units (UDUNITS style), a short long name and a description per parameter path.
const PATH_META: &[(&str, &str, &str, &str)] = &[
    ("impact.z", "m", "impact z", "impact position from the knob"),
    (
        "impact.offset",
        "m",
        "offset",
        "distance of the ball's centre line below (+) or above (-) the bat's axis",
    ),
    (
        "ball.spin",
        "rad/s",
        "pitch spin",
        "pitch's spin about the bat's axis, backspin positive",
    ),
    ("ball.radius", "m", "ball radius", "ball radius"),
    (
        "ball.inertia_factor",
        "1",
        "ball I/mr²",
        "ball moment of inertia over m r^2",
    ),
    (
        "ball.law.friction",
        "1",
        "friction",
        "coefficient of friction between ball and bat",
    ),
    (
        "ball.law.tangential_ratio",
        "1",
        "k_t / k_n",
        "ball's tangential stiffness over its normal (secant) stiffness",
    ),
    (
        "swing.attack_angle",
        "rad",
        "attack angle",
        "elevation of the bat's path",
    ),
    (
        "swing.attack_direction",
        "rad",
        "attack direction",
        "direction of the bat's path from straight to the pitcher, toward first base positive",
    ),
    (
        "swing.tilt",
        "rad",
        "vertical bat angle",
        "tilt of the bat's axis about its path, barrel down negative",
    ),
    (
        "batter.pitch_speed",
        "m/s",
        "pitch speed",
        "lab speed of the pitch, arriving along the bat's path",
    ),
    (
        "pitch.speed",
        "m/s",
        "pitch speed",
        "lab speed of the pitch at contact",
    ),
    (
        "pitch.descent_angle",
        "rad",
        "descent angle",
        "angle of the pitch's path below the horizontal at contact",
    ),
    (
        "pitch.horizontal_angle",
        "rad",
        "horizontal approach angle",
        "angle of the pitch's path from straight to the catcher, toward first base positive",
    ),
    (
        "batter.bat_speed",
        "m/s",
        "swing speed",
        "the batter's swing speed with the reference bat",
    ),
    (
        "batter.bat_speed_at",
        "m",
        "swing speed at",
        "where the swing speed is measured",
    ),
    (
        "batter.reference_moi",
        "kg m^2",
        "reference MOI",
        "the reference bat's moment of inertia about the pivot",
    ),
    (
        "batter.exponent",
        "1",
        "swing exponent n",
        "exponent of the swing speed's MOI law",
    ),
    (
        "batter.pivot",
        "m",
        "swing pivot",
        "the point the swing turns about, from the knob",
    ),
    (
        "flight.temperature",
        "K",
        "air temperature",
        "air temperature",
    ),
    (
        "flight.pressure",
        "Pa",
        "pressure",
        "barometric pressure at sea level",
    ),
    (
        "flight.elevation",
        "m",
        "elevation",
        "elevation of the field",
    ),
    ("flight.humidity", "1", "humidity", "relative humidity"),
    ("flight.wind_speed", "m/s", "wind", "wind speed"),
    (
        "flight.wind_direction",
        "rad",
        "wind direction",
        "where the wind blows to, from centre field",
    ),
    (
        "flight.height",
        "m",
        "contact height",
        "height of the contact point",
    ),
    (
        "swing.omega",
        "rad/s",
        "swing ω",
        "initial angular velocity of the bat (negative: toward the ball)",
    ),
    (
        "swing.cm_speed",
        "m/s",
        "bat CM speed",
        "lab-frame speed of the bat's centre of mass",
    ),
    (
        "bat.material.density",
        "kg/m^3",
        "bat density",
        "bat wall density",
    ),
    (
        "bat.material.youngs_modulus",
        "Pa",
        "bat Y",
        "bat Young's modulus",
    ),
    (
        "bat.material.poisson_ratio",
        "1",
        "bat ν",
        "bat Poisson's ratio",
    ),
    (
        "bat.material.shear_modulus",
        "Pa",
        "bat G",
        "bat shear modulus",
    ),
    (
        "bat.material.quality_factor",
        "1",
        "bat Q",
        "bat modal quality factor",
    ),
    ("bat.length", "m", "bat length", "bat length"),
    (
        "bat.radius",
        "m",
        "cylinder radius",
        "radius of the rigid cylinder (bat.preset cylinder)",
    ),
    (
        "bat.shell.thickness",
        "m",
        "shell",
        "bat shell wall thickness",
    ),
    (
        "bat.shell.from",
        "m",
        "shell from",
        "start of the hollow part, from the knob",
    ),
    (
        "bat.bore.diameter",
        "m",
        "bore",
        "diameter of the axial bore",
    ),
    (
        "bat.bore.depth",
        "m",
        "bore depth",
        "depth of the bore from the barrel end",
    ),
    (
        "bat.bore.fill_density",
        "kg/m^3",
        "bore fill",
        "density of the bore's filling",
    ),
    (
        "bat.fill.density",
        "kg/m^3",
        "fill density",
        "density of the bat's filling",
    ),
    (
        "bat.handle.radius_scale",
        "1",
        "handle scale",
        "handle radius multiplier",
    ),
    (
        "bat.handle.end",
        "m",
        "handle end",
        "end of the handle from the knob",
    ),
    (
        "bat.handle.blend",
        "m",
        "handle blend",
        "length of the handle blend",
    ),
    ("bat.preset", "", "bat", "built-in bat"),
    ("bat.ends.knob", "", "knob end", "knob end condition"),
    ("bat.ends.barrel", "", "barrel end", "barrel end condition"),
    ("bat.profile.csv", "", "profile", "bat profile file"),
    ("bat.grip.kind", "", "grip", "kind of grip (the hands)"),
    ("bat.grip.z", "m", "grip z", "grip position from the knob"),
    (
        "bat.grip.stiffness",
        "N/m",
        "grip k",
        "grip spring stiffness",
    ),
    ("bat.grip.damping", "N s/m", "grip c", "grip damping"),
    ("ball.mass", "kg", "ball mass", "ball mass"),
    (
        "ball.speed",
        "m/s",
        "ball speed",
        "ball speed toward the bat (bat CM frame)",
    ),
    ("ball.law.kind", "", "ball law", "ball force law"),
    (
        "ball.law.stiffness",
        "N/m",
        "ball k",
        "ball loading stiffness",
    ),
    (
        "ball.law.cor",
        "1",
        "ball COR",
        "ball coefficient of restitution",
    ),
    (
        "ball.law.k1",
        "N m^-alpha",
        "ball k1",
        "ball power-law loading coefficient",
    ),
    (
        "ball.law.alpha",
        "1",
        "ball α",
        "ball power-law loading exponent",
    ),
    (
        "ball.law.reference_speed",
        "m/s",
        "COR speed",
        "speed at which the ball's COR is ball.law.cor",
    ),
    (
        "ball.law.cor_slope",
        "s/m",
        "COR slope",
        "change of the ball's COR per m/s of impact speed",
    ),
    (
        "ball.law.cor_exponent",
        "1",
        "COR exponent",
        "exponent of the ball's COR curve e(v) = cor (v / reference_speed)^-exponent",
    ),
    (
        "ball.law.cor_at_rest",
        "1",
        "COR at rest",
        "the ball's COR as the speed goes to 0, of e(v) = cor_at_rest - (cor_at_rest - cor) (v / reference_speed)^cor_power",
    ),
    (
        "ball.law.cor_shift",
        "1",
        "COR shift",
        "shift added to the ball's COR at every speed (one ball or lot off the curve)",
    ),
    (
        "ball.law.cor_power",
        "1",
        "COR power",
        "power of the speed in e(v) = cor_at_rest - (cor_at_rest - cor) (v / reference_speed)^cor_power",
    ),
    ("ball.preset", "", "ball", "built-in calibrated ball"),
    (
        "ball.law.curvature",
        "",
        "ball sees curvature",
        "whether the ball's law sees the target's curvature (Hertz's stiffness, the COR at equal strain)",
    ),
    (
        "ball.law.loading",
        "",
        "ball loading",
        "loading branch of the speed-dependent ball",
    ),
    (
        "numerics.max_steps",
        "1",
        "max steps",
        "step budget of one collision",
    ),
    ("hoop.frequency", "Hz", "hoop f", "hoop-mode frequency"),
    ("hoop.mass", "kg", "hoop mass", "hoop-mode effective mass"),
    (
        "hoop.patch_radius",
        "m",
        "patch radius",
        "radius of a fixed contact patch over which the shell's modes are loaded",
    ),
    (
        "hoop.footprint_ratio",
        "1",
        "footprint ratio",
        "the ball's footprint on the wall over the overlap of ball and barrel",
    ),
    (
        "numerics.shell_elements",
        "1",
        "shell elements",
        "elements along the hollow part solved as a shell",
    ),
    (
        "numerics.shell_wave_numbers",
        "",
        "shell wave numbers",
        "circumferential wave numbers of the shell's modes",
    ),
    (
        "numerics.shell_modes_per_wave",
        "1",
        "shell modes per wave",
        "axial modes kept per wave number",
    ),
    (
        "numerics.segments",
        "1",
        "segments",
        "number of beam segments",
    ),
    ("numerics.dt", "s", "dt", "time step"),
    ("numerics.integrator", "", "integrator", "time integrator"),
    ("model", "", "model", "collision model"),
];

/// Units, a short long name and a description per path (unknown paths: the path itself).
pub fn meta(path: &str) -> PathMeta {
    let (u, short, long) = PATH_META
        .iter()
        .find(|(p, ..)| *p == path)
        .map_or(("", "", ""), |&(_, u, short, long)| (u, short, long));
    let or_path = |t: &str| {
        if t.is_empty() {
            path.to_string()
        } else {
            t.to_string()
        }
    };
    PathMeta {
        units: u,
        long_name: or_path(short),
        description: or_path(long),
    }
}

/// The base tree with every defaulted field filled in (as far as the base deserializes
/// with a placeholder impact), so that coordinates show the values points really use.
pub fn with_defaults(base: &Value) -> Value {
    let mut v = base.clone();
    if super::paths::get_path(&v, "impact.z").is_none() {
        let _ = set_path(&mut v, "impact.z", Value::from(0.0));
    }
    serde_json::to_value(&v)
        .ok()
        .and_then(|j| serde_json::from_value::<crate::model::spec::CollisionSpec>(j).ok())
        .and_then(|spec| yaml_serde::to_value(spec).ok())
        .unwrap_or_else(|| base.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn public_paths_are_known() {
        // the public spellings of study files
        for p in [
            "bat.material.density",
            "bat.material.youngs_modulus",
            "bat.preset",
            "bat.handle.radius_scale",
            "bat.length",
            "bat.radius",
            "bat.shell.thickness",
            "bat.shell.from",
            "bat.ends.barrel",
            "bat.ends.knob",
            "bat.profile.knots",
            "bat.profile.csv",
            "swing.omega",
            "hoop.frequency",
            "hoop.mass",
            "ball.speed",
            "ball.mass",
            "ball.law.kind",
            "ball.law.stiffness",
            "ball.law.cor",
            "ball.law.k1",
            "ball.law.alpha",
            "impact.z",
            "model",
            "numerics.segments",
            "numerics.dt",
            "numerics.integrator",
        ] {
            assert!(
                known_paths().contains_key(p),
                "{p} missing: {:?}",
                known_paths()
            );
        }
        assert_eq!(known_paths()["bat.material"], PathKind::Record);
        assert_eq!(known_paths()["hoop"], PathKind::Record);
        assert!(children("bat.material").contains(&"density"));
    }

    #[test]
    fn set_path_creates_records() {
        let mut v: Value = yaml_serde::from_str("hoop: null\nbat: {profile: {knots: []}}").unwrap();
        set_path(&mut v, "hoop.frequency", Value::from(1000.0)).unwrap();
        set_path(&mut v, "impact.z", Value::from(0.7)).unwrap();
        set_path(&mut v, "bat.profile.csv", Value::from("x.csv")).unwrap();
        assert_eq!(
            get_path(&v, "hoop.frequency").unwrap().as_f64(),
            Some(1000.0)
        );
        assert_eq!(get_path(&v, "impact.z").unwrap().as_f64(), Some(0.7));
        assert!(get_path(&v, "bat.profile.knots").is_none());
        assert!(set_path(&mut v, "impact.z.q", Value::from(1)).is_err());
    }
}
