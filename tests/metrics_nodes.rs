//! Nodes of the first two free–free modes, as exposed for the sweet-spot definitions.
//!
//! References: Blevins, Formulas for Natural Frequency and Mode Shape (1979), Table 8-1,
//! free–free uniform beam: mode 1 nodes at 0.2242 L and 0.7758 L, mode 2 at 0.1321 L, 0.5 L
//! and 0.8679 L; Nathan, Am. J. Phys. 68, 979 (2000), Table II, R161: barrel nodes 68 cm
//! (mode 1) and 72 cm (mode 2) — docs/physics.md says our profile table reproduces the nodes
//! within 1 cm.

use batstudy::model::measures::metrics::{barrel_node, bat_metrics};
use batstudy::model::prepare_bat;
use batstudy::model::spec::{BatSpec, MaterialSpec, NumericsSpec, ProfileSpec};

const L: f64 = 0.84;

#[test]
fn uniform_free_free_beam_nodes_match_blevins() {
    let spec = BatSpec {
        profile: Some(ProfileSpec::Knots(vec![[0.0, 0.03], [L, 0.03]])),
        material: MaterialSpec {
            density: Some(649.0),
            youngs_modulus: Some(1.814e10),
            ..MaterialSpec::default()
        },
        ..BatSpec::default()
    };
    let numerics = NumericsSpec::default();
    let bat = prepare_bat(&spec, &numerics).unwrap();
    let m = bat_metrics(&bat, &spec, &numerics).unwrap();
    let p = bat.properties();
    // Exposed barrel nodes are the modal analysis' last nodes, exactly.
    assert_eq!(m.node1_barrel, barrel_node(&p.mode_nodes[0]));
    assert_eq!(m.node2_barrel, barrel_node(&p.mode_nodes[1]));
    // Against Blevins: nodes at segment centres (d = 5 mm), linear interpolation of the
    // shape between nodes, second-order discretisation: 1 mm is ~ d²-level plus the
    // interpolation error of a smooth shape (measured ≈ 0.1 mm).
    let tol = 1e-3;
    for (got, want) in p.mode_nodes[0].iter().zip([0.2242, 0.7758]) {
        assert!(
            (got - want * L).abs() < tol,
            "mode 1: {got} vs {}",
            want * L
        );
    }
    for (got, want) in p.mode_nodes[1].iter().zip([0.1321, 0.5, 0.8679]) {
        assert!(
            (got - want * L).abs() < tol,
            "mode 2: {got} vs {}",
            want * L
        );
    }
    assert!((m.node1_barrel - 0.7758 * L).abs() < tol);
    assert!((m.node2_barrel - 0.8679 * L).abs() < tol);
}

#[test]
fn r161_barrel_nodes_match_nathan() {
    let spec = BatSpec::default();
    let numerics = NumericsSpec::default();
    let bat = prepare_bat(&spec, &numerics).unwrap();
    let m = bat_metrics(&bat, &spec, &numerics).unwrap();
    assert!((m.node1_barrel - 0.68).abs() < 0.01, "{}", m.node1_barrel);
    assert!((m.node2_barrel - 0.72).abs() < 0.01, "{}", m.node2_barrel);
}
