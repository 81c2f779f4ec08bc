"""The explorer of a results file: one HTML file that any browser opens, no server, no network.

The page shows, for any batstudy results file:

- exit speed against impact position, with one control per other dimension of the study
  (model, swing speed, case, ...), and the sweet spot of the chosen curve (position, exit
  speed, width) as numbers and as a marker;
- the force history of any point that recorded one;
- the bat's bending (displacement with time along the bat) for the points that recorded
  displacement, with a time slider.

Plotly's JavaScript (from the `plotly` package: ``pip install 'batstudy[plot]'``) is inlined,
and so are the data, read through :func:`batstudy.open_results`: the summary's exit speeds,
the sweet spots (the file's numbers) and the stored histories (to what a plot shows:
:data:`DIGITS`, :data:`MAX_SAMPLES`), so that the page grows with the file as the file does. Every string of the file reaches the page through
one escaping function per context (``batstudy._html``).
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
from pathlib import Path
from typing import Union

import numpy as np
import xarray as xr

from . import _html
from ._files import ResultsFileError, reading
from ._open import dim_labels, history_grid_index, open_results, text_of

IMPACT = "impact_z"
MAX_DISPLACEMENT_HISTORIES = 8  # bending animations embedded (each time × z values)
MAX_FRAMES = 80  # time samples of an animation
MAX_SAMPLES = 1000  # time samples of a force history: about a plot's width in pixels
# A history's values to this many significant digits of its largest: a step of at most
# 1/1 000 of the plot's range, under half a pixel on the page's plots. With no more digits
# than that, a history costs the page about what it costs the file (deflated).
DIGITS = 4


def _numbers(a) -> list:
    """Floats for JSON: NaN → null; full precision (repr round-trips)."""
    return [None if not math.isfinite(x) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def _rounded(a, peak: float | None = None, digits: int = DIGITS) -> list:
    """Floats for JSON rounded to `digits` significant digits of `peak` (default: the largest
    magnitude of `a`), in their shortest form (whole numbers without ``.0``); NaN → null."""
    a = np.asarray(a, dtype=float).ravel()
    finite = np.isfinite(a)
    if peak is None:
        peak = float(np.max(np.abs(a[finite]))) if finite.any() else 0.0
    if not peak:
        return [0 if f else None for f in finite.tolist()]
    places = digits - 1 - math.floor(math.log10(peak))
    values = np.round(np.where(finite, a, 0.0), places) + 0.0  # + 0.0: no -0.0
    kind = int if places <= 0 else float
    return [kind(v) if f else None for v, f in zip(values.tolist(), finite.tolist())]


def collect(tree: xr.DataTree) -> dict:
    """What the page shows, as plain data for its script."""
    if "summary" not in tree.children or "exit_speed" not in tree["summary"]:
        raise ValueError("the file has no /summary/exit_speed; nothing to plot")
    summary = tree["summary"].to_dataset()
    exit_speed = summary["exit_speed"]
    dims = [str(d) for d in exit_speed.dims]
    # a file without an impact axis (a design search's run at its best impact point) has no
    # curve to draw; the rest of the page still shows its answers
    along = IMPACT in dims
    controls = [{"name": d, "labels": dim_labels(summary, d)} for d in dims if d != IMPACT]
    data = {
        "study": text_of(tree.attrs.get("study_name", "study")),
        "dims": dims,
        "shape": list(exit_speed.shape),
        "controls": controls,
        "impact_z": _numbers(summary[IMPACT].values) if along else None,
        "exit_speed": _numbers(exit_speed.values),
        "units": text_of(exit_speed.attrs.get("units", "m/s")),
    }
    if along and "sweet_spot" in tree.children:
        sweet = tree["sweet_spot"].to_dataset()
        order = [d for d in dims if d != IMPACT]
        data["sweet"] = {k: _numbers(sweet[k].transpose(*order).values)
                         for k in ("position", "exit_speed", "width", "exit_speed_lab") if k in sweet}  # fmt: skip
    data["histories"] = histories(tree, dims, controls)
    data["time_ms"] = history_time(tree)
    data["cards"] = card_rows(tree)
    data["search"] = search_panel(tree)
    data["uncertainty"] = uncertainty_rows(tree)
    return data


def search_panel(tree: xr.DataTree) -> dict | None:
    """A design search's record (`/optimize`): each candidate's objective in the order
    evaluated and its status, and the best feasible design; None for a file without one."""
    if "optimize" not in tree.children:
        return None
    o = tree["optimize"].to_dataset()
    panel = {
        "objective": text_of(o.attrs.get("objective", "objective")),
        "units": text_of(o.attrs.get("objective_units", "")),
        "values": _numbers(o["objective"].values),
        "feasible": [bool(x == 0) for x in o["status"].values],
        "best": [],
    }
    if "best" in tree["optimize"].children:
        best = tree["optimize/best"].to_dataset()
        panel["best"].append([f"{panel['objective']} ({panel['units']})", f"{float(best['objective']):.6g}"])
        for name in best["design"]["variable"].values:
            value = float(best["design"].sel(variable=name))
            panel["best"].append([text_of(name), f"{value:.6g}"])
    return panel


# The answers of a `sample` study the explorer shows (`/uncertainty`), with their units.
UNCERTAIN = (("bbcor_max", "1"), ("sweet_spot_position", "m"), ("sweet_spot_exit_speed", "m/s"))


def uncertainty_rows(tree: xr.DataTree) -> list[list[str]] | None:
    """A `sample` study's answers over its sample (`/uncertainty`): each answer's mean, SD and
    its 2.5 / 50 / 97.5 % quantiles, and the probability that BBCOR exceeds 0.50; the first
    value of any dimension beside the quantile. None for a file without one."""
    if "uncertainty" not in tree.children:
        return None
    u = tree["uncertainty"].to_dataset()

    def first(a):
        return a.isel({d: 0 for d in a.dims if d != "quantile"})

    rows = []
    for name, units in UNCERTAIN:
        if name not in u:
            continue
        q = first(u[name])
        quantiles = [f"{float(q.sel(quantile=p, method='nearest')):.4g}" for p in (0.025, 0.5, 0.975)]
        mean, sd = (float(first(u[f"{name}_{k}"])) for k in ("mean", "std"))
        rows.append([name, units, f"{mean:.4g} ± {sd:.2g}", *quantiles])
    if "bbcor_max_above_limit" in u:
        rows.append(["P(BBCOR > 0.50)", "1", f"{float(first(u['bbcor_max_above_limit'])):.3f}", "", "", ""])
    return rows


def card_rows(tree: xr.DataTree) -> list[dict]:
    """Each bat's card (:func:`batstudy.bat_card`) as rows of text; none for a file written
    before bats had cards."""
    from ._card import bat_card

    try:
        card = bat_card(tree)
    except ValueError:
        return []

    def num(x, digits):
        return "–" if not np.isfinite(x) else f"{x:.{digits}f}"

    out = []
    for k, label in enumerate(card["bat"].values):
        c = card.isel(bat=k)
        v = {name: float(c[name]) for name in c.data_vars if c[name].ndim == 0 and c[name].dtype.kind == "f"}
        rows = [
            ["length", f"{num(v['length'], 4)} m ({num(v['length_in'], 2)} in)"],
            ["mass", f"{num(v['mass'], 4)} kg ({num(v['mass_oz'], 2)} oz), drop {num(v['drop'], 2)}"],
            ["balance point", f"{num(v['balance_point'], 4)} m ({num(v['balance_point_in'], 2)} in) from the knob"],
            ["MOI about the knob", f"{num(v['moment_of_inertia_knob'], 4)} kg m² ({num(v['moment_of_inertia_knob_oz_in2'], 0)} oz in²)"],
            ["MOI about 6 in", f"{num(v['moment_of_inertia_knob6'], 4)} kg m² ({num(v['moment_of_inertia_knob6_oz_in2'], 0)} oz in²)"],
            ["barrel diameter", f"{num(v['barrel_diameter'], 5)} m ({num(v['barrel_diameter_in'], 3)} in)"],
            ["BBCOR", f"{num(v['bbcor_max'], 4)} at {num(v['bbcor_max_position'], 4)} m"],
            ["sweet zone", f"{num(v['sweet_zone_length'], 4)} m ({num(v['sweet_zone_length_in'], 2)} in), "
                           f"{num(v['sweet_zone_start'], 4)}–{num(v['sweet_zone_end'], 4)} m"],
            ["bending mode 1", f"{num(v['bending_frequency'], 0)} Hz"],
            ["hoop mode", f"{num(v['hoop_mode_frequency'], 0)} Hz" if np.isfinite(v["hoop_mode_frequency"]) else "none (solid)"],
            ["barrel compression", f"{num(v['barrel_compression_lbf'], 0)} lbf at 0.040 in, 6 in from the end"
                                   if np.isfinite(v.get("barrel_compression", np.nan)) else "none (no shell barrel)"],
        ]  # fmt: skip
        applies = [bool(c["rule_applies"].isel(rule_check=j)) for j in range(card.sizes["rule_check"])]
        rules = [[text_of(r), num(float(c["rule_value"].isel(rule_check=j)), 6), text_of(c["rule_units"].values[j]),
                  num(float(c["rule_margin"].isel(rule_check=j)), 6),
                  "passes" if bool(c["rule_passes"].isel(rule_check=j)) else "FAILS"]
                 for j, r in enumerate(card["rule_check"].values) if applies[j]]  # fmt: skip
        not_for = dict.fromkeys(str(r).split(":")[0] for j, r in enumerate(card["rule_check"].values) if not applies[j])
        rules += [[text_of(f"{rule_set}:"), "", "", "", "not for this bat (a rule set for wood bats)"] for rule_set in not_for]
        out.append({"label": text_of(label), "rows": rows, "rules": rules})
    return out


def histories(tree: xr.DataTree, dims: list[str], controls: list[dict]) -> list[dict]:
    """The stored histories: force always, displacement for the first few."""
    if "history" not in tree.children or "force" not in tree["history"]:
        return []
    h = tree["history"].to_dataset()
    where = history_grid_index(tree)
    labels = {c["name"]: c["labels"] for c in controls}
    t_ms, force, impact_z = h["time"].values * 1e3, h["force"].values, h[IMPACT].values
    step = max(1, math.ceil(len(t_ms) / MAX_SAMPLES))
    out = []
    for row in range(h.sizes["history"]):
        index = [int(where[d][row]) for d in dims]
        label = ", ".join(f"{d}={impact_z[row]:g}" if d == IMPACT else f"{d}={labels[d][i]}"
                          for d, i in zip(dims, index))  # fmt: skip
        entry = {"label": label, "index": index, "force": _rounded(force[row, ::step])}
        if "displacement" in h and row < MAX_DISPLACEMENT_HISTORIES:
            entry["bending"] = bending(h["displacement"].isel(history=row).values, h["z"].values, t_ms)
        out.append(entry)
    return out


def history_time(tree: xr.DataTree) -> list:
    """The force histories' time axis (ms), shared by all of them, as many samples as each."""
    if "history" not in tree.children or "time" not in tree["history"].coords:
        return []
    t_ms = tree["history"]["time"].values * 1e3
    return _rounded(t_ms[:: max(1, math.ceil(len(t_ms) / MAX_SAMPLES))], digits=6)


