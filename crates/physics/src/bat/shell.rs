//! The barrel wall as a thin shell of revolution: its breathing (hoop) modes of
//! circumferential wave number n ≥ 2, discretised along the axis.
//!
//! Theory: Love's first-approximation shell (Love 1888; Leissa, "Vibration of Shells",
//! NASA SP-288, 1973, ch. 2, the Love–Timoshenko strain–displacement relations), taken as
//! locally cylindrical (the barrel's taper, a few degrees, is neglected in the strains; the
//! radius and the wall vary along the axis). With u = U(x) cos nθ, v = V(x) sin nθ,
//! w = W(x) cos nθ (w outward) the strains are
//! ε_x = U′, ε_θ = (nV + W)/a, γ = V′ − nU/a,
//! κ_x = −W″, κ_θ = (nV + n²W)/a², τ = 2(V′ + nW′)/a,
//! and the energies per unit length, after the θ integral (π for every term),
//! U = (π/2) a [A₁₁ε_x² + 2A₁₂ε_xε_θ + A₂₂ε_θ² + A₆₆γ² + D₁₁κ_x² + 2D₁₂κ_xκ_θ + D₂₂κ_θ² +
//! D₆₆τ²], T = (π/2) a ρ_s (U̇² + V̇² + Ẇ²), with A and D the wall's membrane and bending
//! stiffnesses (classical lamination theory for a layered wall, `laminate`).
//!
//! Every function of x is a cubic Hermite interpolant on two-node elements (U, U′, V, V′,
//! W, W′ at each node), so that the inextensional motions the lowest modes are made of
//! (ε_θ = 0 needs nV and W from the same space) are represented without membrane locking.
//! The free ends are natural conditions; a wall that joins a solid section (a bored wood
//! bat, a shell that starts inside the bat) is clamped there.
//!
//! These modes are orthogonal to the beam's (n = 1) bending: they carry no net force or
//! momentum across a section, so the wall's mass is in the beam's translation and in the
//! shell's breathing without being counted twice, and the contact force drives both in
//! parallel (the contact point's displacement is the beam's plus the shell's).

use super::laminate::Wall;
use super::subspace::{self, Band};
use crate::error::ModelError;

/// Degrees of freedom per node: U, U′, V, V′, W, W′.
const NODE_DOF: usize = 6;
/// Gauss–Legendre points per element (exact for the element's polynomial integrands with
/// constant properties).
const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// How each end of the shell is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellEnd {
    /// No force or moment: the knob end of a tube, the barrel's end (its cap neglected).
    Free,
    /// Joined to a solid section: every displacement and slope zero.
    Clamped,
    /// Simply supported (w = v = 0, u and the slope free): the textbook case the closed
    /// forms are written for.
    Supported,
}

/// The wall along the shell: what each station's stiffness and mass are.
pub trait WallAlong {
    /// The wall at axial position x, m.
    fn wall(&self, x: f64) -> Wall;

    /// The wall's loss stiffnesses at x (`Laminate::loss_wall`), `None` for a wall without
    /// loss.
    fn loss(&self, _x: f64) -> Option<Wall> {
        None
    }
}

/// The loss stiffnesses of a wall as a wall, to be assembled as one.
struct LossOf<'w>(&'w dyn WallAlong);

impl WallAlong for LossOf<'_> {
    fn wall(&self, x: f64) -> Wall {
        self.0.loss(x).unwrap_or_else(|| Wall {
            radius: self.0.wall(x).radius,
            ..Wall::default()
        })
    }
}

/// One mode: its wave number, angular frequency and its radial shape W (and W′) at the
/// nodes, scaled to unit modal mass (∫ ρ_s (U² + V² + W²) π a dx = 1, kg).
#[derive(Debug, Clone)]
pub struct ShellMode {
    pub wave_number: u32,
    /// rad/s.
    pub omega: f64,
    /// The mode's loss factor: the energy its strains dissipate per cycle over 2π, over
    /// their stored energy (the loss stiffnesses' Rayleigh quotient, xᵀK″x / xᵀKx; 0 for a
    /// wall without loss).
    pub loss_factor: f64,
    pub w: Vec<f64>,
    pub dw: Vec<f64>,
    /// Every dof at the nodes (U, U′, V, V′, W, W′ per node), for the mode's strains.
    pub shape: Vec<f64>,
}

