//! The full specification of one collision: every parameter in SI units.
//!
//! These types are what a study's `base` block deserializes into, and what a
//! dotted path such as `bat.material.density` addresses. Their field names are
//! the public interface of study files (see README): rename none.
//!
//! Optional fields (`Option<_>`) fall back to the preset's value; the resolved
//! numbers are what the model uses and what the store records.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

mod batter;
pub use batter::{swing_law_extrapolated, BatterSpec, FlightSpec, PitchSpec, SWING_LAW_MOI6};
pub mod ball_law;
pub use ball_law::{BallLaw, BallLawKind, BallPreset, Loading};

/// Which collision model to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "snake_case")]
pub enum ModelKind {
    /// Euler–Bernoulli beam bat with a lossy-spring ball (the paper's section 3).
    #[default]
    Wave,
    /// Brody's rigid-body recoil model with COR `ball.law.cor` (the paper's section 2).
    Rigid,
}

/// Every parameter of one collision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CollisionSpec {
    /// Collision model. Default: `wave`.
    #[serde(default)]
    pub model: ModelKind,
    /// The bat: profile, material, shell, ends.
    #[serde(default)]
    pub bat: BatSpec,
    /// The ball: mass, speed and force law.
    #[serde(default)]
    pub ball: BallSpec,
    /// The swing: the bat's initial rigid rotation.
    #[serde(default)]
    pub swing: SwingSpec,
    /// Optional hoop mode (a mass on a spring between ball and impact point); `null` for none.
    /// A study gives a hollow preset (`alloy_bbcor`, `composite_bbcor`) its wall's own
    /// breathing when `hoop` is unset ([`CollisionSpec::with_preset_hoop`]); `{from_geometry:
    /// false}` alone turns it off.
    #[serde(default)]
    pub hoop: Option<HoopSpec>,
    /// Where the ball hits.
    pub impact: ImpactSpec,
    /// Numerical resolution; every field defaults to a converged automatic choice.
    #[serde(default)]
    pub numerics: NumericsSpec,
    /// A batter whose swing answers to the bat's moment of inertia. Default `null`: the
    /// swing is `swing` as given, the same for every bat.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub batter: Option<BatterSpec>,
    /// The batted ball's flight to the ground (carry, apex, hang time). Default `null`: no
    /// flight (those results are NaN).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flight: Option<FlightSpec>,
    /// The pitch's speed and path at contact, independent of the swing's; needs a `batter`.
    /// Default `null`: the pitch arrives along the bat's path at `batter.pitch_speed`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch: Option<PitchSpec>,
}

impl CollisionSpec {
    /// The paper's base case at impact position `impact_z` (m): the R161 wood bat with free
    /// ends at rest, the default ball (0.145 kg, 40 m/s, linear hysteresis, e = 0.5), no hoop,
    /// the wave model with automatic numerics.
    pub fn base_case(impact_z: f64) -> Self {
        CollisionSpec {
            model: ModelKind::Wave,
            bat: BatSpec::default(),
            ball: BallSpec::default(),
            swing: SwingSpec::default(),
            hoop: None,
            impact: ImpactSpec {
                z: impact_z,
                offset: 0.0,
            },
            numerics: NumericsSpec::default(),
            batter: None,
            flight: None,
            pitch: None,
        }
    }

    /// The hoop a study means: a hollow preset's wall breathes as a shell unless `hoop` says
    /// otherwise (unset: `{from_geometry: true}`), and `{from_geometry: false}` with nothing
    /// else set means no hoop at all, for any bat.
    pub fn with_preset_hoop(mut self) -> Self {
        self.hoop = match self.hoop.take() {
            None if self.bat.preset.is_hollow_preset() => Some(HoopSpec {
                from_geometry: true,
                ..HoopSpec::default()
            }),
            Some(h) if h == HoopSpec::default() => None,
            other => other,
        };
        self
    }

