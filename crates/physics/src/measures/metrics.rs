//! Standard bat metrics and the bat-only sweet-spot definitions: centre of percussion for a
//! pivot at the hands, barrel nodes of the first two free–free modes, BBCOR (NCAA / ASTM
//! F2219) and its maximum along the barrel; plus the per-collision "felt at the hands"
//! quantities' building blocks live in `bat::motion`.
//!
//! # Centre of percussion (Brody, Am. J. Phys. 54, 640 (1986); Cross, Am. J. Phys. 66, 772 (1998))
//! A rigid bat (mass M, CM at z_cm, moment of inertia I_cm) receives an impulse J at z. Just
//! after, V = J/M and Ω = J (z − z_cm)/I_cm, so the point z_p moves at
//! `v_p = J [1/M + (z − z_cm)(z_p − z_cm)/I_cm]`. It stays at rest (no jolt at a pivot or the
//! hands at z_p) when `(z − z_cm)(z_cm − z_p) = I_cm/M`, i.e.
//! `z_cop = z_cm + I_cm/(M (z_cm − z_p)) = z_p + I_p/(M (z_cm − z_p))` with
//! `I_p = I_cm + M (z_cm − z_p)²` the moment of inertia about the pivot (parallel axes).
//! Uniform rod of length L pivoted at an end: `I_p = M L²/3`, `z_cm = L/2`, `z_cop = 2L/3`.
//!
//! # BBCOR of a pivoted bat (NCAA BBCOR protocol, built on ASTM F2219)
//! The bat, at rest, turns freely about a pivot at z_p (6 in from the knob); a ball of mass m
//! is fired at it with speed v_i and hits at arm r = z − z_p. The pivot force has no moment
//! about the pivot, so angular momentum about it is conserved:
//! `m v_i r = −m v_r r + I_p Ω`, i.e. with the impact point's speed V = Ω r and the
//! effective mass `M_e = I_p / r²`: `m (v_i + v_r) = M_e V` (v_r = rebound speed, + back).
//! The protocol defines the bat–ball COR as relative separation over approach,
//! `BBCOR = (v_r + V)/v_i`, and infers V from the measured v_r through the line above:
//! `BBCOR = e_A (1 + r_m) + r_m`, `e_A = v_r/v_i`, `r_m = m/M_e`; conversely
//! `e_A = (BBCOR − r_m)/(1 + r_m)` (Nathan's form, docs/physics.md).
//! For a *rigid* pivoted bat with a ball of COR e, restitution at the impact point
//! `V + v_r = e v_i` together with the momentum line gives `V = m (1 + e) v_i/(m + M_e)`,
//! `v_r = v_i (e − r_m)/(1 + r_m)`: the protocol's BBCOR is exactly e, whatever the bat's
//! inertia — the point of the protocol. Only a flexible bat (vibration losses) has a BBCOR
//! below e that varies along the barrel, with a maximum: see [`bbcor_scan`].
//!
//! The same algebra holds for a free (unpivoted) rigid bat with `1/M_e = 1/M + l²/I_cm`
//! (l = z − z_cm); the two effective masses are equal exactly at the centre of percussion of
//! the pivot (the conjugate point).

use crate::bat::compression::{barrel_compression, BASEBALL, RESOLUTION};
use crate::bat::wall_stress;
use crate::bat::PreparedBat;
use crate::collision::simulate::simulate;
use crate::error::ModelError;
use crate::field::{
    collision_efficiency_q, BAT_SPEED_FROM_END, REFERENCE_BAT_SPEED, REFERENCE_PITCH_SPEED,
};
use crate::measures::sweet::{find_maximum, find_zone, BBCOR_ZONE_DROP};
use crate::outcome::BatMetrics;
use crate::protocol::{
    bbcor_from_efficiency, free_effective_mass, moment_of_inertia_about, BBCOR_BALL_SPEED, KNOB6,
};
use crate::spec::{
    BallSpec, BatSpec, BatterSpec, CollisionSpec, EndsSpec, HoopSpec, ImpactSpec, ModelKind,
    NumericsSpec, SwingSpec,
};

/// Spacing of the BBCOR scan along the barrel, m.
pub const BBCOR_SCAN_STEP: f64 = 0.005;
/// The scan stops this far from the barrel end (the ball's radius, 3.66 cm, so the ball is
/// fully on the bat), m.
pub const BBCOR_SCAN_END_MARGIN: f64 = 0.0366;

