//! A bat's wall as a stack of layers: the membrane and bending stiffnesses of classical
//! lamination theory (Jones, "Mechanics of Composite Materials", 2nd ed. 1999, §4.2–4.3;
//! Daniel & Ishai, "Engineering Mechanics of Composite Materials", ch. 7), and a small
//! library of the materials bats are made of.
//!
//! Axes: 1 along the bat, 2 around it; a ply's fibre angle is measured from the bat's axis.
//! The shell keeps A₁₁, A₁₂, A₂₂, A₆₆ and D₁₁, D₁₂, D₂₂, D₆₆. The shear–extension terms
//! (A₁₆, A₂₆) vanish for balanced ±θ stacks; the bending–twisting ones (D₁₆, D₂₆) and the
//! coupling B are dropped (zero for symmetric stacks, small for the thin ones of a bat).
//! A `gap` layer separates walls that slide on each other (a double-wall barrel): their
//! membrane stiffnesses add, and each wall bends about its own mid-plane.

use crate::error::ModelError;

/// A ply's (or an isotropic metal's) elastic constants and density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ply {
    /// Modulus along the fibres (or the metal's Young's modulus), Pa.
    pub e1: f64,
    /// Modulus across the fibres, Pa.
    pub e2: f64,
    /// In-plane shear modulus, Pa.
    pub g12: f64,
    /// Major Poisson's ratio ν₁₂.
    pub nu12: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Whether a break-in (matrix cracking) softens it: a polymer-matrix ply.
    pub matrix: bool,
    /// Loss factors η (the loss modulus over the storage modulus) along the fibres, across
    /// them and in in-plane shear: the share of each strain energy a cycle dissipates,
    /// over 2π (Adams & Bacon's decomposition, J. Compos. Mater. 7, 402 (1973)).
    pub loss: [f64; 3],
    /// What the ply can carry (`Strength::Unknown` where no source gives it).
    pub strength: Strength,
}

/// A material's strength, Pa: a metal's yield, or a ply's along and across its fibres
/// (tension and compression) and in in-plane shear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Strength {
    Unknown,
    Yield(f64),
    Ply {
        xt: f64,
        xc: f64,
        yt: f64,
        yc: f64,
        s12: f64,
    },
}

impl Ply {
    /// An isotropic material without loss.
    pub const fn isotropic(e: f64, nu: f64, density: f64) -> Self {
        Ply {
            e1: e,
            e2: e,
            g12: e / (2.0 * (1.0 + nu)),
            nu12: nu,
            density,
            matrix: false,
            loss: [0.0; 3],
            strength: Strength::Unknown,
        }
    }

    /// The same material with `strength`.
    pub const fn with_strength(self, strength: Strength) -> Self {
        Ply { strength, ..self }
    }

    /// The stress ratio of the ply at fibre angle `angle` (rad from the bat's axis) under
    /// the wall strains (ε_x, ε_θ) with no shear: the factor by which the load could grow
    /// before it fails, inverted (1 at failure). A metal's von Mises stress over its
    /// yield; a ply's Tsai–Hill index (Jones 1999, §2.9) with the tensile or compressive
    /// strength each stress's sign calls for, as a stress ratio (its square root). NaN
    /// with no strength.
    pub fn stress_ratio(&self, angle: f64, (ex, et): (f64, f64)) -> f64 {
        let (c, s) = (angle.cos(), angle.sin());
        let e1 = ex * c * c + et * s * s;
        let e2 = ex * s * s + et * c * c;
        let g12 = 2.0 * s * c * (et - ex);
        let [q11, q12, q22, q66] = self.reduced();
        let (s1, s2, t12) = (q11 * e1 + q12 * e2, q12 * e1 + q22 * e2, q66 * g12);
        match self.strength {
            Strength::Unknown => f64::NAN,
            Strength::Yield(y) => (s1 * s1 - s1 * s2 + s2 * s2 + 3.0 * t12 * t12).sqrt() / y,
            Strength::Ply {
                xt,
                xc,
                yt,
                yc,
                s12,
            } => {
                let x = if s1 >= 0.0 { xt } else { xc };
                let y = if s2 >= 0.0 { yt } else { yc };
                ((s1 / x).powi(2) - s1 * s2 / (x * x) + (s2 / y).powi(2) + (t12 / s12).powi(2))
                    .sqrt()
            }
        }
    }

    /// An isotropic material with loss factor η in every direction.
    pub const fn isotropic_lossy(e: f64, nu: f64, density: f64, eta: f64) -> Self {
        Ply {
            loss: [eta; 3],
            ..Ply::isotropic(e, nu, density)
        }
    }

