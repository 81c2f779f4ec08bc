"""`batstudy figures` draws what a results file is for: a design search's record (`search`,
from `/optimize`) and a `sample` study's answers over the sample (`uncertainty`, from
`/uncertainty`), and skips each where the file has no such group."""

import batstudy
from batstudy import plot
from PIL import Image

from test_optimize import STUDY as SEARCH

SAMPLE = {
    "name": "small_sample",
    "model": "wave",
    "base": {"bat": {"preset": "r161"}, "ball": {"preset": "mlb", "speed": 60.8}},
    "grid": {"swing.omega": [0], "impact.z": {"range": [0.62, 0.78, 0.02]}},
    "sample": {
        "n": 16,
        "seed": 3,
        "params": {"bat.material.youngs_modulus": {"lognormal": {"mean": 1.814e10, "cov": 0.2}}},
    },
}


def drawn(path):
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        return im.size


def test_a_design_search_and_a_sample_are_drawn_and_skipped_elsewhere(tmp_path):
    search = tmp_path / "search.h5"
    batstudy.optimize(SEARCH, search)
    sample = batstudy.run(SAMPLE, output=tmp_path / "sample.h5", progress=False)
    for results, name, other in ((search, "search", "uncertainty"), (sample, "uncertainty", "search")):
        out = tmp_path / f"figures_{name}"
        written = plot.figures(results, out, only=f"{name},{other}")
        assert [p.name for p in written] == [f"{name}.png"], written
        width, height = drawn(written[0])
        assert width > 400 and height > 300