/// Centre of percussion for a pivot at `pivot`: `z_p + I_p/(M (z_cm − z_p))` (module docs).
pub fn centre_of_percussion(mass: f64, z_cm: f64, inertia_cm: f64, pivot: f64) -> f64 {
    let i_p = moment_of_inertia_about(mass, z_cm, inertia_cm, pivot);
    pivot + i_p / (mass * (z_cm - pivot))
}

/// A rigid bat pivoted at rest hit by a ball (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PivotedOutcome {
    /// Ball rebound speed, m/s, + back toward the cannon.
    pub rebound_speed: f64,
    /// Angular velocity of the bat about the pivot after the collision, rad/s.
    pub bat_omega: f64,
    /// e_A = rebound / inbound speed.
    pub collision_efficiency: f64,
    /// The protocol's BBCOR, from e_A and the pivoted effective mass.
    pub bbcor: f64,
}

/// Solve the rigid pivoted collision: angular momentum about the pivot and restitution `cor`
/// at the impact point, `arm` = z − z_p (> 0), `inertia_pivot` = I_p.
pub fn rigid_pivoted_collision(
    ball_mass: f64,
    ball_speed: f64,
    inertia_pivot: f64,
    arm: f64,
    cor: f64,
) -> PivotedOutcome {
    let m_e = inertia_pivot / (arm * arm);
    let tip_speed = ball_mass * (1.0 + cor) * ball_speed / (ball_mass + m_e);
    let rebound_speed = cor * ball_speed - tip_speed;
    let e_a = rebound_speed / ball_speed;
    PivotedOutcome {
        rebound_speed,
        bat_omega: tip_speed / arm,
        collision_efficiency: e_a,
        bbcor: bbcor_from_efficiency(e_a, ball_mass, m_e),
    }
}

/// The node of a mode nearest the barrel end (the largest z), NaN without nodes.
pub fn barrel_node(nodes: &[f64]) -> f64 {
    nodes
        .iter()
        .copied()
        .filter(|z| z.is_finite())
        .fold(f64::NAN, f64::max)
}

/// What the BBCOR protocol fires at a bat (head-on, at the protocol's speed, the bat at rest
/// and free): a ball, and the hoop mode the barrel is given. A study's is the ball and hoop of
/// the first point that uses the bat ([`BbcorShot::of`]), so that the bat's BBCOR is the one
/// its own collisions and `batstudy optimize` see.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct BbcorShot {
    pub ball: BallSpec,
    pub hoop: Option<HoopSpec>,
}

impl BbcorShot {
    /// The ball and hoop of a collision.
    pub fn of(spec: &CollisionSpec) -> Self {
        BbcorShot {
            ball: spec.ball.clone(),
            hoop: spec.hoop.clone(),
        }
    }

    /// Its canonical JSON, stored beside the BBCOR it gave (`/bat/bbcor_shot`).
    pub fn json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }
}

/// Every bat-only metric of a prepared bat, pivot at [`KNOB6`], the BBCOR with the default
/// ball and no hoop. `bat_spec` and `numerics` must be those `bat` was prepared with. The
/// BBCOR scan runs the wave model (see [`bbcor_scan`]).
pub fn bat_metrics(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
) -> Result<BatMetrics, ModelError> {
    bat_metrics_mapped(bat, bat_spec, numerics, &BbcorShot::default(), &in_order)
}

/// Runs a scan's collisions: `f` at each position, the values in the positions' order. Each
/// value depends on its position alone, so a caller may run them in any order or in
/// parallel (the runner does: the BBCOR scan is most of preparing a bat).
pub type ScanMap<'a> = dyn Fn(&[f64], &ScanPoint) -> Vec<[f64; 2]> + Sync + 'a;

/// What a scan computes at one position: its value, and a second one beside it (the wall's
/// stress ratio in the BBCOR scan; NaN where there is none).
pub type ScanPoint<'a> = dyn Fn(f64) -> [f64; 2] + Sync + 'a;

/// The scan's collisions one after the other.
pub fn in_order(z: &[f64], f: &ScanPoint) -> Vec<[f64; 2]> {
    z.iter().map(|&z| f(z)).collect()
}

