"""The validation page (docs/validation.md): the six studies of studies/validation/ run,
scripts/validation.py evaluates every row, and each row's verdict is the one recorded in the
script (a row that agreed and drifts out of its band fails, and so does a row that starts to
agree: the table must then be re-judged). The committed docs/validation.md must be the table
these files give. Needs BATSTUDY_BIN (set by scripts/test.sh)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")


def test_every_row_keeps_its_verdict_and_the_page_is_current(tmp_path):
    files = []
    for study in ("certification", "wall", "game", "low_speed", "oblique", "field"):
        out = tmp_path / f"{study}.h5"
        r = subprocess.run([BIN, "run", str(ROOT / "studies" / "validation" / f"{study}.yaml"), "-o", str(out),
                            "--jobs", "2", "--quiet"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        files.append(str(out))
    page = tmp_path / "validation.md"
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "validation.py"), *files, "-o", str(page), "--check"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    text = page.read_text()
    # three tables kept apart; the headline counts the prediction table's independent tests only
    for heading in ("## Verification", "## Consistency", "## Prediction"):
        assert heading in text, heading
    prediction = text.split("## Prediction")[1].split("\n## ")[0]
    tests = [line for line in prediction.splitlines() if line.startswith("| ") and line.endswith(" yes |")]
    agreeing = sum(" | agrees | yes |" in line for line in tests)
    assert f"**Prediction: {agreeing} of {len(tests)} independent tests agree**" in text
    # the rules of the count come first, before any table, and every row they leave out of the
    # count names its rule; a null test, a part of a curve or a second-hand number is never counted
    assert text.index("## How the tests are counted") < text.index("## Verification")
    left_out = [line for line in prediction.splitlines() if line.startswith("| ") and " | no" in line[-400:]]
    assert left_out and all(" | no: " in line for line in left_out), left_out[:3]
    for line in tests:
        assert "second-hand" not in line.split(" | ")[3], line[:120]
    assert not any("a null test" in line and line.endswith(" yes |") for line in tests)
    sources = text.split("primary sources: ")[1].split("), counted by the rules")[0].split("; ")
    assert len(set(sources)) == len(sources) and len(sources) >= 1, sources
    assert page.read_text() == (ROOT / "docs" / "validation.md").read_text(), (
        "docs/validation.md is not the table these results give: run bash scripts/validation.sh")