/// The shell's lowest modes for the wave numbers asked, on one axial mesh.
#[derive(Debug, Clone)]
pub struct ShellModes {
    /// Node positions, m (along the bat, from the knob).
    pub nodes: Vec<f64>,
    /// Every mode found, sorted by frequency.
    pub modes: Vec<ShellMode>,
    /// Each wave number's stiffness (ends held) on `static_nodes`, factored: the static
    /// response to a load, all modes of that wave number at once (what the kept modes leave
    /// out, `static_over_footprint`).
    pub factors: Vec<(u32, Band)>,
    /// The finer mesh of the static solves (a load on a shell bends it locally, which
    /// converges more slowly with the mesh than the lowest modes do).
    pub static_nodes: Vec<f64>,
    /// The dofs the ends hold on `static_nodes` (no load reaches them).
    pub held: Vec<usize>,
}

/// Elements of the static solves' mesh (`ShellModes::static_nodes`), besides the knots.
pub const STATIC_ELEMENTS: usize = 240;

/// The axial mesh: the breakpoints inside [start, end] (in any order) kept as nodes, each piece cut into
/// equal elements no longer than (end − start)/`elements`.
pub fn mesh(start: f64, end: f64, breakpoints: &[f64], elements: usize) -> Vec<f64> {
    let mut cuts = vec![start];
    cuts.extend(
        breakpoints
            .iter()
            .copied()
            .filter(|&z| z > start + 1e-9 && z < end - 1e-9),
    );
    cuts.push(end);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let target = (end - start) / elements as f64;
    let mut nodes = vec![start];
    for w in cuts.windows(2) {
        let pieces = ((w[1] - w[0]) / target).ceil().max(1.0) as usize;
        for i in 1..=pieces {
            nodes.push(w[0] + (w[1] - w[0]) * i as f64 / pieces as f64);
        }
    }
    nodes
}

/// Cubic Hermite shape functions on an element of length `le` at ξ ∈ [0, 1]: values, first
/// and second x-derivatives, for (value₁, slope₁, value₂, slope₂).
fn hermite(xi: f64, le: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let n = [
        1.0 - 3.0 * x2 + 2.0 * x3,
        le * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        le * (-x2 + x3),
    ];
    let d = [
        (-6.0 * xi + 6.0 * x2) / le,
        1.0 - 4.0 * xi + 3.0 * x2,
        (6.0 * xi - 6.0 * x2) / le,
        -2.0 * xi + 3.0 * x2,
    ];
    let dd = [
        (-6.0 + 12.0 * xi) / (le * le),
        (-4.0 + 6.0 * xi) / le,
        (6.0 - 12.0 * xi) / (le * le),
        (-2.0 + 6.0 * xi) / le,
    ];
    (n, d, dd)
}

/// The element dof index of field f (0 U, 1 V, 2 W) for Hermite function k (0..4).
fn dof(field: usize, k: usize) -> usize {
    (k / 2) * NODE_DOF + 2 * field + (k % 2)
}

/// The strains (ε_x, ε_θ, γ, κ_x, κ_θ, τ) per element dof at one point, and the
/// displacements (U, V, W) per element dof.
fn strain_rows(
    n: f64,
    a: f64,
    h: &([f64; 4], [f64; 4], [f64; 4]),
) -> ([[f64; 12]; 6], [[f64; 12]; 3]) {
    let (val, d1, d2) = h;
    let mut b = [[0.0; 12]; 6];
    let mut disp = [[0.0; 12]; 3];
    for k in 0..4 {
        let (u, v, w) = (dof(0, k), dof(1, k), dof(2, k));
        b[0][u] = d1[k];
        b[1][v] = n * val[k] / a;
        b[1][w] = val[k] / a;
        b[2][v] = d1[k];
        b[2][u] = -n * val[k] / a;
        b[3][w] = -d2[k];
        b[4][v] = n * val[k] / (a * a);
        b[4][w] = n * n * val[k] / (a * a);
        b[5][v] = 2.0 * d1[k] / a;
        b[5][w] = 2.0 * n * d1[k] / a;
        disp[0][u] = val[k];
        disp[1][v] = val[k];
        disp[2][w] = val[k];
    }
    (b, disp)
}

