"""The explorer (batstudy.report) in a real headless browser: Debian's Chromium, driven by
Playwright.

- On the smoke study's output (SMOKE_H5, set by scripts/test.sh): the page loads with no
  console error and no network request, a control changes the plotted curve, and the
  numbers it shows (the curve, the sweet spot) are the file's.
- On a synthetic file whose every string carries HTML and script (tests/python/
  synthetic_results.py): nothing of it runs, and the page shows it as written.

Needs /usr/bin/chromium (scripts/test.sh installs Debian's chromium)."""
import json
import os
import shutil
import subprocess
from contextlib import contextmanager
from pathlib import Path

import h5py
import numpy as np
import pytest

import batstudy
import synthetic_results

SMOKE = os.environ.get("SMOKE_H5")
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
# What a user's string might hold: the end of the script it is written into, markup with an
# event handler, a comment opener, the line separators JavaScript once took as line ends, an
# entity, and a placeholder of the page's template.
PAYLOAD = (' </script><script>window.__pwned=1</script> "><img src=x onerror="window.__pwned=2">'
           " '><svg onload=window.__pwned=3> <!-- <script> \u2028 \u2029 &amp; ` ${x} __DATA__ end")  # fmt: skip


@contextmanager
def browser_page(errors: list, requests: list):
    """A page of headless Chromium that records console errors and network requests."""
    if not Path(CHROMIUM).exists():
        if os.environ.get("CI") == "true":
            pytest.fail("chromium is missing (scripts/test.sh installs Debian's chromium in CI)")
        pytest.skip("no chromium on this machine")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
            "--no-first-run", "--disable-sync"])  # fmt: skip
        page = browser.new_page()
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.on("dialog", lambda d: (errors.append(f"dialog: {d.message}"), d.dismiss()))
        page.on("request", lambda q: requests.append(q.url) if not q.url.startswith(("file:", "data:")) else None)
        try:
            yield page
        finally:
            browser.close()


@pytest.mark.skipif(not SMOKE, reason="SMOKE_H5 not set (scripts/test.sh sets it)")
def test_the_explorer_works_in_a_browser(tmp_path):
    page_path = batstudy.report(SMOKE, tmp_path / "report.html")
    assert page_path == tmp_path / "report.html"
    with h5py.File(SMOKE, "r") as f:
        exit_speed = f["summary/exit_speed"][()]  # (model, swing_omega, impact_z, case)
        position = f["sweet_spot/position"][()]  # (model, swing_omega, case)
        bats = [b.decode() for b in f["bat/bat"][()]]
    errors, requests = [], []
    with browser_page(errors, requests) as page:
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
        # the cases are named by their labels
        assert page.text_content("#control-case option") == "base"
        # a force history is drawn, and the bending slider moves the curve
        assert page.evaluate("document.getElementById('force').data[0].y.length") > 10
        page.fill("#frame", "20")
        page.dispatch_event("#frame", "input")
        assert "t = " in page.text_content("#frame-time")
        # every bat's card, under its label
        assert page.evaluate("[...document.querySelectorAll('#cards h3')].map(h => h.textContent)") == bats
        assert "sweet zone" in page.text_content("#cards") and "ncaa_bbcor" in page.text_content("#cards")
    assert not errors, errors
    assert not requests, f"the page reached the network: {requests}"


