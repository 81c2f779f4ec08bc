//! A bat resolved to numbers: outer and inner radius, material and fill along z, and the
//! cross-section properties (A, I, mass per length) with exact-enough integrals over z.

use crate::bat::laminate::{self, Laminate, Layer, AL6061_YIELD, ALUMINIUM_LOSS};
use crate::bat::profile::{handle_factor, Profile};
use crate::error::{out_of_range, ModelError};
use crate::spec::{BatPreset, BatSpec, BoreSpec, HandleSpec, ProfileSpec, ShellSpec};

/// Wood (R161, Nathan 2000).
pub const WOOD_DENSITY: f64 = 649.0;
pub const WOOD_YOUNGS_MODULUS: f64 = 1.814e10;
/// Aluminum (the paper).
pub const ALUMINUM_DENSITY: f64 = 2700.0;
pub const ALUMINUM_YOUNGS_MODULUS: f64 = 6.9e10;
pub const ALUMINUM_SHELL: f64 = 0.003;
/// Corked bat (the paper): 1 cm shell from z = 0.55 m, cork 240 kg/m³.
pub const CORKED_SHELL: f64 = 0.01;
pub const CORKED_SHELL_FROM: f64 = 0.55;
pub const CORK_DENSITY: f64 = 240.0;
/// Poisson's ratios: wood ν_LR of white ash (USDA Wood Handbook, table 5-2: 0.371);
/// aluminum 6061-T6 (ASM: 0.33).
pub const WOOD_POISSON: f64 = 0.37;
pub const ALUMINUM_POISSON: f64 = 0.33;
/// Shear modulus of the R161 wood, N/m² (Nathan 2000's Timoshenko calculation).
pub const WOOD_SHEAR_MODULUS: f64 = 1.05e9;

/// Cowper's (1966) shear coefficient of a hollow circular section (m = r/R; m = 0 solid).
pub fn cowper_shear_coefficient(poisson: f64, m: f64) -> f64 {
    let m2 = m * m;
    let a = (1.0 + m2).powi(2);
    6.0 * (1.0 + poisson) * a / ((7.0 + 6.0 * poisson) * a + (20.0 + 12.0 * poisson) * m2)
}

/// Solid circular section: area πR².
pub fn solid_area(r: f64) -> f64 {
    std::f64::consts::PI * r * r
}

/// Hollow section (outer R, inner r): area π(R² − r²).
pub fn hollow_area(outer: f64, inner: f64) -> f64 {
    std::f64::consts::PI * (outer * outer - inner * inner)
}

/// Hollow section second moment of area π(R⁴ − r⁴)/4 (r = 0: solid).
pub fn hollow_second_moment(outer: f64, inner: f64) -> f64 {
    std::f64::consts::PI * (outer.powi(4) - inner.powi(4)) / 4.0
}

/// Every number of a bat's geometry and material, presets and overrides applied.
#[derive(Debug, Clone, PartialEq)]
pub struct BatGeometry {
    pub profile: Profile,
    pub handle: HandleSpec,
    /// Overall length, m (≥ the profile's; beyond it the barrel continues at its end radius).
    pub length: f64,
    pub density: f64,
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Shear modulus G, N/m².
    pub shear_modulus: f64,
    /// Shear coefficient κ (None: Cowper's at each section).
    pub shear_coefficient: Option<f64>,
    /// Modal damping ratio ζ = 1/(2Q) of the flexible modes (0: undamped).
    pub damping_ratio: f64,
    /// (wall thickness, start z) of the hollow part, if any.
    pub shell: Option<(f64, f64)>,
    /// The wall thickness along the bat, `[z, t]` knots (empty: `shell`'s one thickness).
    pub shell_knots: Vec<[f64; 2]>,
    /// Density of the filling of the hollow part, kg/m³ (0: empty).
    pub fill_density: f64,
    /// (radius, start z) of an axial bore from the barrel end, if any (exclusive with
    /// `shell`; its filling is `fill_density`).
    pub bore: Option<(f64, f64)>,
    /// The hollow part's wall as layers (after any break-in), if given.
    pub laminate: Option<Laminate>,
    /// The loss factor of a wall without layers: aluminium's for the metal preset, none for
    /// wood (no loss across the grain was found; docs/physics.md, "Losses in the wall").
    pub wall_loss_factor: f64,
    /// The yield strength of a wall without layers, Pa (NaN for wood: a wood wall's
    /// strength across the grain is not modelled).
    pub yield_strength: f64,
}