/// The wall's stiffness as the 6×6 matrix of the strains above.
fn wall_matrix(wall: &Wall) -> [[f64; 6]; 6] {
    let mut c = [[0.0; 6]; 6];
    c[0][0] = wall.a11;
    c[0][1] = wall.a12;
    c[1][0] = wall.a12;
    c[1][1] = wall.a22;
    c[2][2] = wall.a66;
    c[3][3] = wall.d11;
    c[3][4] = wall.d12;
    c[4][3] = wall.d12;
    c[4][4] = wall.d22;
    c[5][5] = wall.d66;
    c
}

/// Stiffness and mass matrices of wave number n on the mesh (before the end conditions),
/// as bands in node order (half-bandwidth 11: an element couples its two nodes' dofs).
pub fn assemble(n: u32, nodes: &[f64], walls: &dyn WallAlong) -> (Band, Band) {
    let size = nodes.len() * NODE_DOF;
    let band = 2 * NODE_DOF - 1;
    let (mut k, mut m) = (Band::zeros(size, band), Band::zeros(size, band));
    let nf = f64::from(n);
    for (e, x) in nodes.windows(2).enumerate() {
        let le = x[1] - x[0];
        let base = e * NODE_DOF;
        for &(xi, weight) in &GAUSS {
            let wall = walls.wall(x[0] + xi * le);
            let (b, disp) = strain_rows(nf, wall.radius, &hermite(xi, le));
            let c = wall_matrix(&wall);
            let scale = std::f64::consts::PI * wall.radius * weight * le;
            for i in 0..12 {
                let cb: [f64; 6] = std::array::from_fn(|r| (0..6).map(|s| c[r][s] * b[s][i]).sum());
                for j in i..12 {
                    let kij: f64 = (0..6).map(|r| b[r][j] * cb[r]).sum();
                    let mij: f64 = (0..3).map(|r| disp[r][i] * disp[r][j]).sum();
                    k.add(base + i, base + j, scale * kij);
                    m.add(base + i, base + j, scale * wall.mass_per_area * mij);
                }
            }
        }
    }
    (k, m)
}

/// The dofs an end condition removes at the node `node`.
fn held(end: ShellEnd, node: usize) -> Vec<usize> {
    let b = node * NODE_DOF;
    match end {
        ShellEnd::Free => vec![],
        ShellEnd::Clamped => (b..b + NODE_DOF).collect(),
        ShellEnd::Supported => vec![b + 2, b + 4],
    }
}

/// The stiffness and mass with the ends held: a held dof's row and column cleared, its
/// stiffness 1 and mass 0 (an infinite eigenvalue: it never enters the lowest modes).
pub fn held_matrices(
    n: u32,
    nodes: &[f64],
    walls: &dyn WallAlong,
    ends: (ShellEnd, ShellEnd),
) -> (Band, Band) {
    let (mut k, mut m) = assemble(n, nodes, walls);
    for &i in &held_dofs(ends, nodes.len()) {
        k.hold(i, 1.0);
        m.hold(i, 0.0);
    }
    (k, m)
}

