"""Three users' sessions, end to end, from the installed wheel: a Jupyter analyst, a bat
engineer and a field (Statcast) analyst, each doing what they came for in the units they
type. Every step is one a user hit a wall at before; here each runs through, and each answer
is held to something outside the code: a conservation law, a closed form, a rule book, or the
step's own earlier answer under another name (a path and its tree, SI and the trade's units).
"""

import math
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import batstudy

ROOT = pathlib.Path(__file__).resolve().parents[2]
BATSTUDY = shutil.which("batstudy") or str(pathlib.Path(sys.executable).with_name("batstudy"))


def cli(*args, cwd=None):
    return subprocess.run([BATSTUDY, *map(str, args)], capture_output=True, text=True, cwd=cwd)


def test_the_jupyter_analyst(tmp_path):
    """NumPy numbers in, the bat's card and the field's verdict out; a sampled study's Sobol
    indices from its path, the same as from its tree and the same again with the same seed;
    every group of the file with units pint parses."""
    pint_xarray = pytest.importorskip("pint_xarray")
    r = batstudy.simulate({"swing": {"omega": np.int64(-45)}, "ball": {"speed": np.float64(38.0)},
                           "impact": {"z": np.float32(0.70)}})
    assert r["squared_up"] in (0.0, 1.0)
    assert 0.8 < r["bat"]["mass"] < 0.9 and 0.4 < r["bat"]["bbcor_max"] < 0.6
    # energy: what the ball and the bat carry away and what is lost is what came in
    parts = ("ball_final", "ball_loss", "bat_rigid", "bat_vibration", "hoop", "bat_damping",
             "grip_damping", "friction")
    out = sum(r.get(f"energy_{p}", 0.0) for p in parts)
    assert math.isclose(out, r["energy_initial"], rel_tol=1e-3), (out, r["energy_initial"])

    study = tmp_path / "wall.yaml"
    study.write_text("name: wall\nbase: {bat: {preset: wall}, impact: {z: 0.7}}\n"
                     "sample:\n  n: 64\n  seed: 3\n  params:\n"
                     "    ball.speed: {uniform: {min: 20, max: 40}}\n"
                     "    ball.law.cor: {uniform: {min: 0.45, max: 0.6}}\n")
    out = batstudy.run(study, output=tmp_path / "wall.h5", progress=False)
    by_path = batstudy.sobol_indices(out, "exit_speed", seed=11)
    tree = batstudy.open_results(out)
    assert by_path == batstudy.sobol_indices(tree, "exit_speed", seed=11)
    assert by_path == batstudy.sobol_indices(out, "exit_speed", seed=11)
    # a wall's exit speed is e v: its variance is mostly the speed's (relative spreads 0.19
    # against 0.08, so about 0.84 of it), the rest the COR's
    assert by_path["ball.speed"][0] > 0.7 and by_path["ball.law.cor"][0] > 0.05
    ureg = pint_xarray.unit_registry
    for node in tree.subtree:
        ds = node.to_dataset()
        q = ds.pint.quantify()
        for name, var in ds.data_vars.items():
            u = var.attrs.get("units")
            if u not in (None, ""):
                assert q[name].pint.units == ureg.Unit(u), (node.path, name, u)
    speed = tree["summary"].to_dataset().pint.quantify()["exit_speed"]
    assert float(speed.pint.to("mph").pint.magnitude.max()) < 40 / 0.44704


