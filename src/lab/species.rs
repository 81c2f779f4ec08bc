//! Wood species for the lab's bat: each species' density and Young's modulus as the R161's
//! (white ash, Nathan 2000's fitted 649 kg/m³ and 1.814e10 Pa) scaled by the species'
//! specific gravity and bending modulus relative to white ash's in the USDA Wood Handbook
//! (table 5-3a at 12 % moisture, second-hand: data/wood_species.md). The handbook's means
//! are of small clear specimens, not bat billets; their ratios carry over to the calibrated
//! ash, their absolute values would not (the handbook's ash bends at 12.0 GPa, the R161's
//! fitted modulus is 18.1).

use crate::model::bat::section::{WOOD_DENSITY, WOOD_YOUNGS_MODULUS};
use serde_json::{json, Value};

/// The handbook's table as the repository keeps it.
const TABLE: &str = include_str!("../../data/wood_species.csv");

/// The reference species the R161's material is.
const ASH: &str = "white ash";

/// The species offered: (name in the table, the name shown).
const OFFERED: [(&str, &str); 5] = [
    ("white ash", "ash (the R161's)"),
    ("sugar maple", "maple"),
    ("yellow birch", "birch"),
    ("American beech", "beech"),
    ("shagbark hickory (true hickory)", "hickory (shagbark)"),
];

/// (specific gravity, bending modulus in Pa) of a species in the table.
fn row(name: &str) -> Option<(f64, f64)> {
    TABLE.lines().skip(1).find_map(|line| {
        let cells: Vec<&str> = line.split(',').collect();
        (cells.first() == Some(&name))
            .then(|| Some((cells.get(2)?.parse().ok()?, cells.get(3)?.parse().ok()?)))
            .flatten()
    })
}

/// The materials a wall's layer may name (`laminate::MATERIALS` and the gap between two
/// walls).
pub fn layer_materials() -> Value {
    let mut names: Vec<&str> = crate::model::bat::laminate::MATERIALS
        .iter()
        .map(|(n, _)| *n)
        .collect();
    names.push(crate::model::bat::laminate::GAP);
    json!(names)
}

/// Every offered species with the `bat.material` it stands for: `[{name, density,
/// youngs_modulus}]` (kg/m³, Pa).
pub fn species() -> Value {
    let Some((sg_ash, e_ash)) = row(ASH) else {
        return json!([]);
    };
    let list: Vec<Value> = OFFERED
        .iter()
        .filter_map(|(key, shown)| {
            let (sg, e) = row(key)?;
            Some(json!({
                "name": shown,
                "density": WOOD_DENSITY * sg / sg_ash,
                "youngs_modulus": WOOD_YOUNGS_MODULUS * e / e_ash,
            }))
        })
        .collect();
    Value::Array(list)
}

#[cfg(test)]
mod tests {
    /// Every offered species is in the table, and ash is the R161 itself.
    #[test]
    fn every_species_is_in_the_table_and_ash_is_the_r161() {
        let list = super::species();
        let list = list.as_array().unwrap();
        assert_eq!(list.len(), super::OFFERED.len());
        assert_eq!(list[0]["density"], super::WOOD_DENSITY);
        assert_eq!(list[0]["youngs_modulus"], super::WOOD_YOUNGS_MODULUS);
        // maple: denser and stiffer than ash in the handbook (0.63 against 0.60; 12.6 GPa
        // against 12.0)
        assert!(list[1]["density"].as_f64().unwrap() > super::WOOD_DENSITY);
    }
}
