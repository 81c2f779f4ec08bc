//! The data that flows from the runner to the store: the shape of a study's result
//! arrays, and one finished point. Plain data; no I/O.

use batstudy_physics::outcome::{BatProperties, HistoryRequest, Outcome};
use std::ops::Range;
use std::sync::Arc;

/// The names the results file gives its own variables beside a study's coordinates (in
/// `/summary`, `/sweet_spot`, `/history`; `history` is the Python reader's dimension of
/// stored histories): a study's dimension or coordinate may not take one.
/// `store::layout`'s tests keep this list complete.
pub const RESERVED_NAMES: &[&str] = &[
    "exit_speed",
    "exit_speed_lab",
    "collision_efficiency",
    "approach_speed",
    "contact_time",
    "peak_force",
    "max_compression",
    "impulse",
    "energy_initial",
    "energy_ball_final",
    "energy_ball_loss",
    "energy_bat_rigid",
    "energy_bat_vibration",
    "energy_hoop",
    "grip_vibration_amplitude",
    "grip_recoil_speed",
    "energy_bat_damping",
    "energy_grip_damping",
    "impulse_time_99",
    "bbcor",
    "besr",
    "bpf",
    "hoop_mode_frequency",
    "hoop_mode_mass",
    "tangential_cor",
    "bat_speed",
    "launch_angle",
    "spray_angle",
    "spin",
    "sidespin",
    "carry",
    "apex",
    "hang_time",
    "energy_friction",
    "bat_speed_6in",
    "pitch_speed_plate",
    "collision_efficiency_q",
    "squared_up",
    "trajectory_x",
    "trajectory_y",
    "trajectory_z",
    "flight_time",
    "recontact",
    "status",
    "point_id",
    "bat_index",
    "position",
    "width",
    "min_vibration_position",
    "min_vibration_amplitude",
    "min_vibration_energy_position",
    "carry_position",
    "position_at_edge",
    "time",
    "z",
    "force",
    "compression",
    "ball_velocity",
    "displacement",
    "rigid_translation",
    "rigid_rotation",
    "hoop_displacement",
    "modal_coordinate",
    "bat_load",
    "static_shape",
    "bat_mode",
    "shape_point",
    "history",
];

/// The names `/uncertainty` gives its variables beside the study's coordinates:
/// reserved too ([`is_reserved`]); `store::build::uncertainty` writes them.
pub const UNCERTAINTY_NAMES: &[&str] = &[
    "quantile",
    "exit_speed",
    "exit_speed_mean",
    "exit_speed_std",
    "bbcor",
    "bbcor_mean",
    "bbcor_std",
    "sweet_spot_position",
    "sweet_spot_position_mean",
    "sweet_spot_position_std",
    "sweet_spot_exit_speed",
    "sweet_spot_exit_speed_mean",
    "sweet_spot_exit_speed_std",
    "bbcor_max",
    "bbcor_max_mean",
    "bbcor_max_std",
    "bbcor_max_above_limit",
];

/// Whether the results file uses `name` for a variable of its own beside a study's
/// coordinates ([`RESERVED_NAMES`], [`UNCERTAINTY_NAMES`]).
pub fn is_reserved(name: &str) -> bool {
    RESERVED_NAMES.contains(&name) || UNCERTAINTY_NAMES.contains(&name)
}

/// Every reserved name once: [`RESERVED_NAMES`], then the names only `/uncertainty` uses.
pub fn reserved_names() -> impl Iterator<Item = &'static str> {
    let own = UNCERTAINTY_NAMES
        .iter()
        .filter(|n| !RESERVED_NAMES.contains(n));
    RESERVED_NAMES.iter().chain(own).copied()
}

/// A stable identifier of one point: a hash of its canonical (fully resolved) parameters.
pub type PointId = u64;

/// Values of one coordinate variable.
#[derive(Debug, Clone, PartialEq)]
pub enum CoordValues {
    Numbers(Vec<f64>),
    Labels(Vec<String>),
}

impl CoordValues {
    pub fn len(&self) -> usize {
        match self {
            CoordValues::Numbers(v) => v.len(),
            CoordValues::Labels(v) => v.len(),
        }
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A coordinate variable along one dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct Coord {
    /// Variable name, e.g. `impact_z` (dotted path with `.` → `_`).
    pub name: String,
    /// The dotted parameter path it came from, e.g. `impact.z`.
    pub path: String,
    /// Unit string (UDUNITS style: `m`, `rad/s`, `kg/m^3`, `1` for none, `` for labels).
    pub units: String,
    /// Short, for a plot's axis label.
    pub long_name: String,
    /// The full sentence.
    pub description: String,
    pub values: CoordValues,
}

/// One dimension of the result arrays. A grid axis has one coordinate of the same name
/// (its dimension scale); a `zip` or `points` block has one coordinate per parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Dim {
    pub name: String,
    pub size: usize,
    pub coords: Vec<Coord>,
}

/// The N-dimensional index space of a study's results, row-major (last dim fastest).
/// A point's flat index is its position in this row-major order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ResultShape {
    pub dims: Vec<Dim>,
}