/// [`bat_metrics`] with `shot`'s ball and hoop and the BBCOR scan's collisions run by `map`.
pub fn bat_metrics_mapped(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    shot: &BbcorShot,
    map: &ScanMap,
) -> Result<BatMetrics, ModelError> {
    let p = bat.properties();
    let node = |k: usize| p.mode_nodes.get(k).map_or(f64::NAN, |n| barrel_node(n));
    let scan = protocol_scan(bat, bat_spec, numerics, shot, map, true)?;
    let (bbcor_z, bbcor) = (scan.z, scan.bbcor);
    let (wall_stress_ratio_position, wall_stress_ratio) = scan
        .z_stress
        .iter()
        .zip(&scan.wall_stress_ratio)
        .filter(|(_, r)| r.is_finite())
        .fold((f64::NAN, f64::NAN), |best, (&z, &r)| {
            if best.1.is_nan() || r > best.1 {
                (z, r)
            } else {
                best
            }
        });
    let zone = find_zone(&bbcor_z, &bbcor, BBCOR_ZONE_DROP);
    let (best_q, best_q_position) = if bbcor_z.is_empty() {
        (f64::NAN, f64::NAN)
    } else {
        best_q(
            bat,
            bat_spec,
            numerics,
            (&shot.ball, shot.hoop.as_ref()),
            map,
        )?
    };
    let (bbcor_max_position, bbcor_max) =
        zone.map_or((f64::NAN, f64::NAN), |z| (z.position, z.peak));
    Ok(BatMetrics {
        pivot: KNOB6,
        centre_of_percussion: centre_of_percussion(p.mass, p.z_cm, p.moment_of_inertia, KNOB6),
        node1_barrel: node(0),
        node2_barrel: node(1),
        bbcor_ball_speed: BBCOR_BALL_SPEED,
        bbcor_z,
        bbcor,
        bbcor_max,
        bbcor_max_position,
        sweet_zone_start: zone.map_or(f64::NAN, |z| z.left),
        sweet_zone_end: zone.map_or(f64::NAN, |z| z.right),
        hoop_mode_frequency: lowest_breathing_frequency(bat)?,
        barrel_compression: if bat_spec.has_wood_wall() {
            f64::NAN
        } else {
            barrel_compression(bat.geometry(), &BASEBALL, RESOLUTION)?
        },
        wall_stress_ratio,
        wall_stress_ratio_position,
        bbcor_shot: shot.json(),
        best_q,
        best_q_position,
    })
}

/// The lowest breathing mode of a hollow bat's wall, Hz (NaN for a solid bat).
fn lowest_breathing_frequency(bat: &PreparedBat) -> Result<f64, ModelError> {
    Ok(bat
        .shell_modes()?
        .and_then(|s| s.modes.first())
        .map_or(f64::NAN, |m| m.omega / std::f64::consts::TAU))
}

/// BBCOR along the barrel with the wave model: the bat at rest (ω = 0), the ball
/// (`ball`, at [`BBCOR_BALL_SPEED`]) fired at it at z from the CM to
/// L − [`BBCOR_SCAN_END_MARGIN`] every [`BBCOR_SCAN_STEP`].
///
/// The wave bat is free (the pivot is not modelled here): by Nathan (Am. J. Phys. 68, 979
/// (2000)) a pivoted bat gives the same exit speeds as a free one for barrel impacts, since
/// the collision is over before the handle responds, and ASTM F2219-23 (§1.3) itself
/// evaluates the bat as unconstrained. So e_A is the free bat's and the conversion uses the
/// free bat's effective mass, `BBCOR = e_A (1 + m/M_e) + m/M_e` with
/// `1/M_e = 1/M + l²/I_cm`: exactly e for a rigid bat, like the pivoted formula (module
/// docs). Returns empty vectors for a bat whose ends are not free.
pub fn bbcor_scan(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    ball: &BallSpec,
) -> Result<(Vec<f64>, Vec<f64>), ModelError> {
    let shot = BbcorShot {
        ball: ball.clone(),
        hoop: None,
    };
    bbcor_scan_mapped(bat, bat_spec, numerics, &shot, &in_order)
}