    /// The ball's radius, m (`ball.radius`, else the rule book's middle).
    pub fn ball_radius(&self) -> f64 {
        self.ball.radius.unwrap_or(crate::ball::DEFAULT_BALL_RADIUS)
    }

    /// The surface radius of a rigid target across the ball's path: the cylinder's; `None`
    /// for the flat wall (and for a bat, whose radius is its profile's at the impact).
    pub fn rigid_target_radius(&self) -> Option<f64> {
        (self.bat.preset == BatPreset::Cylinder)
            .then_some(self.bat.radius)
            .flatten()
    }
}

/// Built-in bats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "snake_case")]
pub enum BatPreset {
    /// Louisville Slugger R161 wood bat (Nathan 2000), solid, ρ 649 kg/m³, Y 1.814e10 N/m².
    #[default]
    R161,
    /// The paper's aluminum bat: R161 outer profile as a 3 mm shell, ρ 2700 kg/m³, Y 6.9e10 N/m².
    Aluminum,
    /// R161 with the barrel hollowed to a 1 cm shell from z = 0.55 m, filled with cork (240 kg/m³).
    Corked,
    /// A single-wall 7050 alloy BBCOR bat: 33 in, 2 5/8-in barrel on the R161's handle, the
    /// wall 1.5–6.1 mm along the barrel (the design search's; docs/physics.md, "The hollow
    /// presets"), 30.5 oz. Geometry and wall not those of a measured bat.
    AlloyBbcor,
    /// A composite BBCOR bat: the same outer profile, a wall of hoop glass and ±30° carbon
    /// plies (`bat.shell.layers`), 4.5 mm in the handle and 5.2–5.6 mm in the barrel,
    /// 30.2 oz. Not a measured bat.
    CompositeBbcor,
    /// A rigid, immovable wall: the target of ball certification. The ball comes back at
    /// e(v) v, so exit speed / approach speed is the wall COR. Bat fields other than
    /// `preset` do not apply; `impact.z` and `swing` are ignored.
    Wall,
    /// A rigid, immovable cylinder of radius `bat.radius` with its axis across the ball's
    /// path: the target of the ball's cylindrical COR and dynamic-stiffness test (ASTM
    /// F2845), shaped like a bat's barrel. As for `wall`, the other bat fields, `impact.z`
    /// and `swing` do not apply. A ball whose law sees curvature (`ball.law.curvature`, the
    /// `mlb` ball) meets it softer and strained harder than a wall (docs/physics.md, "The
    /// calibrated ball").
    Cylinder,
}

impl BatPreset {
    /// A hollow BBCOR bat built in, whose wall breathes as a shell by default.
    pub fn is_hollow_preset(self) -> bool {
        matches!(self, BatPreset::AlloyBbcor | BatPreset::CompositeBbcor)
    }

    /// A rigid, immovable target (the wall or the cylinder), not a bat.
    pub fn is_rigid_target(self) -> bool {
        matches!(self, BatPreset::Wall | BatPreset::Cylinder)
    }
}

/// The bat. Unset fields take the preset's values.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BatSpec {
    /// Built-in bat to start from. Default: `r161`.
    #[serde(default)]
    pub preset: BatPreset,
    /// Outer-radius profile replacing the preset's (knots or a CSV file).
    #[serde(default)]
    pub profile: Option<ProfileSpec>,
    /// `bat.preset: cylinder`: the cylinder's radius, m (required there, refused elsewhere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Overall length in m. Longer than the profile: the barrel is extended at its end
    /// radius (the paper's 110 cm bat). Shorter: an error. Default: the profile's length.
    #[serde(default)]
    pub length: Option<f64>,
    /// Wall material. Default: the preset's.
    #[serde(default)]
    pub material: MaterialSpec,
    /// Hollow part of the bat (a shell). Default: the preset's (none for `r161`).
    #[serde(default)]
    pub shell: Option<ShellSpec>,
    /// Light filling of the hollow part (cork): adds mass, no stiffness.
    /// Default: the preset's (cork 240 kg/m³ for `corked`, none otherwise); `null` for none.
    #[serde(default)]
    pub fill: Option<FillSpec>,
    /// An axial bore drilled into the barrel end, as bats are corked: a cylinder of
    /// constant diameter, optionally filled. Exclusive with `shell`. Default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bore: Option<BoreSpec>,
    /// Handle thickness variant (the paper's Fig. 11b).
    #[serde(default)]
    pub handle: HandleSpec,
    /// Boundary condition at each end.
    #[serde(default)]
    pub ends: EndsSpec,
    /// The batter's hands: a pinned pivot or a spring grip at a chosen z. Default `null`
    /// (a free bat, the paper's assumption).
    #[serde(default)]
    pub grip: Option<GripSpec>,
    /// Beam theory of the wave model. Default `euler_bernoulli` (the paper's).
    #[serde(default)]
    pub beam: BeamTheory,
}

