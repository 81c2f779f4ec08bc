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
/// about 6 deep). Each level costs the scan its path: a document nested 100,000 deep took
/// 21 s to refuse (issue 31); past this depth the scan stops at once.
pub const MAX_DEPTH: usize = 64;

enum Frame {
    Map { want_key: bool, key: Option<String> },
    Seq { next: usize },
}

impl SourceMap {
    /// Scan `text`; a malformed document yields the positions found before the error.
    pub fn build(text: &str) -> SourceMap {
        let mut map = HashMap::new();
        let mut frames: Vec<(Frame, bool)> = Vec::new(); // (frame, pushed a path segment)
        let mut path: Vec<Seg> = Vec::new();
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
                    return SourceMap {
                        pos: map,
                        too_deep: deep.then_some(at),
                    };
                }
            };
            let here = Pos {
                line: span.start.line(),
                column: span.start.col() + 1,
            };
            match ev {
                Event::Scalar(v, ..) => {
                    if let Some((Frame::Map { want_key, key }, _)) = frames.last_mut() {
                        if *want_key {
                            let mut p = path.clone();
                            p.push(Seg::Key(v.to_string()));
                            map.insert(p, here);
                            *key = Some(v.to_string());
                            *want_key = false;
                            continue;
                        }
                    }
                    if let Some(seg) = value_seg(&frames) {
                        if matches!(seg, Seg::Index(_)) {
                            let mut p = path.clone();
                            p.push(seg);
                            map.insert(p, here);
                        }
                    }
                    complete(&mut frames);
                }
                Event::Alias(_) => complete(&mut frames),
                Event::MappingStart(..) | Event::SequenceStart(..) => {
                    if frames.len() >= MAX_DEPTH {
                        return SourceMap {
                            pos: map,
                            too_deep: Some(here),
                        };
                    }
                    let seg = match frames.last() {
                        Some((Frame::Map { want_key: true, .. }, _)) => Some(Seg::Key("?".into())),
                        _ => value_seg(&frames),
                    };
                    let pushed = seg.is_some();
                    if let Some(seg) = seg {
                        path.push(seg.clone());
                        if matches!(seg, Seg::Index(_)) {
                            map.insert(path.clone(), here);
                        }
                    }
                    let frame = if matches!(ev, Event::MappingStart(..)) {
                        Frame::Map {
                            want_key: true,
                            key: None,
                        }
                    } else {
                        Frame::Seq { next: 0 }
                    };
                    frames.push((frame, pushed));
                }
                Event::MappingEnd | Event::SequenceEnd => {
                    if let Some((_, pushed)) = frames.pop() {
                        if pushed {
                            path.pop();
                        }
                    }
                    complete(&mut frames);
                }
                _ => {}
            }
        }
        SourceMap {
            pos: map,
            too_deep: None,
        }
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
pub fn dotted(path: &str) -> Vec<Seg> {
    if path.is_empty() {
        return Vec::new();
    }
    path.split('.').map(|s| Seg::Key(s.to_string())).collect()
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

    // issue 31: a document nested 100,000 deep took 21 s to refuse (the YAML parser behind
    // serde is quadratic in the depth); the scan now stops at MAX_DEPTH, in microseconds
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