impl BatGeometry {
    /// Apply the preset, then the spec's overrides, and check the result.
    pub fn resolve(bat: &BatSpec) -> Result<Self, ModelError> {
        stack_at_thickest_knot(bat.shell.as_ref())?;
        let expanded = super::hollow_presets::expand(bat);
        let bat = &expanded;
        let profile = match &bat.profile {
            None => Profile::r161(),
            Some(ProfileSpec::Knots(k)) => Profile::from_knots(k)?,
            Some(ProfileSpec::Csv(path)) => {
                return Err(ModelError::UnresolvedCsvProfile(path.clone()))
            }
        };
        let preset = PresetMaterial::of(bat.preset)?;
        let is_wood = bat.preset != BatPreset::Aluminum;
        let material = &bat.material;
        let poisson_ratio = material.poisson_ratio.unwrap_or(if is_wood {
            WOOD_POISSON
        } else {
            ALUMINUM_POISSON
        });
        let laminate = laminate_of(bat.shell.as_ref())?;
        // a layered wall sets the beam's modulus and density unless the material does
        let smeared = laminate.as_ref().map(Laminate::smeared);
        let youngs_modulus = material
            .youngs_modulus
            .or(smeared.map(|s| s.0))
            .unwrap_or(preset.youngs_modulus);
        let shear_modulus = material.shear_modulus.unwrap_or(if is_wood {
            WOOD_SHEAR_MODULUS
        } else {
            youngs_modulus / (2.0 * (1.0 + poisson_ratio))
        });
        let damping_ratio = damping_ratio(material.quality_factor)?;
        let length = bat.length.unwrap_or(profile.length());
        check_length(length, &profile)?;
        let geometry = Self {
            profile,
            handle: bat.handle.clone(),
            length,
            density: bat
                .material
                .density
                .or(smeared.map(|s| s.1))
                .unwrap_or(preset.density),
            youngs_modulus,
            poisson_ratio,
            shear_modulus,
            shear_coefficient: material.shear_coefficient,
            damping_ratio,
            wall_loss_factor: if is_wood { 0.0 } else { ALUMINIUM_LOSS },
            yield_strength: match (material.yield_strength, is_wood) {
                (Some(y), _) if !(y > 0.0 && y.is_finite()) => {
                    return Err(out_of_range(
                        "bat.material.yield_strength",
                        y,
                        "a finite number > 0 Pa",
                    ))
                }
                (Some(y), _) => y,
                (None, true) => f64::NAN,
                (None, false) => AL6061_YIELD,
            },
            shell: shell_of(
                bat.shell.as_ref(),
                preset.shell,
                laminate.as_ref().map(Laminate::thickness),
            )?,
            shell_knots: shell_knots(bat.shell.as_ref())?,
            fill_density: bat
                .fill
                .as_ref()
                .map(|f| f.density)
                .unwrap_or(preset.fill_density),
            bore: None,
            laminate,
        };
        let geometry = match &bat.bore {
            None => geometry,
            Some(bore) => geometry.with_bore(bore, bat.shell.is_some() || bat.fill.is_some())?,
        };
        geometry.check()?;
        Ok(geometry)
    }

