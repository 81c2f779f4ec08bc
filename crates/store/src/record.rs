//! A journal record's payload (`store::journal` frames and checksums it): one point's
//! summary, or a group's head and its points' summaries, then the history chunks, each by
//! its bytes or by where it is in the results file. Encoding and decoding only; no I/O.

use super::layout::{self, N_SUMMARY_FLOATS};
use crate::results::PointRecord;

/// Size of the fixed part of an ok record's payload (everything before the histories).
pub(crate) const OK_SUMMARY_LEN: usize = 8 + 8 + 4 + 1 + 8 * N_SUMMARY_FLOATS + 1 + 1;
/// Offset of the ok flag in a payload.
pub(super) const OK_FLAG_AT: usize = 20;
/// The ok byte of a group record's head, where a point's record has 1 (ok) or 0 (failed).
pub const GROUP_FLAG: u8 = 2;
/// Bytes of a group record's head: first index, points, bytes of their summaries, 0, flag.
pub(super) const GROUP_HEAD_LEN: usize = OK_FLAG_AT + 1;
/// Most points a group record may hold (a corrupt count beyond this is not a record).
const MAX_GROUP: usize = 1 << 16;

/// Encode a record's summary part: everything but its histories, with the flag saying
/// whether histories follow (`has_history`; the caller appends them).
pub fn encode_summary(rec: &PointRecord, has_history: bool, out: &mut Vec<u8>) {
    out.extend_from_slice(&(rec.index as u64).to_le_bytes());
    out.extend_from_slice(&rec.id.to_le_bytes());
    out.extend_from_slice(&rec.bat.to_le_bytes());
    match &rec.result {
        Ok(o) => {
            out.push(1);
            for x in layout::summary_floats(o) {
                out.extend_from_slice(&x.to_le_bytes());
            }
            out.push(o.recontact as u8);
            out.push(has_history as u8);
        }
        Err(msg) => {
            out.push(0);
            out.extend_from_slice(&(msg.len() as u64).to_le_bytes());
            out.extend_from_slice(msg.as_bytes());
        }
    }
}

/// Encode a group record's summary part: its head, then each point's summary, with whether
/// its histories are in the group's chunks (`has_history`, one per point; the caller
/// appends the chunks). The points must be in increasing flat-index order.
pub fn encode_group_summaries(points: &[PointRecord], has_history: &[bool], out: &mut Vec<u8>) {
    debug_assert!(points.windows(2).all(|w| w[1].index > w[0].index));
    debug_assert!(!points.is_empty() && points.len() <= MAX_GROUP);
    let head = out.len();
    out.extend_from_slice(&(points[0].index as u64).to_le_bytes());
    out.extend_from_slice(&(points.len() as u32).to_le_bytes());
    out.extend_from_slice(&[0u8; 8]); // the summaries' length, below; then 0
    out.push(GROUP_FLAG);
    for (p, &h) in points.iter().zip(has_history) {
        encode_summary(p, h, out);
    }
    let len = (out.len() - head - GROUP_HEAD_LEN) as u32;
    out[head + 12..head + 16].copy_from_slice(&len.to_le_bytes());
}

/// Append one history variable's stored bytes to a payload.
pub fn put_history_chunk(bytes: &[u8], out: &mut Vec<u8>) {
    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(bytes);
}

/// Set in a history chunk's length word: the chunk is not in the record but in the results
/// file the run is writing, at the offset that follows (format 3).
pub const IN_FILE: u32 = 1 << 31;

/// One history chunk of a record: its bytes, or where the run wrote them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece<'a> {
    Bytes(&'a [u8]),
    /// `len` bytes at offset `at` of `OUT.h5.partial`, whose CRC-32 is `sum`.
    InFile {
        at: u64,
        len: u32,
        sum: u32,
    },
}

/// Append a reference to a history chunk in the results file to a payload ([`Piece::InFile`]).
pub fn put_history_in_file(at: u64, len: u32, sum: u32, out: &mut Vec<u8>) {
    debug_assert!(len < IN_FILE);
    out.extend_from_slice(&(IN_FILE | len).to_le_bytes());
    out.extend_from_slice(&at.to_le_bytes());
    out.extend_from_slice(&sum.to_le_bytes());
}

/// Every history chunk of a payload (after its summary part), bytes or references, or
/// `None` if they do not add up to the payload.
pub fn history_pieces(payload: &[u8]) -> Option<Vec<Piece<'_>>> {
    let mut c = Cursor {
        b: payload,
        p: summary_part(payload)?.0,
    };
    let mut out = Vec::new();
    while c.p < payload.len() {
        let word = c.u32()?;
        out.push(match word & IN_FILE {
            0 => Piece::Bytes(c.take(word as usize)?),
            _ => Piece::InFile {
                at: c.u64()?,
                len: word & !IN_FILE,
                sum: c.u32()?,
            },
        });
    }
    Some(out)
}

/// Every history chunk of a payload whose chunks are all in it, or `None` if they do not
/// add up to the payload or one is in the results file (a resume puts those back in the
/// journal first: `store::by_reference`).
pub fn history_chunks(payload: &[u8]) -> Option<Vec<&[u8]>> {
    history_pieces(payload)?
        .into_iter()
        .map(|p| match p {
            Piece::Bytes(b) => Some(b),
            Piece::InFile { .. } => None,
        })
        .collect()
}

