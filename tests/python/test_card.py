"""The bat card in Python (`batstudy.bat_card`) and on the terminal (`batstudy card`): the
same numbers, the trade's units by their definitions, and a file without a card refused."""

import os
import re
import subprocess

import numpy as np
import pytest

import batstudy
import synthetic_results

SMOKE = os.environ.get("SMOKE_H5")
BIN = os.environ.get("BATSTUDY_BIN")
# avoirdupois ounce and inch by definition (international yard and pound agreement, 1959)
OUNCE, INCH = 0.028349523125, 0.0254


@pytest.mark.skipif(not SMOKE, reason="SMOKE_H5 not set (scripts/test.sh sets it)")
def test_the_card_is_the_files_bat_in_the_trades_units():
    tree = batstudy.open_results(SMOKE)
    card = batstudy.bat_card(tree)
    stored = tree["bat"].to_dataset()
    assert list(card["bat"].values) == list(stored["bat"].values)
    np.testing.assert_array_equal(card["balance_point"].values, stored["z_cm"].values)
    np.testing.assert_allclose(card["mass_oz"] * OUNCE, card["mass"], rtol=1e-14)
    np.testing.assert_allclose(card["drop"], card["mass_oz"] - card["length_in"], atol=1e-9)
    np.testing.assert_allclose(card["moment_of_inertia_knob6_oz_in2"] * OUNCE * INCH**2,
                               card["moment_of_inertia_knob6"], rtol=1e-14)
    assert card["mass_oz"].attrs["units"] == "oz"
    # the verdicts are the margins' signs
    margin = card["rule_margin"].values
    np.testing.assert_array_equal(card["rule_passes"].values, margin >= 0)
    # the smoke study's aluminum bat is hollow: its hoop mode is the wall's; the wood bat has none
    labels = [str(b) for b in card["bat"].values]
    hoop = card["hoop_mode_frequency"].values
    assert np.isnan(hoop[labels.index("r161")]) and np.isfinite(hoop[labels.index("aluminum")])
    one = batstudy.bat_card(tree, bat="aluminum")
    assert "bat" not in one.dims and float(one["mass"]) == float(card["mass"][labels.index("aluminum")])
    with pytest.raises(ValueError, match="not a bat of the file"):
        batstudy.bat_card(tree, bat="no such bat")


@pytest.mark.skipif(not (SMOKE and BIN), reason="SMOKE_H5 and BATSTUDY_BIN not set")
def test_the_terminal_card_shows_the_same_numbers():
    card = batstudy.bat_card(batstudy.open_results(SMOKE), bat="aluminum")
    out = subprocess.run([BIN, "card", SMOKE, "--bat", "aluminum"], capture_output=True, text=True, check=True).stdout
    bbcor = float(re.search(r"BBCOR\s+([0-9.]+)", out).group(1))
    assert bbcor == round(float(card["bbcor_max"]), 4)
    oz = float(re.search(r"\(([0-9.]+) oz, drop", out).group(1))
    assert oz == round(float(card["mass_oz"]), 2)
    # the rules judged are those whose set is for the bat: an aluminum bat is not judged by
    # MLB's wood-bat rules, which the card names as not for it
    assert out.count("passes") + out.count("FAILS") == int(card["rule_applies"].sum())
    assert not bool(card["rule_applies"].all()) and "not for this bat" in out


def test_a_file_without_a_card_is_refused(tmp_path):
    tree = batstudy.open_results(synthetic_results.write(tmp_path / "old.h5"))
    with pytest.raises(ValueError, match="older batstudy"):
        batstudy.bat_card(tree)


@pytest.mark.skipif(not SMOKE, reason="SMOKE_H5 not set (scripts/test.sh sets it)")
def test_the_comparison_figure_draws_every_bat_and_its_sweet_zone():
    import matplotlib

    matplotlib.use("Agg")
    import batstudy.plot

    tree = batstudy.open_results(SMOKE)
    card = batstudy.bat_card(tree)
    axes = batstudy.plot.compare(tree, model="wave", swing_omega=0.0)
    assert len(axes) == 3
    n = card.sizes["bat"]
    # BBCOR along the barrel: a line per bat (the fixed-end bat has no free-bat scan, an empty one)
    assert len(axes[0].lines) == n
    # each sweet zone shaded where the card puts it
    zones = sorted((p.get_x(), p.get_x() + p.get_width()) for p in axes[0].patches)
    want = sorted(zip(card["sweet_zone_start"].values, card["sweet_zone_end"].values))
    want = [w for w in want if np.isfinite(w).all()]
    np.testing.assert_allclose(zones, want)
    # the lab exit speed against impact position: each bat's curve is the file's
    summary = tree["summary"].to_dataset().sel(model="wave", swing_omega=0.0)
    line = axes[1].lines[0]
    first = summary["exit_speed_lab"].where(summary["bat_index"] == 0, drop=True)
    np.testing.assert_array_equal(line.get_ydata(), first.isel(case=0).values)
