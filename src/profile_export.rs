//! A bat of a results file as a profile CSV (stations from the knob, the outer diameter and
//! the wall, rounded to what a lathe holds in the chosen unit) that a study reads back as the
//! same bat (`bat.profile.csv`): `batstudy export-profile` and the Python package's
//! `export_profile`.

use crate::model::bat::export::{profile_rows, ProfileRow};
use crate::model::bat::section::BatGeometry;
use crate::model::spec::BatSpec;
use crate::store;
use crate::study::error::printable;
use std::path::Path;

/// Units a profile CSV may be written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Units {
    M,
    Mm,
    In,
}

impl Units {
    /// The header's suffix and units per metre.
    fn suffix_and_scale(self) -> (&'static str, f64) {
        match self {
            Units::M => ("m", 1.0),
            Units::Mm => ("mm", 1e3),
            Units::In => ("in", 1.0 / 0.0254),
        }
    }

    /// Decimals of a station and a diameter, and of a wall, in this unit: what a lathe holds
    /// on a diameter (0.001 in, 0.01 mm) and a micrometer reads on a wall (0.0001 in,
    /// 0.001 mm); stations as the diameters.
    fn decimals(self) -> (usize, usize) {
        match self {
            Units::M => (5, 6),
            Units::Mm => (2, 3),
            Units::In => (3, 4),
        }
    }
}

impl std::str::FromStr for Units {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "m" => Ok(Units::M),
            "mm" => Ok(Units::Mm),
            "in" => Ok(Units::In),
            _ => Err(format!("units {}: allowed m, mm, in", printable(s, false))),
        }
    }
}

/// The CSV of bat `bat` (a label or an index; may be left out when the file holds one bat)
/// of the results file `file`, in `units`; or what is wrong, naming the file.
pub fn profile_csv(file: &Path, bat: Option<&str>, units: Units) -> Result<String, String> {
    let shown = printable(&file.display().to_string(), false).to_string();
    let bats = store::inspect::bat_specs(file).map_err(|e| e.to_string())?;
    let labels: Vec<String> = bats.iter().map(|b| b.0.clone()).collect();
    let k = store::inspect::pick_bat(&labels, bat)
        .map_err(|allowed| format!("{shown}: --bat: {allowed}"))?;
    let (label, spec) = (&bats[k].0, &bats[k].1);
    let stored: serde_json::Value = serde_json::from_str(spec)
        .map_err(|e| format!("{shown}: the bat's stored spec is not JSON ({e})"))?;
    let spec: BatSpec = serde_json::from_value(stored["bat"].clone())
        .map_err(|e| format!("{shown}: the bat's stored spec is not a bat ({e})"))?;
    if spec.preset.is_rigid_target() {
        return Err(format!(
            "{shown}: bat {}: a rigid target has no profile",
            printable(label, false)
        ));
    }
    let g = BatGeometry::resolve(&spec).map_err(|e| format!("{shown}: {e}"))?;
    Ok(csv_text(&profile_rows(&g), &g, label, &shown, units))
}

/// The CSV: comment lines (the bat, what the CSV leaves to the study), the header, the rows.
fn csv_text(rows: &[ProfileRow], g: &BatGeometry, label: &str, file: &str, units: Units) -> String {
    let (u, scale) = units.suffix_and_scale();
    let hollow = rows.iter().any(|r| r.wall > 0.0);
    let mut s = format!(
        "# bat {} of {file}, written by batstudy export-profile\n\
         # read back with bat.profile.csv; the CSV holds the outer diameter{}, not the material:\n\
         # bat.material.density {} kg/m3, bat.material.youngs_modulus {} Pa{}\n",
        printable(label, false),
        if hollow {
            " and the wall (0: solid)"
        } else {
            ""
        },
        g.density,
        g.youngs_modulus,
        if g.fill_density > 0.0 {
            format!(", bat.fill.density {} kg/m3", g.fill_density)
        } else {
            String::new()
        }
    );
    s.push_str(&format!("z_{u},diameter_{u}"));
    if hollow {
        s.push_str(&format!(",wall_{u}"));
    }
    s.push('\n');
    let (d, w) = units.decimals();
    for r in rows {
        s.push_str(&format!(
            "{:.d$},{:.d$}",
            r.z * scale,
            2.0 * r.radius * scale
        ));
        if hollow {
            s.push_str(&format!(",{:.w$}", r.wall * scale));
        }
        s.push('\n');
    }
    s
}
