"""`batstudy.export_profile` from the installed wheel: a hollow bat written as a profile CSV
in inches reads back (`bat.profile.csv`) as the same bat, mass and moment of inertia within
0.1 % (conservation of the geometry: equal profiles, equal integrals); a bat the file does not
hold is refused, naming the ones it does."""

import pytest
import xarray as xr

import batstudy


def test_a_hollow_bat_reads_back_as_itself(tmp_path):
    out = tmp_path / "alloy.h5"
    batstudy.run(
        {"name": "alloy", "base": {"bat": {"preset": "alloy_bbcor"}}, "grid": {"impact.z": [0.7]}},
        out,
        progress=False,
    )
    csv = tmp_path / "alloy.csv"
    text = batstudy.export_profile(out, units="in", path=csv)
    assert text.splitlines()[3] == "z_in,diameter_in,wall_in"
    assert csv.read_text() == text
    study = tmp_path / "back.yaml"
    study.write_text(
        "name: back\nbase:\n  bat: {preset: aluminum, profile: {csv: alloy.csv},"
        " material: {density: 2830, youngs_modulus: 7.17e10}}\ngrid:\n  impact.z: [0.7]\n"
    )
    back = tmp_path / "back.h5"
    batstudy.run(study, back, progress=False)
    with xr.open_dataset(out, engine="h5netcdf", group="bat") as a, xr.open_dataset(
        back, engine="h5netcdf", group="bat"
    ) as b:
        for v in ("mass", "moment_of_inertia_knob6"):
            assert abs(float(b[v][0]) / float(a[v][0]) - 1) < 1e-3, v


def test_a_bat_not_in_the_file_is_refused(tmp_path):
    out = tmp_path / "two.h5"
    batstudy.run(
        {"name": "two", "base": {}, "grid": {"bat.preset": ["r161", "aluminum"], "impact.z": [0.7]}},
        out,
        progress=False,
    )
    with pytest.raises(batstudy.ResultsFileError, match="0: r161; 1: aluminum"):
        batstudy.export_profile(out, bat="steel")
    assert "wall_mm" in batstudy.export_profile(out, bat=1, units="mm")