impl BatSpec {
    /// One piece of solid wood (what MLB's rule 3.02(a) allows): the wood preset with no
    /// shell, bore or fill.
    pub fn is_solid_wood(&self) -> bool {
        self.preset == BatPreset::R161
            && self.shell.is_none()
            && self.bore.is_none()
            && self.fill.is_none()
    }

    /// Whether a hollow part's wall is wood: a wood preset's shell without layers of its
    /// own (the shell model takes it isotropic, where wood across the grain is a tenth as
    /// stiff, so its static squeeze is not reported).
    pub fn has_wood_wall(&self) -> bool {
        matches!(self.preset, BatPreset::R161 | BatPreset::Corked)
            && self.shell.as_ref().is_none_or(|s| s.layers.is_none())
    }
}

/// Beam theory of the wave model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BeamTheory {
    /// Euler–Bernoulli: bending only (the paper's section 3).
    #[default]
    EulerBernoulli,
    /// Timoshenko: bending + shear deformation + rotary inertia (Van Zandt; Nathan 2000).
    /// Uses `bat.material.shear_modulus` and `bat.material.shear_coefficient`.
    Timoshenko,
}

/// Kinds of grip.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GripKind {
    /// The bat's displacement at `z` is held (it can still rotate about it): Nathan's pivot.
    #[default]
    Pinned,
    /// A transverse spring of stiffness `stiffness` between the hands and the bat at `z`.
    Spring,
}

/// The hands. They move uniformly during the collision with the velocity that their point
/// of the bat has initially (ω (z − z_cm) in the bat-CM frame), i.e. the collision is
/// solved in the frame of the hands; `swing.cm_speed` then gives exact lab-frame speeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GripSpec {
    /// Position of the pivot / grip in m from the knob. Default 0.15 (Nathan 2000's pivot).
    #[serde(default = "default_grip_z")]
    pub z: f64,
    /// `pinned` or `spring`. Default `pinned`.
    #[serde(default)]
    pub kind: GripKind,
    /// Spring stiffness in N/m (`spring` only; required there).
    #[serde(default)]
    pub stiffness: Option<f64>,
    /// Damper in parallel with the spring, N·s/m (`spring` only). Default 0.
    #[serde(default)]
    pub damping: f64,
}

impl Default for GripSpec {
    fn default() -> Self {
        Self {
            z: default_grip_z(),
            kind: GripKind::default(),
            stiffness: None,
            damping: 0.0,
        }
    }
}

/// A user-supplied outer-radius profile R(z), z in m from the knob, linear between knots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum ProfileSpec {
    /// `[[z, R], ...]` in metres, z increasing from 0 (the knob).
    Knots(Vec<[f64; 2]>),
    /// A CSV file with columns `z` and `radius` in metres (header required; `#` comments
    /// allowed), path relative to the study file.
    Csv(String),
}

