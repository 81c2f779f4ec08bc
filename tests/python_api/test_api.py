"""The Python API: simulate, run, open, histories, the `batstudy` command.
Physics references are cited where a number is asserted."""

import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import threading
import time

import h5py
import numpy as np
import pytest
import xarray as xr

import batstudy

# the command the wheel installed, next to this Python (a venv need not be activated)
BATSTUDY = shutil.which("batstudy", path=os.path.dirname(sys.executable)) or "batstudy"


def test_simulate_matches_the_closed_form_of_a_wall():
    # A linear spring with a hysteresis loop that returns e² of the stored energy against an
    # immovable wall sends the ball back at e·v: the definition of the COR (docs/physics.md).
    for v in (10.0, 25.9, 40.0):
        r = batstudy.simulate({"bat": {"preset": "wall"}, "ball": {"speed": v}, "impact": {"z": 0.7}})
        assert r["exit_speed"] == pytest.approx(0.5 * v, rel=2e-4)
        assert r["bbcor"] == pytest.approx(0.5, rel=2e-4)  # the wall's BBCOR is the ball's COR


def test_simulate_takes_numpy_numbers_as_the_numbers_they_are():
    # a NumPy integer or float in a spec is the number it holds (json.dumps refused np.int64)
    plain = batstudy.simulate({"swing": {"omega": -30}, "impact": {"z": 0.7}})
    numpy = batstudy.simulate({"swing": {"omega": np.int64(-30)}, "impact": {"z": np.float64(0.7)}})
    assert numpy["exit_speed"] == plain["exit_speed"]
    with pytest.raises(TypeError, match="a study holds numbers"):
        batstudy.simulate({"impact": {"z": object()}})


def test_simulate_gives_the_bats_card_and_the_fields_verdict():
    # squared up as a study's point is: exit >= 80 % of best_q pitch + (1 + best_q) bat speed
    # (Baseball Savant's definition), with the bat's own best q from its card
    r = batstudy.simulate({"swing": {"omega": -45}, "ball": {"speed": 38}, "impact": {"z": 0.70}})
    bat = r["bat"]
    most = bat["best_q"] * r["pitch_speed_plate"] + (1 + bat["best_q"]) * r["bat_speed_6in"]
    assert r["squared_up"] == float(r["exit_speed_lab"] >= 0.8 * most)
    assert 0.4 < bat["bbcor_max"] < 0.6 and bat["sweet_zone_start"] < bat["bbcor_max_position"] < bat["sweet_zone_end"]
    value, units, margin = bat["rules"]["ncaa_bbcor: bat.bbcor <= 0.5"]
    assert units == "1" and value == bat["bbcor_max"] and abs(margin - (0.5 - value)) < 1e-12
    assert np.isnan(batstudy.simulate({"impact": {"z": 0.7}})["squared_up"])  # no swing


def test_simulate_takes_the_trades_units():
    # 28 in = 0.7112 m and 90 mph = 40.2336 m/s by definition (NIST SP 811); a bare number in
    # the trade's unit where SI is implausible is refused, naming the suffix meant
    si = batstudy.simulate({"ball": {"speed": 90 * 0.44704}, "impact": {"z": 28 * 0.0254}})
    trade = batstudy.simulate({"ball": {"speed": "90mph"}, "impact": {"z": "28in"}})
    assert trade["exit_speed"] == si["exit_speed"]
    with pytest.raises(batstudy.StudyError, match="is not a unit of `impact.z`"):
        batstudy.simulate({"impact": {"z": "28oz"}})
    with pytest.raises(batstudy.StudyError, match="write `34in`"):
        batstudy.simulate({"bat": {"length": 34}, "impact": {"z": 0.7}})


def test_simulate_conserves_energy():
    # Energy balance of the paper's base case: what the ball and bat hold after the
    # collision plus what the ball's hysteresis dissipated is the initial kinetic energy.
    r = batstudy.simulate("impact: {z: 0.7}\n")
    after = (
        r["energy_ball_final"] + r["energy_ball_loss"] + r["energy_bat_rigid"]
        + r["energy_bat_vibration"] + r["energy_hoop"]
    )
    assert after == pytest.approx(r["energy_initial"], rel=1e-3)
    # Nathan (2000)'s R161 (docs/physics.md): 0.885 kg; the preset reproduces it to 2 %
    assert r["bat"]["mass"] == pytest.approx(0.885, rel=0.02)