/// The lowest modes of wave number n (at most `count`), with the ends held as asked.
pub fn modes_of(
    n: u32,
    nodes: &[f64],
    walls: &dyn WallAlong,
    ends: (ShellEnd, ShellEnd),
    count: usize,
) -> Result<Vec<ShellMode>, ModelError> {
    let (k, m) = held_matrices(n, nodes, walls, ends);
    let count = count.min(k.n / 2);
    let (values, vectors) = subspace::lowest(&k, &m, count)?;
    let lossy = nodes.iter().any(|&x| walls.loss(x).is_some());
    let loss = lossy.then(|| held_matrices(n, nodes, &LossOf(walls), ends).0);
    Ok((0..values.len())
        .map(|c| {
            let col = vectors.column(c);
            let w: Vec<f64> = (0..nodes.len()).map(|p| col[p * NODE_DOF + 4]).collect();
            // the sign: W positive where it is largest
            let peak = w
                .iter()
                .copied()
                .fold(0.0, |acc: f64, x| if x.abs() > acc.abs() { x } else { acc });
            let sign = if peak < 0.0 { -1.0 } else { 1.0 };
            // unit modal mass: xᵀKx = ω²
            let loss_factor = loss.as_ref().map_or(0.0, |kl| {
                let x: Vec<f64> = col.iter().copied().collect();
                let mut y = vec![0.0; x.len()];
                kl.mul(&x, &mut y);
                (x.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>() / values[c]).max(0.0)
            });
            ShellMode {
                wave_number: n,
                omega: values[c].max(0.0).sqrt(),
                loss_factor,
                w: w.iter().map(|x| sign * x).collect(),
                dw: (0..nodes.len())
                    .map(|p| sign * col[p * NODE_DOF + 5])
                    .collect(),
                shape: col.iter().map(|x| sign * x).collect(),
            }
        })
        .collect())
}

/// The stiffness of wave number n for a static solve, the ends held. n = 0 is the
/// axisymmetric squeeze: its energies integrate over 2π (twice the n ≥ 1 matrices), its V
/// (torsion, which no radial load drives) is held, and so is U at the first node when no
/// end holds the tube along its axis.
pub fn static_stiffness(
    n: u32,
    nodes: &[f64],
    walls: &dyn WallAlong,
    ends: (ShellEnd, ShellEnd),
) -> Band {
    let (mut k, _) = held_matrices(n, nodes, walls, ends);
    if n == 0 {
        k.scale(2.0);
        for p in 0..nodes.len() {
            k.hold(p * NODE_DOF + 2, 1.0);
            k.hold(p * NODE_DOF + 3, 1.0);
        }
        if ends.0 != ShellEnd::Clamped && ends.1 != ShellEnd::Clamped {
            k.hold(0, 1.0);
        }
    }
    k
}

/// The dofs the ends hold on a mesh of `nodes` nodes.
pub fn held_dofs(ends: (ShellEnd, ShellEnd), nodes: usize) -> Vec<usize> {
    let mut removed = held(ends.0, 0);
    removed.extend(held(ends.1, nodes - 1));
    removed
}

/// The membrane strains and curvature changes (ε_x, ε_θ, κ_x, κ_θ) at axial position x on
/// the line θ = 0 of the wave-number-n field `u` (every dof at `nodes`), on a wall of
/// mid-surface radius `radius`. γ and τ go as sin nθ and vanish on that line.
pub fn strains_at(n: u32, nodes: &[f64], u: &[f64], radius: f64, x: f64) -> [f64; 4] {
    let e = nodes.partition_point(|&z| z <= x).clamp(1, nodes.len() - 1) - 1;
    let le = nodes[e + 1] - nodes[e];
    let xi = ((x - nodes[e]) / le).clamp(0.0, 1.0);
    let (b, _) = strain_rows(f64::from(n), radius, &hermite(xi, le));
    let at = |row: usize| -> f64 {
        (0..12)
            .map(|i| b[row][i] * u[e * NODE_DOF + i])
            .sum::<f64>()
    };
    [at(0), at(1), at(3), at(4)]
}