    /// The ply after a break-in that has taken `fraction` of its matrix's stiffness: the
    /// matrix-dominated E₂ and G₁₂ scaled by 1 − fraction (the fibres' E₁ unchanged).
    pub fn broken_in(self, fraction: f64) -> Self {
        if !self.matrix {
            return self;
        }
        Ply {
            e2: self.e2 * (1.0 - fraction),
            g12: self.g12 * (1.0 - fraction),
            ..self
        }
    }

    /// The reduced stiffnesses Q₁₁, Q₁₂, Q₂₂, Q₆₆ in the ply's own axes.
    fn reduced(&self) -> [f64; 4] {
        let nu21 = self.nu12 * self.e2 / self.e1;
        let den = 1.0 - self.nu12 * nu21;
        [
            self.e1 / den,
            self.nu12 * self.e2 / den,
            self.e2 / den,
            self.g12,
        ]
    }

    /// The reduced stiffnesses Q̄₁₁, Q̄₁₂, Q̄₂₂, Q̄₆₆ of the ply turned by `angle` (rad).
    fn turned(&self, angle: f64) -> [f64; 4] {
        rotated(self.reduced(), angle)
    }

    /// The ply's loss stiffnesses turned by `angle`: each energy term of the ply's axes
    /// times its loss factor (σ₁ε₁ by η₁, σ₂ε₂ by η₂, τ₁₂γ₁₂ by η₁₂, the Poisson term Q₁₂
    /// shared between the first two), so that a strain's energy dissipated per cycle over
    /// 2π is the quadratic form of these, as its stored energy is of Q̄.
    fn turned_loss(&self, angle: f64) -> [f64; 4] {
        let [q11, q12, q22, q66] = self.reduced();
        let [e1, e2, e12] = self.loss;
        rotated(
            [e1 * q11, 0.5 * (e1 + e2) * q12, e2 * q22, e12 * q66],
            angle,
        )
    }
}

/// A symmetric in-plane stiffness [Q₁₁, Q₁₂, Q₂₂, Q₆₆] (no shear coupling in its own
/// axes) turned by `angle` (rad): Jones 1999, §2.6.
fn rotated([q11, q12, q22, q66]: [f64; 4], angle: f64) -> [f64; 4] {
    let (s, c) = angle.sin_cos();
    let (s2, c2) = (s * s, c * c);
    [
        q11 * c2 * c2 + 2.0 * (q12 + 2.0 * q66) * s2 * c2 + q22 * s2 * s2,
        (q11 + q22 - 4.0 * q66) * s2 * c2 + q12 * (s2 * s2 + c2 * c2),
        q11 * s2 * s2 + 2.0 * (q12 + 2.0 * q66) * s2 * c2 + q22 * c2 * c2,
        (q11 + q22 - 2.0 * q12 - 2.0 * q66) * s2 * c2 + q66 * (s2 * s2 + c2 * c2),
    ]
}

/// An aluminium alloy's loss factor: Cremer & Heckl's "Structure-Borne Sound" table, about
/// 1e-4 (second-hand: data/shell_materials.md). Russell's aluminium bats ring with Q ≈
/// 1000–3000 in bending (η ≤ 1e-3), a bound that includes their joints and grips.
pub const ALUMINIUM_LOSS: f64 = 1e-4;

/// AS4/3501-6's loss factors: twice the damping ratios measured along and across the
/// fibres, 0.0556 % and 0.55 % (J. Eng. Mater. Technol. 112, 277 (1990), abstract read);
/// in-plane shear, matrix-dominated as the transverse is, taken equal to the transverse
/// (the Adams school's ψ₁₂ is larger, about 7 %, recalled and not read).
const CARBON_EPOXY_LOSS: [f64; 3] = [1.11e-3, 1.1e-2, 1.1e-2];

/// Typical 0.2 % tensile yield of 7050-T7451 and of 6061-T6, Pa (Aluminum Association
/// typical values, second-hand: data/shell_strengths.md). The handbook's design minima for
/// 7050-T7451 plate are 441–462 MPa.
pub const AL7050_YIELD: f64 = 469e6;
pub const AL6061_YIELD: f64 = 276e6;

