"""The figures of any results file (batstudy.plot.exit_speed, sweet_spots, history,
displacement, bat_profiles) draw the file's numbers, selected by coordinate value, on the
synthetic file of tests/python/synthetic_results.py."""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

import batstudy
import synthetic_results
from batstudy import plot


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    return batstudy.open_results(synthetic_results.write(tmp_path_factory.mktemp("views") / "synthetic.h5"))


def axes():
    return Figure().subplots()


def test_exit_speed_one_line_per_value_of_a_dimension(tree):
    ax = plot.exit_speed(tree, by="model", case_label="aluminum", ax=axes())
    summary = tree["summary"].to_dataset()
    aluminum = list(summary["case_label"].values).index("aluminum")
    assert [line.get_label() for line in ax.get_lines()] == ["model=wave", "model=rigid"]
    for line, model in zip(ax.get_lines(), range(2)):
        np.testing.assert_array_equal(line.get_ydata(), summary["exit_speed"].values[model, :, aluminum])
        np.testing.assert_array_equal(line.get_xdata(), summary["impact_z"].values)
    assert "case=aluminum" in ax.get_title() and "(study: synthetic)" in ax.get_title()
    assert ax.get_ylabel() == "exit speed (m/s)"


def test_exit_speed_takes_an_unselected_dimension_at_its_first_value(tree):
    ax = plot.exit_speed(tree, by="case", bat_preset="corked", ax=axes())
    assert [line.get_label() for line in ax.get_lines()] == ["case=corked 1 cm", "case=corked 1.5 cm"]
    assert "model=wave" in ax.get_title()
    with pytest.raises(KeyError, match="no coordinate 'colour'"):
        plot.exit_speed(tree, colour="red", ax=axes())


def test_sweet_spots_against_a_labelled_dimension(tree):
    ax = plot.sweet_spots(tree, against="case", model="rigid", ax=axes())
    sweet = tree["sweet_spot"].to_dataset()
    line = ax.get_lines()[0]  # then the error bars' caps
    np.testing.assert_array_equal(line.get_ydata(), sweet["position"].values[1])
    assert [t.get_text() for t in ax.get_xticklabels()][:2] == ["base (R161 wood)", "density 500"]
    assert "model=rigid" in ax.get_title()


def test_history_one_line_per_stored_history(tree):
    ax = plot.history(tree, "force", ax=axes())
    stored = batstudy.histories(tree)
    assert [line.get_label() for line in ax.get_lines()] == [f"case_label={c}" for c in stored["case_label"].values]
    for line, row in zip(ax.get_lines(), range(stored.sizes["history"])):
        np.testing.assert_array_equal(line.get_ydata(), stored["force"].values[row])
    with pytest.raises(ValueError, match="displacement"):
        plot.history(tree, "displacement", ax=axes())
    with pytest.raises(plot.Skip, match="no stored force history matches"):
        plot.history(tree, "force", case_label="density 500", ax=axes())


def test_displacement_with_and_without_the_rigid_motion(tree):
    raw = plot.displacement(tree, times=[1.0e-3], case_label="aluminum", ax=axes())
    flex = plot.displacement(tree, times=[1.0e-3], rigid=False, case_label="aluminum", ax=axes())
    h = batstudy.histories(tree, case_label="aluminum")
    k = int(np.argmin(np.abs(h["time"].values - 1.0e-3)))
    np.testing.assert_allclose(raw.get_lines()[0].get_ydata(), h["displacement"].values[0, k] * 1e3)
    # what was removed is the recorded rigid motion: translation + rotation (z - z_cm), the
    # synthetic aluminum bat's centre of mass at 0.60 m
    z_cm = 0.60
    rigid = h["rigid_translation"].values[0, k] + h["rigid_rotation"].values[0, k] * (h["z"].values - z_cm)
    removed = raw.get_lines()[0].get_ydata() - flex.get_lines()[0].get_ydata()
    assert np.abs(rigid).max() > 0
    np.testing.assert_allclose(removed, rigid * 1e3, rtol=1e-9, atol=1e-12)
    assert "recorded rigid motion removed" in flex.get_title()


def test_bat_profiles_and_a_new_figure_by_default(tree):
    import matplotlib.pyplot as plt

    ax = plot.bat_profiles(tree)
    try:
        assert ax.figure in map(plt.figure, plt.get_fignums())
        bats = tree["bat"].to_dataset()
        profiles = {(tuple(np.nan_to_num(o)), tuple(np.nan_to_num(i)))
                    for o, i in zip(bats["outer_radius"].values, bats["inner_radius"].values)}  # fmt: skip
        outer = [line for line in ax.get_lines() if line.get_linestyle() == "-"]
        assert len(outer) == len(profiles) > 1
    finally:
        plt.close(ax.figure)
