//! The sweet spots of a block's curves along `impact_z` (the `/sweet_spot` variables): the
//! one place the store calls the physics' sweet-spot finders.

use crate::layout as l;
use batstudy_physics::measures::sweet::{find_sweet_spot, SweetSpot};
use batstudy_physics::measures::sweet_defs::vibration_sweet_spot;

/// The sweet-spot variables along `impact_z` for every curve inside one block (`fv` the
/// block's summary floats).
pub(super) fn block_sweet_spots(
    fv: &[&[f64]],
    count: &[usize],
    iz: usize,
    z: &[f64],
) -> ([Vec<f64>; l::N_SWEET_FLOATS], Vec<i8>) {
    let m: usize = count.iter().product();
    let nz = count[iz];
    let stride: usize = count[iz + 1..].iter().product();
    let outer = m / nz;
    // A study may list impact_z in any order (a descending range is documented, and read
    // as it is listed would give no sweet spot at all): the finders read each curve in
    // ascending z.
    let mut order: Vec<usize> = (0..nz).collect();
    order.sort_by(|&a, &b| z[a].total_cmp(&z[b]));
    let z: Vec<f64> = order.iter().map(|&q| z[q]).collect();
    let curve = |slot: usize| -> ([f64; l::N_SWEET_FLOATS], i8) {
        let (hi, lo) = (slot / stride, slot % stride);
        let base = hi * nz * stride + lo;
        let along =
            |k: usize| -> Vec<f64> { order.iter().map(|&q| fv[k][base + q * stride]).collect() };
        let s = maximum_along(&z, &along(0));
        let carry = maximum_along(&z, &along(l::CARRY_INDEX));
        let lab = maximum_along(&z, &along(l::EXIT_SPEED_LAB_INDEX));
        let v = vibration_sweet_spot(
            &z,
            &along(l::GRIP_VIBRATION_INDEX),
            &along(l::VIBRATION_ENERGY_INDEX),
        );
        let at_edge = s.map_or(-1, |s| s.at_edge as i8);
        (
            [
                s.map_or(f64::NAN, |s| s.position),
                s.map_or(f64::NAN, |s| s.exit_speed),
                s.map_or(f64::NAN, |s| s.width),
                v.min_vibration_position,
                v.min_vibration_amplitude,
                v.min_vibration_energy_position,
                carry.map_or(f64::NAN, |s| s.position),
                carry.map_or(f64::NAN, |s| s.exit_speed),
                lab.map_or(f64::NAN, |s| s.exit_speed),
            ],
            at_edge,
        )
    };
    let rows: Vec<([f64; l::N_SWEET_FLOATS], i8)> = (0..outer).map(curve).collect();
    (
        std::array::from_fn(|k| rows.iter().map(|r| r.0[k]).collect()),
        rows.iter().map(|r| r.1).collect(),
    )
}

/// The maximum of a curve over its finite points (`find_sweet_spot`: parabola-refined).
fn maximum_along(z: &[f64], values: &[f64]) -> Option<SweetSpot> {
    let (zz, vv): (Vec<f64>, Vec<f64>) = z
        .iter()
        .zip(values)
        .filter(|(_, v)| v.is_finite())
        .map(|(&z, &v)| (z, v))
        .unzip();
    find_sweet_spot(&zz, &vv)
}