/// The materials a layer may name, with their sources (docs/physics.md,
/// data/shell_materials.md).
pub const MATERIALS: &[(&str, Ply)] = &[
    // 7050-T7451: Aluminum Association typical values (second-hand)
    (
        "al7050",
        Ply::isotropic_lossy(71.7e9, 0.33, 2830.0, ALUMINIUM_LOSS)
            .with_strength(Strength::Yield(AL7050_YIELD)),
    ),
    // 7075-T6: E and ρ second-hand; ν that of the 7xxx alloys
    (
        "al7075",
        Ply::isotropic_lossy(72.0e9, 0.33, 2810.0, ALUMINIUM_LOSS)
            .with_strength(Strength::Yield(503e6)),
    ),
    // the paper's aluminum; ν from ASM 6061-T6
    (
        "al6061",
        Ply::isotropic_lossy(69.0e9, 0.33, 2700.0, ALUMINIUM_LOSS)
            .with_strength(Strength::Yield(AL6061_YIELD)),
    ),
    // AS4/3501-6 carbon/epoxy, unidirectional, V_f 0.63 (Daniel & Ishai's table)
    (
        "carbon_epoxy",
        Ply {
            e1: 147.0e9,
            e2: 10.3e9,
            g12: 7.0e9,
            nu12: 0.27,
            density: 1600.0,
            matrix: true,
            loss: CARBON_EPOXY_LOSS,
            // the World-Wide Failure Exercise's AS4/3501-6 (data/shell_strengths.md)
            strength: Strength::Ply {
                xt: 1950e6,
                xc: 1480e6,
                yt: 48e6,
                yc: 200e6,
                s12: 79e6,
            },
        },
    ),
    // E-glass/epoxy, unidirectional, V_f 0.55 (Daniel & Ishai's table)
    (
        "glass_epoxy",
        Ply {
            e1: 41.0e9,
            e2: 10.4e9,
            g12: 4.3e9,
            nu12: 0.28,
            density: 1970.0,
            matrix: true,
            // no glass/epoxy damping was read: the same epoxy's values across the
            // fibres and in shear, and carbon's along them
            loss: CARBON_EPOXY_LOSS,
            // the World-Wide Failure Exercise's E-glass/LY556 (V_f 0.62, data/shell_strengths.md)
            strength: Strength::Ply {
                xt: 1140e6,
                xc: 570e6,
                yt: 35e6,
                yc: 114e6,
                s12: 72e6,
            },
        },
    ),
];

/// The name of the empty layer between two walls.
pub const GAP: &str = "gap";

/// The ply a material name stands for (`None` for the gap).
pub fn material(path: &str, name: &str) -> Result<Option<Ply>, ModelError> {
    if name == GAP {
        return Ok(None);
    }
    MATERIALS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, p)| Some(*p))
        .ok_or_else(|| ModelError::UnknownName {
            path: path.to_string(),
            name: name.to_string(),
            allowed: MATERIALS
                .iter()
                .map(|(n, _)| *n)
                .chain([GAP])
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// One layer of a wall: its ply (`None`: a gap), thickness (m) and fibre angle (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    pub ply: Option<Ply>,
    pub thickness: f64,
    pub angle: f64,
}

/// A wall's layers from the outside in.
#[derive(Debug, Clone, PartialEq)]
pub struct Laminate {
    pub layers: Vec<Layer>,
}

/// The wall at one station: mid-surface radius, mass per area and the stiffnesses the
/// shell uses.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wall {
    /// Mid-surface radius, m.
    pub radius: f64,
    /// Mass per unit area, kg/m².
    pub mass_per_area: f64,
    /// Membrane stiffnesses, N/m.
    pub a11: f64,
    pub a12: f64,
    pub a22: f64,
    pub a66: f64,
    /// Bending stiffnesses, N·m.
    pub d11: f64,
    pub d12: f64,
    pub d22: f64,
    pub d66: f64,
}

impl Wall {
    /// A homogeneous isotropic wall of thickness h.
    pub fn isotropic(e: f64, nu: f64, density: f64, h: f64, radius: f64) -> Wall {
        Laminate::single(Ply::isotropic(e, nu, density), h).wall(1.0, radius)
    }

    /// The wall's stiffnesses times `factor` (its mass unchanged): an isotropic wall's loss
    /// stiffnesses are its stiffnesses times its loss factor.
    pub fn stiffness_times(&self, factor: f64) -> Wall {
        Wall {
            a11: self.a11 * factor,
            a12: self.a12 * factor,
            a22: self.a22 * factor,
            a66: self.a66 * factor,
            d11: self.d11 * factor,
            d12: self.d12 * factor,
            d22: self.d22 * factor,
            d66: self.d66 * factor,
            ..*self
        }
    }
}

