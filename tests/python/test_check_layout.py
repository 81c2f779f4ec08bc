"""The layout checker itself (scripts/check_layout.py): it passes real files of every shape the
layout allows (with and without /history, with and without an impact_z dim, with failed
points), and it catches a file broken in each of the ways docs/layout.md rules out.

Each broken file is a copy of a good one with one thing changed through h5py; the test asserts
that the checker exits 1 and names that problem, and that the good file did not already have
it. Needs BATSTUDY_BIN (set by scripts/test.sh) to write the real files; skipped without it."""
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")
xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

from conftest import run_check_layout  # noqa: E402

BIN = os.environ.get("BATSTUDY_BIN")
needs_bin = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")

# A small wave study with histories and failed points (a step budget of 300 is far too few
# for a collision: the points of case 1 fail when they run).
WITH_HISTORY = """\
name: checker_fixture
model: wave
base:
  bat: {preset: r161}
grid:
  swing.omega: [0, -30]
  impact.z: {range: [0.60, 0.75, 0.01]}
points:
  name: case
  sets:
    - {}
    - {numerics.max_steps: 300}         # too few steps for a collision: fails when run
history: {fields: [force, displacement], interval: 1.0e-5, duration: 1.0e-3, z_step: 0.05,
          only: {impact.z: [0.70]}}
"""
# Summary only: /history exists only when a study asks for histories.
SUMMARY_ONLY = """\
name: summary_only
model: wave
base:
  bat: {preset: r161}
grid:
  impact.z: {range: [0.60, 0.75, 0.01]}
"""
# No impact_z dim, so no /sweet_spot; a zip dim (integer index coordinate).
NO_IMPACT_Z = """\
name: no_impact_z
model: rigid
base:
  bat: {preset: r161}
  impact: {z: 0.70}
zip:
  - {swing.omega: [0, -20, -40], ball.speed: [35, 40, 45]}
"""


def run_study(text, tmp_path, name, expect_rc):
    study = tmp_path / f"{name}.yaml"
    study.write_text(text)
    out = tmp_path / f"{name}.h5"
    r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--jobs", "1", "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == expect_rc, r.stderr
    return out


@pytest.fixture(scope="module")
def good(tmp_path_factory):
    if not BIN:
        pytest.skip("BATSTUDY_BIN not set (scripts/test.sh sets it)")
    # exit status 1: some points failed (recorded in /errors), the rest written
    return run_study(WITH_HISTORY, tmp_path_factory.mktemp("layout"), "good", 1)


@needs_bin
def test_a_file_with_histories_and_failed_points_passes(good):
    r = run_check_layout(good)
    assert r.returncode == 0 and "layout ok" in r.stdout, r.stdout + r.stderr
    with h5py.File(good, "r") as f:
        assert "history" in f and f.attrs["n_failed"] > 0


@needs_bin
def test_a_summary_only_file_passes(tmp_path):
    out = run_study(SUMMARY_ONLY, tmp_path, "summary_only", 0)
    with h5py.File(out, "r") as f:
        assert "history" not in f
    r = run_check_layout(out)
    assert r.returncode == 0 and "layout ok" in r.stdout, r.stdout + r.stderr


@needs_bin
def test_a_file_without_impact_z_passes(tmp_path):
    out = run_study(NO_IMPACT_Z, tmp_path, "no_impact_z", 0)
    with h5py.File(out, "r") as f:
        assert "sweet_spot" not in f
    r = run_check_layout(out)
    assert r.returncode == 0 and "layout ok" in r.stdout, r.stdout + r.stderr


