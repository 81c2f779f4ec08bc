"""Every bundled study (studies/*.yaml) runs and writes a file with the public layout: the
project's checker scripts/check_layout.py passes on each, and xarray opens every group.

The bundled studies also keep what the figure scripts need, beyond what the layout requires
of any study (docs/layout.md, "/summary"): named `swing_omega` and `impact_z` dims (a fixed
swing is a one-value grid axis) and a `/history` group with `force` and `displacement`
(several studies once wrote no /history and no swing_omega dim). Needs BATSTUDY_BIN (set by
scripts/test.sh); skipped without it.

The bundled studies store the displacement in modal form (the default); each is
run again with `history.displacement: grid`, and the displacement `batstudy.open` computes
from the modal form equals the grid's, value by value, to float32 rounding of the history's
largest displacement Y: within one f32 ulp of Y (the modal form is kept to half an ulp of
Y, by an analytic bound, docs/layout.md; the grid's own f32 rounding adds at most another
half), NaN at the same places."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

xr = pytest.importorskip("xarray")

from conftest import assert_layout_ok  # noqa: E402

np = pytest.importorskip("numpy")
import batstudy  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
BIN = os.environ.get("BATSTUDY_BIN")
STUDIES = sorted((ROOT / "studies").glob("*.yaml"))
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")


@pytest.mark.parametrize("study", STUDIES, ids=[s.stem for s in STUDIES])
def test_bundled_study_has_the_public_layout(study, tmp_path):
    out = tmp_path / f"{study.stem}.h5"
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--jobs", "2", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert_layout_ok(out)
    if "preset: wall" in study.read_text():
        # A ball test (the wall): no bat, no impact position, no sweet spot; its figure.
        for group in ["summary", "history", "bat", "errors"]:
            xr.open_dataset(out, engine="h5netcdf", group=group).close()
        figures_dir = tmp_path / "figures"
        r = subprocess.run([sys.executable, str(ROOT / "scripts" / "figures.py"), str(out), "-o",
                            str(figures_dir), "--only", "ball_tests"], capture_output=True, text=True)
        assert r.returncode == 0 and (figures_dir / "ball_tests.png").stat().st_size > 5_000, r.stdout + r.stderr
        return
    if "\noptimize:" in study.read_text():
        # a design study's `run` is its start design, for `batstudy optimize`
        # (tested in Rust: tests/optimize_*.rs); it keeps no histories
        for group in ["summary", "sweet_spot", "bat", "errors"]:
            xr.open_dataset(out, engine="h5netcdf", group=group).close()
        return
    for group in ["summary", "sweet_spot", "history", "bat", "errors"]:
        xr.open_dataset(out, engine="h5netcdf", group=group).close()
    with xr.open_dataset(out, engine="h5netcdf", group="summary") as s:
        # a batter sets the swing itself: its studies sweep where the ball is met
        swept = {"impact_offset"} if "batter:" in study.read_text() else {"swing_omega", "impact_z"}
        assert swept <= set(s.exit_speed.dims), s.exit_speed.dims
    with xr.open_dataset(out, engine="h5netcdf", group="history") as h:
        modal = {"modal_coordinate", "bat_load", "static_shape"}
        assert {"force"} | modal <= set(h.data_vars), list(h.data_vars)
        assert "displacement" not in h.data_vars, "the modal form is the default"
    grid = tmp_path / f"{study.stem}-grid.yaml"
    grid.write_text(grid_form_of_the_histories(study.read_text(), out))
    out_grid = tmp_path / f"{study.stem}-grid.h5"
    r = subprocess.run([BIN, "run", str(grid), "-o", str(out_grid), "--jobs", "2", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert_layout_ok(out_grid)
    assert_same_displacement(out, out_grid)
    with pytest.raises(ValueError, match="modal form"):
        batstudy.open(out_grid, z=[0.5])


def grid_form_of_the_histories(text, out):
    """The study again with `history.displacement: grid`, its grid cut to the points that
    record a history: each grid axis `history.only` names keeps the values it lists, as the
    first run's file holds them (the same floats, so the same collisions bit for bit), in the
    grid's order. The histories are the same, in the same order; the rest is not run twice."""
    yaml = pytest.importorskip("yaml")
    study = yaml.safe_load(text)
    assert "history" in study
    history = study["history"]
    history["displacement"] = "grid"
    summary = batstudy.open(out)["summary"].to_dataset()
    for path, wanted in history.get("only", {}).items():
        dim = path.replace(".", "_")
        if path not in study.get("grid", {}) or dim not in summary.coords:
            continue  # set by a `points` block: left as it is
        taken = summary[dim].values.tolist()
        keep = [v for v in taken if any(same_value(v, w) for w in wanted)]
        assert keep, (path, wanted, taken)
        study["grid"][path] = keep
    return yaml.safe_dump(study, sort_keys=False)


def same_value(taken, wanted):
    if isinstance(taken, str) or isinstance(wanted, str):
        return str(taken) == str(wanted)
    return bool(np.isclose(taken, wanted, rtol=1e-9, atol=1e-12))


def assert_same_displacement(modal, grid):
    """The displacement computed from the modal form equals the grid form's (f32) value by
    value to f32 rounding of each history's largest |y|: within one f32 ulp of it, NaN at
    the same places."""
    hm = batstudy.open(modal)["history"].to_dataset()
    hg = batstudy.open(grid)["history"].to_dataset()
    assert hg.displacement.dtype == np.float32
    assert hm.sizes["history"] == hg.sizes["history"] > 0
    for name in ("impact_z", "swing_omega", "time", "z"):
        if name in hg.variables:  # a batter's study has no swing_omega
            np.testing.assert_array_equal(hm[name].values, hg[name].values)
    y, g = hm.displacement.values, hg.displacement.values
    assert y.shape == g.shape
    np.testing.assert_array_equal(np.isfinite(y), np.isfinite(g))
    ok = np.isfinite(g)
    assert ok.any()
    g64 = np.where(ok, g, 0.0).astype(np.float64)
    rows = g64.reshape(g64.shape[0], -1)
    ulp = np.spacing(np.abs(rows).max(axis=1).astype(np.float32)).astype(np.float64)
    diff = np.abs(np.where(ok, y, 0.0) - g64).reshape(rows.shape)
    worst = (diff / ulp[:, None]).max()
    assert worst <= 1.0, f"a value {worst:.3f} f32 ulps of its history's largest |y| apart"