/// The static response of wave number n to a radial load spread evenly over
/// [`centre` − `half_length`, `centre` + `half_length`] along the axis, of unit total
/// amplitude (∫ q dx = 1 N for the cos nθ component): the mean radial displacement W over
/// that length, m/N (n = 0 as [`static_stiffness`] holds it). The load's edges should be
/// nodes of `nodes` (then the element integrals are exact).
pub fn static_radial(
    n: u32,
    nodes: &[f64],
    walls: &dyn WallAlong,
    ends: (ShellEnd, ShellEnd),
    centre: f64,
    half_length: f64,
) -> Result<f64, ModelError> {
    let k = static_stiffness(n, nodes, walls, ends);
    let load = |x: f64| (x - centre).abs() <= half_length * (1.0 + 1e-12);
    let mut weights = vec![0.0; k.n];
    for (e, x) in nodes.windows(2).enumerate() {
        let (le, mid) = (x[1] - x[0], 0.5 * (x[0] + x[1]));
        if !load(mid) {
            continue;
        }
        for &(xi, weight) in &GAUSS {
            let (val, _, _) = hermite(xi, le);
            for (j, v) in val.iter().enumerate() {
                let i = e * NODE_DOF + dof(2, j);
                weights[i] += weight * le * v / (2.0 * half_length);
            }
        }
    }
    let w = k.solve_positive(&weights).ok_or(ModelError::Unsupported(
        "the shell's stiffness is not positive definite (a wall of zero thickness?)",
    ))?;
    // the mean of W over the load = Σ wᵢ ∫ Nᵢ / (2 b): the same weights as the load's
    Ok(weights.iter().zip(&w).map(|(a, b)| a * b).sum())
}

impl ShellModes {
    /// The modes of every wave number in `wave_numbers`, `per_wave` of each, on `nodes`;
    /// their static stiffness on `static_nodes`.
    pub fn solve(
        (nodes, static_nodes): (Vec<f64>, Vec<f64>),
        walls: &dyn WallAlong,
        ends: (ShellEnd, ShellEnd),
        wave_numbers: &[u32],
        per_wave: usize,
    ) -> Result<Self, ModelError> {
        let mut modes = Vec::new();
        let mut factors = Vec::new();
        for &n in wave_numbers {
            modes.extend(modes_of(n, &nodes, walls, ends, per_wave)?);
            let k = held_matrices(n, &static_nodes, walls, ends).0;
            let factored = k.factor().ok_or(ModelError::Unsupported(
                "the shell's stiffness is not positive definite (a wall of zero thickness?)",
            ))?;
            factors.push((n, factored));
        }
        modes.sort_by(|a, b| a.omega.total_cmp(&b.omega));
        Ok(ShellModes {
            held: held_dofs(ends, static_nodes.len()),
            nodes,
            modes,
            factors,
            static_nodes,
        })
    }

    /// The static radial displacement, averaged over an elliptic footprint (semi-axes
    /// `axes` along and around, m, centred at x on a wall of outer radius `radius`), of a
    /// unit force spread evenly over it, summed over the wave numbers solved, m/N: fᵀK⁻¹f,
    /// which the modal expansion writes Σ φⱼ²/ωⱼ² over every mode of those wave numbers. Less
    /// the kept modes' sum, it is what the truncation leaves out.
    pub fn static_over_footprint(&self, x: f64, axes: (f64, f64), radius: f64) -> f64 {
        let points = footprint_points(x, axes);
        self.factors
            .iter()
            .map(|(n, k)| {
                let f = footprint_load(*n, &self.static_nodes, &self.held, &points, radius);
                let mut u = f.clone();
                k.solve_factored(&mut u);
                f.iter().zip(&u).map(|(a, b)| a * b).sum::<f64>()
            })
            .sum()
    }

    /// Mode `j`'s radial shape W at axial position x (Hermite interpolation; 0 off the
    /// shell).
    pub fn radial(&self, j: usize, x: f64) -> f64 {
        let nodes = &self.nodes;
        let (first, last) = (nodes[0], nodes[nodes.len() - 1]);
        if !(first..=last).contains(&x) {
            return 0.0;
        }
        let e = nodes.partition_point(|&z| z <= x).clamp(1, nodes.len() - 1) - 1;
        let le = nodes[e + 1] - nodes[e];
        let (val, _, _) = hermite((x - nodes[e]) / le, le);
        let mode = &self.modes[j];
        val[0] * mode.w[e] + val[1] * mode.dw[e] + val[2] * mode.w[e + 1] + val[3] * mode.dw[e + 1]
    }

    /// Mode `j`'s radial shape averaged over a circular contact patch of radius `patch`
    /// centred at axial position x on a wall of outer radius `radius` ([`Self::over_footprint`]
    /// with both semi-axes `patch`).
    pub fn over_patch(&self, j: usize, x: f64, patch: f64, radius: f64) -> f64 {
        self.over_footprint(j, x, (patch, patch), radius)
    }

