//! A bat prepared once for many collisions: geometry, lumped beam, modal basis and derived
//! properties. Read-only after construction, so one `PreparedBat` is shared by every point
//! of a study that uses the same (bat, numerics).

use crate::bat::beam::Beam;
use crate::bat::modal::ModalBasis;
use crate::bat::section::BatGeometry;
use crate::error::{out_of_range, ModelError};
use crate::outcome::BatProperties;
use crate::spec::{BatSpec, EndsSpec, GripKind, GripSpec, NumericsSpec};

/// Default segment length, m: the largest that keeps the exit speed within 0.1 % of the
/// halved-segment value and the uniform-beam modes 1–5 within 0.1 % (see tests).
pub const DEFAULT_SEGMENT_LENGTH: f64 = 0.005;
/// Fewest segments accepted.
pub const MIN_SEGMENTS: usize = 8;
/// Most segments accepted (the dense eigenproblem is O(N³)).
pub const MAX_SEGMENTS: usize = 4000;
/// Flexible modes reported in the properties.
const REPORTED_MODES: usize = 10;
/// NCAA: moment of inertia about the point 6 in from the knob.
const NCAA_PIVOT: f64 = 0.1524;

/// A bat ready to collide.
#[derive(Debug, Clone)]
pub struct PreparedBat {
    pub(crate) geometry: BatGeometry,
    pub(crate) beam: Beam,
    pub(crate) modes: ModalBasis,
    /// Σ_i m_i φ_n,i: the linear momentum carried by unit modal velocity.
    pub(crate) momentum_weight: Vec<f64>,
    /// Σ_i m_i (z_i − z_cm) φ_n,i: the angular momentum about the CM per unit modal velocity.
    pub(crate) angular_weight: Vec<f64>,
    /// CM and moment of inertia of the lumped masses (+ rotary inertias; consistent with
    /// the integrator).
    pub(crate) z_cm: f64,
    pub(crate) inertia_cm: f64,
    /// The lumped beam's mass (`Beam::total_mass`), kg: summed once, not per history sample.
    pub(crate) total_mass: f64,
    /// Modal damping ratio of the flexible modes (0: undamped).
    pub(crate) damping_ratio: f64,
    /// Grip damper, N·s/m (0: none).
    pub(crate) grip_damping: f64,
    /// Moment of inertia about the long axis, kg·m² (the bat's roll, for oblique impacts).
    pub(crate) roll_inertia: f64,
    /// Each mode's largest |scaled shape| over the shape points (`shapes::shape_maxima`),
    /// found when a history first needs it.
    pub(crate) shape_max: std::sync::OnceLock<Vec<f64>>,
    /// The static shapes of the histories in modal form at each contact point asked
    /// (`static_memo`).
    pub(crate) static_shapes: super::static_memo::StaticShapes,
    /// The hollow part's breathing modes (`barrel::barrel_modes`), found when a collision
    /// first asks for them.
    pub(crate) shell_modes:
        std::sync::OnceLock<Result<Option<super::shell::ShellModes>, ModelError>>,
    /// The hollow part's stiffness for the wall's stress (`wall_stress::WallStatics`),
    /// factored when a stress is first asked for.
    pub(crate) wall_statics:
        std::sync::OnceLock<Result<Option<super::wall_stress::WallStatics>, ModelError>>,
    /// The resolution those modes are solved at (`numerics.shell_*`).
    shell_resolution: super::barrel::ShellResolution,
    properties: BatProperties,
}

/// Discretise and analyse a bat.
pub fn prepare_bat(bat: &BatSpec, numerics: &NumericsSpec) -> Result<PreparedBat, ModelError> {
    let geometry = BatGeometry::resolve(bat)?;
    let segments = match numerics.segments {
        Some(n) if !(MIN_SEGMENTS..=MAX_SEGMENTS).contains(&n) => {
            return Err(out_of_range(
                "numerics.segments",
                n as f64,
                &format!("[{MIN_SEGMENTS}, {MAX_SEGMENTS}]"),
            ))
        }
        Some(n) => n,
        None => default_segments(geometry.length),
    };
    if let Some(g) = &bat.grip {
        check_grip(g, geometry.length)?;
    }
    let beam = Beam::build(&geometry, segments, bat.ends, bat.beam, bat.grip.as_ref());
    let modes = ModalBasis::of(&beam);
    // The reported modes are free–free (no grip) whatever the ends of the collision.
    let (free_beam, free_modes);
    let (fb, fm) = if bat.ends == EndsSpec::default() && bat.grip.is_none() {
        (&beam, &modes)
    } else {
        free_beam = Beam::build(&geometry, segments, EndsSpec::default(), bat.beam, None);
        free_modes = ModalBasis::of(&free_beam);
        (&free_beam, &free_modes)
    };
    let properties = properties(&geometry, fb, fm);

    let z_cm = beam.center_of_mass();
    let inertia_cm: f64 = beam
        .mass
        .iter()
        .zip(&beam.z)
        .map(|(m, z)| m * (z - z_cm).powi(2))
        .sum::<f64>()
        + beam.total_rotary();
    let nodes = beam.len();
    let n = beam.dofs();
    let mut momentum_weight = vec![0.0; n];
    let mut angular_weight = vec![0.0; n];
    for k in 0..n {
        let col = modes.shapes.column(k);
        for i in 0..nodes {
            momentum_weight[k] += beam.mass[i] * col[i];
            angular_weight[k] += beam.mass[i] * (beam.z[i] - z_cm) * col[i];
        }
        for (i, j) in beam.rotary.iter().enumerate() {
            angular_weight[k] += j * col[nodes + i];
        }
    }
    // each cross section's polar moment: twice its diametral one
    let roll_inertia = geometry.integrate(0.0, geometry.length, |z| {
        2.0 * geometry.rotary_inertia_per_length(z)
    });
    let total_mass = beam.total_mass();
    Ok(PreparedBat {
        roll_inertia,
        damping_ratio: geometry.damping_ratio,
        grip_damping: bat.grip.as_ref().map_or(0.0, |g| g.damping),
        geometry,
        beam,
        modes,
        momentum_weight,
        angular_weight,
        z_cm,
        inertia_cm,
        total_mass,
        shape_max: std::sync::OnceLock::new(),
        static_shapes: Default::default(),
        shell_modes: std::sync::OnceLock::new(),
        wall_statics: std::sync::OnceLock::new(),
        shell_resolution: super::barrel::ShellResolution::of(numerics),
        properties,
    })
}