    /// The solid bat drilled with `bore` (its fill replaces the preset's hollow part).
    fn with_bore(mut self, bore: &BoreSpec, shell_given: bool) -> Result<Self, ModelError> {
        if shell_given || self.shell.is_some() {
            return Err(out_of_range(
                "bat.bore",
                f64::NAN,
                "a bore in a solid bat: preset r161, without bat.shell or bat.fill",
            ));
        }
        let ok = |v: f64| v > 0.0 && v.is_finite();
        if !ok(bore.diameter) {
            return Err(out_of_range(
                "bat.bore.diameter",
                bore.diameter,
                "a finite number > 0 m",
            ));
        }
        if !(ok(bore.depth) && bore.depth < self.length) {
            return Err(out_of_range(
                "bat.bore.depth",
                bore.depth,
                &format!("(0, {}) m (the bat's length)", self.length),
            ));
        }
        let (radius, from) = (0.5 * bore.diameter, self.length - bore.depth);
        for z in self.breakpoints().into_iter().chain([from]) {
            if z >= from && radius >= self.outer_radius(z) {
                return Err(out_of_range(
                    "bat.bore.diameter",
                    bore.diameter,
                    &format!(
                        "< {:.4} m, the bat's diameter at z = {z:.3} m",
                        2.0 * self.outer_radius(z)
                    ),
                ));
            }
        }
        self.bore = Some((radius, from));
        self.fill_density = bore.fill_density;
        Ok(self)
    }

    fn check(&self) -> Result<(), ModelError> {
        let positive = |path: &str, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(out_of_range(path, v, "a finite number > 0"))
            }
        };
        positive("bat.material.density", self.density)?;
        positive("bat.material.youngs_modulus", self.youngs_modulus)?;
        positive("bat.handle.radius_scale", self.handle.radius_scale)?;
        positive("bat.material.shear_modulus", self.shear_modulus)?;
        if !(self.poisson_ratio > -1.0 && self.poisson_ratio < 0.5) {
            return Err(out_of_range(
                "bat.material.poisson_ratio",
                self.poisson_ratio,
                "(-1, 0.5)",
            ));
        }
        if let Some(k) = self.shear_coefficient {
            if !(k > 0.0 && k <= 1.0) {
                return Err(out_of_range("bat.material.shear_coefficient", k, "(0, 1]"));
            }
        }
        if !(self.handle.end >= 0.0 && self.handle.end.is_finite()) {
            return Err(out_of_range("bat.handle.end", self.handle.end, "[0, ∞) m"));
        }
        if !(self.handle.blend >= 0.0 && self.handle.blend.is_finite()) {
            return Err(out_of_range(
                "bat.handle.blend",
                self.handle.blend,
                "[0, ∞) m",
            ));
        }
        if !(self.fill_density >= 0.0 && self.fill_density.is_finite()) {
            return Err(out_of_range(
                "bat.fill.density",
                self.fill_density,
                "[0, ∞) kg/m³ (0: no fill)",
            ));
        }
        if let Some((thickness, from)) = self.shell {
            positive("bat.shell.thickness", thickness)?;
            if !(from >= 0.0 && from < self.length) {
                return Err(out_of_range(
                    "bat.shell.from",
                    from,
                    &format!("[0, {}) m (the bat's length)", self.length),
                ));
            }
            // R and the wall are piecewise linear between breakpoints, so the thinnest
            // margin over the hollow part sits at one of them.
            for z in self.breakpoints() {
                if z >= from {
                    let r = self.outer_radius(z);
                    let thickness = self.wall_thickness(z).unwrap_or(thickness);
                    if thickness >= r {
                        return Err(ModelError::ShellTooThick {
                            thickness,
                            radius: r,
                            z,
                        });
                    }
                }
            }
        }
        Ok(())
    }

    /// Outer radius R(z), m.
    pub fn outer_radius(&self, z: f64) -> f64 {
        self.profile.radius(z) * handle_factor(&self.handle, z)
    }

    /// The shell's wall thickness at z from `shell_knots` (None without knots), m.
    pub fn wall_thickness(&self, z: f64) -> Option<f64> {
        let k = &self.shell_knots;
        let (first, last) = (k.first()?, k.last()?);
        if z <= first[0] {
            return Some(first[1]);
        }
        if z >= last[0] {
            return Some(last[1]);
        }
        let i = k.partition_point(|p| p[0] <= z).clamp(1, k.len() - 1);
        let (a, b) = (k[i - 1], k[i]);
        Some(a[1] + (b[1] - a[1]) * (z - a[0]) / (b[0] - a[0]))
    }

    /// Inner radius r(z) (0 where solid), m.
    pub fn inner_radius(&self, z: f64) -> f64 {
        match (self.shell, self.bore) {
            (Some((thickness, from)), _) if z >= from => {
                let t = self.wall_thickness(z).unwrap_or(thickness);
                (self.outer_radius(z) - t).max(0.0)
            }
            (_, Some((radius, from))) if z >= from => radius,
            _ => 0.0,
        }
    }

    /// Mass per unit length ρ·A + ρ_fill·π r², kg/m.
    pub fn mass_per_length(&self, z: f64) -> f64 {
        let (outer, inner) = (self.outer_radius(z), self.inner_radius(z));
        self.density * hollow_area(outer, inner) + self.fill_density * solid_area(inner)
    }

    /// Second moment of area of the load-bearing wall (the fill adds no stiffness), m⁴.
    pub fn second_moment(&self, z: f64) -> f64 {
        hollow_second_moment(self.outer_radius(z), self.inner_radius(z))
    }

    /// Cross-section area of the load-bearing wall, m².
    pub fn wall_area(&self, z: f64) -> f64 {
        hollow_area(self.outer_radius(z), self.inner_radius(z))
    }

    /// Rotary inertia per unit length ρ I_wall + ρ_fill π r⁴/4, kg·m.
    pub fn rotary_inertia_per_length(&self, z: f64) -> f64 {
        let inner = self.inner_radius(z);
        self.density * self.second_moment(z) + self.fill_density * hollow_second_moment(inner, 0.0)
    }

    /// Shear stiffness κ G A of the wall, N.
    pub fn shear_stiffness(&self, z: f64) -> f64 {
        let (outer, inner) = (self.outer_radius(z), self.inner_radius(z));
        let kappa = self
            .shear_coefficient
            .unwrap_or_else(|| cowper_shear_coefficient(self.poisson_ratio, inner / outer));
        kappa * self.shear_modulus * hollow_area(outer, inner)
    }

    /// Positions where the integrands' pieces change (profile knots, handle blend, shell
    /// start, ends), sorted, inside [0, L].
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self.profile.knots_z().to_vec();
        b.push(self.handle.end);
        b.push(self.handle.end + self.handle.blend);
        if let Some((_, from)) = self.shell.or(self.bore) {
            b.push(from);
        }
        b.extend(self.shell_knots.iter().map(|k| k[0]));
        b.push(0.0);
        b.push(self.length);
        b.retain(|&z| (0.0..=self.length).contains(&z));
        b.sort_by(f64::total_cmp);
        b.dedup_by(|a, c| (*a - *c).abs() < 1e-12);
        b
    }

    /// ∫ₐᵇ f(z) dz by 3-point Gauss–Legendre on every piece between breakpoints (exact for
    /// the polynomial pieces of A(z) and nearly so for I(z)).
    pub fn integrate(&self, a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        let mut cuts = vec![a];
        cuts.extend(self.breakpoints().into_iter().filter(|&z| z > a && z < b));
        cuts.push(b);
        let x = (0.6f64).sqrt();
        let mut sum = 0.0;
        for w in cuts.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            // the shell start is a jump: nudge evaluation points off it
            sum += half
                * (5.0 / 9.0 * f(mid - half * x)
                    + 8.0 / 9.0 * f(mid)
                    + 5.0 / 9.0 * f(mid + half * x));
        }
        sum
    }
}

