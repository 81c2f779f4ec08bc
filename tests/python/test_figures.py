"""Tests of the paper's figures (batstudy.plot, from the sources) and of scripts/figures.py,
which calls it.

- On the CI smoke study output (env var SMOKE_H5, written by scripts/test.sh before pytest):
  every figure is written and is a real image.
- On a synthetic file following docs/layout.md (tests/python/synthetic_results.py), so the
  figures stay testable without the Rust build: the same check.
- The curve logic on small hand-made inputs: one-factor selection, rigid-motion removal.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr
from PIL import Image

import synthetic_results
from batstudy import plot

ROOT = Path(__file__).resolve().parents[2]

MIN_BYTES = 5_000


def assert_all_figures(outdir: Path, log: str = ""):
    for name in plot.FIGURES:
        path = outdir / plot.file_name(name)
        assert path.exists(), f"{path.name} not written; batstudy.plot said:\n{log}"
        assert path.stat().st_size > MIN_BYTES, f"{path.name} is only {path.stat().st_size} bytes"
        with Image.open(path) as im:
            im.verify()
        with Image.open(path) as im:
            assert im.size[0] > 200 and im.size[1] > 150
            if name.startswith("anim"):
                assert 2 <= im.n_frames <= plot.MAX_FRAMES


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    return synthetic_results.write(tmp_path_factory.mktemp("synthetic") / "synthetic.h5")


def run_all(path, outdir, capsys):
    status = plot.main([str(path), "-o", str(outdir)])
    out = capsys.readouterr()
    log = out.out + out.err
    assert status == 0, f"a figure failed:\n{log}"
    assert_all_figures(outdir, log)


def test_smoke_study_figures(tmp_path, capsys):
    smoke = os.environ.get("SMOKE_H5")
    if not smoke:
        pytest.skip("SMOKE_H5 is not set (scripts/test.sh sets it to the smoke study's output)")
    assert Path(smoke).exists(), f"SMOKE_H5={smoke} does not exist"
    run_all(smoke, tmp_path, capsys)


def test_synthetic_figures(synthetic, tmp_path, capsys):
    run_all(synthetic, tmp_path, capsys)


def test_only_selects_figures(synthetic, tmp_path):
    written = plot.figures(synthetic, tmp_path, only="fig6,fig13b,bat_profiles", format="svg")
    names = ["bat_profiles.svg", "fig06_exit_speed_vs_omega.svg", "fig13b_aluminum.svg"]
    assert sorted(p.name for p in written) == names
    assert sorted(p.name for p in tmp_path.iterdir()) == names
    with pytest.raises(ValueError, match="unknown figure"):
        plot.figures(synthetic, tmp_path, only="fig99")


def test_the_script_draws_with_the_package_on_two_processes(synthetic, tmp_path):
    """scripts/figures.py (what scripts/run.sh runs with .venv's Python, which has no wheel)
    finds the package in the sources and draws on two processes."""
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "figures.py"), synthetic, "-o", str(tmp_path),
                        "--only", "fig6,fig8,anim", "--jobs", "2"], capture_output=True, text=True, cwd="/")  # fmt: skip
    assert r.returncode == 0, r.stdout + r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "anim_displacement.gif", "fig06_exit_speed_vs_omega.png", "fig08_optimal_position_vs_omega.png"]  # fmt: skip
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "figures.py"), str(tmp_path / "missing.h5")],
                       capture_output=True, text=True)  # fmt: skip
    assert r.returncode == 2 and "missing.h5" in r.stderr


def test_missing_data_is_skipped(tmp_path, capsys):
    """A plain grid study (swing_omega x impact_z, no cases, no history, no /bat): Fig. 6
    is drawn from the grid axis, the figures it cannot make are skipped, none fails."""
    z = np.linspace(0.5, 0.8, 7)
    omega = np.array([0.0, -20.0, -40.0])
    speed = 20 + 10 * np.exp(-(((z[None, :] - 0.7) / 0.1) ** 2)) - 0.1 * omega[:, None]
    status = np.zeros(speed.shape, dtype=np.int8)  # every point ran
    ds = xr.Dataset({"exit_speed": (("swing_omega", "impact_z"), speed, {"units": "m/s"}),
                     "status": (("swing_omega", "impact_z"), status)},
                    coords={"swing_omega": ("swing_omega", omega, {"units": "rad/s"}),
                            "impact_z": ("impact_z", z, {"units": "m"})})  # fmt: skip
    path = tmp_path / "grid.h5"
    ds.to_netcdf(path, engine="h5netcdf", group="summary")
    # what marks a file as batstudy's (another program's HDF5 file is refused)
    with h5py.File(path, "r+") as f:
        f.attrs["layout_version"] = np.int64(5)
    out = tmp_path / "out"
    assert plot.main([str(path), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert (out / "fig06_exit_speed_vs_omega.png").exists()
    assert (out / "fig08_optimal_position_vs_omega.png").exists()
    assert "skip  fig13b_aluminum" in text and "skip  fig14_displacement_along_bat" in text
    # a file without a design search or a sample: those figures say what makes them
    assert "skip  search: no /optimize group" in text and "skip  uncertainty: no /uncertainty group" in text
    with plot.Results(path) as res:
        labels = [res.label(c) for c in res.curves]
    assert labels == ["base case", "ω = -20 rad/s", "ω = -40 rad/s"]
    # in figures over ω the base curve says which ω it is (Figs. 6 and 7 once showed only
    # "base case" beside "ω = -10 rad/s" ...)
    with plot.Results(path) as res:
        labels = [res.label(c, always=("swing_omega",)) for c in res.curves]
    assert labels == ["ω = 0 rad/s (base case)", "ω = -20 rad/s", "ω = -40 rad/s"]


def _curve(i, **params):
    return plot.Curve(index={"case": i}, params={"model": "wave", **params}, key=(i,))


def test_one_factor_selection():
    nan = float("nan")
    base = _curve(0, rho=649.0, shell=nan, preset="r161", omega=0.0)
    curves = [
        base,
        _curve(1, rho=700.0, shell=nan, preset="r161", omega=0.0),  # density only
        _curve(2, rho=500.0, shell=nan, preset="r161", omega=0.0),  # density only
        _curve(3, rho=700.0, shell=nan, preset="r161", omega=-20.0),  # density and omega
        _curve(4, rho=649.0, shell=0.01, preset="corked", omega=0.0),  # preset and shell
        _curve(5, rho=649.0, shell=nan, preset="r161", omega=-20.0),  # omega only
    ]
    assert [c.key[0] for c in plot.one_factor(curves, base, "rho")] == [2, 0, 1]
    assert [c.key[0] for c in plot.one_factor(curves, base, "omega")] == [5, 0]
    corked = plot.select(curves, base, free={"shell"}, where={"preset": "corked"})
    assert [c.key[0] for c in corked] == [4]
    assert plot.select(curves, base, where={"preset": "corked"}) == []  # shell differs too
    assert plot.differing(curves[3], base) == ["omega", "rho"]


def test_same_treats_nan_as_equal():
    assert plot.same(float("nan"), float("nan"))
    assert not plot.same(float("nan"), 0.0)
    assert plot.same(1.814e10, 1.814e10 * (1 + 1e-12))
    assert not plot.same("free", "fixed")
    assert not plot.same(None, 0.0)


def test_remove_rigid_motion_of_pure_rigid_motion_is_zero():
    t = np.linspace(0, 2e-3, 50)
    z = np.linspace(0, 0.84, 30)
    z_cm = 0.59
    translation = 0.3 * t**2 + 1e-3 * np.sin(3000 * t)
    rotation = -5.0 * t**2
    disp = translation[:, None] + rotation[:, None] * (z[None, :] - z_cm)
    assert np.abs(plot.remove_rigid(disp, z, translation, rotation, z_cm)).max() < 1e-15
    bump = 1e-4 * np.exp(-(((z - 0.6) / 0.05) ** 2))
    flex = plot.remove_rigid(disp + bump[None, :], z, translation, rotation, z_cm)
    np.testing.assert_allclose(flex, np.broadcast_to(bump, flex.shape), atol=1e-15)


def test_rigid_projection_recovers_rigid_motion():
    t = np.linspace(0, 1e-3, 20)
    z = np.linspace(0, 0.84, 43)
    area = np.pi * (0.012 + 0.02 * (z > 0.45)) ** 2
    disp = (2e-3 * t)[:, None] + (-0.5 * t)[:, None] * (z[None, :] - 0.61)
    trans, rot, z_c = plot.rigid_projection(disp, z, area)
    assert np.abs(plot.remove_rigid(disp, z, trans, rot, z_c)).max() < 1e-15
    np.testing.assert_allclose(rot, -0.5 * t, atol=1e-15)


def test_results_reads_synthetic_file(synthetic):
    with plot.Results(synthetic) as res:
        base = res.base()
        assert base.params["bat_preset"] == "r161" and base.params["model"] == "wave"
        assert res.models() == ["wave", "rigid"]
        densities = [c.params["bat_material_density"] for c in plot.one_factor(res.curves, base, "bat_material_density")]
        assert densities == [500.0, 640.0, 649.0, 700.0, 1000.0]
        z_imp, force = res.history_of(base, "force", 0.61)
        assert abs(z_imp - 0.60) < 1e-9 and np.isfinite(force.values).all()
        assert res.history_of(res.partner(base, "rigid"), "force", 0.6) is None  # not recorded
        z_imp, flex = res.flex_displacement(base, 0.6)
        assert np.abs(flex.values).max() < 2.5e-3  # the stand-in pulse only