def test_the_bat_engineer(tmp_path):
    """A bat written in the trade's units; a hollow preset that breathes without being told;
    a ply angle in degrees (a bare number refused); each bat judged by the rules that are for
    it; a shop-ready profile."""
    alloy = tmp_path / "alloy.yaml"
    alloy.write_text("name: alloy\nmodel: wave\nbase:\n  bat: {preset: alloy_bbcor, length: 33in}\n"
                     "  ball: {preset: mlb}\ngrid:\n  impact.z: [27in, 28in]\n")
    wood = tmp_path / "wood.yaml"
    wood.write_text("name: wood\nmodel: wave\nbase:\n  bat: {preset: r161}\n  ball: {preset: mlb}\n"
                    "grid:\n  impact.z: [0.70]\n")
    a = batstudy.run(alloy, output=tmp_path / "alloy.h5", progress=False)
    w = batstudy.run(wood, output=tmp_path / "wood.h5", progress=False)
    one = lambda c, name: float(np.asarray(c[name]).reshape(-1)[0])
    card = batstudy.bat_card(batstudy.open_results(a))
    assert math.isclose(one(card, "length"), 33 * 0.0254, rel_tol=1e-12)
    # the preset's wall breathes by default: a hoop frequency, and a BBCOR above the
    # no-hoop one the same bat gives with `hoop: {from_geometry: false}` (a trampoline adds)
    assert 1000 < one(card, "hoop_mode_frequency") < 4000
    still = tmp_path / "still.yaml"
    still.write_text(alloy.read_text().replace("  ball: {preset: mlb}\n",
                                               "  ball: {preset: mlb}\n  hoop: {from_geometry: false}\n"))
    s = batstudy.run(still, output=tmp_path / "still.h5", progress=False)
    assert one(card, "bbcor_max") > one(batstudy.bat_card(batstudy.open_results(s)), "bbcor_max")

    # a ply's angle: degrees with their unit; a bare 90 (radians?) is refused by name
    layers = ("  bat:\n    preset: alloy_bbcor\n    shell:\n      layers:\n"
              "        - {material: glass_epoxy, thickness: 0.0005, angle: ANGLE}\n"
              "        - {material: carbon_epoxy, thickness: 0.004, angle: 30deg}\n"
              "        - {material: glass_epoxy, thickness: 0.0005, angle: ANGLE}\n")
    ply = tmp_path / "ply.yaml"
    ply.write_text("name: ply\nmodel: wave\nbase:\n" + layers.replace("ANGLE", "90deg") + "grid:\n  impact.z: [0.7]\n")
    assert cli("validate", ply).returncode == 0
    ply.write_text("name: ply\nmodel: wave\nbase:\n" + layers.replace("ANGLE", "90") + "grid:\n  impact.z: [0.7]\n")
    r = cli("validate", ply)
    assert r.returncode == 2 and "angle" in r.stderr, r.stderr

    # several files at once, each bat under its own rule set: the wood bat judged by the
    # NCAA's and MLB's (3 limits each), the alloy bat by the NCAA's alone (MLB's rules are for
    # one piece of solid wood: not a failure of the alloy bat, but not its rules)
    r = cli("compare", a, w)
    assert r.returncode == 0, r.stderr
    kept = {}
    for line in r.stdout.splitlines():
        m = re.search(r" (\d+)/(\d+) +(\S+\.h5)", line)
        if m:
            kept[pathlib.Path(m.group(3)).stem] = (int(m.group(1)), int(m.group(2)))
    assert kept["alloy"][1] == 3 and kept["wood"] == (6, 6), r.stdout

    # the profile as a shop would turn it: diameters in inches, rounded to what a lathe holds
    text = batstudy.export_profile(a, units="in")
    header = next(l for l in text.splitlines() if not l.startswith("#"))
    assert header == "z_in,diameter_in,wall_in"
    rows = [l.split(",") for l in text.splitlines() if l and l[0].isdigit()]
    # stations and diameters to a thousandth of an inch, the wall to a ten-thousandth
    assert all(len(c.split(".")[-1]) == 3 for row in rows for c in row[:2])
    assert all(len(row[2].split(".")[-1]) == 4 for row in rows)
    assert math.isclose(max(float(r[1]) for r in rows), 2 * 0.03333 / 0.0254, abs_tol=0.001)


def test_the_field_analyst(tmp_path):
    """A batted ball in mph and degrees with the spin a batted ball has; a bare 100 refused;
    a tracked-bat CSV read from the DataFrame already in the notebook; the same collision in
    the trade's units and in SI."""
    pd = pytest.importorskip("pandas")
    r = cli("fly", "--exit-speed", "100mph", "--launch-angle", "28deg", "--backspin", "2000rpm")
    knuckle = cli("fly", "--exit-speed", "100mph", "--launch-angle", "28deg", "--backspin", "0rpm")
    assert r.returncode == 0 and knuckle.returncode == 0, r.stderr + knuckle.stderr
    carry = lambda out: float(re.search(r"\(([\d.]+) ft\)", out).group(1))
    # the Magnus lift of a batted ball's backspin carries it farther than a knuckleball
    assert carry(r.stdout) > carry(knuckle.stdout) + 20
    bare = cli("fly", "--exit-speed", "100", "--launch-angle", "28deg", "--backspin", "2000rpm")
    assert bare.returncode == 2 and "100mph" in bare.stderr, bare.stderr
    no_spin = cli("fly", "--exit-speed", "100mph", "--launch-angle", "28deg")
    assert no_spin.returncode == 2 and "backspin" in no_spin.stderr

    csv = ROOT / "data" / "bat_tracking_2025.csv"
    from batstudy import tracking
    swings = tracking.read(pd.read_csv(csv))
    assert swings.identical(tracking.read(csv).assign_attrs(swings.attrs))
    assert 0 < swings.sizes["swing"] and swings["bat_speed"].attrs["units"] == "m/s"
    assert float(swings["bat_speed"].max()) < 100 * 0.44704

    si = batstudy.simulate({"ball": {"speed": 90 * 0.44704}, "impact": {"z": 28 * 0.0254}})
    trade = batstudy.simulate({"ball": {"speed": "90mph"}, "impact": {"z": "28in"}})
    assert si["exit_speed"] == trade["exit_speed"]
