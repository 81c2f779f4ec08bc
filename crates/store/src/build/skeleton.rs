//! The file's skeleton: groups, coordinates, dimension scales and empty variables, begun
//! from the study's shape alone and completed with the root attributes, `/history` and `/bat`.

use super::attrs::root_attrs;
use super::bat::write_bats;
use super::errors::{create_errors, Errors};
use super::grid::{summary_chunk, without};
use super::history_vars::{create_history, HistoryVars};
use super::shapes::BatShapes;
use super::vars::{new_var, study_dims};
use crate::dimscale::{attr_str, attr_vec, Attacher};
use crate::error::{H5Ctx, StoreError};
use crate::layout as l;
use crate::options::RunMeta;
use crate::results::{CoordValues, Dim, ResultShape, StudyInfo};
use hdf5::Dataset;
use std::path::{Path, PathBuf};

/// The results file with everything that does not depend on the points' results: root
/// attributes, groups, coordinates and dimension scales, every variable (empty), `/bat`. The
/// store creates it in two steps off the critical path, so that finishing a run only fills
/// in the data (most of a small study's HDF5 time is this fixed part): the
/// shape's part ([`begin_skeleton`]) while the bats are prepared, the rest
/// ([`complete_skeleton`]) on the writer thread while the workers compute.
pub struct Skeleton {
    pub(super) f: hdf5::File,
    pub(super) out: PathBuf,
    /// The shape it was begun for, and whether [`complete_skeleton`] has run.
    shape: ResultShape,
    complete: bool,
    pub(super) floats: Vec<Dataset>,
    pub(super) recontact: Dataset,
    pub(super) status: Dataset,
    pub(super) point_id: Dataset,
    pub(super) bat_index: Dataset,
    /// `impact_z`'s position among the dims, the sweet-spot variables and the z values.
    pub(super) sweet: Option<(usize, Vec<Dataset>, Vec<f64>)>,
    pub(super) errors: Errors,
    /// Stored history variables: index into [`l::HISTORY_VARS`], dataset, full shape.
    pub(super) history: HistoryVars,
    /// The bats' mode shapes, with the displacement's modal form.
    pub(super) shapes: Option<BatShapes>,
}

impl Skeleton {
    /// Send what the file's driver has gathered to the OS, waiting for it (`store::direct`).
    pub fn write_gathered(&self) -> hdf5::Result<()> {
        crate::direct::write_gathered(&self.f)
    }

    /// An offset below which every byte written to the file is in the OS (`store::direct`).
    pub fn in_os(&self) -> hdf5::Result<u64> {
        crate::direct::in_os(&self.f)
    }

    /// The file's end of allocation: every byte written so far lies below it.
    pub fn end_of_allocation(&self) -> Option<u64> {
        crate::chunks::end_of_allocation(self.f.id())
    }

    /// The file alone, every dataset the skeleton held closed. What is read back from the
    /// file being written must be read through datasets opened afresh: HDF5 1.10.8 reads a
    /// chunk written with `H5Dwrite_chunk` into a dataset of one chunk (its "single chunk"
    /// index, which the 1.10 object formats give a small study's `/summary`) as the chunk's
    /// filtered bytes, not its values, as long as the dataset stays open (tested in
    /// `tests/uncertainty_stored.rs`; on reopening it reads the values).
    pub fn into_file(self) -> hdf5::File {
        self.f
    }
}

/// Create `out` with everything but the results (see [`Skeleton`]).
pub fn create_skeleton(
    info: &StudyInfo,
    meta: &RunMeta,
    out: &Path,
) -> Result<Skeleton, StoreError> {
    let mut sk = begin_skeleton(&info.shape, out)?;
    complete_skeleton(&mut sk, info, meta)?;
    Ok(sk)
}