def test_simulate_gives_every_summary_variable_and_histories():
    r = batstudy.simulate({"impact": {"z": 0.6}}, history={"fields": ["force", "displacement"]})
    with_h5_names = {
        "exit_speed", "exit_speed_lab", "collision_efficiency", "approach_speed", "contact_time",
        "impulse_time_99", "bbcor", "besr", "bpf", "hoop_mode_frequency", "hoop_mode_mass",
        "peak_force", "max_compression", "impulse", "energy_initial", "energy_ball_final",
        "energy_ball_loss", "energy_bat_rigid", "energy_bat_vibration", "energy_hoop",
        "grip_vibration_amplitude", "grip_recoil_speed", "energy_bat_damping",
        "energy_grip_damping", "recontact", "tangential_cor", "bat_speed", "launch_angle",
        "spray_angle", "spin", "sidespin", "carry", "apex", "hang_time", "energy_friction",
    }
    assert with_h5_names <= set(r)
    h = r["history"]
    assert h["force"].shape == h["time"].shape
    assert h["displacement"].shape == (h["time"].size, h["z"].size)
    # the impulse is the integral of the force (trapezoid over the 10 µs samples)
    assert np.trapezoid(h["force"], h["time"]) == pytest.approx(r["impulse"], rel=0.02)
    assert "compression" not in h


def test_simulate_refuses_a_bad_spec_with_its_place():
    with pytest.raises(batstudy.StudyError) as e:
        batstudy.simulate("impact: {z: 0.7}\nball:\n  speed: -3\n")
    text = str(e.value)
    assert "spec:3" in text and "ball.speed" in text, text
    with pytest.raises(batstudy.StudyError, match="bat.material.densty|densty"):
        batstudy.simulate({"impact": {"z": 0.7}, "bat": {"material": {"densty": 600}}})


def test_simulate_releases_the_gil():
    # While one thread simulates, another Python thread keeps running.
    spec = {"impact": {"z": 0.7}, "numerics": {"integrator": "verlet"}}
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.0005)

    t = threading.Thread(target=count)
    t.start()
    before = len(ticks)
    batstudy.simulate(spec)
    during = len(ticks) - before
    done.set()
    t.join()
    assert during > 5, f"the other thread ran {during} times during a Verlet collision"


def test_run_open_and_the_cli_give_the_same_numbers(small_study, tmp_path):
    out = batstudy.run(small_study, output=tmp_path / "a.h5", jobs=2, progress=False)
    assert out == tmp_path / "a.h5" and out.exists()
    cli = tmp_path / "b.h5"
    rc = subprocess.run(
        [BATSTUDY, "run", str(small_study), "-o", str(cli), "--jobs", "1", "--quiet"]
    ).returncode
    assert rc == 0
    with h5py.File(out) as fa, h5py.File(cli) as fb:
        for name in ("exit_speed", "peak_force", "status"):
            np.testing.assert_array_equal(fa["summary"][name][()], fb["summary"][name][()])
    # one collision through simulate() is bit-identical to the same point of the study
    tree = batstudy.open(out)
    s = tree["summary"].to_dataset()
    point = s.sel(case=1, swing_omega=-40.0).isel(impact_z=3)
    one = batstudy.simulate(
        {"bat": {"preset": "aluminum"}, "ball": {"speed": 40},
         "swing": {"omega": -40.0}, "impact": {"z": float(point.impact_z)}}
    )
    assert one["exit_speed"] == float(point.exit_speed)


def test_open_gives_named_dims_resolved_coordinates_and_labels(small_study, tmp_path):
    out = batstudy.run(small_study, output=tmp_path / "r.h5", progress=False)
    tree = batstudy.open(out)
    assert isinstance(tree, xr.DataTree)
    s = tree["summary"]
    assert list(s.dims) == ["swing_omega", "impact_z", "case"]
    # the presets' densities: R161 wood 649 kg/m³ (Nathan 2000), aluminum 2700 (the paper)
    # (the base case and the aluminum cases leave the density to their preset)
    assert list(s["bat_material_density"].values) == [649.0, 2700.0, 2700.0, 700.0]
    assert list(s["case_label"].values) == [
        "base",
        "bat.preset=aluminum",
        "bat.preset=aluminum, hoop.frequency=1500, hoop.mass=0.03",
        "bat.material.density=700",
    ]
    assert not np.isnan(s["hoop_frequency"].values[2])
    # selection by label works without knowing the case numbers
    alu = s.to_dataset().swap_dims(case="case_label").sel(case_label="bat.preset=aluminum")
    assert np.isfinite(alu.exit_speed).all()
    # text coordinates carry no units; every long_name is short
    for name, v in {**s.coords, **s.data_vars}.items():
        if v.dtype.kind in "OUS":
            assert "units" not in v.attrs, name
        assert len(v.attrs.get("long_name", "")) <= 40, name
    assert "position_at_edge" in tree["sweet_spot"]


