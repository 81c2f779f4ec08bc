"""examples/quickstart.ipynb runs from top to bottom (nbclient) against the installed
package, and answers its four questions."""

import pathlib
import shutil

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("matplotlib")


def test_quickstart_notebook_runs(root, tmp_path):
    for name in ("quickstart.ipynb", "quickstart.yaml"):
        shutil.copy(root / "examples" / name, tmp_path / name)
    nb = nbformat.read(tmp_path / "quickstart.ipynb", as_version=4)
    nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    ).execute()
    text = "".join(
        o.get("text", "") for c in nb.cells for o in c.get("outputs", []) if o.get("output_type") == "stream"
    )
    images = sum(
        1 for c in nb.cells for o in c.get("outputs", []) if "image/png" in o.get("data", {})
    )
    assert "omega  -60.0 rad/s: sweet spot" in text
    assert "peak force" in text and "moves it most:" in text
    assert images == 4, f"{images} figures"
    # batstudy.run's progress bar is a Jupyter widget (tqdm.auto with ipywidgets)
    widgets = [
        o for o in nb.cells[1].get("outputs", []) if "application/vnd.jupyter.widget-view+json" in o.get("data", {})
    ]
    assert widgets, "no progress widget in the run cell"
    assert (tmp_path / "results" / "quickstart.h5").exists()