/// Wall material (homogeneous, isotropic).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Density in kg/m³. Default: the preset's (649 wood, 2700 aluminum).
    #[serde(default)]
    pub density: Option<f64>,
    /// Young's modulus in N/m² (Pa). Default: the preset's (1.814e10 wood, 6.9e10 aluminum).
    #[serde(default)]
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio (hoop modes from geometry, Cowper's shear coefficient). Default: the
    /// preset's (0.33 aluminum, ASM 6061-T6; 0.37 wood, ν_LR of white ash, USDA Wood
    /// Handbook table 5-2).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// Shear modulus G in N/m² (Timoshenko beam). Default: 1.05e9 for wood (Nathan 2000),
    /// Y / (2 (1 + ν)) for aluminum (isotropic).
    #[serde(default)]
    pub shear_modulus: Option<f64>,
    /// Timoshenko shear coefficient κ. Default: Cowper (1966) for a hollow circle at each
    /// section, κ = 6(1+ν)(1+m²)² / ((7+6ν)(1+m²)² + (20+12ν)m²), m = r/R: ≈ 0.88 solid,
    /// → 2(1+ν)/(4+3ν) ≈ 0.53 for a thin tube.
    #[serde(default)]
    pub shear_coefficient: Option<f64>,
    /// Material damping: quality factor Q of every flexible mode (modal damping ratio
    /// ζ = 1/(2Q), applied exactly by the modal integrator). Default `null`: undamped.
    #[serde(default)]
    pub quality_factor: Option<f64>,
    /// Yield strength of a metal wall in Pa (0.2 % offset, tension), what its stress under
    /// the certification impact is measured against (`/bat/wall_stress_ratio`). Default:
    /// the preset's (276e6 aluminum, 6061-T6; 469e6 alloy_bbcor, 7050-T7451: typical values,
    /// data/shell_strengths.md); none for wood.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_strength: Option<f64>,
}

/// A hollow shell: the wall of thickness `thickness` for z ≥ `from`; solid before.
/// Fields left out take the preset's values (aluminum: 3 mm from 0; corked: 1 cm from
/// 0.55 m); a bat whose preset is solid needs `thickness`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShellSpec {
    /// Wall thickness in m. Default: the preset's (aluminum 0.003, corked 0.01).
    #[serde(default)]
    pub thickness: Option<f64>,
    /// z in m where the hollow part starts. Default: the preset's (aluminum 0, corked
    /// 0.55), else 0.
    #[serde(default)]
    pub from: Option<f64>,
    /// The wall thickness along the bat instead of one `thickness`: `[[z, t], ...]` (m from
    /// the knob, m), linear between knots and constant beyond the first and the last
    /// (a barrel wall thicker than the handle's). Default none: `thickness`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness_knots: Option<Vec<[f64; 2]>>,
    /// The wall as layers from the outside in (classical lamination theory; a `gap` layer
    /// between two walls makes a double wall). Sets the wall's stiffness for the shell's
    /// breathing modes, and, unless `bat.material` says otherwise, the beam's axial modulus
    /// and density (the stack smeared over its thickness). `thickness` defaults to the
    /// stack's; with `thickness_knots` every layer scales with the local thickness.
    /// Default none: a homogeneous wall of `bat.material`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layers: Option<Vec<LayerSpec>>,
    /// Break-in: the fraction of the matrix's stiffness a composite wall has lost to
    /// cracking with use (0 new, < 1), applied to every polymer-matrix ply's E₂ and G₁₂.
    /// No effect on a metal. Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub break_in: f64,
}

/// One layer of a wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LayerSpec {
    /// The layer's material: `al7050`, `al7075`, `al6061` (bat alloys), `carbon_epoxy`,
    /// `glass_epoxy` (unidirectional plies), or `gap` (an empty layer between two walls).
    /// Properties and sources: docs/physics.md.
    pub material: String,
    /// Thickness, m.
    pub thickness: f64,
    /// Fibre angle from the bat's axis, rad (ignored for a metal). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub angle: f64,
}