impl Laminate {
    /// A wall of one ply of thickness `h`, m, its axes the bat's.
    pub fn single(ply: Ply, h: f64) -> Laminate {
        Laminate {
            layers: vec![Layer {
                ply: Some(ply),
                thickness: h,
                angle: 0.0,
            }],
        }
    }

    /// Total thickness, gaps included, m.
    pub fn thickness(&self) -> f64 {
        self.layers.iter().map(|l| l.thickness).sum()
    }

    /// Mass per unit area, kg/m².
    pub fn mass_per_area(&self) -> f64 {
        self.layers
            .iter()
            .filter_map(|l| l.ply.map(|p| p.density * l.thickness))
            .sum()
    }

    /// The laminate after a break-in (`Ply::broken_in`).
    pub fn broken_in(&self, fraction: f64) -> Laminate {
        Laminate {
            layers: self
                .layers
                .iter()
                .map(|l| Layer {
                    ply: l.ply.map(|p| p.broken_in(fraction)),
                    ..*l
                })
                .collect(),
        }
    }

    /// The walls the gaps separate, each a run of plies.
    fn walls(&self) -> Vec<&[Layer]> {
        self.layers
            .split(|l| l.ply.is_none())
            .filter(|w| !w.is_empty())
            .collect()
    }

    /// The wall with every layer's thickness times `scale` (a wall that thins along the
    /// barrel keeps its stack's proportions), at mid-surface radius `radius`.
    pub fn wall(&self, scale: f64, radius: f64) -> Wall {
        self.stack(scale, radius, Ply::turned)
    }

    /// The wall's loss stiffnesses (`Ply::turned_loss` summed as [`Self::wall`] sums the
    /// stiffnesses): the energy a strain dissipates per cycle over 2π is their quadratic
    /// form. Its mass per area is the wall's.
    pub fn loss_wall(&self, scale: f64, radius: f64) -> Wall {
        self.stack(scale, radius, Ply::turned_loss)
    }

    /// A, D of the stack from each ply's in-plane matrix `q_of(ply, angle)`.
    fn stack(&self, scale: f64, radius: f64, q_of: fn(&Ply, f64) -> [f64; 4]) -> Wall {
        let mut w = Wall {
            radius,
            mass_per_area: self.mass_per_area() * scale,
            ..Wall::default()
        };
        for plies in self.walls() {
            let total: f64 = plies.iter().map(|l| l.thickness * scale).sum();
            let mut top = 0.5 * total;
            for layer in plies {
                let t = layer.thickness * scale;
                let bottom = top - t;
                let q = q_of(&layer.ply.expect("a wall holds plies"), layer.angle);
                let (m1, m3) = (t, (top.powi(3) - bottom.powi(3)) / 3.0);
                w.a11 += q[0] * m1;
                w.a12 += q[1] * m1;
                w.a22 += q[2] * m1;
                w.a66 += q[3] * m1;
                w.d11 += q[0] * m3;
                w.d12 += q[1] * m3;
                w.d22 += q[2] * m3;
                w.d66 += q[3] * m3;
                top = bottom;
            }
        }
        w
    }

    /// The largest stress ratio (`Ply::stress_ratio`) over the plies' faces of the stack
    /// scaled by `scale`, under the mid-surface strains and curvature changes
    /// [ε_x, ε_θ, κ_x, κ_θ] on a line with no shear: each wall (between gaps) strained as
    /// ε + z κ about its own mid-plane, z outward. NaN where a ply's strength is unknown.
    pub fn stress_ratio(&self, scale: f64, [ex, et, kx, kt]: [f64; 4]) -> f64 {
        let mut worst = 0.0_f64;
        for plies in self.walls() {
            let mut top = 0.5 * plies.iter().map(|l| l.thickness * scale).sum::<f64>();
            for layer in plies {
                let ply = layer.ply.expect("a wall holds plies");
                for z in [top, top - layer.thickness * scale] {
                    let r = ply.stress_ratio(layer.angle, (ex + z * kx, et + z * kt));
                    worst = if r.is_nan() || worst.is_nan() {
                        f64::NAN
                    } else {
                        worst.max(r)
                    };
                }
                top -= layer.thickness * scale;
            }
        }
        worst
    }

    /// The axial modulus the beam sees, (A₁₁ − A₁₂²/A₂₂)/thickness over the whole
    /// thickness (gaps included, as the beam's wall area is), Pa; and the mean density.
    pub fn smeared(&self) -> (f64, f64) {
        let w = self.wall(1.0, 1.0);
        let t = self.thickness();
        ((w.a11 - w.a12 * w.a12 / w.a22) / t, w.mass_per_area / t)
    }
}
