"""A study explorer in one HTML file: open it in any browser, no server, no network.

    python scripts/report.py RESULTS.h5 [-o report.html]

The page shows, for any batstudy results file:
- exit speed against impact position, with one control per other dimension of the study
  (model, swing speed, case, ...), and the sweet spot of the chosen curve (position, exit
  speed, width) as numbers and as a marker;
- the force history of any point that recorded one;
- the bat's bending (displacement with time along the bat) for the points that recorded
  displacement, with a time slider.

Plotly's JavaScript (from the `plotly` Python package) is inlined, and so are the data, read
with h5py: the summary's exit speeds, the sweet spots, and the recorded histories only (found
from `/history/force`, so a dense history grid is never read whole).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import h5py
import numpy as np

IMPACT = "impact_z"
MAX_DISPLACEMENT_HISTORIES = 8  # bending animations embedded (each time × z values)
MAX_FRAMES = 80  # time samples of an animation


def text(v) -> str:
    return v.decode() if isinstance(v, bytes) else str(v)


def dim_names(ds: h5py.Dataset) -> list[str]:
    """The dimension-scale names of a variable (its HDF5 dims are attached scales)."""
    return [d[0].name.rsplit("/", 1)[-1] if len(d) else d.label for d in ds.dims]


def clean(a) -> list:
    """Floats for JSON: NaN → null; full precision (repr round-trips)."""
    return [None if (x is None or not math.isfinite(x)) else float(x) for x in np.asarray(a, dtype=float).ravel()]


def dim_labels(group: h5py.Group, dim: str, n: int) -> list[str]:
    """A label per index of `dim`: its own coordinate, or the coordinates that vary along it
    (for a `case` dimension: `bat_preset=aluminum, hoop_frequency=700`)."""
    if dim in group and group[dim].dtype.kind in "fiu" and dim not in ("case", "point", "law", "bat"):
        return [f"{x:g}" for x in group[dim][()]]
    if dim in group and group[dim].dtype.kind in "OSU":
        return [text(x) for x in group[dim][()]]
    parts: list[list[str]] = [[] for _ in range(n)]
    for name, ds in group.items():
        if not isinstance(ds, h5py.Dataset) or name == dim:
            continue
        if dim_names(ds) != [dim]:
            continue
        values = ds[()]
        texts = [text(v) if ds.dtype.kind in "OSU" else (f"{v:g}" if math.isfinite(v) else "") for v in values]
        for i, t in enumerate(texts):
            if t and t != texts[0]:  # what differs from the first (the base) entry
                parts[i].append(f"{name}={t}")
    return [f"{i}: " + (", ".join(p) if p else ("base" if i == 0 else "as the base")) for i, p in enumerate(parts)]


def collect(path: str) -> dict:
    with h5py.File(path, "r") as f:
        s = f["summary"]
        exit_speed = s["exit_speed"]
        dims = dim_names(exit_speed)
        if IMPACT not in dims:
            raise SystemExit(f"{path}: the summary has no {IMPACT} dimension; nothing to plot against")
        controls = [{"name": d, "labels": dim_labels(s, d, exit_speed.shape[k])}
                    for k, d in enumerate(dims) if d != IMPACT]  # fmt: skip
        data = {
            "study": text(f.attrs.get("study_name", "study")),
            "dims": dims,
            "shape": list(exit_speed.shape),
            "controls": controls,
            "impact_z": clean(s[IMPACT][()]),
            "exit_speed": clean(exit_speed[()]),
            "units": text(exit_speed.attrs.get("units", "m/s")),
        }
        if "sweet_spot" in f:
            ss = f["sweet_spot"]
            data["sweet"] = {k: clean(ss[k][()]) for k in ("position", "exit_speed", "width") if k in ss}
        data["histories"] = histories(f, dims, controls)
    return data


def histories(f: h5py.File, dims: list[str], controls: list[dict]) -> list[dict]:
    """The recorded histories: force always, displacement for the first few."""
    if "history" not in f or "force" not in f["history"]:
        return []
    h = f["history"]
    force = h["force"]
    hdims = dim_names(force)
    if hdims[:-1] != dims:
        return []
    t = h["time"][()] * 1e3
    recorded = np.argwhere(np.isfinite(force[..., 0]) if force.shape[-1] else np.zeros(force.shape[:-1], bool))
    out = []
    z = h["z"][()] if "z" in h else None
    for k, idx in enumerate(recorded):
        idx = tuple(int(i) for i in idx)
        label = ", ".join(
            f"{d}={(f['summary'][IMPACT][idx[j]]):g}" if d == IMPACT else
            f"{d}={controls[[c['name'] for c in controls].index(d)]['labels'][idx[j]]}"
            for j, d in enumerate(dims))  # fmt: skip
        entry = {"label": label, "index": list(idx), "time_ms": clean(t), "force": clean(force[idx])}
        if "displacement" in h and z is not None and k < MAX_DISPLACEMENT_HISTORIES:
            disp = h["displacement"][idx]  # (time, z)
            step = max(1, math.ceil(disp.shape[0] / MAX_FRAMES))
            keep = np.isfinite(disp).any(axis=0)
            entry["bending"] = {
                "z": clean(z[keep]),
                "time_ms": clean(t[::step]),
                "mm": [clean(row[keep] * 1e3) for row in disp[::step]],
            }
        out.append(entry)
    return out


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
</style>
<script>__PLOTLY__</script>
</head><body>
<h1>batstudy explorer: <span id="study"></span></h1>
<p>Exit speed against impact position for the chosen values of every other dimension of the study.</p>
<div class="controls" id="controls"></div>
<div class="numbers">sweet spot: <span id="sweet-position">–</span> m,
 exit speed <span id="sweet-exit">–</span> m/s, width <span id="sweet-width">–</span> m</div>
<div id="exit" class="plot"></div>
<h2>Force histories (points that recorded one)</h2>
<div class="controls"><label>history <select id="history"></select></label></div>
<div id="force" class="plot"></div>
<h2>The bat bending (displacement along the bat)</h2>
<div class="controls"><label>time <input type="range" id="frame" min="0" max="0" value="0"></label>
 <span id="frame-time"></span></div>
<div id="bending" class="plot"></div>
<script>
const DATA = __DATA__;
document.getElementById("study").textContent = DATA.study;
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
  const y = curve();
  const traces = [{ x: DATA.impact_z, y: y, mode: "lines+markers", name: "exit speed" }];
  if (DATA.sweet) {
    const i = sweetIndex();
    const p = DATA.sweet.position[i], v = DATA.sweet.exit_speed[i], w = DATA.sweet.width ? DATA.sweet.width[i] : null;
    document.getElementById("sweet-position").textContent = fmt(p, 4);
    document.getElementById("sweet-exit").textContent = fmt(v, 3);
    document.getElementById("sweet-width").textContent = fmt(w, 4);
    if (p !== null) traces.push({ x: [p], y: [v], mode: "markers", marker: { size: 12, symbol: "star" }, name: "sweet spot" });
  }
  Plotly.react("exit", traces, { xaxis: { title: { text: "impact position z (m from the knob)" } },
    yaxis: { title: { text: "exit speed (" + DATA.units + ")" } }, margin: { t: 20 } });
}
const hs = DATA.histories;
const hsel = document.getElementById("history");
hs.forEach((h, i) => { const o = document.createElement("option"); o.value = i; o.textContent = h.label; hsel.appendChild(o); });
function drawHistory() {
  if (!hs.length) { document.getElementById("force").textContent = "This study recorded no force history."; return; }
  const h = hs[+hsel.value];
  Plotly.react("force", [{ x: h.time_ms, y: h.force.map(f => f === null ? null : f / 1000), mode: "lines", name: "force" }],
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
hsel.addEventListener("change", drawHistory);
document.getElementById("frame").addEventListener("input", drawBending);
drawExit();
drawHistory();
</script>
</body></html>
"""


def plotly_js() -> str:
    import plotly

    return (Path(plotly.__file__).parent / "package_data" / "plotly.min.js").read_text()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="batstudy results file (HDF5)")
    ap.add_argument("-o", "--output", default="report.html", help="the HTML file to write (default report.html)")
    args = ap.parse_args(argv)
    data = collect(args.results)
    page = (PAGE.replace("__PLOTLY__", plotly_js().replace("</script>", "<\\/script>"))
            .replace("__STUDY__", data["study"]).replace("__DATA__", json.dumps(data, allow_nan=False)))  # fmt: skip
    Path(args.output).write_text(page)
    print(f"wrote {args.output} ({len(page) // 1024} KiB, {len(data['histories'])} histories)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
