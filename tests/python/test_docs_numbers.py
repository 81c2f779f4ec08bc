"""Numbers the README states about the bundled default study are the study's own: the count
of collisions and its factors, as `batstudy plan` reports them (they went stale once when a
case was added). Needs BATSTUDY_BIN."""
import os
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = os.environ.get("BATSTUDY_BIN")
pytestmark = pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")


def plan(study: str) -> str:
    r = subprocess.run([BIN, "plan", str(ROOT / study)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_the_readme_counts_the_default_study_as_it_is():
    readme = (ROOT / "README.md").read_text()
    m = re.search(r"`studies/param_space\.yaml` \(([\d,]+) collisions: both models × (\d+) swing speeds ×\s+"
                  r"(\d+) impact positions × (\d+) one-factor cases\)", readme)
    assert m, "the README's sentence about the default study"
    total, swings, positions, cases = (int(g.replace(",", "")) for g in m.groups())
    out = plan("studies/param_space.yaml")
    points = int(re.search(r"(\d+) points", out).group(1))
    sizes = dict(re.findall(r"^  (\w+) \[(\d+)\]", out, flags=re.M))
    assert (int(sizes["model"]), int(sizes["swing_omega"]), int(sizes["impact_z"]), int(sizes["case"])) == \
        (2, swings, positions, cases)
    assert total == points == 2 * swings * positions * cases