/// An axial bore from the barrel end (a corked bat as drilled: Nathan's 2003 test bat had
/// a 1-in bore 10 in deep, filled with cork).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoreSpec {
    /// Diameter of the bore in m (1 in = 0.0254).
    pub diameter: f64,
    /// Depth in m, measured from the barrel end toward the knob (10 in = 0.254).
    pub depth: f64,
    /// Density of what fills the bore in kg/m³ (cork ≈ 240). Default 0: empty.
    #[serde(default)]
    pub fill_density: f64,
}

/// Filling of the hollow part.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FillSpec {
    /// Fill density in kg/m³ (cork ≈ 240).
    pub density: f64,
}

/// Scale the handle's radius: R(z) × (1 + (radius_scale − 1)·w(z)) with w = 1 for
/// z ≤ `end`, falling linearly to 0 at `end + blend`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HandleSpec {
    /// Radius multiplier in the handle (> 0). Default 1 (unchanged). The paper's thicker
    /// and narrower handles: e.g. 1.2 and 0.8.
    #[serde(default = "one")]
    pub radius_scale: f64,
    /// End of the handle in m from the knob. Default 0.40.
    #[serde(default = "default_handle_end")]
    pub end: f64,
    /// Length in m over which the scaling fades out. Default 0.10.
    #[serde(default = "default_handle_blend")]
    pub blend: f64,
}

impl Default for HandleSpec {
    fn default() -> Self {
        Self {
            radius_scale: 1.0,
            end: default_handle_end(),
            blend: default_handle_blend(),
        }
    }
}

/// Boundary condition of a bat end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum EndCondition {
    /// Free end (no moment, no shear): a real bat.
    #[default]
    Free,
    /// Clamped end (zero displacement and slope): Cross's fixed beam end.
    Fixed,
}

/// Boundary conditions at both ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EndsSpec {
    /// Knob (handle) end, z = 0. Default `free`.
    #[serde(default)]
    pub knob: EndCondition,
    /// Barrel end, z = L. Default `free`.
    #[serde(default)]
    pub barrel: EndCondition,
}

/// The ball.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BallSpec {
    /// Built-in ball whose law fills every `law` field the study leaves out. Default none
    /// (the law's own defaults: the paper's linear ball).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<BallPreset>,
    /// Mass in kg. Default 0.145.
    #[serde(default = "default_ball_mass")]
    pub mass: f64,
    /// Speed toward the bat in m/s, in the frame where the bat's CM is initially at rest.
    /// Default 40.
    #[serde(default = "default_ball_speed")]
    pub speed: f64,
    /// Spin of the pitch about the bat's axis, rad/s, positive for backspin (a fastball's),
    /// negative for topspin (a curveball's). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub spin: f64,
    /// Radius in m. Default 0.0369 (a 9.125-in circumference, the rule book's middle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Moment of inertia over m r². Default 0.4 (a uniform sphere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_factor: Option<f64>,
    /// Force–compression law.
    #[serde(default)]
    pub law: BallLaw,
}

impl Default for BallSpec {
    fn default() -> Self {
        Self {
            preset: None,
            mass: default_ball_mass(),
            speed: default_ball_speed(),
            spin: 0.0,
            radius: None,
            inertia_factor: None,
            law: BallLaw::default(),
        }
    }
}

/// `ball.law` as a study writes it: every field optional, so that a preset can fill the
/// ones left out (field names and meanings: [`BallLaw`]).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct BallLawFields {
    kind: Option<BallLawKind>,
    stiffness: Option<f64>,
    cor: Option<f64>,
    k1: Option<f64>,
    alpha: Option<f64>,
    reference_speed: Option<f64>,
    cor_slope: Option<f64>,
    loading: Option<Loading>,
    cor_exponent: Option<f64>,
    cor_at_rest: Option<f64>,
    cor_power: Option<f64>,
    cor_shift: Option<f64>,
    curvature: Option<bool>,
    friction: Option<f64>,
    tangential_ratio: Option<f64>,
}