/// [`bbcor_scan`] with its collisions run by `map`.
pub fn bbcor_scan_mapped(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    shot: &BbcorShot,
    map: &ScanMap,
) -> Result<(Vec<f64>, Vec<f64>), ModelError> {
    let scan = protocol_scan(bat, bat_spec, numerics, shot, map, false)?;
    Ok((scan.z, scan.bbcor))
}

/// The BBCOR protocol's scan along the barrel, and the wall's stress ratio under each of its
/// shots (`bat::wall_stress`; NaN where the ball does not meet a shell).
#[derive(Debug, Clone, Default)]
pub struct ProtocolScan {
    pub z: Vec<f64>,
    pub bbcor: Vec<f64>,
    /// The positions the stress is read at (the scan's, within the barrel's shell) and its
    /// ratio to the wall's strength there.
    pub z_stress: Vec<f64>,
    pub wall_stress_ratio: Vec<f64>,
}

/// [`bbcor_scan_mapped`], and the wall's stress ratio at each shot when `with_stress` (for
/// a bat with the shell's breathing modes in its shot's hoop).
pub fn protocol_scan(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    shot: &BbcorShot,
    map: &ScanMap,
    with_stress: bool,
) -> Result<ProtocolScan, ModelError> {
    if bat_spec.ends != EndsSpec::default() {
        return Ok(ProtocolScan::default());
    }
    let p = bat.properties();
    let (z0, z1) = (p.z_cm, p.length - BBCOR_SCAN_END_MARGIN);
    let n = ((z1 - z0) / BBCOR_SCAN_STEP).floor().max(0.0) as usize + 1;
    let z: Vec<f64> = (0..n)
        .map(|k| z0 + k as f64 * BBCOR_SCAN_STEP)
        .filter(|&z| z <= z1 + 1e-12)
        .collect();
    let spec = protocol_shot(bat_spec, numerics, shot, z0);
    // the stress needs the shell's breathing modes in the shot (the collisions keep the
    // wall's state only then)
    let breathing = shot.hoop.as_ref().is_some_and(|h| h.from_geometry);
    let stress = match with_stress && breathing && !bat_spec.has_wood_wall() {
        true => bat.wall_statics()?.zip(bat.shell_modes()?),
        false => None,
    };
    let at = |zi: f64| {
        let mut spec = spec.clone();
        spec.impact.z = zi;
        match simulate(&spec, bat, None) {
            Ok(o) => {
                let m_e = free_effective_mass(p.mass, p.z_cm, p.moment_of_inertia, zi);
                let ratio = stress.map_or(f64::NAN, |(statics, modes)| {
                    wall_stress::peak_ratio(bat.geometry(), statics, modes, zi, &o.wall_instants)
                });
                [
                    bbcor_from_efficiency(o.collision_efficiency, spec.ball.mass, m_e),
                    ratio,
                ]
            }
            Err(_) => [f64::NAN; 2],
        }
    };
    let out = map(&z, &at);
    let stressed: Vec<(f64, f64)> = z
        .iter()
        .zip(&out)
        .filter(|(_, v)| v[1].is_finite())
        .map(|(&z, v)| (z, v[1]))
        .collect();
    Ok(ProtocolScan {
        bbcor: out.iter().map(|v| v[0]).collect(),
        z_stress: stressed.iter().map(|s| s.0).collect(),
        wall_stress_ratio: stressed.iter().map(|s| s.1).collect(),
        z,
    })
}

/// The protocol's shot at `z`: `shot`'s ball at [`BBCOR_BALL_SPEED`] without spin, head-on,
/// its hoop, the bat at rest and free (ASTM F2219: unconstrained).
fn protocol_shot(
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    shot: &BbcorShot,
    z: f64,
) -> CollisionSpec {
    CollisionSpec {
        model: ModelKind::Wave,
        bat: BatSpec {
            grip: None,
            ..bat_spec.clone()
        },
        ball: BallSpec {
            speed: BBCOR_BALL_SPEED,
            spin: 0.0,
            ..shot.ball.clone()
        },
        swing: SwingSpec::default(),
        hoop: shot.hoop.clone(),
        impact: ImpactSpec { z, offset: 0.0 },
        numerics: numerics.clone(),
        batter: None,
        flight: None,
        pitch: None,
    }
}

/// Spacing of the best-q scan along the barrel, m (the peak is refined by a parabola).
pub const BEST_Q_SCAN_STEP: f64 = 0.015;

