//! The hollow part of a bat as a shell: its wall along the axis (the bat's section, or its
//! laminate scaled to the local thickness) and its breathing modes, found once per bat.

use super::laminate::Wall;
use super::section::BatGeometry;
use super::shell::{mesh, ShellEnd, ShellModes, WallAlong, STATIC_ELEMENTS};
use crate::error::ModelError;

/// Circumferential wave numbers solved: the ovalling n = 2 is the trampoline; n = 3 and 4
/// add the rest of the wall's compliance under a patch. Measured on the presets' BBCOR at
/// their best point: leaving out n = 4 moves it by up to 3e-4 (composite_bbcor), adding
/// n = 5 by up to 4e-5.
pub const WAVE_NUMBERS: [u32; 3] = [2, 3, 4];
/// Axial modes kept per wave number.
pub const MODES_PER_WAVE: usize = 4;
/// Elements along the hollow part, besides the profile's and the wall's knots: the presets'
/// BBCOR at their best point moves by at most 2e-6 from 24 to 80 elements.
pub const ELEMENTS: usize = 24;
/// The finest resolution a study may ask for (`numerics.shell_*`): bounds on the solve's
/// size and time.
pub const MAX_ELEMENTS: usize = 400;
pub const MAX_WAVE_NUMBER: u32 = 12;
pub const MAX_MODES_PER_WAVE: usize = 16;

/// The shell's resolution: elements, wave numbers and modes per wave number.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellResolution {
    pub elements: usize,
    pub wave_numbers: Vec<u32>,
    pub per_wave: usize,
}

impl ShellResolution {
    /// A study's numerics, the defaults where it says nothing.
    pub fn of(numerics: &crate::spec::NumericsSpec) -> Self {
        ShellResolution {
            elements: numerics.shell_elements.unwrap_or(ELEMENTS),
            wave_numbers: numerics
                .shell_wave_numbers
                .clone()
                .unwrap_or_else(|| WAVE_NUMBERS.to_vec()),
            per_wave: numerics.shell_modes_per_wave.unwrap_or(MODES_PER_WAVE),
        }
    }
}

/// The wall of a bat's hollow part at each station.
struct BarrelWall<'g>(&'g BatGeometry);

impl WallAlong for BarrelWall<'_> {
    fn wall(&self, x: f64) -> Wall {
        let g = self.0;
        let (outer, inner) = (g.outer_radius(x), g.inner_radius(x));
        let h = outer - inner;
        let radius = outer - 0.5 * h;
        match &g.laminate {
            Some(l) => l.wall(h / l.thickness(), radius),
            None => Wall::isotropic(g.youngs_modulus, g.poisson_ratio, g.density, h, radius),
        }
    }

    fn loss(&self, x: f64) -> Option<Wall> {
        let g = self.0;
        let (outer, inner) = (g.outer_radius(x), g.inner_radius(x));
        let h = outer - inner;
        let radius = outer - 0.5 * h;
        match &g.laminate {
            Some(l) => Some(l.loss_wall(h / l.thickness(), radius)),
            None if g.wall_loss_factor > 0.0 => {
                Some(self.wall(x).stiffness_times(g.wall_loss_factor))
            }
            None => None,
        }
    }
}

/// The bat's hollow part as a shell: its first station, m from the knob, and how its two
/// ends are held (`None` for a solid bat). A hollow part that starts inside the bat (a bore,
/// a shell from z > 0) is clamped to the solid section there; the knob end of a tube is
/// free. At the barrel's end a hollow bat's end cap, or a bore's plug where the bore is
/// filled, holds the wall round (w = v = 0, a supported end: the cap's own flexibility is
/// left out); an empty bore's end is open and free.
pub fn hollow_part(g: &BatGeometry) -> Option<(f64, (ShellEnd, ShellEnd))> {
    let (start, capped) = match (g.shell, g.bore) {
        (Some((_, from)), _) => (from, true),
        (None, Some((_, from))) => (from, g.fill_density > 0.0),
        (None, None) => return None,
    };
    let start_end = if start > 0.0 {
        ShellEnd::Clamped
    } else {
        ShellEnd::Free
    };
    let barrel_end = if capped {
        ShellEnd::Supported
    } else {
        ShellEnd::Free
    };
    Some((start, (start_end, barrel_end)))
}

/// The wall of a bat's hollow part at each station, as the shell reads it.
pub fn barrel_wall(g: &BatGeometry) -> impl WallAlong + '_ {
    BarrelWall(g)
}

/// The breathing modes of the bat's hollow part (`None` for a solid bat), held as
/// [`hollow_part`] says.
pub fn barrel_modes(
    g: &BatGeometry,
    resolution: &ShellResolution,
) -> Result<Option<ShellModes>, ModelError> {
    let Some((start, ends)) = hollow_part(g) else {
        return Ok(None);
    };
    let nodes = mesh(start, g.length, &g.breakpoints(), resolution.elements);
    let static_nodes = mesh(start, g.length, &g.breakpoints(), STATIC_ELEMENTS);
    ShellModes::solve(
        (nodes, static_nodes),
        &BarrelWall(g),
        ends,
        &resolution.wave_numbers,
        resolution.per_wave,
    )
    .map(Some)
}