impl ResultShape {
    /// The same dims and coordinates, numbers compared bit for bit (a NaN coordinate, as a
    /// parameter left unset along a `zip`, equals itself here, unlike under `==`).
    pub fn identical(&self, other: &ResultShape) -> bool {
        let values = |a: &CoordValues, b: &CoordValues| match (a, b) {
            (CoordValues::Numbers(x), CoordValues::Numbers(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits())
            }
            (CoordValues::Labels(x), CoordValues::Labels(y)) => x == y,
            _ => false,
        };
        let coord = |a: &Coord, b: &Coord| {
            (&a.name, &a.path, &a.units, &a.long_name) == (&b.name, &b.path, &b.units, &b.long_name)
                && values(&a.values, &b.values)
        };
        self.dims.len() == other.dims.len()
            && self.dims.iter().zip(&other.dims).all(|(a, b)| {
                a.name == b.name
                    && a.size == b.size
                    && a.coords.len() == b.coords.len()
                    && a.coords.iter().zip(&b.coords).all(|(p, q)| coord(p, q))
            })
    }

    pub fn n_points(&self) -> usize {
        self.dims.iter().map(|d| d.size).product()
    }
    /// Row-major multi-index of a flat index.
    pub fn unravel(&self, mut flat: usize) -> Vec<usize> {
        let mut idx = vec![0; self.dims.len()];
        for (k, d) in self.dims.iter().enumerate().rev() {
            idx[k] = flat % d.size;
            flat /= d.size;
        }
        idx
    }
}

/// One distinct bat of a study (many points share one).
#[derive(Debug, Clone, PartialEq)]
pub struct BatVariant {
    /// Short human label, e.g. `r161` or `r161, bat.material.density=700`.
    pub label: String,
    /// The bat's resolved parameters as canonical JSON.
    pub spec_json: String,
    pub properties: BatProperties,
    /// Its mode shapes, for the modal form of its displacement histories (None: a wall, or
    /// a bat that could not be prepared).
    pub shapes: Option<ShapeSource>,
}

/// A bat's mode shapes at its shape points (`model::bat::shapes`), taken a block of modes at
/// a time when a stored history first needs them: the store writes only the modes some
/// history steps (a bat's every mode is some 230 KB, a history's coordinates a tenth of it).
#[derive(Clone)]
pub struct ShapeSource {
    /// Positions of the shape points, m from the knob.
    pub z: Vec<f64>,
    /// Number of modes of the bat.
    pub modes: usize,
    /// The scaled shapes of a range of modes at the shape points, mode-major.
    pub shapes: Arc<dyn Fn(Range<usize>) -> Vec<f64> + Send + Sync>,
}

impl std::fmt::Debug for ShapeSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeSource")
            .field("points", &self.z.len())
            .field("modes", &self.modes)
            .finish_non_exhaustive()
    }
}

/// The same points and number of modes (the shapes themselves come from the bat).
impl PartialEq for ShapeSource {
    fn eq(&self, other: &Self) -> bool {
        self.modes == other.modes
            && self.z.len() == other.z.len()
            && self
                .z
                .iter()
                .zip(&other.z)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

/// Everything the store needs to know about a study before the first point arrives.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyInfo {
    pub name: String,
    pub description: String,
    /// The study file's text, verbatim.
    pub study_text: String,
    /// Hex SHA-256 of `study_text`.
    pub study_sha256: String,
    /// Path of the study file as given.
    pub study_path: String,
    pub shape: ResultShape,
    /// Histories to store (None: summary only).
    pub history: Option<HistoryRequest>,
    pub bats: Vec<BatVariant>,
    /// The study accepts values outside the plausible ranges (`allow_implausible`).
    pub allow_implausible: bool,
    /// The dimension a `sample` block draws, if any: its statistics go to `/uncertainty`.
    pub sample_dim: Option<String>,
}

/// How a study's points are stored together: runs of `size` consecutive points along its
/// last dim, whose `row` points each row holds (a row's last group may be shorter). The
/// histories of a group share one chunk per variable (`store::encode`), so a group is
/// computed, journalled and placed as one: it is stored whole or not at all.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PointGroups {
    size: usize,
    row: usize,
}

impl PointGroups {
    /// Every point on its own.
    pub fn single() -> Self {
        PointGroups { size: 1, row: 1 }
    }

