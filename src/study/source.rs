//! Source positions of a YAML document: a span-aware scan (saphyr-parser events) that
//! records the line and column of every mapping key and sequence element, so that errors
//! found after deserialization (on plain values) can still point into the file.

use saphyr_parser::{Event, Parser};
use std::collections::HashMap;

/// One step of a path into a YAML document.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Seg {
    Key(String),
    Index(usize),
}

/// A position in the source text: line 1-based, column 1-based.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pos {
    pub line: usize,
    pub column: usize,
}

/// Positions of the keys (for mapping entries) and elements (for sequence items).
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    pos: HashMap<Vec<Seg>, Pos>,
    /// Where the document first nests deeper than [`MAX_DEPTH`], if it does: the scan
    /// stops there.
    pub too_deep: Option<Pos>,
}

/// Deepest nesting of mappings and sequences a study file may have (a real one nests
/// about 6 deep). Each level costs the scan its path: a document nested 100,000 deep would
/// take 21 s to refuse; past this depth the scan stops at once.
pub const MAX_DEPTH: usize = 64;

enum Frame {
    Map { want_key: bool, key: Option<String> },
    Seq { next: usize },
}

impl SourceMap {
    /// Scan `text`; a malformed document yields the positions found before the error.
    pub fn build(text: &str) -> SourceMap {
        let mut scan = Scan::default();
        for item in Parser::new_from_str(text) {
            let (ev, span) = match item {
                Ok(x) => x,
                Err(e) => {
                    // the parser's own bound on nesting (deeper than ours: a flow level
                    // costs it two): the document is too deep all the same
                    let deep = e.info().contains("recursion limit");
                    let at = Pos {
                        line: e.marker().line(),
                        column: e.marker().col() + 1,
                    };
                    return scan.finish(deep.then_some(at));
                }
            };
            let here = Pos {
                line: span.start.line(),
                column: span.start.col() + 1,
            };
            match ev {
                Event::Scalar(v, ..) => scan.scalar(&v, here),
                Event::Alias(_) => complete(&mut scan.frames),
                Event::MappingStart(..) | Event::SequenceStart(..) => {
                    if scan.frames.len() >= MAX_DEPTH {
                        return scan.finish(Some(here));
                    }
                    scan.start(matches!(ev, Event::MappingStart(..)), here);
                }
                Event::MappingEnd | Event::SequenceEnd => scan.end(),
                _ => {}
            }
        }
        scan.finish(None)
    }

    /// Position of exactly this path.
    pub fn get(&self, path: &[Seg]) -> Option<Pos> {
        self.pos.get(path).copied()
    }

    /// Position of the longest prefix of `path` that is in the document.
    pub fn nearest(&self, path: &[Seg]) -> Option<Pos> {
        (1..=path.len()).rev().find_map(|n| self.get(&path[..n]))
    }
}

/// The scan's state: the positions found, the open mappings and sequences, the path to
/// where the scan is.
#[derive(Default)]
struct Scan {
    map: HashMap<Vec<Seg>, Pos>,
    /// (frame, whether it pushed a path segment)
    frames: Vec<(Frame, bool)>,
    path: Vec<Seg>,
}

impl Scan {
    /// A scalar: a mapping's key (its position recorded), or a value (a sequence
    /// element's position recorded).
    fn scalar(&mut self, v: &str, here: Pos) {
        if let Some((Frame::Map { want_key, key }, _)) = self.frames.last_mut() {
            if *want_key {
                let mut p = self.path.clone();
                p.push(Seg::Key(v.to_string()));
                self.map.insert(p, here);
                *key = Some(v.to_string());
                *want_key = false;
                return;
            }
        }
        if let Some(seg) = value_seg(&self.frames) {
            if matches!(seg, Seg::Index(_)) {
                let mut p = self.path.clone();
                p.push(seg);
                self.map.insert(p, here);
            }
        }
        complete(&mut self.frames);
    }

    /// A mapping or a sequence opens.
    fn start(&mut self, is_mapping: bool, here: Pos) {
        let seg = match self.frames.last() {
            Some((Frame::Map { want_key: true, .. }, _)) => Some(Seg::Key("?".into())),
            _ => value_seg(&self.frames),
        };
        let pushed = seg.is_some();
        if let Some(seg) = seg {
            self.path.push(seg.clone());
            if matches!(seg, Seg::Index(_)) {
                self.map.insert(self.path.clone(), here);
            }
        }
        let frame = match is_mapping {
            true => Frame::Map {
                want_key: true,
                key: None,
            },
            false => Frame::Seq { next: 0 },
        };
        self.frames.push((frame, pushed));
    }

