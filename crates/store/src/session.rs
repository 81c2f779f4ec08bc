//! An open output: [`open`] (a new run, or the continuation of an interrupted one) and the
//! [`Session`] the runner's writer thread owns, which appends finished points to the journal
//! and, at [`Session::finish`], builds the final file from it and renames it into place.
//! [`begin`] makes the file's skeleton ahead of the session.

use super::build;
use super::by_reference::{self, Recovered};
use super::encode::{EncodedRecord, RecordEncoder};
use super::error::{H5Ctx, StoreError};
use super::gather::GroupGatherer;
use super::header::JournalHeader;
use super::journal::{self, JournalWriter};
use super::options::{iso8601_now, RunMeta, StoreOptions, Summary};
use super::paths::{
    journal_path, partial_path, previous_partial_path, remove_if_exists, set_aside_partial,
};
use super::placer::{HistoryPlacer, Place};
use super::read;
use super::writeback::Writeback;
use crate::pointset::PointSet;
use crate::results::{PointRecord, ResultShape, StudyInfo};
use std::collections::{BTreeSet, VecDeque};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// An open output: owned by the runner's single writer thread.
pub struct Session {
    path: PathBuf,
    journal_path: PathBuf,
    info: StudyInfo,
    meta: RunMeta,
    journal: Option<JournalWriter>,
    /// The points stored so far: one bit each, the session's only per-point state.
    done: PointSet,
    /// Memory budget of the final file's build (bytes of summary values held at once).
    build_memory: usize,
    /// `OUT.h5.partial` with everything but the results: begun while the bats are prepared
    /// ([`begin`]) or with the first record, completed with the first record.
    skeleton: Option<build::Skeleton>,
    /// The summary gathered as records arrive, when the study fits one build window and
    /// the journal is this session's own (not resumed).
    gathered: Option<build::Gathered>,
    /// Encodes the points handed to [`Session::write`]; the runner's workers use clones.
    encoder: RecordEncoder,
    /// The points handed to [`Session::write`] whose group is not whole yet (when points
    /// share history chunks).
    gatherer: Option<GroupGatherer>,
    /// Writes the histories into the final file as the run goes on, in flat-index order
    /// (a fresh journal of a study with histories; `store::placer`).
    placer: Option<HistoryPlacer>,
    /// Where the histories the run has not placed are, once the placer gave up.
    history_tail: Option<build::HistoryTail>,
    /// Starts the final file's writeback as the placer writes it (`store::writeback`).
    writeback: Writeback,
    /// The journal names history chunks in the final file (`store::by_reference`): the file
    /// is kept if the session ends unfinished, for the resume.
    names_file: bool,
    /// It has named some since the journal was last made durable: the file is made durable
    /// first.
    names_unsynced: bool,
    /// Points stored whose records the placer holds and the journal does not have yet
    /// (journalled at the next flush, or once placed).
    unjournalled: BTreeSet<usize>,
    /// Records of placed points, in the order placed, each with an offset of the final file
    /// its chunks lie below, waiting for those chunks to reach the OS (the file's driver
    /// gathers them and writes them around the page cache, `store::direct`).
    placed: VecDeque<(u64, Vec<u8>)>,
    flush_interval: Duration,
    sync_interval: Duration,
    last_flush: Instant,
    last_sync: Instant,
    /// Records recovered on resume (journal records; a dropped torn tail is not counted).
    pub resumed: usize,
    /// Bytes of torn or corrupt journal tail dropped on resume.
    pub dropped_bytes: u64,
    /// On resume: the records whose history chunks were read back from the interrupted
    /// run's file, and those dropped because a chunk was not there intact.
    pub recovered: Recovered,
}

fn check_info(info: &StudyInfo, path: &Path) -> Result<(), StoreError> {
    let bad = |what: String| {
        Err(StoreError::BadRecord {
            path: path.to_path_buf(),
            what,
        })
    };
    for d in &info.shape.dims {
        for c in &d.coords {
            if c.values.len() != d.size {
                return bad(format!(
                    "coordinate {} has {} values but dim {} has size {}",
                    c.name,
                    c.values.len(),
                    d.name,
                    d.size
                ));
            }
        }
    }
    Ok(())
}

/// The final file of output `path` (`OUT.h5.partial`), begun from the study's shape alone
/// by [`begin`] before the bats are known; [`open_begun`] takes it over. Dropped unused, it
/// removes its file.
pub struct BegunFile {
    path: PathBuf,
    skeleton: Option<build::Skeleton>,
}

