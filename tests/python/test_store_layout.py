"""The results layout as outside scripts see it: h5py, xarray (h5netcdf) and the project's
layout checker (scripts/check_layout.py). Builds its fixtures with cargo
(tests/store_roundtrip.rs, write_python_fixture).

Run: pytest tests/python  (needs h5py, xarray, h5netcdf; skipped only when cargo is absent)."""
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")
xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

from conftest import assert_layout_ok  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    if shutil.which("cargo") is None:
        pytest.skip("cargo not found: cannot build the fixture files")
    d = tmp_path_factory.mktemp("store")
    subprocess.run(
        ["cargo", "test", "--quiet", "--test", "store_roundtrip", "write_python_fixture",
         "--", "--ignored", "--exact"],
        cwd=ROOT, check=True, env={**os.environ, "BATSTUDY_STORE_FIXTURES": str(d)},
    )
    return d


GROUPS = ["summary", "sweet_spot", "history", "bat", "errors"]


@pytest.mark.parametrize("name", ["synth.h5", "zip.h5", "partial.h5", "single.h5"])
def test_check_layout_passes(files, name):
    assert_layout_ok(files / name)


def test_root_attributes(files):
    with h5py.File(files / "synth.h5", "r") as f:
        a = f.attrs
        for k in ["Conventions", "title", "batstudy_version", "git_commit", "git_dirty", "created",
                  "host", "threads", "command_line", "study_yaml", "study_sha256", "layout_version"]:
            assert k in a, k
        assert a["Conventions"] == "CF-1.8"
        assert int(a["layout_version"]) == 7
        assert a["complete"] == 1


@pytest.mark.parametrize("group", GROUPS)
def test_every_group_opens_with_named_dims_units_long_names(files, group):
    ds = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group=group)
    for name, v in ds.variables.items():
        assert not any(d.startswith("phony_dim") for d in v.dims), (group, name, v.dims)
        # layout 3: numbers have units, text has none; every variable a short long_name
        # (a variable whose rows have units of their own names them: `units_from`)
        has_units = "units" in v.attrs or v.attrs.get("units_from") in ds
        assert has_units == (v.dtype.kind not in "OUS"), (group, name, v.attrs)
        assert 0 < len(v.attrs["long_name"]) <= 40, (group, name)
    for d in ds.dims:
        assert d in ds.coords, (group, d)


def test_summary_values_and_selection(files):
    ds = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group="summary")
    assert ds.exit_speed.dims == ("swing_omega", "impact_z")
    assert ds.status.dtype == np.int8
    assert int((ds.status == 1).sum()) == 4
    assert np.isnan(ds.exit_speed.where(ds.status == 1)).all()
    curve = ds.exit_speed.sel(swing_omega=-30.0)
    assert curve.dims == ("impact_z",)
    assert ds.point_id.dtype == np.uint64
    assert ds.exit_speed.attrs["units"] == "m/s"
    assert ds.exit_speed.attrs["long_name"] == "exit speed"
    assert "CM frame" in ds.exit_speed.attrs["description"]


def test_sweet_spot_and_history(files):
    sw = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group="sweet_spot")
    assert sw.position.dims == ("swing_omega",)
    assert ((sw.position > 0.6) & (sw.position < 0.75)).all()
    h = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group="history")
    assert h.displacement.dims == ("swing_omega", "impact_z", "time", "z")
    assert h.force.dtype == np.float32
    assert h.time.size == 20 and h.z.size == 5
    one = h.force.isel(swing_omega=0, impact_z=0)
    assert one.dims == ("time",) and np.isfinite(one).all()
    # CF's time axis, as CF names it (axis T, standard_name time), for tools that look for it
    import h5py

    with h5py.File(files / "synth.h5", "r") as f:
        t = f["history/time"].attrs
        assert (t["axis"], t["standard_name"], t["units"]) == ("T", "time", "s")


def test_bat_group(files):
    b = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group="bat")
    assert list(b.bat.values) == ["r161", "r161, bat.material.density=700"]
    assert b.mode_frequency.dims == ("bat", "mode")
    assert np.isnan(b.mode_frequency.values[1, 2])


def test_errors_group(files):
    e = xr.open_dataset(files / "synth.h5", engine="h5netcdf", group="errors")
    assert e.sizes["error"] == 4
    assert "solver diverged" in str(e.message.values[0])


def test_zip_dim_coordinates(files):
    ds = xr.open_dataset(files / "zip.h5", engine="h5netcdf", group="summary")
    assert ds.exit_speed.dims == ("point", "impact_z")
    assert "ball_speed" in ds.coords and "bat_preset" in ds.coords
    assert list(ds.bat_preset.values) == ["r161", "c243"]
    assert "sweet_spot" in h5py.File(files / "zip.h5", "r")


def test_partial_file_marks_not_computed(files):
    ds = xr.open_dataset(files / "partial.h5", engine="h5netcdf", group="summary")
    assert int((ds.status == -1).sum()) == 22
    with h5py.File(files / "partial.h5", "r") as f:
        assert f.attrs["complete"] == 0
        assert f.attrs["n_done"] == 5


@pytest.mark.parametrize("group", ["summary", "errors", "bat"])
def test_single_point_study_opens(files, group):
    ds = xr.open_dataset(files / "single.h5", engine="h5netcdf", group=group)
    if group == "summary":
        assert ds.exit_speed.dims == () and int(ds.status) == 0
    if group == "errors":
        assert ds.sizes["error"] == 0
