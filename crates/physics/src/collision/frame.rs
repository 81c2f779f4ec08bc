//! The geometry of a swing: the bat's path, its axis and the pitch in the lab, and the
//! collision's plane across the bat (docs/physics.md, "The geometry of a swing").
//!
//! The lab frame is the flight's (Nathan's trajectory calculator): x horizontal toward the
//! first-base side, y toward centre field, z up. The bat's path at the impact point (the
//! direction its impact point moves) is û = (cos ψ sin α, cos ψ cos α, sin ψ), ψ the
//! attack angle and α the attack direction. The bat's axis from knob to barrel, a
//! right-handed batter's, is a = R_α (cos φ, −sin ψ sin φ, cos ψ sin φ), φ the bat's tilt
//! about its path (negative with the barrel down), R_α the turn by α about z; a ⊥ û. The
//! collision's plane across the bat is spanned by ŷ = −û (the direction the beam bends
//! in) and x̂ = (a × û)/|a × û| (up for a level bat); its spin axis is b̂ = ŷ × x̂ = −a.
//! A left-handed batter's launch is the mirror image (x → −x).
//!
//! The pitch moves along p̂ = (cos δ sin η, −cos δ cos η, −sin δ), δ its descent angle and
//! η its horizontal angle. "On plane" (the pitch arriving along −û) is δ = ψ, η = −α.

use crate::spec::{CollisionSpec, PitchSpec};

pub(crate) type Vec3 = [f64; 3];

pub(crate) fn scaled(v: Vec3, k: f64) -> Vec3 {
    [v[0] * k, v[1] * k, v[2] * k]
}

pub(crate) fn added(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v` turned by `angle` about the vertical, +y toward +x.
fn turned(v: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    [v[0] * c + v[1] * s, -v[0] * s + v[1] * c, v[2]]
}

/// The swing's directions in the lab: the bat's path û, the plane's x̂ and spin axis b̂.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingFrame {
    pub path: Vec3,
    pub across: Vec3,
    pub spin_axis: Vec3,
}

/// The pitch's lab velocity in the collision's frame, m/s: along ŷ (toward the bat), along
/// x̂ and along b̂ (the bat's axis, knob-ward).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PitchComponents {
    pub along: f64,
    pub across: f64,
    pub axial: f64,
}

impl SwingFrame {
    /// The frame of attack angle `attack`, attack direction `direction` and tilt `tilt`,
    /// rad.
    pub fn new(attack: f64, direction: f64, tilt: f64) -> SwingFrame {
        let (sa, ca) = attack.sin_cos();
        let (st, ct) = tilt.sin_cos();
        // a × û with a = (ct, −sa st, ca st), û = (0, ca, sa): a unit vector already
        let across = [-st, -ct * sa, ct * ca];
        SwingFrame {
            path: turned([0.0, ca, sa], direction),
            across: turned(across, direction),
            spin_axis: turned([-ct, sa * st, -ca * st], direction),
        }
    }

    /// The frame of a spec's swing.
    pub fn of(spec: &CollisionSpec) -> SwingFrame {
        let s = &spec.swing;
        SwingFrame::new(s.attack_angle, s.attack_direction, s.tilt)
    }

    /// A pitch's velocity in this frame.
    pub fn pitch(&self, pitch: &PitchSpec) -> PitchComponents {
        let (sd, cd) = pitch.descent_angle.sin_cos();
        let (sh, ch) = pitch.horizontal_angle.sin_cos();
        let v = scaled([cd * sh, -cd * ch, -sd], pitch.speed);
        PitchComponents {
            along: -dot(v, self.path),
            across: dot(v, self.across),
            axial: dot(v, self.spin_axis),
        }
    }

    /// The ball's lab velocity after the collision: the bat's CM moves at `cm_speed` along
    /// the path; `(along, across, axial)` is the ball's velocity in the bat-CM frame along
    /// ŷ = −û, x̂ and b̂.
    pub fn velocity(&self, cm_speed: f64, (along, across, axial): (f64, f64, f64)) -> Vec3 {
        added(
            added(
                scaled(self.path, cm_speed - along),
                scaled(self.across, across),
            ),
            scaled(self.spin_axis, axial),
        )
    }
}

/// The pitch of `spec` in its swing's frame: `None` without a `pitch` block (on plane).
pub fn pitch_components(spec: &CollisionSpec) -> Option<PitchComponents> {
    spec.pitch.as_ref().map(|p| SwingFrame::of(spec).pitch(p))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-15)
    }

    #[test]
    fn the_frame_is_right_handed_and_orthonormal_at_any_angles() {
        for &(psi, alpha, phi) in &[(0.0, 0.0, 0.0), (0.3, -0.2, -0.5), (-0.1, 0.4, 0.2)] {
            let f = SwingFrame::new(psi, alpha, phi);
            let y = scaled(f.path, -1.0);
            for (u, v) in [
                (f.path, f.across),
                (f.path, f.spin_axis),
                (f.across, f.spin_axis),
            ] {
                assert!(dot(u, v).abs() < 1e-15);
            }
            for u in [f.path, f.across, f.spin_axis] {
                assert!((dot(u, u) - 1.0).abs() < 1e-15);
            }
            // b̂ = ŷ × x̂
            let x = f.across;
            let cross = [
                y[1] * x[2] - y[2] * x[1],
                y[2] * x[0] - y[0] * x[2],
                y[0] * x[1] - y[1] * x[0],
            ];
            assert!(close(cross, f.spin_axis));
        }
    }

    #[test]
    fn an_on_plane_pitch_has_no_component_but_along_the_path() {
        let (psi, alpha, phi) = (0.2, -0.15, -0.6);
        let f = SwingFrame::new(psi, alpha, phi);
        let pitch = PitchSpec {
            speed: 40.0,
            descent_angle: psi,
            horizontal_angle: -alpha,
        };
        let c = f.pitch(&pitch);
        assert!((c.along - 40.0).abs() < 1e-12);
        assert!(c.across.abs() < 1e-12 && c.axial.abs() < 1e-12);
    }

    #[test]
    fn a_pitch_falling_onto_a_level_swing_moves_down_across_it() {
        // level bat, level swing, a pitch falling at δ: the descent is all across the
        // plane (−x̂, x̂ being up), none along the bat
        let f = SwingFrame::new(0.0, 0.0, 0.0);
        let d: f64 = 0.1;
        let c = f.pitch(&PitchSpec {
            speed: 40.0,
            descent_angle: d,
            horizontal_angle: 0.0,
        });
        assert!((c.along - 40.0 * d.cos()).abs() < 1e-12);
        assert!((c.across + 40.0 * d.sin()).abs() < 1e-12);
        assert!(c.axial.abs() < 1e-15);
        // a pitch moving toward first base slides along a level bat's axis toward the
        // barrel (a = +x), so along b̂ = −a it is negative
        let c = f.pitch(&PitchSpec {
            speed: 40.0,
            descent_angle: 0.0,
            horizontal_angle: 0.05,
        });
        assert!((c.axial + 40.0 * 0.05f64.sin()).abs() < 1e-12);
    }
}