    /// Mode `j`'s radial shape averaged over an elliptic footprint with semi-axes
    /// (along the bat, around it) = `axes`, m, centred at axial position x on a wall of
    /// outer radius `radius` (the ball's force spread evenly over it: the generalised force
    /// per newton, and the footprint's mean displacement per unit modal coordinate). A 4×4
    /// Gauss rule over the footprint's square in polar form.
    pub fn over_footprint(&self, j: usize, x: f64, axes: (f64, f64), radius: f64) -> f64 {
        let n = f64::from(self.modes[j].wave_number);
        let points = footprint_points(x, axes);
        let weight: f64 = points.iter().map(|p| p.2).sum();
        points
            .iter()
            .map(|&(z, s, w)| w * self.radial(j, z) * (n * s / radius).cos())
            .sum::<f64>()
            / weight
    }
}

/// The consistent load vector of wave number n on `nodes` for a unit force spread over
/// a footprint's quadrature points (x, arc offset, weight): each point's share of cos nθ
/// on the W shape functions of its element; nothing on the `held` dofs (a held dof does not
/// move: the load there goes into the support).
pub fn footprint_load(
    n: u32,
    nodes: &[f64],
    held: &[usize],
    points: &[(f64, f64, f64)],
    radius: f64,
) -> Vec<f64> {
    let mut f = vec![0.0; nodes.len() * NODE_DOF];
    let total: f64 = points.iter().map(|p| p.2).sum();
    for &(x, s, w) in points {
        if !(nodes[0]..=nodes[nodes.len() - 1]).contains(&x) {
            continue;
        }
        let e = nodes.partition_point(|&z| z <= x).clamp(1, nodes.len() - 1) - 1;
        let le = nodes[e + 1] - nodes[e];
        let (val, _, _) = hermite((x - nodes[e]) / le, le);
        let share = w / total * (f64::from(n) * s / radius).cos();
        for (k, v) in val.iter().enumerate() {
            f[e * NODE_DOF + dof(2, k)] += share * v;
        }
    }
    for &i in held {
        f[i] = 0.0;
    }
    f
}

/// A finer quadrature of the footprint for loads of high wave number (a cos nθ that turns
/// many times across it): `rings` × 4 Gauss points in the radius (a composite rule over
/// equal rings) and `spokes` equally spaced angles (exact for the angle's trigonometric
/// polynomials of degree below `spokes`).
pub fn footprint_points_fine(
    x: f64,
    axes: (f64, f64),
    rings: usize,
    spokes: usize,
) -> Vec<(f64, f64, f64)> {
    if axes.0 <= 0.0 || axes.1 <= 0.0 {
        return vec![(x, 0.0, 1.0)];
    }
    let mut points = Vec::with_capacity(rings * GAUSS.len() * spokes);
    for ring in 0..rings {
        for &(g, wg) in &GAUSS {
            let r = (ring as f64 + g) / rings as f64;
            for k in 0..spokes {
                let phi = (k as f64 + 0.5) / spokes as f64 * std::f64::consts::TAU;
                points.push((x + r * axes.0 * phi.cos(), r * axes.1 * phi.sin(), wg * r));
            }
        }
    }
    points
}

/// The footprint's quadrature: (axial position, arc offset, weight) of a 4×4 Gauss rule
/// over the ellipse in polar form; one point at x for a footprint of no size.
fn footprint_points(x: f64, axes: (f64, f64)) -> Vec<(f64, f64, f64)> {
    if axes.0 <= 0.0 || axes.1 <= 0.0 {
        return vec![(x, 0.0, 1.0)];
    }
    let mut points = Vec::with_capacity(GAUSS.len() * GAUSS.len());
    for &(r, wr) in &GAUSS {
        for &(t, wt) in &GAUSS {
            let phi = t * std::f64::consts::TAU;
            points.push((
                x + r * axes.0 * phi.cos(),
                r * axes.1 * phi.sin(),
                wr * wt * r,
            ));
        }
    }
    points
}
