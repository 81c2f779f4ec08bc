"""`batstudy.sobol_indices` against Sobol indices known in closed form, from a
`sample` study's own file.

Brody's rigid bat at rest hit at z by a ball of speed v and COR e: the ball leaves at
Y = v (e - r)/(1 + r), r = m/M + m (z - z_cm)^2/I (Brody 1986; docs/physics.md). With v and e
independent and uniform, E[Y | v] = c v E[d] and E[Y | e] = c E[v] d (c = 1/(1 + r),
d = e - r), so the first-order indices are S_v = c^2 Var(v) E[d]^2 / Var(Y) and
S_e = c^2 E[v]^2 Var(d) / Var(Y), Var(Y) = c^2 (E[v^2] E[d^2] - E[v]^2 E[d]^2). Needs
BATSTUDY_BIN and SALib."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

xr = pytest.importorskip("xarray")
pytest.importorskip("SALib")

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

V, E, Z = (30.0, 50.0), (0.40, 0.60), 0.70

STUDY = f"""name: sensitivity
model: rigid
base: {{ball: {{mass: 0.145}}}}
grid:
  impact.z: [{Z}]
sample:
  n: 1024
  seed: 5
  params:
    ball.speed: {{uniform: {{min: {V[0]}, max: {V[1]}}}}}
    ball.law.cor: {{uniform: {{min: {E[0]}, max: {E[1]}}}}}
"""


def uniform_moments(a, b):
    return (a + b) / 2, (b - a) ** 2 / 12


def test_first_order_indices_match_the_closed_form(tmp_path):
    from batstudy import sobol_indices

    study, out = tmp_path / "s.yaml", tmp_path / "s.h5"
    study.write_text(STUDY)
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out, engine="h5netcdf", group="bat") as b:
        mass, z_cm, inertia = (float(b[k][0]) for k in ("mass", "z_cm", "moment_of_inertia"))
    r_m = 0.145 / mass + 0.145 * (Z - z_cm) ** 2 / inertia
    (mv, vv), (me, ve) = uniform_moments(*V), uniform_moments(*E)
    md = me - r_m
    var_y = (vv + mv**2) * (ve + md**2) - mv**2 * md**2
    exact = {"ball.speed": vv * md**2 / var_y, "ball.law.cor": mv**2 * ve / var_y}
    got = sobol_indices(out, "exit_speed")
    for k, s in exact.items():
        assert abs(got[k][0] - s) < 0.05, (k, got[k], s)
    assert 0.9 < sum(exact.values()) <= 1.0  # nearly additive: most variance is first-order


def test_a_tree_and_a_selection_give_the_same_indices(tmp_path):
    # the same study with a second, unused dimension: selected by index or value, from the
    # tree of open_results, it gives the path's indices of the one-dimension study
    import batstudy
    from batstudy import sobol_indices

    study, out = tmp_path / "s.yaml", tmp_path / "s.h5"
    study.write_text(STUDY.replace(f"impact.z: [{Z}]", f"impact.z: [{Z}]\n  swing.omega: [0.0, -10.0]"))
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with pytest.raises(ValueError, match="select one value"):
        sobol_indices(out, "exit_speed")
    tree = batstudy.open_results(out)
    by_index = sobol_indices(tree, "exit_speed", swing_omega=0)
    by_value = sobol_indices(tree["summary"].to_dataset(), "exit_speed", swing_omega=0.0)
    assert by_index == by_value
    one = tmp_path / "one.yaml"
    one.write_text(STUDY)
    r = subprocess.run([BIN, "run", str(one), "-o", str(tmp_path / "one.h5"), "--quiet"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    assert by_index == sobol_indices(tmp_path / "one.h5", "exit_speed")


def test_total_order_indices_from_saltellis_design_match_the_closed_form(tmp_path):
    """ST_v = 1 - Var(E[Y | e]) / Var(Y) = 1 - E[v]^2 Var(d) / Var(Y) and ST_e = 1 - Var(v)
    E[d]^2 / Var(Y) (the product's interaction belongs to both); a plain Sobol sample has no
    total-order estimate and is refused."""
    from batstudy import sobol_indices

    study, out = tmp_path / "s.yaml", tmp_path / "s.h5"
    study.write_text(STUDY.replace("  n: 1024\n", "  n: 1024\n  method: saltelli\n"))
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with xr.open_dataset(out, engine="h5netcdf", group="bat") as b:
        mass, z_cm, inertia = (float(b[k][0]) for k in ("mass", "z_cm", "moment_of_inertia"))
    with xr.open_dataset(out, engine="h5netcdf", group="summary") as s:
        assert s.sizes["sample"] == 1024 * 4
    r_m = 0.145 / mass + 0.145 * (Z - z_cm) ** 2 / inertia
    (mv, vv), (me, ve) = uniform_moments(*V), uniform_moments(*E)
    md = me - r_m
    var_y = (vv + mv**2) * (ve + md**2) - mv**2 * md**2
    exact = {"ball.speed": 1 - mv**2 * ve / var_y, "ball.law.cor": 1 - vv * md**2 / var_y}
    got = sobol_indices(out, "exit_speed", order="total")
    for k, s in exact.items():
        assert abs(got[k][0] - s) < 0.05, (k, got[k], s)
    assert sum(exact.values()) > 1.0  # the interaction, counted in both
    plain = tmp_path / "p.yaml"
    plain.write_text(STUDY)
    r = subprocess.run([BIN, "run", str(plain), "-o", str(tmp_path / "p.h5"), "--quiet"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    with pytest.raises(ValueError, match="saltelli"):
        sobol_indices(tmp_path / "p.h5", "exit_speed", order="total")


def test_a_path_without_sweet_spots_is_read_as_its_tree(tmp_path):
    # a results file of the ball on the wall has no /sweet_spot group (no curve along the
    # bat): the path works as the tree does. Reference: exit speed = e v on the wall, with
    # e fixed, is the speed's alone, so its first-order index is 1.
    import batstudy
    from batstudy import sobol_indices

    study, out = tmp_path / "w.yaml", tmp_path / "w.h5"
    study.write_text("name: w\nbase: {bat: {preset: wall}, impact: {z: 0.7}}\nsample:\n  n: 64\n  seed: 1\n"
                     "  params:\n    ball.speed: {uniform: {min: 20, max: 40}}\n")
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    by_path = sobol_indices(out, "exit_speed")
    assert by_path == sobol_indices(batstudy.open_results(out), "exit_speed")
    assert abs(by_path["ball.speed"][0] - 1.0) < 0.05