def test_strings_of_the_file_never_run_and_show_as_written(tmp_path):
    results = synthetic_results.write_hostile(tmp_path / "hostile.h5", PAYLOAD)
    page_path = batstudy.report(results)
    assert page_path == tmp_path / "hostile.html"
    study = "synthetic" + PAYLOAD
    errors, requests = [], []
    with browser_page(errors, requests) as page:
        page.goto(page_path.as_uri())  # returns once the page has loaded
        assert page.evaluate("window.__pwned") is None, "a string of the file ran as script"
        page.wait_for_function("document.getElementById('force').data !== undefined")
        assert page.evaluate("document.querySelectorAll('script').length") == 2  # Plotly's and the page's
        assert page.evaluate("document.querySelectorAll('img, svg[onload], [onerror]').length") == 0
        # shown literally: the title, the heading, every control's options, the histories,
        # the units in Plotly's axis title
        assert page.evaluate("document.title") == f"batstudy explorer: {study}"
        assert page.text_content("#study") == study
        options = page.evaluate("[...document.querySelectorAll('#control-model option')].map(o => o.textContent)")
        assert options == ["wave" + PAYLOAD, "rigid" + PAYLOAD]
        cases = page.evaluate("[...document.querySelectorAll('#control-case option')].map(o => o.textContent)")
        assert cases[0] == "base (R161 wood)" + PAYLOAD
        history = page.text_content("#history option")
        assert f"model=wave{PAYLOAD}" in history and f"case=base (R161 wood){PAYLOAD}" in history
        y_title = page.text_content("#exit .ytitle")
        assert y_title == f"exit speed (m/s{PAYLOAD})", y_title
        page.select_option("#control-model", "1")  # the page still works
        assert page.evaluate("document.getElementById('exit').data[0].y.length") > 10
        assert page.evaluate("window.__pwned") is None
    assert not errors, errors
    assert not requests, f"the page reached the network: {requests}"


def test_each_escape_gives_back_the_value_in_its_context():
    """What the HTML parser (Python's, as a browser's in miniature) and JSON.parse read back
    from each context is the value itself, and no markup of it survives."""
    from html.parser import HTMLParser

    from batstudy import _html

    class Reader(HTMLParser):
        def __init__(self):
            super().__init__(convert_charrefs=True)
            self.tags, self.attrs, self.text, self.script = [], [], "", ""

        def handle_starttag(self, tag, attrs):
            self.tags.append(tag)
            self.attrs += attrs

        def handle_data(self, data):
            if self.tags and self.tags[-1] == "script":
                self.script += data
            else:
                self.text += data

    value = "study" + PAYLOAD
    reader = Reader()
    reader.feed(f"<p title={_html.attribute(value)}>{_html.text(value)}</p>"
                f"<script>const DATA = {_html.script_json({'study': value})};</script>")  # fmt: skip
    assert reader.tags == ["p", "script"]
    assert reader.attrs == [("title", value)] and reader.text == value
    data = reader.script.removeprefix("const DATA = ").removesuffix(";")
    assert json.loads(data) == {"study": value}
    assert not set("<>&\u2028\u2029") & set(data)
    # trusted code keeps its meaning but cannot end its script or open a comment
    code = _html.script_code('s = "</script>" + "<!--" + "</SCRIPT>";')
    assert "</script" not in code.lower() and "<!--" not in code
    assert code == 's = "<\\/script>" + "<\\!--" + "<\\/SCRIPT>";'


FORCE_STUDY = """name: forces
model: wave
base: {bat: {preset: r161}, ball: {speed: 40}}
grid:
  impact.z: {range: [0.50, 0.80, 0.01]}
  swing.omega: [0, -10, -20, -30, -40, -50, -60]
history: {fields: [force], interval: 1.0e-5, duration: 3.0e-3}
"""


