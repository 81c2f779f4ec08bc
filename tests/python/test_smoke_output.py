"""The CI smoke study's real output (studies/smoke.yaml, run on 2 threads by scripts/test.sh),
opened the way users open it: h5py, xarray with the h5netcdf engine, and the project's
layout checker (scripts/check_layout.py). Physics spot checks compare it with closed forms
computed here from the stored bat properties, independent of the Rust code.

Needs SMOKE_H5 (set by scripts/test.sh); skipped without it."""
import os

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")
xr = pytest.importorskip("xarray")

from conftest import assert_layout_ok  # noqa: E402

import batstudy  # noqa: E402
from batstudy._open import history_grid_index  # noqa: E402

SMOKE = os.environ.get("SMOKE_H5")
pytestmark = pytest.mark.skipif(not SMOKE, reason="SMOKE_H5 not set (scripts/test.sh sets it)")


def open_group(group):
    return xr.open_dataset(SMOKE, engine="h5netcdf", group=group)


def test_h5py_sees_every_group_and_the_study_text():
    with h5py.File(SMOKE, "r") as f:
        for g in ["summary", "sweet_spot", "history", "bat", "errors"]:
            assert g in f, g
        assert "name: smoke" in f.attrs["study_yaml"]
        assert f.attrs["threads"] == 2  # run with --jobs 2
        assert f.attrs["complete"] == 1


def test_layout_check_passes():
    assert_layout_ok(SMOKE)


def test_xarray_dims_coordinates_and_units():
    s = open_group("summary")
    assert s.exit_speed.dims == ("model", "swing_omega", "impact_z", "case")
    assert list(s.model.values) == ["wave", "rigid"]
    assert s.exit_speed.attrs["units"] == "m/s"
    assert int((s.status != 0).sum()) == 0, "every smoke point succeeds"
    # Selection by coordinate value works as the README promises.
    base = s.exit_speed.sel(model="wave", swing_omega=0, case=0)
    assert base.sizes == {"impact_z": 4}
    h = open_group("history")
    # the displacement in modal form (the default): batstudy.open computes y(z, t) from it
    assert h.modal_coordinate.dims[-2:] == ("bat_mode", "time")
    assert h.static_shape.dims[-1] == "shape_point" and "z" in h.coords
    d = batstudy.open(SMOKE)["history"]["displacement"]
    assert d.dims == ("history", "time", "z") and np.isfinite(d.isel(history=0).values).any()


def test_rigid_points_match_brody_closed_form():
    # docs/physics.md, rigid-body model: v_exit = v (e − m/M*)/(1 + m/M*) at ω = 0,
    # M* = M / (1 + M l²/I), l = z − z_cm; M, I, z_cm from /bat.
    s = open_group("summary").sel(model="rigid", swing_omega=0, case=0)
    bat = open_group("bat")
    i = int(open_group("summary").bat_index.sel(model="rigid", swing_omega=0, case=0).values[0])
    M, I, zcm = (float(bat[k].values[i]) for k in ("mass", "moment_of_inertia", "z_cm"))
    m, v, e = 0.145, 40.0, 0.5
    for z, got in zip(s.impact_z.values, s.exit_speed.values):
        l = z - zcm
        ratio = m * (1 / M + l * l / I)
        assert got == pytest.approx(v * (e - ratio) / (1 + ratio), rel=1e-9)


def test_wave_energy_partition_closes():
    # Energy conservation: what the ball and bat keep plus what the ball's hysteresis
    # dissipates equals the initial kinetic energy (to the integrator's accuracy).
    s = open_group("summary").sel(model="wave")
    total = (s.energy_ball_final + s.energy_ball_loss + s.energy_bat_rigid
             + s.energy_bat_vibration + s.energy_hoop)
    np.testing.assert_allclose(total.values, s.energy_initial.values, rtol=1e-3)


def test_histories_only_where_asked():
    # studies/smoke.yaml: history.only = {impact.z: [0.60], model: [wave]}.
    h = open_group("history")
    recorded = np.isfinite(h.force).any("time")
    assert bool(recorded.sel(model="wave", impact_z=0.6, swing_omega=0).all())
    assert not bool(recorded.sel(model="rigid").any())
    assert not bool(recorded.sel(model="wave", impact_z=0.5).any())
    assert not bool(recorded.sel(model="wave", swing_omega=-30).any())


def test_displacement_at_any_z_is_the_documented_reconstruction():
    """open(path, z=...) computes the modal form's displacement at any positions: the two
    lines of docs/layout.md (h5py and np.interp between the bat's shape points), NaN beyond
    the bat; and at the study's grid by default."""
    zq = np.array([0.0, 0.0013, 0.1, 0.4567, 0.6, 0.83, 0.84, 0.95, 1.2])
    tree = batstudy.open(SMOKE, z=zq)
    h = tree["history"].to_dataset()
    np.testing.assert_array_equal(h.z.values, zq)
    index = history_grid_index(tree)  # each row's position along the summary's dims
    dims = list(tree["summary"]["status"].dims)
    with h5py.File(SMOKE, "r") as f:
        hg, bat = f["history"], f["bat"]
        for row in range(0, h.sizes["history"], 5):
            i = tuple(int(index[d][row]) for d in dims)
            b = f["summary/bat_index"][i]
            k = np.isfinite(bat["shape_z"][b])
            y = hg["modal_coordinate"][i].T @ bat["mode_shape"][b][:, k] + np.outer(hg["bat_load"][i], hg["static_shape"][i][k])
            want = np.array([np.interp(zq, bat["shape_z"][b][k], r, left=np.nan, right=np.nan) for r in y])
            got = h.displacement.isel(history=row).values
            np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)
            assert np.isnan(got[:, zq > bat["length"][b]]).all()
    default = batstudy.open(SMOKE)["history"].to_dataset()
    again = batstudy.open(SMOKE, z=default.z.values)["history"].to_dataset()
    np.testing.assert_array_equal(default.displacement.isel(history=0).values,
                                  again.displacement.isel(history=0).values)

