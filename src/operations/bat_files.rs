//! What a results file's bats are made into: a profile CSV a lathe and `bat.profile.csv`
//! read (written whole or not at all), and the bats' cards as the trade states them.

use super::failure::OpError;
use super::files::side_output_ok;
use crate::profile_export::{profile_csv, Units};
use crate::store::card::{bat_cards, BatCard};
use crate::store::inspect::pick_bat;
use crate::study::error::printable;
use std::path::Path;

/// A bat of `results` (its label or index; may be left out when the file holds one bat) as
/// a profile CSV in `units`: written to `output` whole (None is returned), or returned as
/// text when no output is named.
pub fn export_profile(
    results: &Path,
    bat: Option<&str>,
    units: Units,
    output: Option<&Path>,
) -> Result<Option<String>, OpError> {
    if let Some(path) = output {
        side_output_ok(path, "--output", &[results])?;
    }
    let text = profile_csv(results, bat, units).map_err(OpError::refused)?;
    let Some(path) = output else {
        return Ok(Some(text));
    };
    crate::store::journal::write_whole(path, text.as_bytes()).map_err(|e| {
        OpError::io(format!(
            "cannot write {}: {e}",
            printable(&path.display().to_string(), false)
        ))
    })?;
    Ok(None)
}

/// The cards of a results file's bats: every bat, or the one `bat` names (its label or its
/// index from 0).
pub fn cards(results: &Path, bat: Option<&str>) -> Result<Vec<BatCard>, OpError> {
    let mut cards = bat_cards(results).map_err(OpError::refused)?;
    if let Some(want) = bat {
        let labels: Vec<String> = cards.iter().map(|c| c.label.clone()).collect();
        let k = pick_bat(&labels, Some(want)).map_err(|allowed| {
            let shown = printable(&results.display().to_string(), false).to_string();
            OpError::refused(format!("{shown}: --bat: {allowed}"))
        })?;
        cards = vec![cards.swap_remove(k)];
    }
    Ok(cards)
}

/// Every bat of several results files, in the order given; with more than one file each
/// label says its file (`FILE: label`).
pub fn cards_of_files(files: &[std::path::PathBuf]) -> Result<Vec<BatCard>, OpError> {
    let mut all = Vec::new();
    for file in files {
        let mut cards = cards(file, None)?;
        if files.len() > 1 {
            for c in &mut cards {
                c.label = format!("{}: {}", file.display(), c.label);
            }
        }
        all.extend(cards);
    }
    Ok(all)
}
