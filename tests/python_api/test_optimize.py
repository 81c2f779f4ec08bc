"""`batstudy.optimize` from the installed wheel: the rigid bat's best impact point
(closed form: at rest, the centre of mass, Brody 1986) found from a dict, the record of the
search in `/optimize`, a bad study refused."""

import pytest

import batstudy

STUDY = {
    "name": "best_point",
    "model": "rigid",
    "base": {"impact": {"z": 0.6}},
    "grid": {"swing.cm_speed": [0]},
    "optimize": {
        "max_evaluations": 200,
        "tolerance": 1e-14,
        "variables": {"impact.z": {"min": 0.40, "max": 0.83}},
        "objective": {"maximize": "exit_speed"},
    },
}


def test_optimize_finds_the_centre_of_mass(tmp_path):
    import xarray as xr

    out = tmp_path / "best.h5"
    tree = batstudy.optimize(STUDY, out)
    o, best = tree["optimize"], tree["optimize/best"]
    with xr.open_dataset(out, engine="h5netcdf", group="bat") as b:
        z_cm = float(b.z_cm[0])
    assert abs(float(best.design.sel(variable="impact.z")) - z_cm) < 1e-4
    assert o.sizes["candidate"] == int(o.attrs["evaluations"]) > 5
    assert (o.status.values == 0).all()
    # the file holds the study at the best design too
    with xr.open_dataset(out, engine="h5netcdf", group="summary") as s:
        assert abs(float(s.exit_speed.max()) - float(best.objective)) < 1e-12


def test_optimize_refuses_a_study_without_the_block(tmp_path):
    with pytest.raises(batstudy.StudyError, match="no `optimize` block"):
        batstudy.optimize({k: v for k, v in STUDY.items() if k != "optimize"}, tmp_path / "x.h5")


def test_a_dict_reads_its_profile_from_the_working_folder(tmp_path, monkeypatch):
    """A dict's relative profile path is the working folder's (it was a temporary folder's,
    so the profile was never found), and NumPy values in it are numbers."""
    import numpy as np

    monkeypatch.chdir(tmp_path)
    (tmp_path / "bat.csv").write_text("z,radius\n0,0.012\n0.5,0.016\n0.84,0.033\n")
    study = {
        **STUDY,
        "base": {"impact": {"z": np.float64(0.6)}, "bat": {"profile": {"csv": "bat.csv"}}},
        "grid": {"swing.cm_speed": np.array([0])},
        "optimize": {**STUDY["optimize"], "max_evaluations": np.int64(30)},
    }
    o = batstudy.optimize(study, "out.h5")["optimize"]
    assert 5 < o.sizes["candidate"] <= 30
    assert (tmp_path / "out.h5").is_file()


@pytest.mark.parametrize(
    "change, field",
    [
        ({"max_evaluations": 0}, "optimize.max_evaluations"),
        ({"objective": {"maximize": "exit_sped"}}, "optimize.objective.maximize"),
        ({"variables": {"impact.z": {"min": 0.83, "max": 0.40}}}, "optimize.variables.impact.z"),
    ],
)
def test_validate_and_plan_refuse_what_the_command_refuses(change, field):
    """`validate()` and `plan()` check the `optimize` block as `batstudy optimize` does (they
    accepted these three blocks, which the command refuses with exit status 2)."""
    bad = {**STUDY, "optimize": {**STUDY["optimize"], **change}}
    for call in (batstudy.validate, batstudy.plan):
        with pytest.raises(batstudy.StudyError, match=field.replace(".", r"\.")):
            call(bad)
