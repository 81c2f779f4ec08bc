//! No parameter's coordinate can take the name of a summary variable: both live in
//! `/summary`, and HDF5 refuses a second object of one name (found when `hoop_frequency`
//! was briefly both a swept parameter's coordinate and a stored variable).

use batstudy::store::layout::SUMMARY_FLOATS;
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
