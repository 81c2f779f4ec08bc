//! History chunks journalled by where they are in the results file: each history written
//! once.
//!
//! A fresh run's placer (`store::placer`) writes each point's history chunks into
//! `OUT.h5.partial` as soon as every point before it is stored. The journal used to hold a
//! copy of those bytes too, so every history went to the disk twice, and copying it into
//! the journal was a sixth of the writer thread's time. Now a point that the placer writes
//! as it arrives is journalled after that, with its summary and, for each chunk, where it
//! went in the file (`chunks::write_chunk_at_end`), its length and its CRC-32
//! ([`record_in_file`]). A point that overtakes the placer, every point of a resumed run,
//! and any record with a chunk whose place is not known keep their bytes in the journal.
//!
//! Crash safety:
//! - A chunk's bytes reach the OS (`pwrite`) before the record that names them, so a killed
//!   process loses neither. Before the journal is made durable, the file is
//!   (`Session::sync_if_due`), so a power loss does not lose them either.
//! - A killed or interrupted run leaves its `OUT.h5.partial` in place. The next run sets it
//!   aside as `OUT.h5.partial.prev` before it begins its own (`paths::set_aside_partial`).
//! - On resume, [`bring_back`] rewrites the journal whole: each chunk is read back from
//!   the set-aside file at its offset and checked against its length and CRC-32. A record
//!   with a chunk missing or changed is dropped, and its point is computed again.
//! - The rewritten journal replaces the old one by a rename. A resume killed while it
//!   rewrites therefore starts over from the old journal and the same set-aside file.
//!
//! After that the run goes on as any resumed run, and its data are an uninterrupted run's.

use super::error::StoreError;
use super::journal::{
    begin_frame, checksum, end_frame, history_chunks, history_pieces, put_history_chunk,
    put_history_in_file, refers_to_file, split_prefix, summary_part, sync_parent_dir,
    unfinished_path, Piece, Scan, IN_FILE, REC_PREFIX,
};
use super::paths::create_fresh;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::os::unix::fs::{FileExt, OpenOptionsExt};
use std::path::Path;

/// The journal record of a point whose histories were just written into the results file:
/// the summary of `framed` (its encoded record), then each chunk by where it went
/// (`offsets`, one per chunk in the record's order), its length and its CRC-32. `None` when
/// a chunk's place is not known: the record is then journalled whole.
pub fn record_in_file(framed: &[u8], offsets: &[Option<u64>]) -> Option<Vec<u8>> {
    let payload = framed.get(REC_PREFIX..)?;
    let chunks = history_chunks(payload)?;
    let (summaries, _) = summary_part(payload)?;
    if chunks.len() != offsets.len() {
        return None;
    }
    let mut out = Vec::with_capacity(REC_PREFIX + summaries + 16 * chunks.len());
    begin_frame(&mut out);
    out.extend_from_slice(&payload[..summaries]);
    for (bytes, at) in chunks.iter().zip(offsets) {
        let len = u32::try_from(bytes.len()).ok().filter(|&l| l < IN_FILE)?;
        put_history_in_file((*at)?, len, checksum(bytes), &mut out);
    }
    end_frame(&mut out);
    Some(out)
}

/// What a resume found of the chunks its journal had left in the results file.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Recovered {
    /// Records whose chunks were all found, intact, and are now in the journal.
    pub kept: usize,
    /// Records dropped because a chunk was missing or changed: their points are computed
    /// again.
    pub dropped: usize,
}

/// Rewrite `journal` (scanned as `scan`, its valid records only) with every chunk it has in
/// the set-aside results file `prev` read back into its record, each checked against its
/// length and CRC-32; a record with a chunk that is not there intact is dropped. The new
/// journal replaces the old by a rename, made durable first. `prev` may be missing (every
/// record that refers to it is dropped then); it is opened without following a symbolic
/// link, and only read.
pub fn bring_back(journal: &Path, scan: &Scan, prev: &Path) -> Result<Recovered, StoreError> {
    let read_err = |e| StoreError::io(journal, "read the journal", e);
    let mut r = BufReader::with_capacity(1 << 20, super::journal::open_journal(journal)?);
    let mut header = vec![0u8; scan.header_len as usize];
    r.read_exact(&mut header).map_err(read_err)?;
    let prev = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW)
        .open(prev)
        .ok();
    let temp = unfinished_path(journal);
    let write_err = |e| StoreError::io(&temp, "rewrite the journal", e);
    let mut w = BufWriter::with_capacity(1 << 20, create_fresh(&temp, "rewrite the journal")?);
    w.write_all(&header).map_err(write_err)?;
    let (mut record, mut whole) = (Vec::new(), Vec::new());
    let mut found = Recovered::default();
    let mut pos = scan.header_len;
    while pos < scan.valid_len {
        record.resize(REC_PREFIX, 0);
        r.read_exact(&mut record).map_err(read_err)?;
        let (_, len, sum) = split_prefix(record[..REC_PREFIX].try_into().expect("prefix"));
        record.resize(REC_PREFIX + len as usize, 0);
        r.read_exact(&mut record[REC_PREFIX..]).map_err(read_err)?;
        let payload = &record[REC_PREFIX..];
        if checksum(payload) != sum {
            return Err(StoreError::BadJournal {
                path: journal.to_path_buf(),
                what: format!("record at byte {pos} changed after it was scanned"),
            });
        }
        pos += record.len() as u64;
        let out = match refers_to_file(payload) {
            false => &record,
            true if read_back(payload, prev.as_ref(), &mut whole) => {
                found.kept += 1;
                &whole
            }
            true => {
                found.dropped += 1;
                continue;
            }
        };
        w.write_all(out).map_err(write_err)?;
    }
    let file = w.into_inner().map_err(|e| write_err(e.into_error()))?;
    file.sync_all().map_err(write_err)?;
    drop(file);
    std::fs::rename(&temp, journal)
        .map_err(|e| StoreError::io(journal, "replace the journal", e))?;
    sync_parent_dir(journal);
    Ok(found)
}