/// The part of the skeleton that depends on the study's shape alone: `/summary`,
/// `/sweet_spot` and `/errors`, with their coordinates and empty variables. It can be made
/// before the bats are prepared (while a one-bat study prepares its bat, a core is idle);
/// [`complete_skeleton`] adds the rest.
pub fn begin_skeleton(study_shape: &ResultShape, out: &Path) -> Result<Skeleton, StoreError> {
    // No chunk cache: every chunk is written whole and already filtered (H5Dwrite_chunk),
    // never read back, and HDF5 allocates and zeroes each dataset's cache when it is created
    // (those caches would be a third of a 45-point curve's page faults, 67 datasets).
    // HDF5 1.10's object formats (readable by HDF5 1.10 and later): a chunked dataset of
    // fixed size indexes its chunks in a fixed array, where 1.8's B-tree made every chunk
    // written an insertion (with 1.10's, a modal history study runs 4.5 % faster, the writer
    // thread a tenth lighter; a 45-point summary study unchanged).
    // Every allocation at the end of the file, none from freed space or from blocks set
    // aside for small objects (`FileSpaceStrategy::None`): a history chunk written alone then
    // lies where the file ended before it, which the journal records instead of its bytes
    // (`store::by_reference`). The results are written once and never freed, so
    // the file is as large as with HDF5's default (the modal bench study: 29.54 MB either way).
    // Whatever is at `out` (a stale `.partial`, or a symbolic link planted there) is removed,
    // not followed, and the file is created exclusively (O_EXCL: no link is followed).
    crate::paths::remove_if_exists(out)?;
    // Written around the page cache where it can be (`store::direct`).
    let fapl = hdf5::plist::FileAccess::build()
        .chunk_cache(1, 0, 1.0)
        .libver_v110()
        .finish()
        .ctx(out, "make the results file's access properties")?;
    let fcpl = hdf5::plist::FileCreate::build()
        .file_space_strategy(hdf5::file::FileSpaceStrategy::None)
        .finish()
        .ctx(out, "make the results file's creation properties")?;
    let f = crate::direct::create_excl(out, &fapl, &fcpl).ctx(out, "create the results file")?;
    let dims = &study_shape.dims;
    let chunk = summary_chunk(dims);
    let att = Attacher::default();
    let summary = summary_group(&f, dims, &chunk, &att, out)?;
    let sweet = match dims.iter().position(|d| d.name == l::IMPACT_Z) {
        Some(iz) => Some(sweet_spot_group(&f, dims, iz, &chunk, &att, out)?),
        None => None,
    };
    let errors = create_errors(&f, &att, out)?;
    att.write().ctx(out, "attach the dimension scales")?;
    let SummaryVars {
        floats,
        recontact,
        status,
        point_id,
        bat_index,
    } = summary;
    Ok(Skeleton {
        f,
        out: out.to_path_buf(),
        shape: study_shape.clone(),
        complete: false,
        floats,
        recontact,
        status,
        point_id,
        bat_index,
        sweet,
        errors,
        history: Vec::new(),
        shapes: None,
    })
}

/// The variables of `/summary`.
struct SummaryVars {
    floats: Vec<Dataset>,
    recontact: Dataset,
    status: Dataset,
    point_id: Dataset,
    bat_index: Dataset,
}

/// `/summary`: the study's coordinates and one empty variable per stored quantity.
fn summary_group(
    f: &hdf5::File,
    dims: &[Dim],
    chunk: &[usize],
    att: &Attacher,
    out: &Path,
) -> Result<SummaryVars, StoreError> {
    let shape: Vec<usize> = dims.iter().map(|d| d.size).collect();
    let g = f
        .create_group(l::GROUP_SUMMARY)
        .ctx(out, "create group summary")?;
    let (scales, aux) = study_dims(&g, dims, att, out)?;
    let sref: Vec<&Dataset> = scales.iter().collect();
    let links = (&sref[..], &aux[..], att);
    let sc = (&shape[..], chunk);
    let mut floats = Vec::new();
    for def in &l::SUMMARY_FLOATS {
        floats.push(new_var(&g, def, sc, f64::NAN, links, out)?);
    }
    let recontact = new_var(&g, &l::RECONTACT, sc, -1i8, links, out)?;
    let status = new_var(&g, &l::STATUS, sc, l::STATUS_NOT_COMPUTED, links, out)?;
    attr_vec(&status, "flag_values", &[-1i8, 0, 1]).ctx(out, "describe status")?;
    attr_str(&status, "flag_meanings", "not_computed ok failed").ctx(out, "describe status")?;
    Ok(SummaryVars {
        floats,
        recontact,
        status,
        point_id: new_var(&g, &l::POINT_ID, sc, 0u64, links, out)?,
        bat_index: new_var(&g, &l::BAT_INDEX, sc, -1i32, links, out)?,
    })
}