def test_histories_are_sparse_and_equal_the_dense_file(small_study, tmp_path):
    out = batstudy.run(small_study, output=tmp_path / "h.h5", progress=False)
    tree = batstudy.open(out)
    h = tree["history"]
    assert h.sizes["history"] == 4  # one per case at 0.58 m on the still bat
    assert set(h["impact_z"].values) == {0.58}
    wood = batstudy.histories(tree, case_label="base")
    assert wood.sizes["history"] == 1
    with h5py.File(out) as f:
        dense = f["history/force"]
        summary = f["summary"]
        iz = int(np.argmin(abs(summary["impact_z"][()] - 0.58)))
        np.testing.assert_array_equal(wood.force.values[0], dense[0, iz, 0, :])
    # the sparse rows agree with the summary: the peak of the stored force is peak_force
    # (the history is sampled every 20 µs, so only to within the sampling)
    pf = tree["summary"]["peak_force"].sel(swing_omega=0.0, impact_z=0.58, case=0)
    assert float(wood.force.max()) == pytest.approx(float(pf), rel=0.02)


def test_every_group_opens_with_the_netcdf4_engine(small_study, tmp_path):
    pytest.importorskip("netCDF4")
    out = batstudy.run(small_study, output=tmp_path / "n.h5", progress=False)
    for g in ("summary", "sweet_spot", "history", "bat", "errors"):
        ds = xr.open_dataset(out, group=g, engine="netcdf4")
        assert not [d for d in ds.dims if str(d).startswith("phony_dim")], g
    tree = xr.open_datatree(out, engine="netcdf4")
    assert {"summary", "bat"} <= set(tree.children)


def test_run_refuses_a_bad_study_and_an_existing_output(tmp_path, small_study):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nbase:\n  impact: {z: 0.7}\n  ball: {speed: .nan}\n")
    with pytest.raises(batstudy.StudyError, match="ball.speed"):
        batstudy.run(bad, output=tmp_path / "x.h5", progress=False)
    assert not (tmp_path / "x.h5").exists()
    out = batstudy.run(small_study, output=tmp_path / "y.h5", progress=False)
    with pytest.raises(batstudy.StudyError, match="exists"):
        batstudy.run(small_study, output=out, progress=False)


def test_ctrl_c_stops_like_the_cli_and_resume_finishes(tmp_path, root):
    # A study long enough to interrupt (10 680 points, seconds on one thread); the child
    # process gets a real SIGINT, as a Ctrl-C in a terminal or "interrupt kernel" in Jupyter
    # sends, once its run has begun (the journal exists).
    study = tmp_path / "long.yaml"
    study.write_text(
        "name: long\nmodel: wave\nbase:\n  impact: {z: 0.7}\ngrid:\n"
        "  swing.omega: {linspace: [0, -60, 120]}\n  impact.z: {range: [0.40, 0.84, 0.005]}\n"
    )
    out = tmp_path / "long.h5"
    # Python keeps SIGINT ignored when it starts with it ignored (a shell's background job,
    # as CI may be): give the child the handler an interactive Python has.
    code = (
        "import batstudy, signal, sys\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "try:\n"
        f"    batstudy.run({str(study)!r}, output={str(out)!r}, jobs=1, progress=True)\n"
        "except KeyboardInterrupt as e:\n"
        "    print('INTERRUPTED', e); sys.exit(130)\n"
    )
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    journal = tmp_path / "long.h5.journal"
    deadline = time.monotonic() + 60
    while not journal.exists() and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 130, (stdout, stderr)
    assert "resume=True" in stdout
    assert out.exists()
    with h5py.File(out) as f:
        assert f.attrs["complete"] == 0 and 0 < f.attrs["n_done"] < f.attrs["n_points"]
    batstudy.run(study, output=out, resume=True, progress=False)
    whole = tmp_path / "whole.h5"
    batstudy.run(study, output=whole, progress=False)
    with h5py.File(out) as a, h5py.File(whole) as b:
        assert a.attrs["complete"] == 1
        np.testing.assert_array_equal(a["summary/exit_speed"][()], b["summary/exit_speed"][()])