def test_the_page_is_proportionate_to_the_file(tmp_path):
    """A study that stores little but force histories (217 of them) is the page's worst case:
    the page holds every history, to 4 significant digits of its peak, in at most twice the
    file's bytes besides Plotly's JavaScript (4.8 MB, the same in every page)."""
    bin_ = os.environ.get("BATSTUDY_BIN")
    if not bin_:
        pytest.skip("BATSTUDY_BIN not set (scripts/test.sh sets it)")
    from batstudy import _report

    (tmp_path / "forces.yaml").write_text(FORCE_STUDY)
    results = tmp_path / "forces.h5"
    r = subprocess.run([bin_, "run", str(tmp_path / "forces.yaml"), "-o", str(results), "--quiet"],
                       capture_output=True, text=True)  # fmt: skip
    assert r.returncode == 0, r.stderr
    page = batstudy.report(results)
    data_bytes = page.stat().st_size - len(_report.plotly_js().encode())
    assert data_bytes <= 2 * results.stat().st_size, (data_bytes, results.stat().st_size)
    text = page.read_text(encoding="utf-8")
    start = text.index("const DATA = ") + len("const DATA = ")
    shown = json.loads(text[start : text.index(";\n", start)])
    stored = batstudy.histories(results)
    force = stored["force"].values
    assert len(shown["histories"]) == len(force) == 217
    for h, f in zip(shown["histories"], force):  # every value, to 4 digits of the peak
        step = 10.0 ** (np.floor(np.log10(np.abs(f).max())) - 3)
        np.testing.assert_allclose(np.array(h["force"], dtype=float), f, rtol=0, atol=step / 2)
    np.testing.assert_allclose(shown["time_ms"], stored["time"].values * 1e3)


BIN = os.environ.get("BATSTUDY_BIN")
SEARCH = """name: best_point
model: rigid
base: {impact: {z: 0.6}}
grid:
  swing.cm_speed: [0]
optimize:
  max_evaluations: 60
  tolerance: 1.0e-10
  variables: {impact.z: {min: 0.40, max: 0.83}}
  objective: {maximize: exit_speed}
"""
SAMPLE = """name: small_sample
model: rigid
base: {bat: {preset: r161}, ball: {preset: mlb, speed: 60.8}}
grid:
  swing.omega: [0]
  impact.z: {range: [0.62, 0.78, 0.02]}
sample:
  n: 16
  seed: 3
  params:
    bat.material.density: {normal: {mean: 649, sd: 40}}
"""


@pytest.mark.skipif(not BIN, reason="BATSTUDY_BIN not set (scripts/test.sh sets it)")
def test_a_search_and_a_sample_show_their_own_answers(tmp_path):
    """The explorer of a design search shows every candidate and the best feasible design
    (`/optimize`), and of a `sample` study its answers over the sample (`/uncertainty`), each
    the file's own numbers."""
    files = {}
    for name, text, cmd in (("search", SEARCH, "optimize"), ("sample", SAMPLE, "run")):
        study = tmp_path / f"{name}.yaml"
        study.write_text(text)
        files[name] = tmp_path / f"{name}.h5"
        r = subprocess.run([BIN, cmd, str(study), "-o", str(files[name]), "-q"], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    with h5py.File(files["search"], "r") as f:
        objective = f["optimize/objective"][()]
        best = float(np.ravel(f["optimize"].attrs["best_objective"])[0])
    with h5py.File(files["sample"], "r") as f:
        p_above = float(np.ravel(f["uncertainty/bbcor_max_above_limit"][()])[0])
    errors, requests = [], []
    with browser_page(errors, requests) as page:
        page.goto(batstudy.report(files["search"], tmp_path / "search.html").as_uri())
        page.wait_for_function("document.getElementById('search').data !== undefined")
        shown = page.evaluate("document.getElementById('search').data.slice(0, 2).map(t => t.y.length)")
        assert sum(shown) == len(objective)
        assert page.is_visible("#search-section") and not page.is_visible("#uncertainty-section")
        assert f"{best:.6g}" in page.text_content("#search-best")
        page.goto(batstudy.report(files["sample"], tmp_path / "sample.html").as_uri())
        page.wait_for_function("document.getElementById('uncertainty').textContent.length > 0")
        text = page.text_content("#uncertainty")
        assert "bbcor_max" in text and "sweet_spot_position" in text and f"{p_above:.3f}" in text
        assert not page.is_visible("#search-section")
    assert not errors, errors
    assert not requests, f"the page reached the network: {requests}"
