"""The study explorer (scripts/report.py) in a real headless browser: Debian's Chromium,
driven by Playwright. The page must load with no console error and no network request, a
control must change the plotted curve, and the numbers it shows (the curve, the sweet spot)
must be the file's. Needs SMOKE_H5 (the smoke study's output, set by scripts/test.sh) and
/usr/bin/chromium (scripts/test.sh installs Debian's chromium)."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SMOKE = os.environ.get("SMOKE_H5")
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
pytestmark = pytest.mark.skipif(not SMOKE, reason="SMOKE_H5 not set (scripts/test.sh sets it)")


def test_the_explorer_works_in_a_browser(tmp_path):
    if not Path(CHROMIUM).exists():
        if os.environ.get("CI") == "true":
            pytest.fail("chromium is missing (scripts/test.sh installs Debian's chromium in CI)")
        pytest.skip("no chromium on this machine")
    from playwright.sync_api import sync_playwright

    page_path = tmp_path / "report.html"
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "report.py"), SMOKE, "-o", str(page_path)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(SMOKE, "r") as f:
        exit_speed = f["summary/exit_speed"][()]  # (model, swing_omega, impact_z, case)
        position = f["sweet_spot/position"][()]  # (model, swing_omega, case)
    errors, requests = [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
            "--no-first-run", "--disable-sync"])  # fmt: skip
        page = browser.new_page()
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("request", lambda q: requests.append(q.url) if not q.url.startswith(("file:", "data:")) else None)
        page.goto(page_path.as_uri())
        page.wait_for_function("document.getElementById('exit').data !== undefined")
        first = page.evaluate("document.getElementById('exit').data[0].y")
        # the base selection: every control at index 0
        np.testing.assert_array_equal(np.array(first, dtype=float), exit_speed[0, 0, :, 0])
        # change the swing speed: the curve changes, and is the file's
        page.select_option("#control-swing_omega", "3")
        after = page.evaluate("document.getElementById('exit').data[0].y")
        np.testing.assert_array_equal(np.array(after, dtype=float), exit_speed[0, 3, :, 0])
        assert after != first
        shown = float(page.text_content("#sweet-position"))
        assert abs(shown - position[0, 3, 0]) < 5e-5, (shown, position[0, 3, 0])
        # a force history is drawn, and the bending slider moves the curve
        assert page.evaluate("document.getElementById('force').data[0].y.length") > 10
        page.fill("#frame", "20")
        page.dispatch_event("#frame", "input")
        assert "t = " in page.text_content("#frame-time")
        browser.close()
    assert not errors, errors
    assert not requests, f"the page reached the network: {requests}"