impl Drop for BegunFile {
    fn drop(&mut self) {
        if self.skeleton.take().is_some() {
            let _ = std::fs::remove_file(partial_path(&self.path));
        }
    }
}

/// Begin the final file of output `path` for a study of this shape: the groups, coordinates
/// and empty variables that do not depend on the bats. A run does this while it prepares
/// its bats, when a one-bat study leaves cores idle (the file's fixed cost, off the critical
/// path). Replaces a stale `OUT.h5.partial`; touches nothing else.
pub fn begin(path: &Path, shape: &ResultShape) -> Result<BegunFile, StoreError> {
    set_aside_partial(path)?;
    let partial = partial_path(path);
    let skeleton = build::begin_skeleton(shape, &partial)?;
    Ok(BegunFile {
        path: path.to_path_buf(),
        skeleton: Some(skeleton),
    })
}

/// Whether `--resume` of output `path` can go on for the study of this sha256: its journal
/// (or, without one, its finished file) is readable and of the same study and layout. A
/// run checks this before it touches anything (a refused resume must not have replaced
/// `OUT.h5.partial`). Nothing to resume is not an error.
pub fn check_resumable(path: &Path, study_sha256: &str) -> Result<(), StoreError> {
    let jpath = journal_path(path);
    let journal = jpath.exists() && !journal::ends_in_header(&jpath)?;
    let (found, from) = if journal {
        (journal::header(&jpath)?, jpath)
    } else if path.exists() {
        (read::file_info(path)?.header, path.to_path_buf())
    } else {
        return Ok(());
    };
    let mut want = found.clone();
    want.layout_version = super::layout::LAYOUT_VERSION;
    want.study_sha256 = study_sha256.to_string();
    match found.mismatch(&want, &from) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Open the output `path` for a study: a new run, or (`opts.resume`) the continuation of an
/// interrupted one. Never overwrites an existing output unless `opts.force`.
pub fn open(path: &Path, info: &StudyInfo, opts: &StoreOptions) -> Result<Session, StoreError> {
    open_begun(path, info, opts, None)
}

/// [`open`], taking over the final file [`begin`] made for the same output and shape.
pub fn open_begun(
    path: &Path,
    info: &StudyInfo,
    opts: &StoreOptions,
    begun: Option<BegunFile>,
) -> Result<Session, StoreError> {
    check_info(info, path)?;
    let skeleton = take_begun(path, begun)?;
    build::remove_stale_spills(&partial_path(path));
    let mut s = Session::new(path, info, opts, skeleton);
    let jpath = journal_path(path);
    let want = JournalHeader::of(info);
    if opts.resume && jpath.exists() && journal::ends_in_header(&jpath)? {
        // killed while its journal was being created: nothing was recorded, start over
        remove_if_exists(&jpath)?;
    }
    if opts.resume && jpath.exists() {
        s.resume_journal(&want)?;
        return Ok(s);
    }
    // no journal names anything in an interrupted run's file any more
    remove_if_exists(&previous_partial_path(path))?;
    if opts.resume && path.exists() {
        s.resume_finished_file(&want)?;
        return Ok(s);
    }
    if !opts.resume && (path.exists() || jpath.exists()) {
        if !opts.force {
            return Err(StoreError::Exists {
                path: path.to_path_buf(),
            });
        }
        remove_if_exists(path)?;
        remove_if_exists(&jpath)?;
    }
    s.journal = Some(JournalWriter::create(&jpath, &want)?);
    // a fresh journal: this session sees every record it will store
    s.gathered = build::Gathered::new(info, opts.build_memory);
    if info.history.is_some() {
        let n_points = info.shape.n_points();
        let (start, end) = opts.run_meta.shard_range.unwrap_or((0, n_points));
        s.placer = Some(HistoryPlacer::new(start, end, opts.history_hold));
    }
    Ok(s)
}

/// The skeleton `begin` made for this output (or none: a stale `.partial` is removed).
fn take_begun(
    path: &Path,
    begun: Option<BegunFile>,
) -> Result<Option<build::Skeleton>, StoreError> {
    match begun {
        Some(mut b) => {
            if b.path != path {
                return Err(StoreError::BegunMismatch {
                    path: path.to_path_buf(),
                    what: format!("it was begun for {}", b.path.display()),
                });
            }
            Ok(b.skeleton.take())
        }
        None => {
            set_aside_partial(path)?;
            Ok(None)
        }
    }
}

impl Session {
    /// A session of output `path` with nothing done yet and no journal open.
    fn new(
        path: &Path,
        info: &StudyInfo,
        opts: &StoreOptions,
        skeleton: Option<build::Skeleton>,
    ) -> Session {
        Session {
            path: path.to_path_buf(),
            journal_path: journal_path(path),
            info: info.clone(),
            meta: opts.run_meta.clone(),
            journal: None,
            done: PointSet::new(info.shape.n_points()),
            build_memory: opts.build_memory,
            skeleton,
            gathered: None,
            encoder: RecordEncoder::new(path, info),
            gatherer: {
                let groups = super::layout::history_groups(info);
                (groups.size() > 1).then(|| GroupGatherer::new(groups))
            },
            placer: None,
            history_tail: None,
            writeback: Writeback::new(&partial_path(path)),
            names_file: false,
            names_unsynced: false,
            unjournalled: BTreeSet::new(),
            placed: VecDeque::new(),
            flush_interval: opts.flush_interval,
            sync_interval: opts.sync_interval,
            last_flush: Instant::now(),
            last_sync: Instant::now(),
            resumed: 0,
            dropped_bytes: 0,
            recovered: Recovered::default(),
        }
    }

    /// Continue an interrupted run: the journal's valid records are done, its torn tail is
    /// cut, and new records are appended after them.
    fn resume_journal(&mut self, want: &JournalHeader) -> Result<(), StoreError> {
        let jpath = self.journal_path.clone();
        let (mut scan, names_file) = self.scan_journal()?;
        if let Some(e) = scan.header.mismatch(want, &jpath) {
            return Err(e);
        }
        self.dropped_bytes = scan.dropped_bytes;
        let prev = previous_partial_path(&self.path);
        if names_file {
            // the chunks the interrupted run wrote into its file, back into the journal
            self.recovered = by_reference::bring_back(&jpath, &scan, &prev)?;
            (scan, _) = self.scan_journal()?;
        }
        remove_if_exists(&prev)?;
        self.resumed = self.done.count();
        self.journal = Some(JournalWriter::append_to(&jpath, &scan)?);
        Ok(())
    }

    /// Scan the journal: its valid records are the points done; and whether some name
    /// history chunks in the interrupted run's file.
    fn scan_journal(&mut self) -> Result<(journal::Scan, bool), StoreError> {
        let n_points = self.info.shape.n_points();
        self.done = PointSet::new(n_points);
        let (done, mut names_file) = (&mut self.done, false);
        let scan = journal::scan(&self.journal_path, |r| {
            if r.index < n_points {
                done.insert(r.index);
            }
            names_file |= r.in_file;
        })?;
        Ok((scan, names_file))
    }

    /// Continue a finished (possibly partial, e.g. interrupted-then-finished) file: its
    /// records seed a new journal.
    fn resume_finished_file(&mut self, want: &JournalHeader) -> Result<(), StoreError> {
        let n_points = self.info.shape.n_points();
        let fi = read::file_info(&self.path)?;
        // its points are encoded again in this study's groups, whatever its chunks
        if let Some(e) = fi
            .header
            .mismatch(&want.with_group_of(&fi.header), &self.path)
        {
            return Err(e);
        }
        let mut w = JournalWriter::create(&self.journal_path, want)?;
        let done = &mut self.done;
        let encoder = &self.encoder;
        // Only whole groups are done: a group whose histories share chunks is stored whole,
        // so the points of one the file has only in part are computed again with the rest
        // (to the same bits).
        let mut gather = GroupGatherer::new(encoder.groups());
        read::for_each_record(&self.path, |rec| {
            let index = rec.index;
            if index >= n_points || done.contains(index) {
                return Ok(());
            }
            gather.drop_before(index);
            let Some(points) = gather.add(rec) else {
                return Ok(());
            };
            for p in &points {
                done.insert(p.index);
            }
            w.append(&encoder.encode_group(points)?.framed)?;
            if w.buffered_bytes() > 1 << 22 {
                w.flush()?;
            }
            Ok(())
        })?;
        w.sync()?;
        self.resumed = self.done.count();
        self.journal = Some(w);
        Ok(())
    }

    /// The output path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether the point at this flat index is already stored (resume: skip it). The
    /// journal's header pins the study's sha256 and shape, so an index names the same point
    /// (and point id) in every run of that study.
    pub fn is_done(&self, index: usize) -> bool {
        self.done.contains(index)
    }

    /// Bytes of the journal so far, written and buffered (what a history point costs the
    /// journal: `batstudy bench`).
    pub fn journal_bytes(&self) -> u64 {
        self.journal.as_ref().map_or(0, JournalWriter::bytes)
    }

    /// Number of points stored so far (including those recovered on resume).
    pub fn n_done(&self) -> usize {
        self.done.count()
    }

    fn reject(&self, what: String) -> StoreError {
        StoreError::BadRecord {
            path: self.path.clone(),
            what,
        }
    }

    /// Create the final file's skeleton (`OUT.h5.partial`: coordinates, variables, `/bat`),
    /// or complete the one [`begin`] made, if that is not done yet. The writer thread does
    /// this with its first record, while the workers compute, so that [`Self::finish`] only
    /// has the data left to write.
    fn prepare_final_file(&mut self) -> Result<(), StoreError> {
        match &mut self.skeleton {
            Some(sk) => build::complete_skeleton(sk, &self.info, &self.meta),
            None => {
                let partial = partial_path(&self.path);
                self.skeleton = Some(build::create_skeleton(&self.info, &self.meta, &partial)?);
                Ok(())
            }
        }
    }

    /// The encoder of this output's records, for the workers: [`Self::write_encoded`] then
    /// only appends.
    pub fn encoder(&self) -> RecordEncoder {
        self.encoder.clone()
    }

    /// Store one finished point (buffered; see the module docs for when it becomes durable).
    /// A point already stored is ignored. Encodes it here; the runner's writer thread takes
    /// points its workers encoded ([`Self::write_encoded`]). Where points share history
    /// chunks ([`RecordEncoder::groups`]), a point waits until its group is whole, or until
    /// the finish, which stores what there is of each group (a session dropped unfinished
    /// loses the points of groups not whole).
    pub fn write(&mut self, rec: PointRecord) -> Result<(), StoreError> {
        if rec.index < self.done.len() && self.done.contains(rec.index) {
            return Ok(());
        }
        self.encoder.check(&rec)?;
        let whole = match self.gatherer.as_mut() {
            None => vec![rec],
            Some(g) => match g.add(rec) {
                Some(whole) => whole,
                None => return Ok(()),
            },
        };
        let e = self.encoder.encode_group(whole)?;
        self.write_encoded(e)
    }

    /// Store what [`Self::write`] holds of groups that are not whole.
    fn write_gathered(&mut self) -> Result<(), StoreError> {
        let Some(g) = self.gatherer.take() else {
            return Ok(());
        };
        for points in g.into_rest() {
            let e = self.encoder.encode_group(points)?;
            self.write_encoded(e)?;
        }
        Ok(())
    }

    /// Store one point, or a group of points, encoded by this session's [`RecordEncoder`]
    /// (a clone of [`Self::encoder`]): the record's bytes are appended as they are. A point
    /// already stored is ignored, and so is a group whose first point is: a group is stored
    /// whole or not at all.
    pub fn write_encoded(&mut self, rec: EncodedRecord) -> Result<(), StoreError> {
        let n = self.done.len();
        let (Some(first), Some(last)) = (rec.points.first(), rec.points.last()) else {
            return Err(self.reject("a record of no point".into()));
        };
        let (index, last) = (first.index, last.index);
        if last >= n || !journal::is_framed(&rec.framed) {
            return Err(self.reject(format!(
                "points {index}..={last}: not a record encoded for this study's {n} points"
            )));
        }
        if self.done.contains(index) {
            return Ok(());
        }
        for p in &rec.points {
            self.done.insert(p.index);
            if let Some(g) = self.gathered.as_mut() {
                g.put(p);
            }
        }
        self.prepare_final_file()?;
        if rec.has_history && self.placer.is_some() {
            // journalled once placed, by where its chunks went; if the placer holds it, whole
            // at the next flush (`store::by_reference`)
            self.unjournalled.insert(index);
            self.place_histories(index, Some(rec.framed))?;
        } else {
            self.journal_mut().append(&rec.framed)?;
            self.place_histories(index, None)?;
        }
        if self.last_flush.elapsed() >= self.flush_interval
            || self.journal_mut().buffered_bytes() >= 1 << 22
        {
            self.flush_journal()?;
        }
        self.sync_if_due()
    }

    fn journal_mut(&mut self) -> &mut JournalWriter {
        self.journal.as_mut().expect("open session has a journal")
    }

    /// Hand the journal's records to the OS, and first the records the placer holds that
    /// are not in it yet, whole: a killed run loses no point that finished before the last
    /// flush, as when every record was journalled on arrival. (A record neither held nor
    /// journalled is one whose placing failed: the run stops with that error, and its point
    /// is computed again on resume.)
    fn flush_journal(&mut self) -> Result<(), StoreError> {
        self.journal_placed()?;
        let Some(j) = self.journal.as_mut() else {
            return Ok(());
        };
        if let Some(placer) = self.placer.as_ref() {
            for index in std::mem::take(&mut self.unjournalled) {
                if let Some(framed) = placer.held(index) {
                    j.append(framed)?;
                }
            }
        }
        j.flush()?;
        self.last_flush = Instant::now();
        Ok(())
    }

    /// Journal every record of a placed point, once everything the final file's driver has
    /// gathered is in the OS (waiting for it): at each flush, at most 50 ms apart.
    fn journal_placed(&mut self) -> Result<(), StoreError> {
        if self.placed.is_empty() {
            return Ok(());
        }
        if let Some(skeleton) = self.skeleton.as_ref() {
            skeleton
                .write_gathered()
                .ctx(&self.path, "write the unfinished file's gathered bytes")?;
        }
        self.journal_placed_below(u64::MAX)
    }

    /// Journal the records of placed points whose chunks lie below `end` of the final file,
    /// in the order placed, and hand them to the OS. A record names where its chunks are
    /// (`store::by_reference`), so it goes only once they are in the OS: a kill loses at
    /// most the points placed since, which are computed again on resume, as those whose
    /// records were still in the journal's buffer are.
    fn journal_placed_below(&mut self, end: u64) -> Result<(), StoreError> {
        let j = self.journal.as_mut().expect("open session has a journal");
        let mut any = false;
        while let Some((_, r)) = self.placed.front().filter(|(e, _)| *e <= end) {
            j.append(r)?;
            self.placed.pop_front();
            any = true;
        }
        match any {
            true => j.flush(),
            false => Ok(()),
        }
    }

    /// Hand a stored point to the placer, which writes the histories its cursor can now pass
    /// into the final file (in flat-index order; `store::placer`). Each point it writes that
    /// is not in the journal yet is journalled then, by where its chunks went (whole when
    /// that is not known).
    fn place_histories(&mut self, index: usize, framed: Option<Vec<u8>>) -> Result<(), StoreError> {
        let Some(placer) = self.placer.as_mut() else {
            return Ok(());
        };
        struct IntoFile<'a> {
            skeleton: &'a mut build::Skeleton,
            info: &'a StudyInfo,
            writeback: &'a mut Writeback,
            /// The points not in the journal yet; the records of those placed, to journal,
            /// and whether one names chunks in the file.
            unjournalled: &'a mut BTreeSet<usize>,
            records: Vec<Vec<u8>>,
            names_file: bool,
        }
        impl Place for IntoFile<'_> {
            type Error = StoreError;
            fn place(&mut self, index: usize, framed: &[u8]) -> Result<(), StoreError> {
                let offsets = build::place_history(self.skeleton, self.info, index, framed)?;
                self.writeback.wrote(framed.len());
                if !self.unjournalled.remove(&index) {
                    return Ok(());
                }
                let record = by_reference::record_in_file(framed, &offsets);
                self.names_file |= record.is_some();
                self.records.push(record.unwrap_or_else(|| framed.to_vec()));
                Ok(())
            }
        }
        let mut file = IntoFile {
            skeleton: self
                .skeleton
                .as_mut()
                .expect("prepared with the first record"),
            info: &self.info,
            writeback: &mut self.writeback,
            unjournalled: &mut self.unjournalled,
            records: Vec::new(),
            names_file: false,
        };
        let kept_up = placer.arrived(index, framed, &self.done, &mut file)?;
        let (records, names_file) = (file.records, file.names_file);
        if names_file {
            (self.names_file, self.names_unsynced) = (true, true);
        }
        if !records.is_empty() {
            let skeleton = self
                .skeleton
                .as_ref()
                .expect("prepared with the first record");
            let end = skeleton.end_of_allocation().unwrap_or(u64::MAX);
            self.placed.extend(records.into_iter().map(|r| (end, r)));
            let in_os = skeleton
                .in_os()
                .ctx(&self.path, "write the unfinished file")?;
            self.journal_placed_below(in_os)?;
        }
        if !kept_up {
            // what it holds goes to the journal before the placer goes
            self.flush_journal()?;
            let placer = self.placer.take().expect("checked above");
            self.history_tail = Some(placer.tail(false));
        }
        Ok(())
    }

    /// fsync the journal when `sync_interval` has passed since the last time.
    fn sync_if_due(&mut self) -> Result<(), StoreError> {
        if self.last_sync.elapsed() >= self.sync_interval {
            self.sync_journal()?;
            self.last_sync = Instant::now();
        }
        Ok(())
    }

    /// Make the journal durable, and first the final file when the journal names chunks in
    /// it that may not be durable yet.
    fn sync_journal(&mut self) -> Result<(), StoreError> {
        self.flush_journal()?;
        if self.names_unsynced {
            let partial = partial_path(&self.path);
            self.writeback
                .sync()
                .map_err(|e| StoreError::io(&partial, "sync the unfinished file", e))?;
            self.names_unsynced = false;
        }
        match self.journal.as_mut() {
            Some(j) => j.sync(),
            None => Ok(()),
        }
    }

    /// Call when no record arrived for a while (e.g. on the channel's `recv_timeout`): hands
    /// buffered records to the OS, and fsyncs if one is due, so that slow points are not left
    /// only in this process's memory.
    pub fn idle(&mut self) -> Result<(), StoreError> {
        self.flush_journal()?;
        self.sync_if_due()?;
        self.prepare_final_file()
    }

    /// Make everything written so far durable (e.g. on Ctrl-C, before exiting to resume later).
    pub fn flush(&mut self) -> Result<(), StoreError> {
        self.sync_journal()?;
        self.last_flush = Instant::now();
        self.last_sync = Instant::now();
        Ok(())
    }

    /// Write the final file from the journal (atomically: `.partial`, fsync, rename), then
    /// remove the journal. Works for incomplete studies too (missing points have status -1,
    /// e.g. a shard or an interrupted run); `--resume` continues from such a file.
    pub fn finish(mut self) -> Result<Summary, StoreError> {
        self.write_gathered()?;
        // To the OS, not fsync'd: the journal is removed only after the finished file is
        // fsync'd and renamed into place, and a power loss before that loses at most what an
        // unfinished run would (one fsync less on every run's critical path).
        self.flush_journal()?;
        let Some(mut j) = self.journal.take() else {
            return Err(self.reject("the session is already finished".into()));
        };
        j.flush()?;
        // the writer's own extent, not a second scan: every record is checked against its
        // checksum as the build reads it
        let scan = j.extent(JournalHeader::of(&self.info));
        drop(j);
        self.done = PointSet::default();
        let partial = partial_path(&self.path);
        self.prepare_final_file()?;
        let skeleton = self.skeleton.take().expect("prepared above");
        let histories = match (self.placer.take(), self.history_tail.take()) {
            (Some(placer), _) => placer.tail(true),
            (None, Some(tail)) => tail,
            (None, None) => build::HistoryTail::Journal { from: 0 },
        };
        let summary = build::fill(
            skeleton,
            &self.journal_path,
            &scan,
            &self.info,
            &iso8601_now(),
            self.build_memory,
            build::FromRun {
                gathered: self.gathered.take(),
                histories,
            },
        )?;
        std::fs::File::open(&partial)
            .and_then(|f| f.sync_all())
            .map_err(|e| StoreError::io(&partial, "sync the finished file", e))?;
        // durable whole: nothing left for the drop to sync
        self.names_unsynced = false;
        std::fs::rename(&partial, &self.path)
            .map_err(|e| StoreError::io(&self.path, "rename the finished file into place", e))?;
        journal::sync_parent_dir(&self.path);
        // Not synced: the finished file is durable now, and a journal that comes back after
        // a power loss only makes `--resume` rebuild the same file from it (one directory
        // sync less at the end of every run).
        remove_if_exists(&self.journal_path)?;
        Ok(summary)
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let _ = self.sync_journal();
        // A session dropped without finishing leaves no half-made final file behind, unless
        // its journal names history chunks in it: the resume reads them back from there.
        if self.skeleton.take().is_some() && !self.names_file {
            let _ = std::fs::remove_file(partial_path(&self.path));
        }
    }
}