/// Whether a payload holds histories of which some are in the results file.
pub(super) fn refers_to_file(payload: &[u8]) -> bool {
    summary_part(payload).is_some_and(|(_, history)| history) && names_file_chunks(payload)
}

/// A payload's summary part (one point's, or a group's head and its points'): where the
/// history chunks after it begin, and whether any of its points has histories in them.
/// `None` when it is not a summary part.
pub fn summary_part(payload: &[u8]) -> Option<(usize, bool)> {
    let mut c = Cursor { b: payload, p: 0 };
    if payload.get(OK_FLAG_AT) != Some(&GROUP_FLAG) {
        let history = skip_summary(&mut c)?;
        return Some((c.p, history));
    }
    let (n, len) = group_head(&mut c)?;
    let end = GROUP_HEAD_LEN.checked_add(len)?;
    let mut m = Cursor {
        b: payload.get(..end)?,
        p: GROUP_HEAD_LEN,
    };
    let mut any = false;
    for _ in 0..n {
        any |= skip_summary(&mut m)?;
    }
    (m.p == end).then_some((end, any))
}

/// A group record's head: its points and the bytes of their summaries.
fn group_head(c: &mut Cursor) -> Option<(usize, usize)> {
    let _first = c.u64()?;
    let n = c.u32()? as usize;
    let len = c.u32()? as usize;
    let (zero, flag) = (c.u32()?, c.u8()?);
    (zero == 0 && flag == GROUP_FLAG && (1..=MAX_GROUP).contains(&n)).then_some((n, len))
}

/// Step over one point's summary; whether histories follow it.
fn skip_summary(c: &mut Cursor) -> Option<bool> {
    c.take(OK_FLAG_AT)?;
    match c.u8()? {
        1 => {
            c.take(8 * N_SUMMARY_FLOATS + 1)?;
            Some(c.u8()? != 0)
        }
        0 => {
            let n = usize::try_from(c.u64()?).ok()?;
            c.take(n)?;
            Some(false)
        }
        _ => None,
    }
}

/// Whether the history chunks after a payload's summary name some in the results file.
pub(super) fn names_file_chunks(payload: &[u8]) -> bool {
    history_pieces(payload).is_some_and(|p| p.iter().any(|p| matches!(p, Piece::InFile { .. })))
}

struct Cursor<'a> {
    b: &'a [u8],
    p: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let s = self.b.get(self.p..self.p.checked_add(n)?)?;
        self.p += n;
        Some(s)
    }
    fn u8(&mut self) -> Option<u8> {
        Some(self.take(1)?[0])
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
    fn f64(&mut self) -> Option<f64> {
        Some(f64::from_bits(self.u64()?))
    }
}

/// Decode a payload's summary part (an ok record's first [`OK_SUMMARY_LEN`] bytes, a failed
/// record whole): the point without histories, and whether histories follow.
pub fn decode_summary(payload: &[u8]) -> Option<(PointRecord, bool)> {
    summary_at(&mut Cursor { b: payload, p: 0 })
}

/// Decode a payload's points: its one point, or each point of its group, without
/// histories, each with whether its histories are in the record's chunks. `None` when the
/// summary part is not whole, or a group's points do not begin at its first index and
/// increase.
pub fn decode_points(payload: &[u8]) -> Option<Vec<(PointRecord, bool)>> {
    let mut c = Cursor { b: payload, p: 0 };
    if payload.get(OK_FLAG_AT) != Some(&GROUP_FLAG) {
        return Some(vec![summary_at(&mut c)?]);
    }
    let first = u64::from_le_bytes(payload.get(..8)?.try_into().ok()?) as usize;
    let (n, len) = group_head(&mut c)?;
    let mut m = Cursor {
        b: payload.get(..GROUP_HEAD_LEN.checked_add(len)?)?,
        p: GROUP_HEAD_LEN,
    };
    let points: Vec<(PointRecord, bool)> =
        (0..n).map(|_| summary_at(&mut m)).collect::<Option<_>>()?;
    let ordered =
        points[0].0.index == first && points.windows(2).all(|w| w[1].0.index > w[0].0.index);
    (ordered && m.p == m.b.len()).then_some(points)
}

/// One point's summary at the cursor.
fn summary_at(c: &mut Cursor) -> Option<(PointRecord, bool)> {
    let index = c.u64()? as usize;
    let id = c.u64()?;
    let bat = c.u32()?;
    let ok = c.u8()?;
    let (result, has_history) = if ok == 1 {
        let mut f = [0.0; N_SUMMARY_FLOATS];
        for x in f.iter_mut() {
            *x = c.f64()?;
        }
        let mut o = layout::outcome_from_floats(&f);
        o.recontact = c.u8()? != 0;
        (Ok(o), c.u8()? != 0)
    } else if ok == 0 {
        let n = usize::try_from(c.u64()?).ok()?;
        let s = c.take(n)?;
        (Err(String::from_utf8_lossy(s).into_owned()), false)
    } else {
        return None;
    };
    Some((
        PointRecord {
            index,
            id,
            bat,
            result,
        },
        has_history,
    ))
}