/// A bat's best q in the field's convention at the reference swing, and where (m from the
/// knob): the wave model along the barrel from the CM to a ball's radius from the end,
/// every 1.5 cm, the peak refined by a parabola through its neighbours. The bat is free
/// and turns about its knob; `ball` and `hoop` are those of the bat's BBCOR shot.
pub fn best_q(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    (ball, hoop): (&BallSpec, Option<&HoopSpec>),
    map: &ScanMap,
) -> Result<(f64, f64), ModelError> {
    let spec = reference_swing(bat, bat_spec, numerics, ball, hoop);
    let p = bat.properties();
    let end = p.length - BBCOR_SCAN_END_MARGIN;
    let n = ((end - p.z_cm) / BEST_Q_SCAN_STEP).floor().max(0.0) as usize + 1;
    let z: Vec<f64> = (0..n)
        .map(|k| p.z_cm + k as f64 * BEST_Q_SCAN_STEP)
        .collect();
    let v_bat = REFERENCE_BAT_SPEED;
    let at = |zi: f64| {
        let mut spec = spec.clone();
        spec.impact.z = zi;
        let q = simulate(&spec, bat, None).map_or(f64::NAN, |o| {
            collision_efficiency_q(o.exit_speed_lab, REFERENCE_PITCH_SPEED, v_bat)
        });
        [q, f64::NAN]
    };
    let q: Vec<f64> = map(&z, &at).into_iter().map(|v| v[0]).collect();
    let (position, peak) = find_maximum(&z, &q).unwrap_or((f64::NAN, f64::NAN));
    Ok((peak, position))
}

/// The reference swing's collision on `bat` (impact position to be set).
fn reference_swing(
    bat: &PreparedBat,
    bat_spec: &BatSpec,
    numerics: &NumericsSpec,
    ball: &BallSpec,
    hoop: Option<&HoopSpec>,
) -> CollisionSpec {
    let p = bat.properties();
    let mut spec = CollisionSpec::base_case(p.z_cm);
    spec.model = ModelKind::Wave;
    spec.bat = BatSpec {
        grip: None,
        ..bat_spec.clone()
    };
    spec.ball = BallSpec {
        spin: 0.0,
        ..ball.clone()
    };
    spec.hoop = hoop.cloned();
    spec.impact = ImpactSpec {
        z: p.z_cm,
        offset: 0.0,
    };
    spec.numerics = numerics.clone();
    spec.swing = SwingSpec::default();
    spec.batter = Some(BatterSpec {
        pitch_speed: Some(REFERENCE_PITCH_SPEED),
        bat_speed: REFERENCE_BAT_SPEED,
        bat_speed_at: p.length - BAT_SPEED_FROM_END,
        // the bat's own moment of inertia about the knob: the reference swing as given
        reference_moi: p.moment_of_inertia + p.mass * p.z_cm * p.z_cm,
        exponent: 0.0,
        pivot: 0.0,
    });
    spec
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::{efficiency_from_bbcor, pivoted_effective_mass};

    #[test]
    fn bbcor_round_trip_and_conjugate_point() {
        let e = 0.42;
        for r in [0.1, 0.3, 1.0] {
            let bb = bbcor_from_efficiency(e, 0.145, 0.145 / r);
            assert!((efficiency_from_bbcor(bb, 0.145, 0.145 / r) - e).abs() < 1e-14);
        }
        // Free and pivoted effective masses agree at the pivot's centre of percussion.
        let (m, z_cm, i_cm) = (0.87, 0.56, 0.045);
        let z = centre_of_percussion(m, z_cm, i_cm, KNOB6);
        let i_p = moment_of_inertia_about(m, z_cm, i_cm, KNOB6);
        let a = pivoted_effective_mass(i_p, KNOB6, z);
        let b = free_effective_mass(m, z_cm, i_cm, z);
        assert!((a - b).abs() < 1e-12 * a, "{a} {b}");
    }

    #[test]
    fn barrel_node_is_the_largest() {
        assert_eq!(barrel_node(&[0.17, 0.68]), 0.68);
        assert_eq!(barrel_node(&[0.07, f64::NAN, 0.72, 0.39]), 0.72);
        assert!(barrel_node(&[]).is_nan());
    }
}