@needs_bin
def test_histories_compressed_by_the_workers_read_with_standard_filters(tmp_path):
    # the workers shuffle and deflate the history chunks and the finish writes them
    # raw; h5py's standard filters and xarray read them, the same on 1 and 2 threads
    study = tmp_path / "threads.yaml"
    study.write_text(WITH_HISTORY)
    files = []
    for jobs in ["1", "2"]:
        out = tmp_path / f"threads{jobs}.h5"
        r = subprocess.run([BIN, "run", str(study), "-o", str(out), "--jobs", jobs, "--quiet"],
                           capture_output=True, text=True)
        assert r.returncode == 1, r.stderr  # the step-budget case fails, as in `good`
        files.append(out)
    assert files[0].stat().st_size == files[1].stat().st_size
    with h5py.File(files[0], "r") as a, h5py.File(files[1], "r") as b:
        # the displacement in modal form (the default), blocks of modes mode-major
        for name in ["force", "modal_coordinate", "bat_load", "static_shape"]:
            d = a["history"][name]
            assert d.compression == "gzip" and d.shuffle, name
            va, vb = d[...], b["history"][name][...]
            assert np.isfinite(va).any(), name
            np.testing.assert_array_equal(va, vb)
    h = xr.open_dataset(files[0], engine="h5netcdf", group="history")
    assert np.isfinite(h.force.values).any()


def test_a_file_that_is_not_hdf5_cannot_be_checked(tmp_path):
    p = tmp_path / "not.h5"
    p.write_text("not HDF5\n")
    r = run_check_layout(p)
    assert r.returncode == 2, r.stdout + r.stderr


# ---- broken copies --------------------------------------------------------------------


def drop_units(f):
    del f["summary/exit_speed"].attrs["units"]


def wrong_units(f):
    f["summary/contact_time"].attrs["units"] = "ms"


def drop_long_name(f):
    del f["bat/mass"].attrs["long_name"]


def detach_scale(f):
    ds = f["summary/peak_force"]
    ds.dims[0].detach_scale(f["summary/swing_omega"])


def drop_variable(f):
    del f["summary/impulse"]


def drop_errors(f):
    del f["errors"]


def drop_sweet_spot(f):
    del f["sweet_spot"]


def drop_history(f):
    del f["history"]


def wrong_count(f):
    f.attrs["n_done"] = np.int64(int(f.attrs["n_done"]) - 1)


def edit_study_text(f):
    f.attrs["study_yaml"] = f.attrs["study_yaml"] + "# edited\n"


def value_at_failed_point(f):
    status = f["summary/status"][()]
    v = f["summary/exit_speed"][()]
    v[status == 1] = 1.0
    f["summary/exit_speed"][...] = v


def fill_value_on_integers(f):
    f["summary/status"].attrs["_FillValue"] = np.int8(-1)


def error_row_names_an_ok_point(f):
    status = f["summary/status"][()].ravel()
    f["errors/flat_index"][0] = np.uint64(int(np.flatnonzero(status == 0)[0]))


BROKEN = [
    (drop_units, "/summary/exit_speed: no `units` attribute"),
    (wrong_units, "/summary/contact_time: units 'ms', expected 's'"),
    (drop_long_name, "/bat/mass: no (or an empty) `long_name`"),
    (detach_scale, "/summary/peak_force: axis 0 has no dimension scale attached"),
    (drop_variable, "/summary/impulse: missing"),
    (drop_errors, "/errors: group missing"),
    (drop_sweet_spot, "/sweet_spot: group missing"),
    (drop_history, "/history: group missing"),
    (wrong_count, "n_done"),
    (edit_study_text, "study_sha256 is not the SHA-256 of study_yaml"),
    (value_at_failed_point, "/summary/exit_speed: a value where the point failed"),
    (fill_value_on_integers, "/summary/status: integer variable with a `_FillValue`"),
    (error_row_names_an_ok_point, "/errors/flat_index: names a point whose status is not 1"),
]


@needs_bin
@pytest.mark.parametrize("breakage,message", BROKEN, ids=[b.__name__ for b, _ in BROKEN])
def test_the_checker_finds_a_broken_file(good, tmp_path, breakage, message):
    clean = run_check_layout(good)
    assert message not in clean.stdout, clean.stdout
    broken = tmp_path / "broken.h5"
    shutil.copyfile(good, broken)
    with h5py.File(broken, "r+") as f:
        breakage(f)
    r = run_check_layout(broken)
    assert r.returncode == 1, r.stdout + r.stderr
    assert message in r.stdout, r.stdout + r.stderr
    assert "layout ok" not in r.stdout
