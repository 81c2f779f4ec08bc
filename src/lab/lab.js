// The bat lab's page: it edits a session (a study's base block, the model and an impact
// range), sends it to the server and draws what comes back. Nothing here computes
// physics: every number shown is the server's (batstudy's library). Text from the server
// or a study is only ever set as text, never as markup.
"use strict";

const INCH = 0.0254, OUNCE = 0.028349523125, MPH = 0.44704;
const OZ_IN2 = OUNCE * INCH * INCH, LBF = 0.45359237 * 9.80665;
const SVG = "http://www.w3.org/2000/svg";
const token = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);

let session = null;     // what the page edits
let species = [];       // the wood species the server offers, with their materials
let fileBats = [];      // the bats of the file the lab was started with, with their sessions
let balls = [];         // the balls the server offers (COR shifts about the calibrated mean)
let materials = [];     // the materials a wall's ply may be
let answer = null;      // the server's last answer
let reference = null;   // a pinned answer, drawn dashed
let inFlight = false, pending = false, sentAt = 0;

async function api(path, body) {
  const r = await fetch(path, {
    method: body === undefined ? "GET" : "POST",
    headers: { "X-Batstudy-Token": token, "Content-Type": "application/json" },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  return { status: r.status, json: await r.json() };
}

// An edit: computed at once, or after the one in flight (only the newest edit waits).
function changed() {
  if (inFlight) { pending = true; return; }
  send();
}

async function send() {
  inFlight = true; pending = false; sentAt = performance.now();
  $("status").textContent = "computing…";
  let r;
  try { r = await api("/api/evaluate", session); }
  catch (e) { r = { status: 0, json: { error: "the lab's server did not answer: " + e } }; }
  inFlight = false;
  if (r.status === 200) show(r.json, performance.now() - sentAt);
  else if (r.status !== 409) $("error").textContent = r.json.error || ("HTTP " + r.status);
  if (pending) send();
}

function show(a, ms) {
  $("study").textContent = a.study || "";
  if (a.error) {
    $("error").textContent = a.error;
    $("status").textContent = "not computed (see below)";
    document.body.dataset.state = "error";
    return;
  }
  $("error").textContent = "";
  // a preset just chosen: its knots, wall and plies as the server wrote them (once: the
  // answer echoes the flag, and later edits must not be overwritten by older answers)
  if (session.refill && a.session) { session = a.session; delete session.refill; fillControls(); }
  // turned by the server (`lathe`): the knots as a lathe leaves them, unless newer edits wait
  else if (session.lathe && a.session && !pending) { session.base.bat.profile = a.session.base.bat.profile; }
  answer = a;
  window.__lab_points = a.points;   // the numbers drawn, as the server sent them
  const n = a.points.filter((p) => p.exit_speed_lab !== undefined).length;
  $("status").textContent = `${n} collisions and the bat's card in ${ms.toFixed(0)} ms`;
  drawProfile(); drawCurve(); drawSting(); drawModes(); drawCard(); drawRules();
  document.body.dataset.state = "ready";
  document.body.dataset.answers = String(Number(document.body.dataset.answers || 0) + 1);
}

// ---- the session's fields -------------------------------------------------------------

function bat() { return session.base.bat; }
// the profile's knots, [[z, R], ...] in m (a study may write them bare or under `knots`)
function knots() { const p = bat().profile; return Array.isArray(p) ? p : p.knots; }
function num(x, d) { return x === null || x === undefined || !isFinite(x) ? "–" : Number(x).toFixed(d); }

function fillControls() {
  $("preset").value = bat().preset || "r161";
  const last = knots()[knots().length - 1][0];
  $("length").value = ((bat().length || last) / INCH).toFixed(2);
  $("wall").value = bat().shell && bat().shell.thickness ? (bat().shell.thickness * 1000).toFixed(2) : "";
  $("model").value = session.model;
  $("pitch").value = session.base.pitch ? (session.base.pitch.speed / MPH).toFixed(0) : "";
  $("swing").value = session.base.batter ? (session.base.batter.bat_speed / MPH).toFixed(0) : "";
  $("law").checked = !!(session.base.batter && session.base.batter.exponent);
  $("zfrom").value = (session.impact[0] / INCH).toFixed(1);
  $("zto").value = (session.impact[1] / INCH).toFixed(1);
  $("grip").value = bat().grip ? "pinned" : "";
  const shift = (session.base.ball && session.base.ball.law && session.base.ball.law.cor_shift) || 0;
  $("ball").value = String(Math.max(0, balls.findIndex((b) => b.cor_shift === shift)));
  $("ball").disabled = !(session.base.ball && session.base.ball.preset === "mlb");
  $("lathe").checked = !!session.lathe;
  if (session.lathe) $("lathe-bend").value = String(session.lathe.max_curvature);
  const m = bat().material || {};
  const s = species.findIndex((x) => x.density === m.density && x.youngs_modulus === m.youngs_modulus);
  $("species").value = String(s >= 0 ? s : (m.density === undefined ? 0 : -1));
  $("species").disabled = !isWood();
  fillWallKnots();
  fillPlies();
  const bore = bat().bore;
  $("bored").checked = !!bore;
  if (bore) {
    $("bore-diameter").value = (bore.diameter / INCH).toFixed(2);
    $("bore-depth").value = (bore.depth / INCH).toFixed(1);
    $("bore-fill").value = String(bore.fill_density || 0);
  }
  for (const id of ["bored", "bore-diameter", "bore-depth", "bore-fill"]) $(id).disabled = bat().preset !== "r161";
}

// a layered wall's plies, outside in: material, thickness (mm; they scale with the wall
// along the bat) and fibre angle (degrees from the bat's axis)
function fillPlies() {
  const box = $("plies");
  while (box.firstChild) box.removeChild(box.firstChild);
  const layers = bat().shell && bat().shell.layers;
  if (!layers) return;
  const t = document.createElement("table");
  const head = document.createElement("tr");
  for (const h of ["ply (outside in)", "mm", "deg"]) { const c = document.createElement("td"); c.textContent = h; head.appendChild(c); }
  t.appendChild(head);
  layers.forEach((layer, i) => {
    const tr = document.createElement("tr");
    const pick = document.createElement("select");
    pick.id = `ply-material-${i}`;
    for (const m of materials) { const o = document.createElement("option"); o.value = m; o.textContent = m; pick.appendChild(o); }
    pick.value = layer.material;
    pick.addEventListener("change", () => { layer.material = pick.value; changed(); });
    const thick = Object.assign(document.createElement("input"), { type: "number", step: "0.05", value: (layer.thickness * 1000).toFixed(2) });
    thick.id = `ply-thickness-${i}`;
    thick.addEventListener("change", () => { layer.thickness = Number(thick.value) / 1000; changed(); });
    const angle = Object.assign(document.createElement("input"), { type: "number", step: "5", value: ((layer.angle || 0) * 180 / Math.PI).toFixed(0) });
    angle.id = `ply-angle-${i}`;
    angle.addEventListener("change", () => { layer.angle = Number(angle.value) * Math.PI / 180; changed(); });
    for (const x of [pick, thick, angle]) { const c = document.createElement("td"); c.appendChild(x); tr.appendChild(c); }
    t.appendChild(tr);
  });
  box.appendChild(t);
}

function isWood() { return ["r161", "corked", undefined].includes(bat().preset) && !(bat().shell && bat().shell.layers); }

// a hollow bat's wall along the bat: its thickness knots as numbers to edit (z read-only)
function fillWallKnots() {
  const box = $("wall-knots");
  while (box.firstChild) box.removeChild(box.firstChild);
  const k = bat().shell && bat().shell.thickness_knots;
  if (!k) return;
  const t = document.createElement("table");
  const head = document.createElement("tr");
  for (const h of ["wall at", "mm"]) { const c = document.createElement("td"); c.textContent = h; head.appendChild(c); }
  t.appendChild(head);
  k.forEach((knot, i) => {
    const tr = document.createElement("tr");
    const z = document.createElement("td");
    z.textContent = `${num(knot[0] / INCH, 1)} in`;
    const cell = document.createElement("td");
    const input = document.createElement("input");
    Object.assign(input, { type: "number", step: "0.1", value: (knot[1] * 1000).toFixed(2) });
    input.id = `wall-knot-${i}`;
    input.addEventListener("change", () => { k[i][1] = Number(input.value) / 1000; changed(); });
    cell.appendChild(input);
    tr.append(z, cell);
    t.appendChild(tr);
  });
  box.appendChild(t);
}

function bind(id, apply) {
  $(id).addEventListener("change", () => { apply($(id)); changed(); });
}

function bindControls() {
  bind("preset", (e) => {
    session.base.bat = { preset: e.value };   // the preset's own profile, wall and material
    delete session.base.hoop;
    session.refill = true;   // the server answers with the preset's knots
  });
  bind("length", (e) => { bat().length = Number(e.value) * INCH; });
  bind("wall", (e) => {
    if (e.value === "") { if (bat().shell) delete bat().shell.thickness; return; }
    bat().shell = Object.assign({}, bat().shell || {}, { thickness: Number(e.value) / 1000 });
    delete bat().shell.thickness_knots;   // a layered wall's plies scale with it
    fillWallKnots();
  });
  bind("species", (e) => {
    const s = species[Number(e.value)];
    if (!s) return;
    bat().material = Object.assign({}, bat().material, { density: s.density, youngs_modulus: s.youngs_modulus });
  });
  const lathe = () => {
    if ($("lathe").checked) session.lathe = { max_curvature: Number($("lathe-bend").value) };
    else delete session.lathe;
  };
  bind("lathe", lathe);
  bind("lathe-bend", lathe);
  const bore = () => {
    if (!$("bored").checked) { delete bat().bore; return; }
    bat().bore = {
      diameter: Number($("bore-diameter").value) * INCH,
      depth: Number($("bore-depth").value) * INCH,
      fill_density: Number($("bore-fill").value),
    };
  };
  for (const id of ["bored", "bore-diameter", "bore-depth", "bore-fill"]) bind(id, bore);
  bind("ball", (e) => {
    const b = balls[Number(e.value)];
    const ball = session.base.ball;
    ball.law = Object.assign({}, ball.law, { cor_shift: b.cor_shift });
    if (b.cor_shift === 0) delete ball.law.cor_shift;
    if (Object.keys(ball.law).length === 0) delete ball.law;
  });
  bind("grip", (e) => {
    if (e.value) bat().grip = { z: 6 * INCH, kind: "pinned" };
    else delete bat().grip;
  });
  bind("bats", (e) => {
    session = JSON.parse(JSON.stringify(fileBats[Number(e.value)].session));
    reference = null;
    fillControls();
  });
  bind("model", (e) => { session.model = e.value; });
  bind("pitch", (e) => { session.base.pitch = Object.assign({}, session.base.pitch, { speed: Number(e.value) * MPH }); });
  bind("swing", (e) => { session.base.batter = Object.assign({}, session.base.batter, { bat_speed: Number(e.value) * MPH }); });
  bind("law", (e) => { session.base.batter = Object.assign({}, session.base.batter, { exponent: e.checked ? 0.27 : 0 }); });
  bind("zfrom", (e) => { session.impact[0] = Number(e.value) * INCH; });
  bind("zto", (e) => { session.impact[1] = Number(e.value) * INCH; });
  $("pin").addEventListener("click", () => { reference = answer; drawProfile(); drawCurve(); });
  $("save").addEventListener("click", save);
}

async function save() {
  const r = await api("/api/save", { name: $("save-name").value, session });
  $("saved").textContent = r.status === 200 ? "saved: " + r.json.saved.join(", ") : "";
  $("error").textContent = r.status === 200 ? "" : r.json.error;
}

// ---- drawing ------------------------------------------------------------------------------

function el(tag, attrs, parent) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

function clear(svg) { while (svg.firstChild) svg.removeChild(svg.firstChild); }

// the profile in mm: z along, radius up and down (the SVG's y grows downward)
function outline(z, r) {
  const top = z.map((zi, i) => `${zi * 1000},${-r[i] * 1000}`);
  const bottom = z.map((zi, i) => `${zi * 1000},${r[i] * 1000}`).reverse();
  return top.concat(bottom).join(" ");
}

function drawProfile() {
  const svg = $("profile");
  clear(svg);
  const length = answer ? answer.bat.length : knots()[knots().length - 1][0];
  svg.setAttribute("viewBox", `-10 -45 ${length * 1000 + 20} 90`);
  if (reference) el("polygon", { points: outline(reference.bat.profile_z, reference.bat.outer_radius), class: "ref" }, svg);
  if (answer) {
    el("polygon", { points: outline(answer.bat.profile_z, answer.bat.outer_radius), class: "outline" }, svg);
    if (answer.bat.inner_radius.some((r) => r > 0))
      el("polygon", { points: outline(answer.bat.profile_z, answer.bat.inner_radius), class: "bore" }, svg);
  }
  knots().forEach(([z, r], i) => {
    const c = el("circle", { cx: z * 1000, cy: -r * 1000, r: 4, class: "knot", "data-index": i }, svg);
    c.addEventListener("pointerdown", (ev) => drag(ev, i, c));
  });
}

// A knot moves up and down (its radius), as a lathe would cut it; 0.1 mm steps.
function drag(ev, i, circle) {
  const svg = $("profile");
  circle.setPointerCapture(ev.pointerId);
  const move = (e) => {
    const pt = svg.createSVGPoint();
    pt.x = e.clientX; pt.y = e.clientY;
    const local = pt.matrixTransform(svg.getScreenCTM().inverse());
    const r = Math.min(40, Math.max(4, Math.round(-local.y * 10) / 10)) / 1000;
    knots()[i] = [knots()[i][0], r];
    circle.setAttribute("cy", -r * 1000);
    changed();
  };
  const up = () => {
    circle.removeEventListener("pointermove", move);
    circle.removeEventListener("pointerup", up);
  };
  circle.addEventListener("pointermove", move);
  circle.addEventListener("pointerup", up);
}

function drawCurve() {
  const svg = $("curve");
  clear(svg);
  const ok = (a) => a.points.filter((p) => p.exit_speed_lab !== undefined && p.exit_speed_lab !== null);
  const all = [answer].concat(reference ? [reference] : []);
  const zs = all.flatMap((a) => ok(a).map((p) => p.z));
  const vs = all.flatMap((a) => ok(a).map((p) => p.exit_speed_lab / MPH));
  if (zs.length === 0) return;
  const [z0, z1] = [Math.min(...zs), Math.max(...zs)];
  const [v0, v1] = [Math.floor(Math.min(...vs) / 5) * 5, Math.ceil(Math.max(...vs) / 5) * 5];
  const x = (z) => 50 + (z - z0) / (z1 - z0 || 1) * 800;
  const y = (v) => 280 - (v - v0) / (v1 - v0 || 1) * 260;
  const yb = (b) => 280 - (b - 0.3) / 0.3 * 260;   // BBCOR 0.3–0.6 on the right
  el("line", { x1: 50, y1: 280, x2: 850, y2: 280, class: "axis" }, svg);
  el("line", { x1: 50, y1: 20, x2: 50, y2: 280, class: "axis" }, svg);
  for (let v = v0; v <= v1; v += 5) el("text", { x: 8, y: y(v) + 3, class: "tick" }, svg).textContent = `${v}`;
  for (let z = Math.ceil(z0 / INCH); z <= z1 / INCH; z += 2) el("text", { x: x(z * INCH) - 6, y: 295, class: "tick" }, svg).textContent = `${z}″`;
  const path = (a, key, scale, cls) => {
    const pts = ok(a).map((p) => `${x(p.z)},${scale(p[key])}`);
    el("polyline", { points: pts.join(" "), class: cls }, svg);
  };
  if (reference) path(reference, "exit_speed_lab", (v) => y(v / MPH), "ref");
  path(answer, "exit_speed_lab", (v) => y(v / MPH), "curve");
  const b = answer.bat;
  const scan = b.bbcor_z.map((z, i) => [z, b.bbcor[i]]).filter(([z, v]) => v !== null && z >= z0 && z <= z1);
  el("polyline", { points: scan.map(([z, v]) => `${x(z)},${yb(v)}`).join(" "), class: "bbcor" }, svg);
  for (const v of [0.4, 0.5]) el("text", { x: 856, y: yb(v) + 3, class: "tick" }, svg).textContent = `${v}`;
  const best = ok(answer).reduce((m, p) => (p.exit_speed_lab > m.exit_speed_lab ? p : m));
  const mark = el("circle", { cx: x(best.z), cy: y(best.exit_speed_lab / MPH), r: 4, fill: "#1d3557", id: "best-exit" }, svg);
  mark.dataset.si = String(best.exit_speed_lab);
  mark.dataset.z = String(best.z);
}

// the vibration the hands feel after each impact, along the same barrel as the curve
function drawSting() {
  const svg = $("sting");
  clear(svg);
  const pts = answer.points.filter((p) => p.grip_vibration_amplitude !== undefined && p.grip_vibration_amplitude !== null);
  if (pts.length === 0) return;
  const zs = pts.map((p) => p.z), mm = pts.map((p) => p.grip_vibration_amplitude * 1000);
  const [z0, z1] = [Math.min(...zs), Math.max(...zs)];
  const top = Math.max(...mm) || 1;
  const x = (z) => 50 + (z - z0) / (z1 - z0 || 1) * 800;
  const y = (v) => 125 - v / top * 110;
  el("line", { x1: 50, y1: 125, x2: 850, y2: 125, class: "axis" }, svg);
  el("text", { x: 4, y: 18, class: "tick" }, svg).textContent = `${num(top, 2)} mm`;
  el("text", { x: 30, y: 128, class: "tick" }, svg).textContent = "0";
  el("polyline", { points: pts.map((p, i) => `${x(p.z)},${y(mm[i])}`).join(" "), class: "sting" }, svg);
  const quiet = pts.reduce((m, p) => (p.grip_vibration_amplitude < m.grip_vibration_amplitude ? p : m));
  const mark = el("circle", { cx: x(quiet.z), cy: y(quiet.grip_vibration_amplitude * 1000), r: 4, fill: "#e76f51", id: "quietest" }, svg);
  mark.dataset.z = String(quiet.z);
}

// the bat's two lowest bending modes along the bat and its wall's lowest breathing mode
// along the hollow part, each scaled to its largest value (the server's shapes)
function drawModes() {
  const svg = $("modes");
  clear(svg);
  const m = answer.modes;
  const legend = $("modes-legend");
  legend.textContent = "";
  if (!m) return;
  const length = answer.bat.length;
  const x = (z) => 50 + z / length * 800;
  const y = (v) => 70 - v * 60;
  el("line", { x1: 50, y1: 70, x2: 850, y2: 70, class: "axis" }, svg);
  const words = [];
  m.bending.forEach((b, i) => {
    el("polyline", { points: b.z.map((z, k) => `${x(z)},${y(b.shape[k])}`).join(" "), class: `mode${i + 1}`, id: `bending-${i + 1}` }, svg);
    words.push(`${i === 0 ? "━" : "╍"} bending mode ${i + 1}, ${num(b.frequency, 0)} Hz`);
  });
  if (m.hoop) {
    el("polyline", { points: m.hoop.z.map((z, k) => `${x(z)},${y(m.hoop.shape[k])}`).join(" "), class: "hoopshape", id: "hoop-shape" }, svg);
    words.push(`red: the wall's lowest breathing mode (n = ${m.hoop.wave_number}), ${num(m.hoop.frequency, 0)} Hz, its radial motion along the barrel`);
  }
  legend.textContent = words.join("   ");
}

function row(table, name, text, id, si) {
  const tr = document.createElement("tr");
  const a = document.createElement("td"), b = document.createElement("td");
  a.textContent = name; b.textContent = text;
  if (id) { b.id = id; b.dataset.si = String(si); }
  tr.append(a, b);
  table.appendChild(tr);
}

function drawCard() {
  const t = $("card");
  t.replaceChildren();
  const b = answer.bat;
  row(t, "bat", b.label);
  row(t, "length", `${num(b.length / INCH, 2)} in`, "card-length", b.length);
  row(t, "weight", `${num(b.mass / OUNCE, 2)} oz, drop ${num(b.drop, 1)}`, "card-mass", b.mass);
  row(t, "balance point", `${num(b.z_cm / INCH, 2)} in from the knob`, "card-balance", b.z_cm);
  row(t, "MOI about 6 in", `${num(b.moment_of_inertia_knob6 / OZ_IN2, 0)} oz in²`, "card-moi6", b.moment_of_inertia_knob6);
  row(t, "barrel", `${num(b.barrel_diameter / INCH, 3)} in`, "card-barrel", b.barrel_diameter);
  row(t, "BBCOR", `${num(b.bbcor_max, 4)} at ${num(b.bbcor_max_position / INCH, 1)} in`, "card-bbcor", b.bbcor_max);
  row(t, "sweet zone", `${num(b.sweet_zone_start / INCH, 1)}–${num(b.sweet_zone_end / INCH, 1)} in (BBCOR within 0.01)`);
  row(t, "best q", `${num(b.best_q, 3)}`, "card-best-q", b.best_q);
  row(t, "bending mode 1", `${num(b.bending_frequency, 0)} Hz`);
  row(t, "hoop mode", b.hoop_mode_frequency === null ? "none (solid)" : `${num(b.hoop_mode_frequency, 0)} Hz`);
  const l = answer.lathe;
  if (l) {
    const rise = l.largest_fall === null
      ? `rises from ${num(l.rises_from / INCH, 1)} to ${num(l.rises_to / INCH, 1)} in`
      : `falls ${num(l.largest_fall.by * 1000, 3)} mm at ${num(l.largest_fall.at / INCH, 1)} in, between the handle and the barrel's thickest`;
    row(t, "lathe", `${rise}; sharpest bend ${num(l.sharpest_bend, 2)} /m`, "card-lathe", l.sharpest_bend);
  }
  if (b.barrel_compression !== null) row(t, "barrel compression", `${num(b.barrel_compression / LBF, 0)} lbf at 0.040 in`, "card-compression", b.barrel_compression);
  if (b.wall_stress_ratio !== null) row(t, "wall stress", `${num(b.wall_stress_ratio, 2)} of its strength at ${num(b.wall_stress_ratio_position / INCH, 1)} in${b.wall_stress_ratio > 1 ? " (would dent or crack)" : ""}`, "card-wall-stress", b.wall_stress_ratio);
  const best = ok2(answer.points).reduce((m, p) => (p.exit_speed_lab > m.exit_speed_lab ? p : m));
  row(t, "best exit speed", `${num(best.exit_speed_lab / MPH, 1)} mph at ${num(best.z / INCH, 1)} in`, "card-best-exit", best.exit_speed_lab);
  if (best.carry !== null && best.carry !== undefined) row(t, "its carry", `${num(best.carry / 0.3048, 0)} ft at ${num(best.launch_angle * 180 / Math.PI, 0)}°`);
  row(t, "vibration at the hands", `${num(best.grip_vibration_amplitude * 1000, 2)} mm there`);
  if (reference) {
    const rb = ok2(reference.points).reduce((m, p) => (p.exit_speed_lab > m.exit_speed_lab ? p : m));
    row(t, "reference", `${num(reference.bat.mass / OUNCE, 2)} oz, BBCOR ${num(reference.bat.bbcor_max, 4)}, best ${num(rb.exit_speed_lab / MPH, 1)} mph`);
  }
}

function ok2(points) { return points.filter((p) => p.exit_speed_lab !== undefined && p.exit_speed_lab !== null); }

function drawRules() {
  const t = $("rules");
  t.replaceChildren();
  for (const r of answer.bat.rules) {
    const tr = document.createElement("tr");
    const a = document.createElement("td"), b = document.createElement("td");
    a.textContent = r.label;
    const passes = r.margin !== null && r.margin >= 0;
    b.textContent = r.margin === null ? "cannot judge" : passes ? "passes" : "FAILS";
    b.className = passes ? "passes" : "fails";
    tr.append(a, b);
    t.appendChild(tr);
  }
}

// ---- start ----------------------------------------------------------------------------------

(async function start() {
  const r = await api("/api/start");
  if (r.status !== 200) { $("error").textContent = "the lab refused the page: " + JSON.stringify(r.json); return; }
  session = r.json;
  species = (await api("/api/species")).json;
  for (const [i, s] of species.entries()) {
    const o = document.createElement("option");
    o.value = String(i); o.textContent = s.name;
    $("species").appendChild(o);
  }
  const other = document.createElement("option");
  other.value = "-1"; other.textContent = "the study's own"; other.hidden = true;
  $("species").appendChild(other);
  materials = (await api("/api/materials")).json;
  balls = (await api("/api/balls")).json;
  for (const [i, b] of balls.entries()) {
    const o = document.createElement("option");
    o.value = String(i); o.textContent = b.name;
    $("ball").appendChild(o);
  }
  fileBats = (await api("/api/bats")).json;
  if (fileBats.length > 1) {
    for (const [i, b] of fileBats.entries()) {
      const o = document.createElement("option");
      o.value = String(i); o.textContent = b.label;
      $("bats").appendChild(o);
    }
    $("bats-row").hidden = false;
  }
  fillControls();
  bindControls();
  drawProfile();
  changed();
})();