/// What a preset gives a bat before the study's overrides.
struct PresetMaterial {
    density: f64,
    youngs_modulus: f64,
    /// (wall thickness, start z) of the hollow part, if any.
    shell: Option<(f64, f64)>,
    fill_density: f64,
}

impl PresetMaterial {
    fn of(preset: BatPreset) -> Result<Self, ModelError> {
        let (density, youngs_modulus, shell, fill_density) = match preset {
            BatPreset::Wall | BatPreset::Cylinder => {
                return Err(ModelError::Unsupported(
                    "bat geometry of a rigid target (bat.preset wall or cylinder: not a bat)",
                ))
            }
            BatPreset::R161 => (WOOD_DENSITY, WOOD_YOUNGS_MODULUS, None, 0.0),
            // expanded to aluminum with their own geometry (`hollow_presets::expand`)
            BatPreset::Aluminum | BatPreset::AlloyBbcor | BatPreset::CompositeBbcor => (
                ALUMINUM_DENSITY,
                ALUMINUM_YOUNGS_MODULUS,
                Some((ALUMINUM_SHELL, 0.0)),
                0.0,
            ),
            BatPreset::Corked => (
                WOOD_DENSITY,
                WOOD_YOUNGS_MODULUS,
                Some((CORKED_SHELL, CORKED_SHELL_FROM)),
                CORK_DENSITY,
            ),
        };
        Ok(PresetMaterial {
            density,
            youngs_modulus,
            shell,
            fill_density,
        })
    }
}