def test_a_signal_handlers_own_exception_comes_out_as_itself(tmp_path):
    """A handler that raises (a notebook's time limit, a scheduler's SIGTERM hook) stops the
    run as Ctrl-C does, but its exception is raised, not a KeyboardInterrupt."""

    class TimeLimit(Exception):
        pass

    def handler(signum, frame):
        raise TimeLimit("from the handler")

    study = {
        "name": "long",
        "base": {"impact": {"z": 0.7}},
        "grid": {"swing.omega": np.linspace(0, -60, 120), "impact.z": np.arange(0.40, 0.84, 0.005)},
    }
    old = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, 0.3)
    try:
        with pytest.raises(TimeLimit):
            batstudy.run(study, output=tmp_path / "long.h5", jobs=1, progress=False)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def test_the_batstudy_command_has_the_cli_exit_codes(tmp_path, small_study):
    assert subprocess.run([BATSTUDY, "--version"], capture_output=True).returncode == 0
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nbase: {impact: {z: 0.7}, ball: {speedd: 3}}\n")
    r = subprocess.run([BATSTUDY, "validate", str(bad)], capture_output=True, text=True)
    assert r.returncode == 2 and "speedd" in r.stderr
    r = subprocess.run([BATSTUDY, "plan", str(small_study)], capture_output=True, text=True)
    assert r.returncode == 0 and "72" in r.stdout  # 2 × 9 × 4 points
    r = subprocess.run([sys.executable, "-m", "batstudy", "schema"], capture_output=True, text=True)
    assert r.returncode == 0 and json.loads(r.stdout)


def test_the_native_module_needs_no_system_hdf5(tmp_path, small_study):
    # HDF5 is linked into the module (Cargo feature `static`): no libhdf5 among its needs…
    so = next(pathlib.Path(batstudy.__file__).parent.glob("_native*.so"))
    needed = subprocess.run(["readelf", "-d", str(so)], capture_output=True, text=True).stdout
    libs = [l for l in needed.splitlines() if "NEEDED" in l]
    assert libs and not [l for l in libs if "hdf5" in l.lower()], libs
    # … and a process that runs a study and reads it back maps no HDF5 library from outside
    # the venv (h5py and netCDF4 bring their own copies in site-packages): so a machine
    # without libhdf5-dev runs it the same.
    code = (
        "import batstudy, sys\n"
        f"t = batstudy.open(batstudy.run({str(small_study)!r}, output={str(tmp_path / 'm.h5')!r}, progress=False))\n"
        "float(t['summary']['exit_speed'].max())\n"
        "print(open('/proc/self/maps').read())\n"
    )
    maps = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    venv = pathlib.Path(sys.prefix).resolve()
    mapped = {f[5] for f in (line.split() for line in maps.splitlines()) if len(f) >= 6}
    outside = {
        p for p in mapped
        if "hdf5" in p.lower() and not pathlib.Path(p).resolve().is_relative_to(venv)
    }
    assert not outside, f"HDF5 loaded from outside the venv: {outside}"


def test_the_command_draws_the_figures_and_writes_the_explorer(small_study, tmp_path):
    from PIL import Image

    out = batstudy.run(small_study, output=tmp_path / "small.h5", progress=False)
    r = subprocess.run([BATSTUDY, "figures", str(out), "-o", str(tmp_path / "figures")], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    written = {p.name for p in (tmp_path / "figures").iterdir()}
    # the small study varies the swing, the bat (aluminum, a hoop, the density) and stores histories
    assert {"fig06_exit_speed_vs_omega.png", "fig10_density.png", "fig13b_aluminum.png", "fig15_hoop_frequencies.png",
            "fig04a_force.png", "bat_profiles.png", "anim_displacement.gif"} <= written, sorted(written)  # fmt: skip
    assert "skip  fig05a_fixed_vs_free" in r.stdout
    for name in written:
        with Image.open(tmp_path / "figures" / name) as im:
            im.verify()
    r = subprocess.run([BATSTUDY, "report", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    page = (tmp_path / "small.html").read_text(encoding="utf-8")
    assert "<title>batstudy explorer: small</title>" in page and "Plotly" in page
    r = subprocess.run([BATSTUDY, "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and "figures   RESULTS [-o DIR]" in r.stdout and "report    RESULTS [-o FILE]" in r.stdout
    r = subprocess.run([BATSTUDY, "report", str(tmp_path / "missing.h5")], capture_output=True, text=True)
    assert r.returncode == 2 and "missing.h5" in r.stderr


def test_the_package_draws_and_opens_under_both_names(small_study, tmp_path):
    out = batstudy.run(small_study, output=tmp_path / "p.h5", progress=False)
    assert batstudy.open is batstudy.open_results
    written = batstudy.plot.figures(out, tmp_path / "figs", only="fig6,fig13b")
    assert sorted(p.name for p in written) == ["fig06_exit_speed_vs_omega.png", "fig13b_aluminum.png"]
    ax = batstudy.plot.exit_speed(out, by="case", swing_omega=-40.0)
    assert len(ax.get_lines()) == 4 and "swing_omega=-40" in ax.get_title()
    # `import *` gives open_results and leaves the builtin open alone
    code = "from batstudy import *\nimport builtins\nassert open is builtins.open\nprint(open_results.__name__)\n"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == "open_results", r.stderr