/// `/sweet_spot`: the summary's coordinates without `impact_z` (dimension `iz`), the sweet
/// spots' variables, and the impact positions they are found along.
fn sweet_spot_group(
    f: &hdf5::File,
    dims: &[Dim],
    iz: usize,
    chunk: &[usize],
    att: &Attacher,
    out: &Path,
) -> Result<(usize, Vec<Dataset>, Vec<f64>), StoreError> {
    let z = match dims[iz]
        .coords
        .iter()
        .find(|c| c.name == l::IMPACT_Z)
        .map(|c| &c.values)
    {
        Some(CoordValues::Numbers(z)) => z.clone(),
        _ => {
            return Err(StoreError::BadRecord {
                path: out.to_path_buf(),
                what: "dim impact_z has no numeric coordinate impact_z".into(),
            })
        }
    };
    let sg = f
        .create_group(l::GROUP_SWEET_SPOT)
        .ctx(out, "create group sweet_spot")?;
    let rest: Vec<Dim> = dims
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != iz)
        .map(|(_, d)| d.clone())
        .collect();
    let (ss, saux) = study_dims(&sg, &rest, att, out)?;
    let ssref: Vec<&Dataset> = ss.iter().collect();
    let rshape: Vec<usize> = rest.iter().map(|d| d.size).collect();
    let rchunk = without(chunk, iz);
    let links = (&ssref[..], &saux[..], att);
    let sc = (&rshape[..], &rchunk[..]);
    let mut vars = Vec::new();
    for def in l::SWEET_FLOATS {
        vars.push(new_var(&sg, def, sc, f64::NAN, links, out)?);
    }
    let edge = new_var(&sg, &l::SWEET_AT_EDGE, sc, -1i8, links, out)?;
    attr_vec(&edge, "flag_values", &[-1i8, 0, 1]).ctx(out, "describe at_edge")?;
    attr_str(&edge, "flag_meanings", "no_curve inside at_edge").ctx(out, "describe at_edge")?;
    vars.push(edge);
    Ok((iz, vars, z))
}

/// Add what depends on the bats and the run to a begun skeleton: the root attributes,
/// `/history` and `/bat`; then hand the metadata to the OS.
pub fn complete_skeleton(
    sk: &mut Skeleton,
    info: &StudyInfo,
    meta: &RunMeta,
) -> Result<(), StoreError> {
    let out = sk.out.as_path();
    if sk.complete {
        return Ok(());
    }
    if !sk.shape.identical(&info.shape) {
        return Err(StoreError::BegunMismatch {
            path: out.to_path_buf(),
            what: "it was begun for another study shape".into(),
        });
    }
    let f = &sk.f;
    root_attrs(f, info, meta, out)?;
    let att = Attacher::default();
    if let Some(h) = &info.history {
        sk.history = create_history(f, h, info, &att, out)?;
    }
    sk.shapes = write_bats(f, info, &att, out)?;
    att.write().ctx(out, "attach the dimension scales")?;
    // hand the metadata to the OS now, not on the critical path at the end
    f.flush().ctx(out, "flush the results file")?;
    sk.complete = true;
    Ok(())
}