impl BallLawFields {
    /// The law: these fields over `base` (a preset's law, or the defaults).
    fn over(self, base: BallLaw) -> BallLaw {
        BallLaw {
            kind: self.kind.unwrap_or(base.kind),
            stiffness: self.stiffness.unwrap_or(base.stiffness),
            cor: self.cor.unwrap_or(base.cor),
            k1: self.k1.unwrap_or(base.k1),
            alpha: self.alpha.unwrap_or(base.alpha),
            reference_speed: self.reference_speed.or(base.reference_speed),
            cor_slope: self.cor_slope.or(base.cor_slope),
            loading: self.loading.or(base.loading),
            // a study that gives a slope asks for the line, one that gives an exponent for
            // the power, whatever the preset's curve
            cor_exponent: self
                .cor_exponent
                .or(base.cor_exponent.filter(|_| self.cor_slope.is_none())),
            cor_at_rest: self.cor_at_rest.or(base
                .cor_at_rest
                .filter(|_| self.cor_slope.is_none() && self.cor_exponent.is_none())),
            cor_power: self.cor_power.or(base
                .cor_power
                .filter(|_| self.cor_slope.is_none() && self.cor_exponent.is_none())),
            cor_shift: self.cor_shift.or(base.cor_shift),
            curvature: self.curvature.or(base.curvature),
            friction: self.friction.or(base.friction),
            tangential_ratio: self.tangential_ratio.or(base.tangential_ratio),
        }
    }
}

impl<'de> Deserialize<'de> for BallSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Fields {
            #[serde(default)]
            preset: Option<BallPreset>,
            #[serde(default = "default_ball_mass")]
            mass: f64,
            #[serde(default = "default_ball_speed")]
            speed: f64,
            #[serde(default)]
            spin: f64,
            #[serde(default)]
            radius: Option<f64>,
            #[serde(default)]
            inertia_factor: Option<f64>,
            // `law: null` leaves every field to the preset (or the defaults), which lets a
            // study's points set pick a preset over a base that gives a law
            #[serde(default)]
            law: Option<BallLawFields>,
        }
        let f = Fields::deserialize(d)?;
        let base = f.preset.map(crate::ball::preset_law).unwrap_or_default();
        Ok(Self {
            preset: f.preset,
            mass: f.mass,
            speed: f.speed,
            spin: f.spin,
            radius: f.radius,
            inertia_factor: f.inertia_factor,
            law: f.law.unwrap_or_default().over(base),
        })
    }
}

/// The swing.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SwingSpec {
    /// Initial angular velocity about the CM in rad/s; negative = barrel toward the ball.
    /// Default 0.
    #[serde(default)]
    pub omega: f64,
    /// Lab-frame speed of the bat's CM toward the ball in m/s, used only to report lab-frame
    /// exit speeds (the collision itself is solved in the CM frame). Default 0.
    #[serde(default)]
    pub cm_speed: f64,
    /// Attack angle: the elevation of the bat's path (its impact point's velocity) above the
    /// horizontal, rad, positive for an upward swing. Without a `pitch` block the pitch
    /// arrives along that path (an "on plane" swing, docs/physics.md "The geometry of a
    /// swing"). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub attack_angle: f64,
    /// Attack direction: the angle of the bat's path from straight toward the pitcher, seen
    /// from above, rad, positive toward the first-base side (a right-handed batter's
    /// opposite field). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub attack_direction: f64,
    /// The bat's vertical angle: the tilt of its axis (knob to barrel) about its path, rad,
    /// negative with the barrel below the hands (measured swings average about −0.5).
    /// Default 0: a level bat.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub tilt: f64,
}

