"""batstudy.open_results from the sources: linear in the number of stored histories, and the
package's analysis importable without its native module or the plotting extra."""
from __future__ import annotations

import shutil
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

import batstudy
import synthetic_results
from batstudy import _open

ROOT = Path(__file__).resolve().parents[2]


def test_twenty_thousand_histories_open_and_list_in_seconds(tmp_path):
    path, n_stored = synthetic_results.write_many_histories(tmp_path / "many.h5")
    assert n_stored == 20_000
    start = time.perf_counter()
    tree = batstudy.open_results(path)
    h = tree["history"]
    impact_z, case = h["impact_z"].values, h["case"].values
    elapsed = time.perf_counter() - start
    # one pass over the chunk index (0.1 s here); the old one call per chunk took 27 s
    assert elapsed < 20, f"open and list: {elapsed:.1f} s"
    assert h.sizes["history"] == n_stored
    # in flat order (impact_z, then case), every other case, each row its own point's history
    z_index = np.searchsorted(tree["summary"]["impact_z"].values, impact_z)
    np.testing.assert_array_equal(z_index, np.repeat(np.arange(200), 100))
    np.testing.assert_array_equal(case, np.tile(np.arange(0, 200, 2), 200))
    rows = [0, 1, 12_345, n_stored - 1]
    np.testing.assert_array_equal(h["force"].isel(history=rows).values[:, 0], z_index[rows] + 1000.0 * case[rows])
    assert len(batstudy.histories(tree, case=[2, 4])["history"]) == 400


class _WithoutChunkIter:
    """A dataset whose HDF5 handle lacks H5Dchunk_iter (h5py before 3.8, HDF5 before 1.12.1)."""

    def __init__(self, ds: h5py.Dataset):
        self.ds, self.ndim, self.chunks = ds, ds.ndim, ds.chunks
        self.id = type("Handle", (), {"get_num_chunks": ds.id.get_num_chunks, "get_chunk_info": ds.id.get_chunk_info})()


def test_without_chunk_iter_the_positions_are_the_same(tmp_path):
    path, _ = synthetic_results.write_many_histories(tmp_path / "few.h5", n_cases=6, n_impacts=5)
    with h5py.File(path) as f:
        ds = f["history/force"]
        fast, slow = _open._stored_positions(ds, 2), _open._stored_positions(_WithoutChunkIter(ds), 2)
    np.testing.assert_array_equal(fast, slow)
    np.testing.assert_array_equal(fast, [[i, c] for i in range(5) for c in (0, 2, 4)])


def test_the_analysis_needs_neither_the_native_module_nor_the_plot_extra(tmp_path):
    """A copy of the package's Python sources (no native module), with matplotlib and plotly
    made unimportable: opening works, the rest says what is missing."""
    sources = shutil.ignore_patterns("*.so", "__pycache__")
    shutil.copytree(ROOT / "python" / "batstudy", tmp_path / "batstudy", ignore=sources)
    results = synthetic_results.write(tmp_path / "synthetic.h5")
    code = f"""
import sys
sys.modules["matplotlib"] = sys.modules["plotly"] = None  # not installed
import batstudy
assert "batstudy._native" not in sys.modules and "batstudy.plot" not in sys.modules
assert batstudy.open is batstudy.open_results
assert "open_results" in batstudy.__all__ and "open" not in batstudy.__all__
tree = batstudy.open_results({results!r})
assert tree["summary"]["exit_speed"].attrs["units"] == "m/s"
for use, needs in ((lambda: batstudy.simulate, "native module"), (lambda: batstudy.plot, "batstudy[plot]"),
                   (lambda: batstudy.report({results!r}), "batstudy[plot]")):
    try:
        use()
    except ImportError as err:
        assert needs in str(err), err
    else:
        raise AssertionError(needs)
print("ok")
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path,
                       env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert r.returncode == 0 and r.stdout == "ok\n", r.stdout + r.stderr