def bending(displacement: np.ndarray, z: np.ndarray, t_ms: np.ndarray) -> dict:
    """At most MAX_FRAMES time samples of a (time, z) displacement, in mm, on the z the bat
    covers."""
    step = max(1, math.ceil(displacement.shape[0] / MAX_FRAMES))
    keep = np.isfinite(displacement).any(axis=0)
    mm = displacement[::step][:, keep] * 1e3
    peak = float(np.nanmax(np.abs(mm))) if np.isfinite(mm).any() else 0.0
    return {"z": _rounded(z[keep], digits=6), "time_ms": _rounded(t_ms[::step], digits=6),
            "mm": [_rounded(row, peak) for row in mm]}  # fmt: skip


PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>batstudy explorer: __STUDY__</title>
<style>
 body { font-family: system-ui, sans-serif; margin: 1em 2em; color: #222; }
 .controls label { margin-right: 1.2em; display: inline-block; margin-bottom: .4em; }
 select { max-width: 34em; }
 .numbers { font-family: monospace; margin: .3em 0 1em 0; }
 .plot { width: 100%; max-width: 1000px; height: 430px; }
 h2 { font-size: 1.1em; margin-top: 1.5em; }
 h3 { font-size: 1em; margin: 1em 0 .3em 0; }
 table.card { border-collapse: collapse; font-size: .9em; }
 table.card td, table.card th { padding: .1em .8em .1em 0; text-align: left; }
</style>
<script>__PLOTLY__</script>
</head><body>
<h1>batstudy explorer: <span id="study">__STUDY__</span></h1>
<p>Exit speed against impact position for the chosen values of every other dimension of the study.</p>
<div class="controls" id="controls"></div>
<div class="numbers">sweet spot: <span id="sweet-position">–</span> m,
 exit speed <span id="sweet-exit">–</span> m/s, width <span id="sweet-width">–</span> m;
 best lab-frame exit speed <span id="sweet-lab">–</span> m/s</div>
<div id="exit" class="plot"></div>
<h2>The bats</h2>
<div id="cards"></div>
<div id="search-section" hidden>
<h2>The design search</h2>
<div id="search" class="plot"></div>
<div id="search-best"></div>
</div>
<div id="uncertainty-section" hidden>
<h2>The answers over the sample</h2>
<div id="uncertainty"></div>
</div>
<h2>Force histories (points that recorded one)</h2>
<div class="controls"><label>history <select id="history"></select></label></div>
<div id="force" class="plot"></div>
<h2>The bat bending (displacement along the bat)</h2>
<div class="controls"><label>time <input type="range" id="frame" min="0" max="0" value="0"></label>
 <span id="frame-time"></span></div>
<div id="bending" class="plot"></div>
<script>
const DATA = __DATA__;
// Plotly reads its titles as text with a few HTML-like tags and entities: the file's
// strings reach it with & < > as entities, so that they show as written
function plotlyText(s) { return s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;"); }
const impactAxis = DATA.dims.indexOf("impact_z");
const strides = DATA.shape.map((_, k) => DATA.shape.slice(k + 1).reduce((a, b) => a * b, 1));
const choice = {};
function select(id, labels, onchange) {
  const s = document.createElement("select");
  s.id = id;
  labels.forEach((l, i) => { const o = document.createElement("option"); o.value = i; o.textContent = l; s.appendChild(o); });
  s.addEventListener("change", onchange);
  return s;
}
DATA.controls.forEach(c => {
  choice[c.name] = 0;
  const label = document.createElement("label");
  label.textContent = c.name + " ";
  label.appendChild(select("control-" + c.name, c.labels, e => { choice[c.name] = +e.target.value; drawExit(); }));
  document.getElementById("controls").appendChild(label);
});
function curve() {
  let base = 0;
  DATA.dims.forEach((d, k) => { if (k !== impactAxis) base += choice[d] * strides[k]; });
  return DATA.impact_z.map((_, i) => DATA.exit_speed[base + i * strides[impactAxis]]);
}
function sweetIndex() {  // the sweet-spot arrays lack impact_z
  let i = 0, stride = 1;
  for (let k = DATA.dims.length - 1; k >= 0; k--) {
    if (k === impactAxis) continue;
    i += choice[DATA.dims[k]] * stride; stride *= DATA.shape[k];
  }
  return i;
}
function fmt(x, d) { return x === null || x === undefined ? "–" : x.toFixed(d); }
function drawExit() {
  if (!DATA.impact_z) { document.getElementById("exit").textContent = "This file's points have no impact_z axis: no curve along the barrel."; return; }
  const y = curve();
  const traces = [{ x: DATA.impact_z, y: y, mode: "lines+markers", name: "exit speed" }];
  if (DATA.sweet) {
    const i = sweetIndex();
    const p = DATA.sweet.position[i], v = DATA.sweet.exit_speed[i], w = DATA.sweet.width ? DATA.sweet.width[i] : null;
    document.getElementById("sweet-position").textContent = fmt(p, 4);
    document.getElementById("sweet-exit").textContent = fmt(v, 3);
    document.getElementById("sweet-width").textContent = fmt(w, 4);
    document.getElementById("sweet-lab").textContent = DATA.sweet.exit_speed_lab ? fmt(DATA.sweet.exit_speed_lab[i], 3) : "–";
    if (p !== null) traces.push({ x: [p], y: [v], mode: "markers", marker: { size: 12, symbol: "star" }, name: "sweet spot" });
  }
  Plotly.react("exit", traces, { xaxis: { title: { text: "impact position z (m from the knob)" } },
    yaxis: { title: { text: "exit speed (" + plotlyText(DATA.units) + ")" } }, margin: { t: 20 } });
}
const hs = DATA.histories;
const hsel = document.getElementById("history");
hs.forEach((h, i) => { const o = document.createElement("option"); o.value = i; o.textContent = h.label; hsel.appendChild(o); });
function drawHistory() {
  if (!hs.length) { document.getElementById("force").textContent = "This study recorded no force history."; return; }
  const h = hs[+hsel.value];
  Plotly.react("force", [{ x: DATA.time_ms, y: h.force.map(f => f === null ? null : f / 1000), mode: "lines", name: "force" }],
    { xaxis: { title: { text: "time from first contact (ms)" } }, yaxis: { title: { text: "contact force (kN)" } }, margin: { t: 20 } });
  const slider = document.getElementById("frame");
  if (h.bending) { slider.max = h.bending.time_ms.length - 1; slider.value = 0; }
  drawBending();
}
function drawBending() {
  const h = hs.length ? hs[+hsel.value] : null;
  if (!h || !h.bending) { document.getElementById("bending").textContent = "No displacement history for this point."; return; }
  const k = +document.getElementById("frame").value, b = h.bending;
  const all = b.mm.flat().filter(v => v !== null);
  const top = Math.max(...all.map(Math.abs)) * 1.1 || 1;
  document.getElementById("frame-time").textContent = "t = " + fmt(b.time_ms[k], 3) + " ms";
  Plotly.react("bending", [{ x: b.z, y: b.mm[k], mode: "lines", name: "displacement" }],
    { xaxis: { title: { text: "z (m from the knob)" } }, yaxis: { title: { text: "displacement (mm)" }, range: [-top, top] }, margin: { t: 20 } });
}
function drawCards() {  // every string as text, never as markup
  const box = document.getElementById("cards");
  if (!DATA.cards.length) { box.textContent = "This file has no bat card (written by an older batstudy)."; return; }
  DATA.cards.forEach(c => {
    const h = document.createElement("h3"); h.textContent = c.label; box.appendChild(h);
    const t = document.createElement("table"); t.className = "card";
    const row = (cells, tag) => { const tr = document.createElement("tr");
      cells.forEach(x => { const td = document.createElement(tag); td.textContent = x; tr.appendChild(td); }); t.appendChild(tr); };
    c.rows.forEach(r => row(r, "td"));
    row(["rule", "value", "units", "margin", "verdict"], "th");
    c.rules.forEach(r => row(r, "td"));
    box.appendChild(t);
  });
}
function table(box, head, rows) {  // every string as text, never as markup
  const t = document.createElement("table"); t.className = "card";
  const row = (cells, tag) => { const tr = document.createElement("tr");
    cells.forEach(x => { const td = document.createElement(tag); td.textContent = x; tr.appendChild(td); }); t.appendChild(tr); };
  row(head, "th");
  rows.forEach(r => row(r, "td"));
  box.appendChild(t);
}
function drawSearch() {
  const s = DATA.search;
  if (!s) return;
  document.getElementById("search-section").hidden = false;
  const k = s.values.map((_, i) => i);
  let best = null;
  const bestSoFar = s.values.map((v, i) => { if (s.feasible[i] && v !== null && (best === null || v > best)) best = v; return best; });
  const pick = ok => k.filter(i => s.feasible[i] === ok);
  Plotly.react("search", [
    { x: pick(true), y: pick(true).map(i => s.values[i]), mode: "markers", name: "feasible" },
    { x: pick(false), y: pick(false).map(i => s.values[i]), mode: "markers", marker: { symbol: "circle-open" }, name: "outside a limit" },
    { x: k, y: bestSoFar, mode: "lines", name: "best feasible so far" }],
    { xaxis: { title: { text: "candidate" } }, yaxis: { title: { text: plotlyText(s.objective + " (" + s.units + ")") } }, margin: { t: 20 } });
  if (s.best.length) table(document.getElementById("search-best"), ["best feasible design", "value"], s.best);
}
function drawUncertainty() {
  if (!DATA.uncertainty) return;
  document.getElementById("uncertainty-section").hidden = false;
  table(document.getElementById("uncertainty"), ["answer", "units", "mean ± SD", "2.5 %", "50 %", "97.5 %"], DATA.uncertainty);
}
hsel.addEventListener("change", drawHistory);
document.getElementById("frame").addEventListener("input", drawBending);
drawExit();
drawHistory();
drawCards();
drawSearch();
drawUncertainty();
</script>
</body></html>
"""


def plotly_js() -> str:
    try:
        import plotly
    except ImportError as err:
        raise ImportError("the explorer inlines Plotly's JavaScript: pip install 'batstudy[plot]'") from err
    return (Path(plotly.__file__).parent / "package_data" / "plotly.min.js").read_text(encoding="utf-8")


def page(data: dict) -> str:
    """The HTML page of `data` (:func:`collect`): every placeholder filled in one pass, each
    value escaped for where it goes."""
    values = {
        "STUDY": _html.text(data["study"]),
        "PLOTLY": _html.script_code(plotly_js()),
        "DATA": _html.script_json(data),
    }
    return re.sub(r"__(STUDY|PLOTLY|DATA)__", lambda m: values[m.group(1)], PAGE)


def report(path: Union[str, os.PathLike], output: Union[str, os.PathLike, None] = None) -> Path:
    """Write the explorer of the results file `path`, one HTML file (default: next to it,
    ``RESULTS.html``), and return its path. Needs Plotly (``pip install 'batstudy[plot]'``)."""
    out = Path(path).with_suffix(".html") if output is None else Path(output)
    tree = open_results(path)
    with reading(os.fspath(path)):  # values are read here, as the page takes them
        data = collect(tree)
    out.write_text(page(data), encoding="utf-8")
    return out


def main(argv=None, prog: str = "batstudy report") -> int:
    ap = argparse.ArgumentParser(prog=prog, description="Write a results file's explorer: one HTML file, "
                                 "opened by any browser (no server, no network).")  # fmt: skip
    ap.add_argument("results", help="batstudy results file (HDF5)")
    ap.add_argument("-o", "--output", help="the HTML file to write (default: RESULTS with .html)")
    args = ap.parse_args(argv)
    try:
        out = report(args.results, args.output)
    except ResultsFileError as err:  # names the file
        print(f"{prog}: {err}", file=sys.stderr)
        return 2
    except (OSError, ValueError) as err:
        print(f"{prog}: {args.results}: {err}", file=sys.stderr)
        return 2
    print(f"wrote {out} ({out.stat().st_size // 1024} KiB)")
    return 0