/// The modal damping ratio ζ = 1/(2Q) of a quality factor (none: undamped).
fn damping_ratio(quality_factor: Option<f64>) -> Result<f64, ModelError> {
    match quality_factor {
        None => Ok(0.0),
        Some(q) if q > 0.5 && q.is_finite() => Ok(0.5 / q),
        Some(q) => Err(out_of_range(
            "bat.material.quality_factor",
            q,
            "(0.5, ∞) (underdamped modes)",
        )),
    }
}

/// The bat's length: finite, positive, and not shorter than its profile.
fn check_length(length: f64, profile: &Profile) -> Result<(), ModelError> {
    if !(length > 0.0 && length.is_finite()) {
        return Err(out_of_range("bat.length", length, "a finite number > 0 m"));
    }
    if length < profile.length() * (1.0 - 1e-12) {
        return Err(ModelError::BatShorterThanProfile {
            length,
            profile_length: profile.length(),
        });
    }
    Ok(())
}

/// The shell's thickness knots, checked: z increasing, every thickness > 0.
fn shell_knots(spec: Option<&ShellSpec>) -> Result<Vec<[f64; 2]>, ModelError> {
    let Some(k) = spec.and_then(|s| s.thickness_knots.clone()) else {
        return Ok(Vec::new());
    };
    let increasing = k.windows(2).all(|w| w[1][0] > w[0][0]);
    match k
        .iter()
        .find(|p| !(p[1] > 0.0 && p[1].is_finite() && p[0].is_finite()))
    {
        _ if k.is_empty() || !increasing => Err(out_of_range(
            "bat.shell.thickness_knots",
            f64::NAN,
            "at least one [z, t] knot, z increasing",
        )),
        Some(p) => Err(out_of_range("bat.shell.thickness_knots", p[1], "t > 0 m")),
        None => Ok(k),
    }
}

/// A study that gives both a wall's layers and its thickness knots gives the layers as the
/// wall where it is thickest (elsewhere each scales), so that every layer's thickness means
/// what it says. (A preset's own stack scales with whatever knots the study gives.)
fn stack_at_thickest_knot(spec: Option<&ShellSpec>) -> Result<(), ModelError> {
    let Some((knots, layers)) =
        spec.and_then(|s| s.thickness_knots.as_ref().zip(s.layers.as_ref()))
    else {
        return Ok(());
    };
    let thickest = knots.iter().map(|p| p[1]).fold(0.0, f64::max);
    let stack: f64 = layers.iter().map(|l| l.thickness).sum();
    if (thickest - stack).abs() <= 1e-9 * thickest {
        return Ok(());
    }
    Err(out_of_range(
        "bat.shell.layers",
        stack,
        &format!(
            "layers adding up to {thickest} m, the thickest of bat.shell.thickness_knots \
             (the layers are the wall where it is thickest; elsewhere each scales)"
        ),
    ))
}

/// The hollow part: the study's shell (its missing fields from the preset's), else the
/// preset's.
fn shell_of(
    spec: Option<&ShellSpec>,
    preset: Option<(f64, f64)>,
    stack: Option<f64>,
) -> Result<Option<(f64, f64)>, ModelError> {
    let Some(s) = spec else { return Ok(preset) };
    if let (Some(t), Some(stack)) = (s.thickness, stack) {
        if (t - stack).abs() > 1e-9 * stack {
            return Err(out_of_range(
                "bat.shell.thickness",
                t,
                &format!("{stack} m, the sum of bat.shell.layers' thicknesses (or unset)"),
            ));
        }
    }
    // with knots, `thickness` is their thickest (what the knots leave to it is nothing)
    let from_knots = s
        .thickness_knots
        .as_ref()
        .map(|k| k.iter().map(|p| p[1]).fold(0.0, f64::max));
    let thickness = s
        .thickness
        .or(from_knots)
        .or(stack)
        .or(preset.map(|p| p.0))
        .ok_or_else(|| {
            out_of_range(
                "bat.shell.thickness",
                f64::NAN,
                "a wall thickness in m (required: this preset is solid)",
            )
        })?;
    Ok(Some((
        thickness,
        s.from.or(preset.map(|p| p.1)).unwrap_or(0.0),
    )))
}