/// `payload` framed in `out` with each chunk it names in `prev` read back into it; false
/// when one is not there intact (or `prev` is missing).
fn read_back(payload: &[u8], prev: Option<&File>, out: &mut Vec<u8>) -> bool {
    let (Some(pieces), Some((summaries, _))) = (history_pieces(payload), summary_part(payload))
    else {
        return false;
    };
    begin_frame(out);
    out.extend_from_slice(&payload[..summaries]);
    for piece in pieces {
        match piece {
            Piece::Bytes(bytes) => put_history_chunk(bytes, out),
            Piece::InFile { at, len, sum } => {
                let Some(file) = prev else {
                    return false;
                };
                out.extend_from_slice(&len.to_le_bytes());
                let start = out.len();
                out.resize(start + len as usize, 0);
                if file.read_exact_at(&mut out[start..], at).is_err()
                    || checksum(&out[start..]) != sum
                {
                    return false;
                }
            }
        }
    }
    end_frame(out);
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::journal::OK_SUMMARY_LEN;

    /// A payload as `store::encode` makes it: a summary part, then chunks.
    fn framed(chunks: &[&[u8]]) -> Vec<u8> {
        let mut f = Vec::new();
        begin_frame(&mut f);
        let mut summary = vec![7u8; OK_SUMMARY_LEN];
        summary[20] = 1; // ok
        summary[OK_SUMMARY_LEN - 1] = 1; // histories follow
        f.extend_from_slice(&summary);
        chunks.iter().for_each(|c| put_history_chunk(c, &mut f));
        end_frame(&mut f);
        f
    }

    /// A record by reference names each chunk's offset, length and CRC-32, and reading the
    /// chunks back from a file that holds them at those offsets gives the record whole
    /// again, bit for bit; a chunk changed in the file, or a file missing, drops it.
    #[test]
    fn a_record_in_the_file_reads_back_whole_or_not_at_all() {
        let (a, b): (Vec<u8>, Vec<u8>) = ((0..300).map(|i| i as u8).collect(), vec![9; 5000]);
        let whole = framed(&[&a, &b]);
        assert!(
            record_in_file(&whole, &[Some(10), None]).is_none(),
            "place unknown"
        );
        assert!(
            record_in_file(&whole, &[Some(10)]).is_none(),
            "a chunk unaccounted for"
        );
        let by_ref = record_in_file(&whole, &[Some(100), Some(1000)]).unwrap();
        // the summary, then 16 bytes a chunk: length, offset, CRC-32
        assert_eq!(by_ref.len(), REC_PREFIX + OK_SUMMARY_LEN + 2 * 16);
        let payload = &by_ref[REC_PREFIX..];
        assert!(refers_to_file(payload) && history_chunks(payload).is_none());
        assert_eq!(
            history_pieces(payload).unwrap()[1],
            Piece::InFile {
                at: 1000,
                len: 5000,
                sum: checksum(&b)
            }
        );

        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("partial");
        let mut file = vec![0u8; 7000];
        file[100..400].copy_from_slice(&a);
        file[1000..6000].copy_from_slice(&b);
        std::fs::write(&path, &file).unwrap();
        let mut out = Vec::new();
        let f = File::open(&path).unwrap();
        assert!(read_back(payload, Some(&f), &mut out));
        assert_eq!(out, whole);
        assert!(!read_back(payload, None, &mut out));
        file[3000] ^= 1;
        std::fs::write(&path, &file).unwrap();
        assert!(!read_back(
            payload,
            Some(&File::open(&path).unwrap()),
            &mut out
        ));
        // a file cut short before the chunk's end
        file[3000] ^= 1;
        std::fs::write(&path, &file[..5999]).unwrap();
        assert!(!read_back(
            payload,
            Some(&File::open(&path).unwrap()),
            &mut out
        ));
    }

    /// A group record (several points sharing chunks) goes by reference and back whole the
    /// same way: its points' summaries are kept as they are, its chunks named.
    #[test]
    fn a_group_record_in_the_file_reads_back_whole() {
        use crate::results::PointRecord;
        use batstudy_physics::outcome::Outcome;
        let point = |index, result| PointRecord {
            index,
            id: index as u64,
            bat: 0,
            result,
        };
        let points = [
            point(8, Ok(Outcome::default())),
            point(9, Err("failed".into())),
        ];
        let chunk: Vec<u8> = (0..900).map(|i| (i * 7) as u8).collect();
        let mut whole = Vec::new();
        begin_frame(&mut whole);
        crate::journal::encode_group_summaries(&points, &[true, false], &mut whole);
        put_history_chunk(&chunk, &mut whole);
        end_frame(&mut whole);
        let by_ref = record_in_file(&whole, &[Some(50)]).unwrap();
        let payload = &by_ref[REC_PREFIX..];
        assert!(refers_to_file(payload));
        let (summaries, _) = summary_part(&whole[REC_PREFIX..]).unwrap();
        assert_eq!(payload.len(), summaries + 16);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("partial");
        let mut file = vec![0u8; 1000];
        file[50..950].copy_from_slice(&chunk);
        std::fs::write(&path, &file).unwrap();
        let mut out = Vec::new();
        assert!(read_back(
            payload,
            Some(&File::open(&path).unwrap()),
            &mut out
        ));
        assert_eq!(out, whole);
    }
}
