//! House rules for the repository's text: it says what is and why, in the present tense,
//! without pointing at an issue tracker or a history a reader cannot see. A tracked text
//! file may not cite an issue by number (the word followed by a number, a list of numbers or
//! `#` and a number), a
//! numbered turn or round ("turn 4", "round 3"), or a round by its ordinal ("the fourth
//! round"): where such a citation carried meaning, the text states the measurement, the
//! number or the document section itself.
//!
//! The scan reads every file `git ls-files` lists, skipping binaries (by extension, and any
//! file that is not valid UTF-8) and this file, which has to spell the patterns out. Without
//! git, or outside a git checkout, the test says so and passes.

use std::path::Path;
use std::process::Command;

/// This file, which names the patterns it looks for.
const SELF: &str = "tests/house_rules.rs";

/// The word the scan looks for, spelled so that this file does not match it itself.
const ISSUE: &str = concat!("iss", "ue");

/// Extensions of tracked files that are not text.
const BINARY_EXTENSIONS: &[&str] = &[
    "png", "jpg", "jpeg", "gif", "h5", "hdf5", "nc", "so", "xlsx", "pdf", "gz", "zip",
];

/// The ordinals that make "<ordinal> round" a citation of a past round of work.
const ORDINALS: &[&str] = &[
    "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth",
    "eleventh", "twelfth",
];

fn is_word(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Whether the word `w` (lower case) starts at `i` of `s` (lower case) with no word
/// character before it.
fn word_starts_at(s: &[u8], i: usize, w: &[u8]) -> bool {
    s[i..].starts_with(w) && (i == 0 || !is_word(s[i - 1]))
}

/// The number of ASCII digits at the start of `s`.
fn digits(s: &[u8]) -> usize {
    s.iter().take_while(|b| b.is_ascii_digit()).count()
}

/// `\bissues? #?[0-9]+` at `i`.
fn issue_at(s: &[u8], i: usize) -> bool {
    if !word_starts_at(s, i, b"issue") {
        return false;
    }
    let mut j = i + "issue".len();
    if s.get(j) == Some(&b's') {
        j += 1;
    }
    if s.get(j) != Some(&b' ') {
        return false;
    }
    j += 1;
    if s.get(j) == Some(&b'#') {
        j += 1;
    }
    digits(&s[j..]) > 0
}

/// `\b<word> [0-9]+\b` at `i`, for `turn` and `round`.
fn numbered_at(s: &[u8], i: usize, word: &[u8]) -> bool {
    if !word_starts_at(s, i, word) || s.get(i + word.len()) != Some(&b' ') {
        return false;
    }
    let start = i + word.len() + 1;
    let n = digits(&s[start..]);
    n > 0 && s.get(start + n).is_none_or(|&b| !is_word(b))
}

/// `(first|…|twelfth) round` at `i` (anywhere, as grep -E matches it).
fn ordinal_round_at(s: &[u8], i: usize) -> bool {
    ORDINALS
        .iter()
        .any(|o| s[i..].starts_with(o.as_bytes()) && s[i + o.len()..].starts_with(b" round"))
}

/// Whether a line cites an issue, a numbered turn or round, or an ordinal round.
fn cites_history(line: &str) -> bool {
    let s = line.to_ascii_lowercase().into_bytes();
    (0..s.len()).any(|i| {
        issue_at(&s, i)
            || numbered_at(&s, i, b"turn")
            || numbered_at(&s, i, b"round")
            || ordinal_round_at(&s, i)
    })
}

/// The matcher against lines it must and must not flag, as `grep -E -i` would.
fn check_the_matcher() {
    for hit in [
        &format!("({ISSUE} 36)")[..],
        &format!("{} 37: the modal form", "Iss".to_owned() + "ue")[..],
        &format!("{ISSUE}s 31 and 32")[..],
        &format!("see {ISSUE} #7")[..],
        "turn 4",
        "in round 12.",
        &format!("{ISSUE} 22, fourth round")[..],
        "the Eleventh round",
        &format!("since {ISSUE} 40")[..],
    ] {
        assert!(cites_history(hit), "{hit:?} should match");
    }
    for clean in [
        "tissue 3",
        &format!("{ISSUE}36_figures.py")[..],
        "an issue with 3 points",
        "turn 4b",
        "return 4",
        "round 3rd",
        "around 5",
        "rounds 3",
        "the thirteenth",
    ] {
        assert!(!cites_history(clean), "{clean:?} should not match");
    }
}

#[test]
fn tracked_text_cites_no_issues_or_rounds() {
    check_the_matcher();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let listed = match Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(root)
        .output()
    {
        Ok(o) if o.status.success() => o.stdout,
        Ok(o) => {
            println!(
                "house_rules: skipped, {} is not a git checkout ({})",
                root.display(),
                String::from_utf8_lossy(&o.stderr).trim()
            );
            return;
        }
        Err(e) => {
            println!("house_rules: skipped, git is not available ({e})");
            return;
        }
    };
    let mut hits = Vec::new();
    let mut scanned = 0usize;
    for name in listed.split(|&b| b == 0).filter(|n| !n.is_empty()) {
        let Ok(name) = std::str::from_utf8(name) else {
            continue;
        };
        let ext = Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if name == SELF || ext.is_some_and(|e| BINARY_EXTENSIONS.contains(&e.as_str())) {
            continue;
        }
        // listed but not readable as text here (deleted in the work tree, a submodule, a
        // binary without a known extension): not this test's business
        let Ok(bytes) = std::fs::read(root.join(name)) else {
            continue;
        };
        let Ok(text) = String::from_utf8(bytes) else {
            continue;
        };
        scanned += 1;
        for (k, line) in text.lines().enumerate() {
            if cites_history(line) {
                hits.push(format!("{name}:{}: {}", k + 1, line.trim()));
            }
        }
    }
    assert!(scanned > 0, "git ls-files listed no readable text file");
    assert!(
        hits.is_empty(),
        "{} line(s) cite an issue number, a numbered turn or round, or an ordinal round; \
         say what is and why instead (the measurement, the number, or a document section):\n{}",
        hits.len(),
        hits.join("\n")
    );
}