/// The most layers a wall may have: real barrels have a few tens of plies; the cap bounds
/// the work and memory a study file can ask for.
pub const MAX_LAYERS: usize = 200;

/// The wall's layers (materials looked up, thicknesses and angles checked, the break-in
/// applied), if the shell lists them.
fn laminate_of(spec: Option<&ShellSpec>) -> Result<Option<Laminate>, ModelError> {
    let Some(s) = spec else { return Ok(None) };
    if !(0.0..1.0).contains(&s.break_in) {
        return Err(out_of_range(
            "bat.shell.break_in",
            s.break_in,
            "[0, 1) (the fraction of the matrix's stiffness lost)",
        ));
    }
    let Some(specs) = &s.layers else {
        return match s.break_in {
            0.0 => Ok(None),
            b => Err(out_of_range(
                "bat.shell.break_in",
                b,
                "0 for a wall without composite plies (break-in softens a polymer matrix)",
            )),
        };
    };
    if specs.is_empty() || specs.len() > MAX_LAYERS {
        return Err(out_of_range(
            "bat.shell.layers",
            specs.len() as f64,
            &format!("1 to {MAX_LAYERS} layers"),
        ));
    }
    let mut layers = Vec::with_capacity(specs.len());
    for (i, l) in specs.iter().enumerate() {
        let path = format!("bat.shell.layers[{i}]");
        let ply = laminate::material(&format!("{path}.material"), &l.material)?;
        if !(l.thickness > 0.0 && l.thickness.is_finite()) {
            return Err(out_of_range(
                &format!("{path}.thickness"),
                l.thickness,
                "(0, ∞) m",
            ));
        }
        if !l.angle.is_finite() || (l.angle != 0.0 && !ply.is_some_and(|p| p.matrix)) {
            return Err(out_of_range(
                &format!("{path}.angle"),
                l.angle,
                "a finite angle in rad for a fibre ply; 0 (or unset) for a metal or a gap",
            ));
        }
        layers.push(Layer {
            ply,
            thickness: l.thickness,
            angle: l.angle,
        });
    }
    let solid = |l: &Layer| l.ply.is_some();
    if !layers.first().is_some_and(solid) || !layers.last().is_some_and(solid) {
        return Err(out_of_range(
            "bat.shell.layers",
            f64::NAN,
            "a stack that starts and ends with a material (a gap only between two walls)",
        ));
    }
    if s.break_in != 0.0 && !layers.iter().any(|l| l.ply.is_some_and(|p| p.matrix)) {
        return Err(out_of_range(
            "bat.shell.break_in",
            s.break_in,
            "0 for a wall without composite plies (break-in softens a polymer matrix)",
        ));
    }
    Ok(Some(Laminate { layers }.broken_in(s.break_in)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hollow_reduces_to_solid() {
        let r = 0.03;
        assert_eq!(hollow_area(r, 0.0), solid_area(r));
        assert!(
            (hollow_second_moment(r, 0.0) - std::f64::consts::PI * r.powi(4) / 4.0).abs() < 1e-20
        );
    }

    #[test]
    fn shell_thicker_than_handle_is_an_error() {
        let bat = BatSpec {
            shell: Some(crate::spec::ShellSpec {
                thickness: Some(0.02),
                from: Some(0.0),
                ..Default::default()
            }),
            ..BatSpec::default()
        };
        let err = BatGeometry::resolve(&bat).unwrap_err();
        assert!(matches!(err, ModelError::ShellTooThick { .. }), "{err}");
    }
}
