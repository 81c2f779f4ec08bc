"""Every image the docs embed exists and is a real image (the figures are committed under
docs/figures/ by scripts/docs_figures.sh), and docs/results.md shows every figure of the
paper that batstudy.plot draws."""
import re
from pathlib import Path

from PIL import Image

from batstudy import plot

ROOT = Path(__file__).resolve().parents[2]

IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)\)")


def embedded():
    for md in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        for target in IMAGE.findall(md.read_text()):
            yield md, target


def test_every_embedded_image_exists_and_opens():
    found = list(embedded())
    assert found, "the docs embed no image"
    for md, target in found:
        path = (md.parent / target).resolve()
        assert path.is_file(), f"{md.name} embeds {target}, which does not exist"
        assert ROOT in path.parents, f"{md.name} embeds {target}, outside the repository"
        with Image.open(path) as im:
            im.verify()


def test_results_shows_every_figure_of_the_paper():
    shown = {Path(t).name for md, t in embedded() if md.name == "results.md"}
    missing = [plot.file_name(n) for n in plot.FIGURES if plot.file_name(n) not in shown]
    assert not missing, f"docs/results.md does not show {missing}"
