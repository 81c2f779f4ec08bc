"""A file that is not a complete batstudy results file, opened by batstudy.open and
batstudy.report: a damaged one (a block of zeros, a flipped bit, a cut-off end), another
program's HDF5 file, or no HDF5 at all. Each raises batstudy.ResultsFileError within seconds,
naming the file and what is wrong: never a hang, a crash or another error's traceback.

The damage that hung and crashed them is in the global heap collections (``GCOL``), which
hold a file's strings and dimension lists and which HDF5 reads without a checksum. The
readers run in a child process (a hang inside HDF5 cannot be interrupted), killed after
LIMIT seconds. Needs BATSTUDY_BIN (set by scripts/test.sh) to write a real results file."""
import json
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

import batstudy

BIN = os.environ.get("BATSTUDY_BIN")
PYTHON_SRC = Path(__file__).resolve().parents[2] / "python"
LIMIT = 30  # seconds: far longer than a clean failure takes; the test is on not hanging
STUDY = """name: s
model: wave
base: {bat: {preset: r161}, ball: {speed: 40}}
grid:
  impact.z: [0.6, 0.7]
points:
  name: case
  sets: [{}, {bat.preset: aluminum}]
history: {fields: [force, displacement], interval: 1.0e-5, duration: 1.0e-3}
"""
# Each reader, on every file given, prints one JSON line: "ok", or the error's type and text.
READERS = {
    "open": "t = batstudy.open(p); [n.to_dataset().load() for n in t.subtree]",
    "report": "batstudy.report(p, p + '.html')",
}
CHILD = """import json, sys
sys.path.insert(0, {src!r})
import batstudy
for p in sys.argv[1:]:
    try:
        {code}
        print(json.dumps(["ok", ""]), flush=True)
    except Exception as e:
        print(json.dumps([type(e).__name__, str(e)]), flush=True)
"""


@pytest.fixture(scope="module")
def good(tmp_path_factory) -> Path:
    if not BIN:
        pytest.skip("BATSTUDY_BIN not set (scripts/test.sh sets it)")
    d = tmp_path_factory.mktemp("damaged")
    (d / "s.yaml").write_text(STUDY)
    r = subprocess.run([BIN, "run", str(d / "s.yaml"), "-o", str(d / "s.h5"), "--quiet"],
                       capture_output=True, text=True)  # fmt: skip
    assert r.returncode == 0, r.stderr
    return d / "s.h5"


def collections(data: bytes) -> list[int]:
    """Where the file's global heap collections start."""
    out, at = [], data.find(b"GCOL\x01")
    while at >= 0:
        out.append(at)
        at = data.find(b"GCOL\x01", at + 1)
    return out


def damaged_copies(good: Path) -> dict[str, Path]:
    """Copies of `good`, each damaged in one way: {what was done: path}."""
    data = good.read_bytes()
    cases = {}
    for k, at in enumerate(collections(data)):
        # a block of zeros after its header: an object of length 0, which HDF5 never passes
        cases[f"zeros in collection {k} (byte {at})"] = data[: at + 16] + bytes(64) + data[at + 80 :]
        # its length (HDF5 reads on past its end), its first object's (HDF5 copies past it)
        for what, byte in (("its length", at + 9), ("its first object's length", at + 26)):
            b = bytearray(data)
            b[byte] ^= 0x80
            cases[f"a bit of {what}, collection {k} (byte {at})"] = bytes(b)
    cases["cut to a third"] = data[: len(data) // 3]
    cases["cut by 100 bytes"] = data[:-100]
    out = {}
    for i, (what, b) in enumerate(cases.items()):
        out[what] = good.with_name(f"damaged{i}.h5")
        out[what].write_bytes(b)
    return out


def run_reader(reader: str, paths: list[Path]) -> list[tuple[str, str]]:
    """Each file's outcome under `reader`, from a child process killed after LIMIT s."""
    code = CHILD.format(src=str(PYTHON_SRC), code=READERS[reader])
    try:
        r = subprocess.run([sys.executable, "-c", code, *map(str, paths)], capture_output=True,
                           text=True, timeout=LIMIT)  # fmt: skip
    except subprocess.TimeoutExpired as err:
        done = (err.stdout or b"").decode().count("\n")
        pytest.fail(f"batstudy.{reader} still running after {LIMIT} s, on {paths[done]}")
    lines = [tuple(json.loads(line)) for line in r.stdout.splitlines()]
    assert r.returncode == 0 and len(lines) == len(paths), \
        f"batstudy.{reader} ended with status {r.returncode} after {len(lines)} files:\n{r.stderr[-2000:]}"
    return lines


@pytest.mark.parametrize("reader", sorted(READERS))
def test_a_damaged_file_is_refused_within_seconds(good, reader):
    cases = damaged_copies(good)
    assert len(cases) >= 8
    for (what, path), (kind, text) in zip(cases.items(), run_reader(reader, list(cases.values()))):
        assert kind == "ResultsFileError", f"{what}: {kind}: {text}"
        assert str(path) in text and "damaged" in text, f"{what}: {text}"


@pytest.mark.parametrize("reader", sorted(READERS))
def test_the_good_file_still_reads(good, reader):
    assert run_reader(reader, [good]) == [("ok", "")]


def foreign_file(path: Path) -> Path:
    """An HDF5 file of another program (h5py's): a dataset and a group with one."""
    with h5py.File(path, "w") as f:
        f["a"] = np.arange(10.0)
        f.create_group("summary")["status"] = np.zeros(3, np.int8)
    return path


def test_open_and_report_refuse_another_programs_file(tmp_path):
    path = foreign_file(tmp_path / "foreign.h5")
    for read in (batstudy.open, batstudy.report):
        with pytest.raises(batstudy.ResultsFileError) as err:
            read(path)
        assert str(path) in str(err.value) and "not a batstudy results file" in str(err.value)
        assert "layout_version" in str(err.value)  # what it lacks
    assert issubclass(batstudy.ResultsFileError, ValueError)


def test_open_refuses_a_file_that_is_not_hdf5(tmp_path):
    path = tmp_path / "notes.h5"
    path.write_text("not HDF5\n")
    with pytest.raises(batstudy.ResultsFileError, match="not an HDF5 file") as err:
        batstudy.open(path)
    assert str(path) in str(err.value)


def test_the_report_command_names_the_file_and_exits_2(tmp_path, capsys):
    from batstudy._report import main

    path = foreign_file(tmp_path / "foreign.h5")
    assert main([str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}: not a batstudy results file" in err and "Traceback" not in err
