//! `/bat/shape_z` and `/bat/mode_shape`, for the displacement's modal form: every
//! bat's shape points, written with `/bat`, and its mode shapes, a block of modes at a time,
//! written just before the first stored history that steps them. Histories are written in
//! flat-index order (during the run and at the finish), so the blocks are too, whatever the
//! threads; the modes of a bat that no stored history steps are never written (they read 0).

use crate::chunks;
use crate::dimscale::{self as h5u, describe, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout as l;
use crate::modal::{padded_points, shape_block, ModalExtents};
use crate::results::StudyInfo;
use batstudy_physics::outcome::HistoryRequest;
use hdf5::{Dataset, Group};
use std::path::Path;

/// `/bat/mode_shape` being written: the blocks of modes written so far, per bat.
pub struct BatShapes {
    ds: Dataset,
    ext: ModalExtents,
    written: Vec<usize>,
    level: u8,
}

/// `bat_mode`, `shape_point`, `shape_z` and the (empty) `mode_shape` in `/bat` (`g`, whose
/// dimension scale `bat` is given).
pub(super) fn create_shapes(
    g: &Group,
    bat: &Dataset,
    info: &StudyInfo,
    h: &HistoryRequest,
    att: &Attacher,
    out: &Path,
) -> Result<BatShapes, StoreError> {
    let e = |what: &str| format!("write bat {what}");
    let ext = ModalExtents::of(info);
    let index = |n: usize| (0..n as i64).collect::<Vec<i64>>();
    let modes = h5u::scale_coord(g, l::BAT_MODE_DIM.name, &index(ext.modes), &l::BAT_MODE_DIM)
        .ctx(out, &e("bat_mode"))?;
    let points = h5u::scale_coord(
        g,
        l::SHAPE_POINT_DIM.name,
        &index(ext.points),
        &l::SHAPE_POINT_DIM,
    )
    .ctx(out, &e("shape_point"))?;
    let z: Vec<f64> = info
        .bats
        .iter()
        .flat_map(|b| padded_points(b.shapes.as_ref().map_or(&[], |s| &s.z[..]), ext.points))
        .collect();
    let nb = info.bats.len();
    let shape_z = g
        .new_dataset::<f64>()
        .shape([nb, ext.points])
        .create(l::BAT_SHAPE_Z.name)
        .ctx(out, &e("shape_z"))?;
    h5u::write_small(&shape_z, &z).ctx(out, &e("shape_z"))?;
    describe(&shape_z, &l::BAT_SHAPE_Z).ctx(out, &e("shape_z"))?;
    att.add(&shape_z, &[bat, &points]);
    let level = l::history_deflate_level(h);
    let dims = [nb, ext.modes, ext.points];
    let chunk = [1, ext.block, ext.points.max(1)];
    let ds = h5u::create_var_level(g, l::BAT_MODE_SHAPE.name, &dims, &chunk, 0.0f64, level)
        .ctx(out, &e("mode_shape"))?;
    describe(&ds, &l::BAT_MODE_SHAPE).ctx(out, &e("mode_shape"))?;
    att.add(&ds, &[bat, &modes, &points]);
    Ok(BatShapes {
        ds,
        ext,
        written: vec![0; nb],
        level,
    })
}

impl BatShapes {
    /// Bat `bat`'s first `blocks` blocks of mode shapes, those not yet in the file.
    pub fn ensure(
        &mut self,
        info: &StudyInfo,
        bat: usize,
        blocks: usize,
        out: &Path,
    ) -> Result<(), StoreError> {
        let Some(source) = info.bats.get(bat).and_then(|b| b.shapes.as_ref()) else {
            return Ok(());
        };
        if self.ext.modes == 0 || self.ext.points == 0 {
            return Ok(());
        }
        while self.written[bat] < blocks.min(source.modes.div_ceil(self.ext.block)) {
            let b = self.written[bat];
            let values = shape_block(source, b, &self.ext);
            let bytes = chunks::filtered_whole(&values, self.level);
            chunks::write_chunk(&self.ds, &[bat, b * self.ext.block, 0], &bytes)
                .ctx(out, "write bat mode_shape")?;
            self.written[bat] += 1;
        }
        Ok(())
    }
}
