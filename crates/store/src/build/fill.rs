//! Filling a skeleton with the journal's records: the histories the run has not placed yet,
//! then window by window the summary and sweet spots, `/errors` and the counts; memory
//! bounded by the build's budget.

use super::attrs::final_attrs;
use super::errors::write_errors;
use super::grid::{plan_windows, summary_chunk, BlockGrid};
use super::history::{write_histories, HistoryTail};
use super::pieces::{block_pieces, compress_and_write, Piece};
use super::skeleton::Skeleton;
use super::spill::{Source, Spill};
use super::window::{Gathered, Tally, Window};
use crate::error::{H5Ctx, StoreError};
use crate::journal::{RecordReader, Scan};
use crate::options::Summary;
use crate::results::StudyInfo;
use hdf5::Dataset;
use rayon::prelude::*;
use std::path::Path;

/// What the session kept while the run went on.
pub struct FromRun {
    /// The summary gathered as records arrived (a one-window study's own journal).
    pub gathered: Option<Gathered>,
    /// The histories not yet placed in the file.
    pub histories: HistoryTail,
}

/// The window of blocks `b0..b1`, its records read from `source`.
fn read_window(
    mut source: Source,
    blocks: &BlockGrid,
    (b0, b1): (usize, usize),
    tally: &mut Tally,
) -> Result<Window, StoreError> {
    let mut w = Window::of_blocks(blocks, b0, b1);
    while let Some(rec) = source.next()? {
        w.put(&rec, blocks, b0, b1, tally);
    }
    Ok(w)
}

/// Fill a skeleton with the journal's records, write the counts and `created`, and close
/// the file. Memory: `memory` bytes of summary values at most (a study larger than that is
/// built window by window, its journal first split into one spill file per window), one
/// history, the failed points' messages; nothing else grows with the study.
pub fn fill(
    mut sk: Skeleton,
    journal: &Path,
    scan: &Scan,
    info: &StudyInfo,
    created: &str,
    memory: usize,
    run: FromRun,
) -> Result<Summary, StoreError> {
    let FromRun {
        mut gathered,
        histories,
    } = run;
    let out_path = sk.out.clone();
    let out = out_path.as_path();
    let n_points = info.shape.n_points();
    let shape: Vec<usize> = info.shape.dims.iter().map(|d| d.size).collect();
    let chunk = summary_chunk(&info.shape.dims);
    // ---- /history first: its chunks follow those placed while the run went on, so that the
    // file's layout is the same however far the placer got
    if info.history.is_some() {
        write_histories(&mut sk, info, journal, scan, out, histories)?;
    }

    let mut tally = Tally::default();
    let blocks = BlockGrid::new(&shape, &chunk);
    let windows = plan_windows(&blocks, memory);
    // the datasets a block writes to, in the order of [`block_pieces`]
    let mut targets: Vec<&Dataset> = sk.floats.iter().collect();
    targets.extend([&sk.recontact, &sk.status, &sk.point_id, &sk.bat_index]);
    if let Some((_, vars, _)) = &sk.sweet {
        targets.extend(vars.iter());
    }
    // One window: read the journal directly. Several: route the records to one spill file
    // per window in a single pass, so that the journal is read once, not once per window.
    let spill = if windows.len() > 1 {
        Some(Spill::split(journal, scan, out, &blocks, &windows)?)
    } else {
        None
    };
    for (k, &(b0, b1)) in windows.iter().enumerate() {
        let w = match gathered.take() {
            // one window, gathered while the run wrote its journal: nothing to read back
            Some(g) if windows.len() == 1 => {
                tally.add(g.tally);
                g.window
            }
            _ => {
                let source = match &spill {
                    Some(sp) => Source::Spill(sp.reader(k)?),
                    None => Source::Journal(RecordReader::open(journal, scan)?),
                };
                read_window(source, &blocks, (b0, b1), &mut tally)?
            }
        };
        // a small study is one block: parallel over (block, variable), not blocks alone
        let pieces: Vec<Piece> = (b0..b1)
            .into_par_iter()
            .flat_map_iter(|b| block_pieces(&w, b - b0, &blocks, &chunk, b, sk.sweet.as_ref()))
            .collect();
        compress_and_write(pieces, &targets, out)?;
    }
    drop(spill);

    let Tally {
        n_done,
        n_failed,
        errors,
    } = tally;
    // ---- /errors: made empty with the skeleton; grown only when points failed
    write_errors(&sk.errors, errors, out)?;
    // ---- /uncertainty: a `sample` dimension's statistics, read back from the data above
    // through datasets opened afresh (`Skeleton::into_file`)
    let f = sk.into_file();
    if let Some(sample) = &info.sample_dim {
        super::uncertainty::write_uncertainty(&f, info, sample, out)?;
    }

    final_attrs(&f, created, (n_done, n_failed, n_points), out)?;
    f.flush().ctx(out, "flush the results file")?;
    drop(f);
    Ok(Summary {
        n_points,
        n_done,
        n_failed,
    })
}
