//! The barrel wall's stress under the ball: what decides whether a hollow barrel yields
//! (dents, for a metal) or cracks (a composite) under a hit, read at the centre of the
//! ball's footprint, where a load on a shell bends it most.
//!
//! The wall's strains there are those of the shell the collisions use (`bat::shell`), by
//! the mode-acceleration method (the classical way to recover stresses from a truncated
//! modal solution; Craig & Kurdila, "Fundamentals of Structural Dynamics", 2006, §14.3):
//! the static response to the contact force F over the footprint, summed over the wave
//! numbers n = 0 and 2..=[`MAX_WAVE_NUMBER`], plus the kept modes' dynamic excess over
//! their static share, Σⱼ (qⱼ − F φⱼ/ωⱼ²) εⱼ. It is read at the two instants of a
//! collision where it can peak: the largest contact force, and the wall's largest
//! displacement under the ball (the kept modes lag the force).
//!
//! n = 1 is the bat's bending as a beam, whose stress at the contact the beam model does
//! not resolve; it is left out (the bending stress of a free bat under a barrel hit is a
//! small part of the local one: `tests/wall_stress.rs` measures the n = 0, 2 terms it sits
//! between).

use super::laminate::{Laminate, Ply, Strength};
use super::section::BatGeometry;
use super::shell::{
    footprint_load, footprint_points_fine, held_dofs, mesh, static_stiffness, strains_at, ShellEnd,
    ShellModes, WallAlong, STATIC_ELEMENTS,
};
use super::subspace::Band;
use crate::error::ModelError;

/// The highest wave number of the static sum (`tests/wall_stress.rs` holds its convergence).
pub const MAX_WAVE_NUMBER: u32 = 40;
/// The footprint's quadrature for the static load: rings in the radius (4 Gauss points
/// each) and equally spaced spokes (a cos nθ up to n = 40 turns about 15 radians across a
/// ball's footprint on a barrel).
const RINGS: usize = 4;
const SPOKES: usize = 64;

/// The wall's state at one instant of a collision: what its stress is recovered from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WallInstant {
    /// The contact force, N.
    pub force: f64,
    /// The footprint's semi-axes (along the bat, around it), m.
    pub axes: (f64, f64),
    /// The kept breathing modes' coordinates and their shapes over the footprint (unit
    /// modal mass), in the order of `ShellModes::modes`.
    pub q: Vec<f64>,
    pub phi: Vec<f64>,
}

/// The hollow part's stiffness for every wave number of the static sum, factored once.
#[derive(Debug, Clone)]
pub struct WallStatics {
    nodes: Vec<f64>,
    factors: Vec<(u32, Band)>,
    held: Vec<usize>,
}

impl WallStatics {
    /// The statics of a bat's hollow part (`None` for a solid bat).
    pub fn of(g: &BatGeometry) -> Result<Option<Self>, ModelError> {
        let Some((start, ends)) = super::barrel::hollow_part(g) else {
            return Ok(None);
        };
        let nodes = mesh(start, g.length, &g.breakpoints(), STATIC_ELEMENTS);
        Self::solve(nodes, &super::barrel::barrel_wall(g), ends).map(Some)
    }

    /// The statics of a shell on `nodes` with its `walls`, held at its `ends` as said.
    pub fn solve(
        nodes: Vec<f64>,
        walls: &dyn WallAlong,
        ends: (ShellEnd, ShellEnd),
    ) -> Result<Self, ModelError> {
        let factors = std::iter::once(0)
            .chain(2..=MAX_WAVE_NUMBER)
            .map(|n| {
                static_stiffness(n, &nodes, walls, ends)
                    .factor()
                    .map(|k| (n, k))
                    .ok_or(ModelError::Unsupported(
                        "the shell's stiffness is not positive definite (a wall of zero thickness?)",
                    ))
            })
            .collect::<Result<_, _>>()?;
        Ok(WallStatics {
            held: held_dofs(ends, nodes.len()),
            nodes,
            factors,
        })
    }

    /// The strains and curvature changes [ε_x, ε_θ, κ_x, κ_θ] at the centre of a footprint
    /// (semi-axes `axes`, centred at x on a wall of outer radius `outer` and mid-surface
    /// radius `mid`) under a unit force spread evenly over it, per newton.
    pub fn strains(&self, x: f64, axes: (f64, f64), outer: f64, mid: f64) -> [f64; 4] {
        let points = footprint_points_fine(x, axes, RINGS, SPOKES);
        self.strains_under(x, mid, |n| {
            footprint_load(n, &self.nodes, &self.held, &points, outer)
        })
    }

    /// The strains at (x, θ = 0) on a wall of mid-surface radius `mid` under the load whose
    /// consistent vector for wave number n is `load(n)` (on [`Self::nodes`]), summed over
    /// the wave numbers.
    pub fn strains_under(&self, x: f64, mid: f64, load: impl Fn(u32) -> Vec<f64>) -> [f64; 4] {
        let mut sum = [0.0; 4];
        for (n, k) in &self.factors {
            let mut u = load(*n);
            k.solve_factored(&mut u);
            let e = strains_at(*n, &self.nodes, &u, mid, x);
            (0..4).for_each(|i| sum[i] += e[i]);
        }
        sum
    }

    /// The static mesh's nodes, m.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The dofs the ends hold.
    pub fn held(&self) -> &[usize] {
        &self.held
    }
}

/// The wall's strains at the footprint's centre at one instant (mode acceleration: the
/// static response to the force, corrected by the kept modes' dynamic excess).
pub fn strains_at_instant(
    statics: &WallStatics,
    modes: &ShellModes,
    (x, outer, mid): (f64, f64, f64),
    instant: &WallInstant,
) -> [f64; 4] {
    let f = instant.force;
    let mut e = statics.strains(x, instant.axes, outer, mid).map(|s| f * s);
    for (j, mode) in modes.modes.iter().enumerate().take(instant.q.len()) {
        let excess = instant.q[j] - f * instant.phi[j] / (mode.omega * mode.omega);
        let ej = strains_at(mode.wave_number, &modes.nodes, &mode.shape, mid, x);
        (0..4).for_each(|i| e[i] += excess * ej[i]);
    }
    e
}

/// The wall's stress ratio at axial position x under the strains `e` (`Ply::stress_ratio`
/// over its plies' faces, or a metal wall's von Mises stress over its yield): 1 where it
/// would yield or fail. NaN where the strength is unknown (a wood wall).
pub fn stress_ratio(g: &BatGeometry, x: f64, e: [f64; 4]) -> f64 {
    let h = g.outer_radius(x) - g.inner_radius(x);
    match &g.laminate {
        Some(l) => l.stress_ratio(h / l.thickness(), e),
        None => {
            let metal =
                Ply::isotropic(g.youngs_modulus, g.poisson_ratio, g.density).with_strength(match g
                    .yield_strength
                {
                    y if y > 0.0 => Strength::Yield(y),
                    _ => Strength::Unknown,
                });
            Laminate::single(metal, h).stress_ratio(1.0, e)
        }
    }
}

/// The largest stress ratio of the wall at x over a collision's `instants` (NaN with
/// none, or where the strength is unknown).
pub fn peak_ratio(
    g: &BatGeometry,
    statics: &WallStatics,
    modes: &ShellModes,
    x: f64,
    instants: &[WallInstant],
) -> f64 {
    let outer = g.outer_radius(x);
    let mid = 0.5 * (outer + g.inner_radius(x));
    instants
        .iter()
        .map(|i| stress_ratio(g, x, strains_at_instant(statics, modes, (x, outer, mid), i)))
        .fold(f64::NAN, f64::max)
}