fn check_grip(g: &GripSpec, length: f64) -> Result<(), ModelError> {
    if !(g.z >= 0.0 && g.z <= length) {
        return Err(out_of_range(
            "bat.grip.z",
            g.z,
            &format!("[0, {length}] m (on the bat)"),
        ));
    }
    if !(g.damping >= 0.0 && g.damping.is_finite())
        || (g.kind == GripKind::Pinned && g.damping != 0.0)
    {
        return Err(out_of_range(
            "bat.grip.damping",
            g.damping,
            "[0, ∞) N·s/m (0 for a pinned grip)",
        ));
    }
    match (g.kind, g.stiffness) {
        (GripKind::Spring, Some(k)) if k > 0.0 && k.is_finite() => Ok(()),
        (GripKind::Spring, k) => Err(out_of_range(
            "bat.grip.stiffness",
            k.unwrap_or(f64::NAN),
            "(0, ∞) N/m (required for a spring grip)",
        )),
        (GripKind::Pinned, None) => Ok(()),
        (GripKind::Pinned, Some(k)) => Err(out_of_range(
            "bat.grip.stiffness",
            k,
            "null (a pinned grip has no stiffness)",
        )),
    }
}

/// Segments for a bat of length `length` at the default resolution.
pub fn default_segments(length: f64) -> usize {
    ((length / DEFAULT_SEGMENT_LENGTH).ceil() as usize).clamp(MIN_SEGMENTS, MAX_SEGMENTS)
}

fn properties(geometry: &BatGeometry, beam: &Beam, modes: &ModalBasis) -> BatProperties {
    let length = geometry.length;
    let mass = geometry.integrate(0.0, length, |z| geometry.mass_per_length(z));
    let z_cm = geometry.integrate(0.0, length, |z| z * geometry.mass_per_length(z)) / mass;
    let moment_of_inertia = geometry.integrate(0.0, length, |z| {
        (z - z_cm).powi(2) * geometry.mass_per_length(z)
    });
    let n_flex = (beam.len() - modes.n_rigid).min(REPORTED_MODES);
    let freqs = modes.flexible_frequencies();
    BatProperties {
        z: beam.z.clone(),
        outer_radius: beam.z.iter().map(|&z| geometry.outer_radius(z)).collect(),
        inner_radius: beam.z.iter().map(|&z| geometry.inner_radius(z)).collect(),
        length,
        mass,
        z_cm,
        moment_of_inertia,
        moment_of_inertia_knob6: moment_of_inertia + mass * (z_cm - NCAA_PIVOT).powi(2),
        mode_frequency: freqs[..n_flex].to_vec(),
        mode_nodes: (0..n_flex).map(|k| modes.nodes(beam, k)).collect(),
        metrics: Default::default(), // filled by metrics::bat_metrics (it simulates)
        rule_checks: Vec::new(),     // filled by the study layer (it knows the rule books)
    }
}

impl PreparedBat {
    /// Derived properties (mass, CM, inertias, free–free modes and nodes).
    pub fn properties(&self) -> &BatProperties {
        &self.properties
    }

    /// Overall length, m.
    pub fn length(&self) -> f64 {
        self.geometry.length
    }

    /// The lumped beam (nodes, masses).
    pub fn beam(&self) -> &Beam {
        &self.beam
    }

    /// The modal basis of the beam with the collision's ends.
    pub fn modes(&self) -> &ModalBasis {
        &self.modes
    }

    /// Resolved geometry and material.
    pub fn geometry(&self) -> &BatGeometry {
        &self.geometry
    }

    /// CM of the lumped beam, m.
    pub fn center_of_mass(&self) -> f64 {
        self.z_cm
    }

    /// Moment of inertia of the lumped beam about its CM, kg·m².
    pub fn inertia_cm(&self) -> f64 {
        self.inertia_cm
    }

    /// The hollow part's statics for the wall's stress (`None` for a solid bat), factored
    /// on first use.
    pub fn wall_statics(&self) -> Result<Option<&super::wall_stress::WallStatics>, ModelError> {
        self.wall_statics
            .get_or_init(|| super::wall_stress::WallStatics::of(&self.geometry))
            .as_ref()
            .map(Option::as_ref)
            .map_err(Clone::clone)
    }

    /// The hollow part's breathing modes (`None` for a solid bat), solved on first use.
    pub fn shell_modes(&self) -> Result<Option<&super::shell::ShellModes>, ModelError> {
        self.shell_modes
            .get_or_init(|| super::barrel::barrel_modes(&self.geometry, &self.shell_resolution))
            .as_ref()
            .map(Option::as_ref)
            .map_err(Clone::clone)
    }

    /// Modal damping ratio ζ = 1/(2Q) of the flexible modes (0: undamped).
    pub fn damping_ratio(&self) -> f64 {
        self.damping_ratio
    }
}