    /// Groups of `size` points along a last dim of `row` points (both at least 1; a group
    /// is no longer than a row).
    pub fn new(size: usize, row: usize) -> Self {
        let row = row.max(1);
        PointGroups {
            size: size.clamp(1, row),
            row,
        }
    }

    /// Points a group spans: its chunk's extent along the last dim.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The first point of the group that holds point `i`.
    pub fn start(&self, i: usize) -> usize {
        let row = i - i % self.row;
        row + (i - row) / self.size * self.size
    }

    /// One past the last point of the group that holds point `i`.
    pub fn end(&self, i: usize) -> usize {
        let row = i - i % self.row;
        (self.start(i) + self.size).min(row + self.row)
    }
}

/// One finished point.
#[derive(Debug, Clone)]
pub struct PointRecord {
    /// Flat index in the study's `ResultShape`.
    pub index: usize,
    pub id: PointId,
    /// Index of the point's bat in `StudyInfo::bats`.
    pub bat: u32,
    /// The outcome, or the error text of a failed point.
    pub result: Result<Outcome, String>,
}

/// Suffix of a `points`/`zip` dim's label coordinate (`case` → `case_label`).
pub const LABEL_SUFFIX: &str = "_label";

/// `s` as it may reach a terminal: control characters (an escape sequence would recolour
/// or clear the user's screen, a carriage return overwrite a line) and the bidirectional
/// overrides (which reorder what is shown) written as `\u{..}` escapes. `lines` keeps line
/// breaks (a description's own). Study files and results files are data, never commands
/// to the terminal.
pub fn printable(s: &str, lines: bool) -> std::borrow::Cow<'_, str> {
    let bidi = |c: char| matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}');
    let bad = |c: char| c.is_control() && !(lines && c == '\n') || bidi(c);
    if !s.chars().any(bad) {
        return s.into();
    }
    s.chars()
        .map(|c| match bad(c) {
            true => c.escape_unicode().to_string(),
            false => c.to_string(),
        })
        .collect::<String>()
        .into()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Groups tile each row from its start, the last one shorter; they never cross rows.
    #[test]
    fn point_groups_tile_each_row() {
        let g = PointGroups::new(4, 10);
        let starts: Vec<usize> = (0..20).map(|i| g.start(i)).collect();
        assert_eq!(
            starts,
            [0, 0, 0, 0, 4, 4, 4, 4, 8, 8, 10, 10, 10, 10, 14, 14, 14, 14, 18, 18]
        );
        assert_eq!((g.end(9), g.end(10), g.end(19)), (10, 14, 20));
        assert_eq!(PointGroups::new(8, 3).size(), 3, "no longer than a row");
        let one = PointGroups::single();
        assert!((0..7).all(|i| one.start(i) == i && one.end(i) == i + 1));
    }

    // `/uncertainty`'s names are reserved, and the listing a refusal prints holds
    // every reserved name once.
    #[test]
    fn uncertainty_names_are_reserved_and_listed_once() {
        let listed: Vec<&str> = reserved_names().collect();
        for n in UNCERTAINTY_NAMES.iter().chain(RESERVED_NAMES) {
            assert!(is_reserved(n), "{n}");
            assert_eq!(listed.iter().filter(|l| *l == n).count(), 1, "{n}");
        }
        assert_eq!(
            listed.len(),
            RESERVED_NAMES.len() + 15,
            "15 names of /uncertainty's own"
        );
    }

    fn shape(density: Vec<f64>) -> ResultShape {
        ResultShape {
            dims: vec![Dim {
                name: "bat".into(),
                size: density.len(),
                coords: vec![Coord {
                    name: "bat_material_density".into(),
                    path: "bat.material.density".into(),
                    units: "kg/m^3".into(),
                    long_name: "bat density".into(),
                    description: "bat wood density".into(),
                    values: CoordValues::Numbers(density),
                }],
            }],
        }
    }

    /// Regression: the smoke study's `points` dim has NaN coordinates (a parameter a point
    /// leaves unset), and a results file begun for its shape was refused as "another shape"
    /// because NaN != NaN.
    #[test]
    fn shapes_with_nan_coordinates_are_identical_to_themselves() {
        let a = shape(vec![f64::NAN, 500.0, 640.0]);
        assert!(
            a != a.clone(),
            "under == a NaN coordinate differs from itself"
        );
        assert!(a.identical(&a.clone()));
        assert!(!a.identical(&shape(vec![f64::NAN, 500.0, 641.0])));
        assert!(!a.identical(&shape(vec![0.0, 500.0, 640.0])));
        assert!(!a.identical(&shape(vec![f64::NAN, 500.0])));
    }
}