/// A hoop mode: mass `mass` on a spring of frequency `frequency` between ball and bat;
/// either given (`frequency` and `mass`) or derived from the shell (`from_geometry`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HoopSpec {
    /// Hoop-mode frequency in Hz (spring k_h = m_h (2π f)²). Required unless `from_geometry`.
    #[serde(default)]
    pub frequency: Option<f64>,
    /// Effective hoop mass in kg (the paper gives none; results depend on it). Required
    /// unless `from_geometry`.
    #[serde(default)]
    pub mass: Option<f64>,
    /// The barrel wall's own breathing modes instead of one given mass–spring: the hollow
    /// part solved as a shell (wave numbers 2–4, four axial modes each, the wall's layers
    /// and thickness along the bat; docs/physics.md), each mode driven by the ball's force
    /// over its contact patch in parallel with the beam. Where the impact point is solid
    /// (before a shell or bore starts) there is none. Default false.
    #[serde(default)]
    pub from_geometry: bool,
    /// A fixed contact patch instead of the contact's own footprint (`from_geometry`): its
    /// radius, m, over which the shell's modes are loaded and felt throughout the contact
    /// (a what-if; the BBCOR then rests on it). Default none: the footprint follows the
    /// contact (`footprint_ratio`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub patch_radius: Option<f64>,
    /// The footprint's area over the area where the undeformed ball and barrel overlap at
    /// the same compression (`from_geometry`): 0.5 is Hertz's contact (a² = R s against the
    /// overlap's 2 R s; Johnson, "Contact Mechanics" §4.2), 1 a ball flattened over all of
    /// the overlap. Its semi-axes grow as √s along the bat (the ball's radius) and around it
    /// (the ball's and the barrel's radii in series). Default 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub footprint_ratio: Option<f64>,
}

/// Where the ball hits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ImpactSpec {
    /// Impact position in m from the knob (0 < z < L).
    pub z: f64,
    /// Distance of the ball's centre line below (+) or above (−) the bat's axis, m, in the
    /// plane across the bat at `z` (|offset| < bat radius + ball radius). Negative is an
    /// undercut: the bat passes below the ball's centre, which leaves with backspin and a
    /// higher launch. Default 0: head-on, the paper's collision.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub offset: f64,
}

/// Default-valued angles and offsets are left out of a spec's canonical form, so that a
/// point that does not use them keeps the id it had before they existed.
pub(crate) fn is_zero(x: &f64) -> bool {
    *x == 0.0 && x.is_sign_positive()
}

/// Time integrator of the wave model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// Beam modes advanced exactly between steps; step set by the contact. Default.
    #[default]
    Modal,
    /// Plain explicit velocity Verlet at a stable step (the baseline).
    Verlet,
}

/// Numerical resolution. Unset fields are chosen automatically (converged defaults).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NumericsSpec {
    /// Number of beam segments. Default: automatic (converged).
    #[serde(default)]
    pub segments: Option<usize>,
    /// Time step in s. Default: automatic. A step above the stability limit is an error.
    #[serde(default)]
    pub dt: Option<f64>,
    /// Time integrator. Default `modal`.
    #[serde(default)]
    pub integrator: Integrator,
    /// Most time steps one collision may take (its budget): a point that would need more
    /// is refused before it runs (at least the re-contact watch after separation, 0.5 ms,
    /// must fit) and stopped with an error if it runs out. Default 10 000 000 (a few
    /// seconds of computing; the base case takes about 600).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<u64>,
    /// Elements along a hollow part solved as a shell (`hoop.from_geometry`), besides the
    /// profile's and the wall's knots. Default 24 (docs/physics.md, "The barrel as a shell":
    /// the presets' BBCOR moves by at most 2e-6 from 24 to 80).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shell_elements: Option<usize>,
    /// The shell's circumferential wave numbers solved (each ≥ 2, the breathing modes).
    /// Default [2, 3, 4].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shell_wave_numbers: Option<Vec<u32>>,
    /// Axial modes kept per wave number. Default 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shell_modes_per_wave: Option<usize>,
}

fn default_grip_z() -> f64 {
    0.15
}
fn one() -> f64 {
    1.0
}
fn default_handle_end() -> f64 {
    0.40
}
fn default_handle_blend() -> f64 {
    0.10
}
fn default_ball_mass() -> f64 {
    0.145
}
fn default_ball_speed() -> f64 {
    40.0
}