    /// A mapping or a sequence closes.
    fn end(&mut self) {
        if let Some((_, pushed)) = self.frames.pop() {
            if pushed {
                self.path.pop();
            }
        }
        complete(&mut self.frames);
    }

    fn finish(self, too_deep: Option<Pos>) -> SourceMap {
        SourceMap {
            pos: self.map,
            too_deep,
        }
    }
}

fn value_seg(frames: &[(Frame, bool)]) -> Option<Seg> {
    match frames.last() {
        Some((Frame::Map { key, .. }, _)) => Some(Seg::Key(key.clone().unwrap_or_default())),
        Some((Frame::Seq { next }, _)) => Some(Seg::Index(*next)),
        None => None,
    }
}

fn complete(frames: &mut [(Frame, bool)]) {
    match frames.last_mut() {
        Some((Frame::Map { want_key, .. }, _)) => *want_key = true,
        Some((Frame::Seq { next }, _)) => *next += 1,
        None => {}
    }
}

/// Path segments from keys, e.g. `keys(&["grid", "impact.z"])`.
pub fn keys(k: &[&str]) -> Vec<Seg> {
    k.iter().map(|s| Seg::Key(s.to_string())).collect()
}

/// `["bat", "material"]` from `"bat.material"` (empty string: no segments).
/// `grid.impact.z[2]` for a path of segments.
pub fn seg_path(at: &[Seg]) -> String {
    let mut s = String::new();
    for seg in at {
        match seg {
            Seg::Key(k) if s.is_empty() => s.push_str(k),
            Seg::Key(k) => {
                s.push('.');
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

pub fn dotted(path: &str) -> Vec<Seg> {
    if path.is_empty() {
        return Vec::new();
    }
    // `layers[2]` is the key `layers` and its element 2
    let mut segs = Vec::new();
    for part in path.split('.') {
        let (key, index) = match part.strip_suffix(']').and_then(|p| p.split_once('[')) {
            Some((k, i)) if i.parse::<usize>().is_ok() => (k, i.parse().ok()),
            _ => (part, None),
        };
        segs.push(Seg::Key(key.to_string()));
        segs.extend(index.map(Seg::Index));
    }
    segs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_of_keys_and_elements() {
        let text = "name: x\nbase:\n  bat: {material: {density: 649}}\n  impact:\n    z: 0.7\ngrid:\n  swing.omega: [0, -10,\n    -20]\n";
        let m = SourceMap::build(text);
        assert_eq!(m.get(&keys(&["name"])), Some(Pos { line: 1, column: 1 }));
        assert_eq!(
            m.get(&keys(&["base", "bat", "material", "density"]))
                .unwrap()
                .line,
            3
        );
        assert_eq!(m.get(&keys(&["base", "impact", "z"])).unwrap().line, 5);
        let mut p = keys(&["grid", "swing.omega"]);
        assert_eq!(m.get(&p).unwrap().line, 7);
        p.push(Seg::Index(2));
        assert_eq!(m.get(&p), Some(Pos { line: 8, column: 5 }));
        assert_eq!(m.nearest(&keys(&["base", "impact", "q"])).unwrap().line, 4);
    }

    // a document nested 100,000 deep, unbounded, takes 21 s to refuse (the YAML parser
    // behind serde is quadratic in the depth); the scan stops at MAX_DEPTH, in microseconds
    #[test]
    fn deep_nesting_is_found_at_once() {
        for text in [
            format!(
                "name: t\nbase: {}{}\n",
                "[".repeat(100_000),
                "]".repeat(100_000)
            ),
            format!("name: t\nbase:\n  {}1\n", "- ".repeat(100_000)),
            (1..2000).fold("name: t\nbase:\n".to_string(), |s, i| {
                s + &" ".repeat(i) + "a:\n"
            }),
        ] {
            let m = SourceMap::build(&text);
            let at = m
                .too_deep
                .unwrap_or_else(|| panic!("not too deep: {:?}", &text[..40]));
            assert!(at.line >= 2, "{at:?}");
        }
        let shallow = SourceMap::build("a: {b: [1, [2, [3]]]}\n");
        assert!(shallow.too_deep.is_none());
    }
}
