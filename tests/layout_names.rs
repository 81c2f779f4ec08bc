//! No parameter's coordinate can take the name of a summary variable: both live in
//! `/summary`, and HDF5 refuses a second object of one name (found when `hoop_frequency`
//! was briefly both a swept parameter's coordinate and a stored variable).

use batstudy::store::layout::{self as l, SUMMARY_FLOATS};
use batstudy::store::layout::{HISTORY_VARS, HIST_Z, SWEET_AT_EDGE, SWEET_FLOATS, TIME};
use batstudy::study::paths::{coord_name, known_paths};

#[test]
fn parameter_coordinates_and_summary_variables_have_different_names() {
    for path in known_paths().keys() {
        let coord = coord_name(path);
        assert!(
            SUMMARY_FLOATS.iter().all(|v| v.name != coord),
            "the coordinate of `{path}` would be named like the summary variable `{coord}`"
        );
    }
}

// every name the store gives a variable in a group that also holds the study's
// coordinates is reserved, so that no dimension or coordinate of a study can take it
#[test]
fn every_stored_name_beside_the_coordinates_is_reserved() {
    let mut names: Vec<&str> = l::SUMMARY_FLOATS.iter().map(|d| d.name).collect();
    names.extend([l::RECONTACT, l::STATUS, l::POINT_ID, l::BAT_INDEX].map(|d| d.name));
    names.extend(SWEET_FLOATS.iter().map(|d| d.name));
    names.extend([SWEET_AT_EDGE, TIME, HIST_Z].map(|d| d.name));
    // the displacement's modal form: its dims in `/history`
    names.extend([l::BAT_MODE_DIM, l::SHAPE_POINT_DIM].map(|d| d.name));
    names.extend(HISTORY_VARS.iter().map(|(d, _, _)| d.name));
    for n in names {
        assert!(
            batstudy::results::is_reserved(n),
            "`{n}` is stored beside the coordinates but not reserved"
        );
    }
}
