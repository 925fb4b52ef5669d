// SPDX-License-Identifier: GPL-3.0-or-later
// btob explore: the page.  The view (r window x coordinate window) lives in the address; every change asks the
// server for the density at the image's size (GET /api/bifurcation), first at a cheap level, then refined while the
// view stays.  A newer request aborts the older one here and, through the session, cancels it on the server.
"use strict";

const COORDS = {  // default windows (the bifurcation command's) and axis labels with units
  theta: { lo: 0, hi: Math.PI / 2, label: "\u03b8 (rad)" },
  log10_theta: { lo: -16, hi: 0.25, label: "log\u2081\u2080 \u03b8 (\u03b8 in rad)" },
  phi: { lo: 0, hi: Math.PI, label: "\u03c6 (rad)" },
  w1: { lo: -4, hi: 4, label: "w\u2081 (strip, eq. 6.4; dimensionless)" },
  w2: { lo: -1, hi: 1, label: "w\u2082 (strip, eq. 6.4; dimensionless)" },
};
const DEFAULT = { r_min: 0.0717, r_max: 0.1717, coord: "theta" };
// Refinement levels: the first returns in about a tenth of a second (its iterations shrink when the server is
// slower than that), the next ones while the view stays.
const LEVELS = [
  { iterations: 2000, tail: 100 },
  { iterations: 6000, tail: 600 },
  { iterations: 50000, tail: 5000 },
];
// levels=N in the address keeps the first N levels (1..3): a lighter page for slow machines and for tests.
const NLEVELS = Math.max(1, Math.min(LEVELS.length, parseInt(new URLSearchParams(location.search).get("levels"), 10) || LEVELS.length));
const ORBITS = 32;  // the paper's grid of Section 4
const M = { left: 78, right: 16, top: 44, bottom: 52 };  // plot margins (px)
const session = Math.random().toString(36).slice(2, 12);

const $ = (id) => document.getElementById(id);
const state = { view: null, image: null, imageView: null, level: -1, picked: null, overlays: null, rate: null };
window.btob = state;  // for tests and the console
let controller = null;

// ---- the view and the address ----------------------------------------------------------------------------------
function defaultView(coord) {
  const c = COORDS[coord] ? coord : "theta";
  return { r_min: DEFAULT.r_min, r_max: DEFAULT.r_max, coord: c, lo: COORDS[c].lo, hi: COORDS[c].hi };
}
function viewFromURL() {
  const q = new URLSearchParams(location.search);
  const v = defaultView(q.get("coord") || "theta");
  for (const k of ["r_min", "r_max", "lo", "hi"]) {
    const x = parseFloat(q.get(k));
    if (Number.isFinite(x)) v[k] = x;
  }
  return v;
}
function viewQuery(v) {
  return `r_min=${v.r_min}&r_max=${v.r_max}&coord=${v.coord}&lo=${v.lo}&hi=${v.hi}`;
}
function setView(v, push) {
  if (!(v.r_min > 0 && v.r_max < 1 && v.r_min < v.r_max && v.lo < v.hi)) return;
  state.view = v;
  if (push) history.pushState(null, "", "?" + viewQuery(v) + (NLEVELS < LEVELS.length ? `&levels=${NLEVELS}` : ""));
  syncInputs();
  render();
}

// ---- geometry ----------------------------------------------------------------------------------------------------
function plotSize() {
  const w = Math.max(400, Math.floor($("plot").clientWidth));
  const h = Math.max(300, Math.min(760, Math.floor(window.innerHeight - 230)));
  return { w, h, iw: w - M.left - M.right, ih: h - M.top - M.bottom };
}
// Column j of an image of iw columns is r = r_min + (r_max - r_min) j / (iw - 1) (the bifurcation command's
// linspace); its pixel's centre is at x = j + 1/2.
function xOf(r, v, iw) { return M.left + 0.5 + (r - v.r_min) / (v.r_max - v.r_min) * (iw - 1); }
function rOf(x, v, iw) { return v.r_min + (x - M.left - 0.5) / (iw - 1) * (v.r_max - v.r_min); }
function yOf(c, v, ih) { return M.top + (v.hi - c) / (v.hi - v.lo) * ih; }
function cOf(y, v, ih) { return v.hi - (y - M.top) / ih * (v.hi - v.lo); }

// ---- requests ----------------------------------------------------------------------------------------------------
function levelWork(level, iw) {
  const L = Object.assign({}, LEVELS[level]);
  if (level === 0 && state.rate) {  // orbit-iterations per ms measured on this server
    const fit = Math.round(80 * state.rate / (iw * ORBITS));
    L.iterations = Math.max(300, Math.min(L.iterations, fit));
    L.tail = Math.min(L.tail, Math.floor(L.iterations / 4));
  }
  return L;
}
async function render() {
  if (controller) controller.abort();
  controller = new AbortController();
  const signal = controller.signal;
  const v = state.view;
  drawAll();
  fetchOverlays(v);
  const { iw, ih } = plotSize();
  for (let level = 0; level < NLEVELS; ++level) {
    const work = levelWork(level, iw);
    const url = `api/bifurcation?${viewQuery(v)}&width=${iw}&height=${ih}&iterations=${work.iterations}` +
      `&tail=${work.tail}&session=${session}`;
    const ok = await fetchLevel(url, v, level, work, signal);
    if (!ok || signal.aborted) return;
  }
}
async function fetchLevel(url, v, level, work, signal) {
  showProgress(level, 0);
  const poll = setInterval(() => pollProgress(level), 150);
  const t0 = performance.now();
  try {
    const res = await fetch(url, { signal });
    if (!res.ok) {
      const e = await res.json();
      if (res.status !== 409) $("timing").textContent = "error: " + e.error;
      return false;
    }
    const timing = res.headers.get("Server-Timing") || "";
    const blob = await res.blob();
    const img = await createImageBitmap(blob);
    const m = /compute;dur=([0-9.]+)/.exec(timing);
    if (m && level === 0) state.rate = ORBITS * work.iterations * img.width / Math.max(1, parseFloat(m[1]));
    state.image = img;
    state.imageView = Object.assign({ iterations: work.iterations, tail: work.tail, width: img.width }, v);
    state.level = level;
    $("level").dataset.level = level;
    $("level").textContent = `level ${level + 1}/${NLEVELS}: ${ORBITS} orbits x ${work.iterations} iterations`;
    $("timing").textContent = `${Math.round(performance.now() - t0)} ms (${timing.replace(/;dur=/g, " ")} ms)`;
    drawAll();
    return true;
  } catch (e) {
    return false;  // aborted by a newer view
  } finally {
    clearInterval(poll);
    showProgress(level, 1);
  }
}
async function pollProgress(level) {
  try {
    const p = await (await fetch(`api/progress?session=${session}`)).json();
    if (p.bifurcation && p.bifurcation.total) showProgress(level, p.bifurcation.done / p.bifurcation.total);
  } catch (e) { /* the next poll will tell */ }
}
function showProgress(level, f) {
  const total = (level + Math.min(1, f)) / NLEVELS;
  $("progress-bar").style.width = (f >= 1 && level === NLEVELS - 1 ? 0 : 100 * total) + "%";
}
async function fetchOverlays(v) {
  try {
    const res = await fetch(`api/overlays?r_min=${v.r_min}&r_max=${v.r_max}`);
    if (res.ok && state.view === v) {
      state.overlays = await res.json();
      drawOverlay();
    }
  } catch (e) { /* shown at the next view */ }
}

// ---- drawing -----------------------------------------------------------------------------------------------------
function drawAll() {
  const { w, h, iw, ih } = plotSize();
  for (const id of ["image-canvas", "overlay-canvas"]) {
    const c = $(id);
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  }
  $("plot").style.height = h + "px";
  const ctx = $("image-canvas").getContext("2d");
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, w, h);
  drawImage(ctx, iw, ih);
  drawAxes(ctx, w, h, iw, ih);
  drawOverlay();
}
// The last image, placed where its window falls in the current view (a preview while the new one computes).
function drawImage(ctx, iw, ih) {
  const img = state.image, iv = state.imageView, v = state.view;
  if (!img || !iv || iv.coord !== v.coord) return;
  const half = 0.5 * (iv.r_max - iv.r_min) / (img.width - 1);  // old pixel j spans r_j -+ half
  const x0 = xOf(iv.r_min - half, v, iw), x1 = xOf(iv.r_max + half, v, iw);
  ctx.save();
  ctx.beginPath();
  ctx.rect(M.left, M.top, iw, ih);
  ctx.clip();
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(img, x0, yOf(iv.hi, v, ih), x1 - x0, yOf(iv.lo, v, ih) - yOf(iv.hi, v, ih));
  ctx.restore();
}
function niceTicks(lo, hi, n) {
  const raw = (hi - lo) / n, p = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((k) => k * p).find((s) => s >= raw);
  const digits = Math.max(0, -Math.floor(Math.log10(step)));
  const ticks = [];
  for (let t = Math.ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push(t);
  return { ticks, digits };
}
function drawAxes(ctx, w, h, iw, ih) {
  const v = state.view;
  ctx.strokeStyle = "#333";
  ctx.lineWidth = 1;
  ctx.strokeRect(M.left - 0.5, M.top - 0.5, iw + 1, ih + 1);
  ctx.fillStyle = "#222";
  ctx.font = "12px system-ui, sans-serif";
  const tx = niceTicks(v.r_min, v.r_max, Math.max(3, Math.floor(iw / 110)));
  ctx.textAlign = "center";
  for (const t of tx.ticks) {
    const x = Math.round(xOf(t, v, iw)) + 0.5;
    ctx.beginPath(); ctx.moveTo(x, M.top + ih); ctx.lineTo(x, M.top + ih + 5); ctx.stroke();
    ctx.fillText(t.toFixed(tx.digits), x, M.top + ih + 18);
  }
  ctx.fillText("restitution coefficient r (dimensionless)", M.left + iw / 2, h - 10);
  const ty = niceTicks(v.lo, v.hi, Math.max(3, Math.floor(ih / 60)));
  ctx.textAlign = "right";
  for (const t of ty.ticks) {
    const y = Math.round(yOf(t, v, ih)) + 0.5;
    ctx.beginPath(); ctx.moveTo(M.left - 5, y); ctx.lineTo(M.left, y); ctx.stroke();
    ctx.fillText(t.toFixed(ty.digits), M.left - 8, y + 4);
  }
  ctx.save();
  ctx.translate(16, M.top + ih / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = "center";
  ctx.fillText(COORDS[v.coord].label, 0, 0);
  ctx.restore();
  ctx.textAlign = "left";
  ctx.font = "bold 13px system-ui, sans-serif";
  ctx.fillText(title(), M.left, 18);
  ctx.font = "12px system-ui, sans-serif";
  ctx.fillText(subtitle(), M.left, 35);
}
function title() {
  const v = state.view, c = v.coord.replace("log10_theta", "log10 theta");
  return `Bifurcation density of ${c}: r in [${fmt(v.r_min)}, ${fmt(v.r_max)}], ${c} in [${fmt(v.lo)}, ${fmt(v.hi)}]`;
}
function subtitle() {
  const iv = state.imageView;
  if (!iv) return "computing...";
  return `${ORBITS} orbits per r (paper's grid, Section 4) x ${iv.iterations} iterations, last ${iv.tail} binned; ` +
    `${iv.width} r values; colour: log(1 + count)`;
}
function fmt(x) { return Math.abs(x) >= 1e-3 || x === 0 ? x.toPrecision(6).replace(/\.?0+$/, "") : x.toExponential(4); }

const OVERLAY_STYLE = {
  window_bounds: { colour: "#1f5fd6", dash: [] },
  r_crit2: { colour: "#d62020", dash: [] },
  thresholds: { colour: "#777", dash: [6, 4] },
  stripes: { colour: "#1c9e4a", dash: [2, 3] },
};
function drawOverlay() {
  const c = $("overlay-canvas"), ctx = c.getContext("2d");
  const { iw, ih } = plotSize();
  ctx.clearRect(0, 0, c.width, c.height);
  const drawn = {};
  const v = state.view;
  if (state.overlays) {
    for (const [kind, style] of Object.entries(OVERLAY_STYLE)) {
      drawn[kind] = 0;
      if (!$("ov-" + kind).checked) continue;
      ctx.strokeStyle = style.colour;
      ctx.setLineDash(style.dash);
      ctx.lineWidth = 1;
      // Lines closer than 3 px to the last one drawn are left out: near 7 - 4 sqrt(3) hundreds of windows share a
      // few pixels, and a solid block would hide the density (zoom in to see them).
      let last = -Infinity;
      for (const r of (state.overlays[kind] || []).slice().sort((a, b) => a - b)) {
        if (r < v.r_min || r > v.r_max) continue;
        const x = Math.round(xOf(r, v, iw)) + 0.5;
        if (x - last < 3) continue;
        last = x;
        ctx.beginPath(); ctx.moveTo(x, M.top); ctx.lineTo(x, M.top + ih); ctx.stroke();
        drawn[kind] += 1;
      }
    }
    ctx.setLineDash([]);
  }
  if (state.picked !== null && state.picked >= v.r_min && state.picked <= v.r_max) {
    const x = Math.round(xOf(state.picked, v, iw)) + 0.5;
    ctx.strokeStyle = "#000";
    ctx.setLineDash([3, 3]);
    ctx.beginPath(); ctx.moveTo(x, M.top); ctx.lineTo(x, M.top + ih); ctx.stroke();
    ctx.setLineDash([]);
  }
  if (state.box) {
    ctx.strokeStyle = "#2b2233";
    ctx.fillStyle = "rgba(43, 34, 51, 0.12)";
    const b = state.box;
    ctx.fillRect(b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
    ctx.strokeRect(b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
  }
  c.dataset.drawn = JSON.stringify(drawn);
}

// ---- interaction -------------------------------------------------------------------------------------------------
function syncInputs() {
  const v = state.view;
  $("r-min-input").value = v.r_min;
  $("r-max-input").value = v.r_max;
  $("coord-select").value = v.coord;
  $("lo-input").value = v.lo;
  $("hi-input").value = v.hi;
}
function viewFromInputs() {
  const coord = $("coord-select").value;
  const v = { r_min: parseFloat($("r-min-input").value), r_max: parseFloat($("r-max-input").value), coord,
    lo: parseFloat($("lo-input").value), hi: parseFloat($("hi-input").value) };
  if (coord !== state.view.coord) { v.lo = COORDS[coord].lo; v.hi = COORDS[coord].hi; }
  return v;
}
function clampView(v) {
  const w = v.r_max - v.r_min;
  if (v.r_min <= 0) { v.r_min = 1e-9; v.r_max = v.r_min + w; }
  if (v.r_max >= 1) { v.r_max = 1 - 1e-9; v.r_min = Math.max(1e-9, v.r_max - w); }
  return v;
}
function mouse(e) {
  const rect = $("overlay-canvas").getBoundingClientRect();
  return { x: e.clientX - rect.left, y: e.clientY - rect.top };
}
function onDown(e) {
  const p = mouse(e);
  const pan = (document.querySelector("input[name=mode]:checked").value === "pan") !== e.shiftKey;
  state.drag = { x: p.x, y: p.y, pan, view: Object.assign({}, state.view), moved: false };
}
function onMove(e) {
  const d = state.drag;
  if (!d) return;
  const p = mouse(e), { iw, ih } = plotSize();
  if (Math.abs(p.x - d.x) + Math.abs(p.y - d.y) > 4) d.moved = true;
  if (!d.moved) return;
  if (d.pan) {
    const dr = (p.x - d.x) / (iw - 1) * (d.view.r_max - d.view.r_min), dc = (p.y - d.y) / ih * (d.view.hi - d.view.lo);
    state.view = clampView({ r_min: d.view.r_min - dr, r_max: d.view.r_max - dr, coord: d.view.coord,
      lo: d.view.lo + dc, hi: d.view.hi + dc });
    drawAll();
  } else {
    state.box = { x0: Math.min(d.x, p.x), x1: Math.max(d.x, p.x), y0: Math.min(d.y, p.y), y1: Math.max(d.y, p.y) };
    drawOverlay();
  }
}
function onUp(e) {
  const d = state.drag;
  state.drag = null;
  if (!d) return;
  const { iw, ih } = plotSize();
  if (!d.moved) {  // a click picks r, unless it was the first of a double click (reset)
    const r = rOf(d.x, state.view, iw);
    clearTimeout(pickTimer);
    pickTimer = setTimeout(() => pick(r), 250);
    return;
  }
  if (d.pan) { setView(state.view, true); return; }
  const b = state.box, v = state.view;
  state.box = null;
  if (b.x1 - b.x0 < 3) return drawOverlay();
  const nv = { r_min: rOf(b.x0, v, iw), r_max: rOf(b.x1, v, iw), coord: v.coord, lo: v.lo, hi: v.hi };
  if (b.y1 - b.y0 >= 3) { nv.hi = cOf(b.y0, v, ih); nv.lo = cOf(b.y1, v, ih); }
  setView(clampView(nv), true);
}
let wheelTimer = null, pickTimer = null;
function onWheel(e) {
  e.preventDefault();
  const p = mouse(e), { iw, ih } = plotSize(), v = state.view;
  const f = Math.pow(1.0015, e.deltaY);
  const nv = Object.assign({}, v);
  if (e.shiftKey) {
    const c = cOf(p.y, v, ih);
    nv.lo = c - (c - v.lo) * f; nv.hi = c + (v.hi - c) * f;
  } else {
    const r = rOf(p.x, v, iw);
    nv.r_min = r - (r - v.r_min) * f; nv.r_max = r + (v.r_max - r) * f;
  }
  state.view = clampView(nv);
  drawAll();
  clearTimeout(wheelTimer);
  wheelTimer = setTimeout(() => setView(state.view, true), 120);  // one request per wheel gesture
}

// ---- the orbit panel -----------------------------------------------------------------------------------------------
let pickController = null;
async function pick(r) {
  state.picked = r;
  drawOverlay();
  $("basins-button").disabled = true;
  $("info").textContent = `r = ${r}: classifying...`;
  if (pickController) pickController.abort();
  pickController = new AbortController();
  try {
    const point = encodeURIComponent($("point-input").value);
    // The classify command of the registry (GET /api/run), then the orbit's points after the classifier's transient.
    const res = await fetch(`api/run?command=classify&r=${r}&point=${point}&session=${session}`,
      { signal: pickController.signal });
    const j = await res.json();
    if (!res.ok) { $("info").textContent = "error: " + j.error; return; }
    const a = j.attrs;
    const lam = Number.isFinite(a.lambda1) ? `${a.lambda1.toPrecision(6)} \u00b1 ${(a.batch_err || 0).toPrecision(2)}` : "n/a";
    $("info").textContent = `r = ${a.r}\npattern ${a.pattern || "-"}  period ${a.period}\n` +
      `type ${a.type}\nlambda1 = ${lam}\nfrom (${a.point}), after ${a.transient} steps`;
    const t = await fetch(`api/tail?r=${r}&point=${point}&transient=${a.transient}&tail=300&session=${session}`,
      { signal: pickController.signal });
    const strip = await t.json();
    if (!t.ok) { $("info").textContent += "\nerror: " + strip.error; return; }
    drawStrip(strip);
    $("basins-button").disabled = false;
  } catch (e) { /* a newer pick */ }
}
function drawStrip(j) {
  const c = $("strip-canvas"), ctx = c.getContext("2d");
  const w1 = j.w1, w2 = j.w2, m = { l: 44, r: 8, t: 20, b: 34 };
  let lo = Math.min(...w1.filter(Number.isFinite)), hi = Math.max(...w1.filter(Number.isFinite));
  if (!(hi > lo)) { lo -= 1; hi += 1; }
  const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
  ctx.clearRect(0, 0, c.width, c.height);
  const X = (x) => m.l + (x - lo) / (hi - lo) * (c.width - m.l - m.r), Y = (y) => m.t + (1 - y) / 2 * (c.height - m.t - m.b);
  ctx.strokeStyle = "#333"; ctx.strokeRect(m.l, m.t, c.width - m.l - m.r, c.height - m.t - m.b);
  ctx.fillStyle = "#2b2233";
  for (let i = 0; i < w1.length; ++i) ctx.fillRect(X(w1[i]) - 1.5, Y(w2[i]) - 1.5, 3, 3);
  ctx.fillStyle = "#222"; ctx.font = "11px system-ui, sans-serif"; ctx.textAlign = "center";
  ctx.fillText(`last ${w1.length} points in the strip (w\u2081, w\u2082)`, c.width / 2, 13);
  ctx.fillText(`w\u2081: ${fmt(lo)} .. ${fmt(hi)}`, c.width / 2, c.height - 8);
  ctx.save(); ctx.translate(12, c.height / 2); ctx.rotate(-Math.PI / 2); ctx.fillText("w\u2082 in [-1, 1]", 0, 0); ctx.restore();
}
async function basins() {
  const r = state.picked;
  $("basins-status").textContent = "computing the basins on a 100 x 100 sphere grid...";
  const poll = setInterval(async () => {
    try {
      const p = await (await fetch(`api/progress?session=${session}`)).json();
      if (p.basins && p.basins.total)
        $("basins-status").textContent = `computing: ${Math.round(100 * p.basins.done / p.basins.total)}%`;
    } catch (e) { /* next poll */ }
  }, 200);
  try {
    // The basins command of the registry on the main grid alone (no replicate grids: the page shows one image).
    const res = await fetch(`api/run?command=basins&r=${r}&grid=sphere:100x100&replicates=0&session=${session}`);
    const j = await res.json();
    if (!res.ok) { $("basins-status").textContent = "error: " + j.error; return; }
    drawBasins(j.attrs, j.arrays);
  } finally { clearInterval(poll); }
}
const BASIN_COLOURS = ["#bbbbbb", "#1f5fd6", "#d62020", "#1c9e4a", "#f0a020", "#8a3ab9", "#20b0c0", "#c05020", "#606060"];
// The basins record: labels [n2 x n1] (0 undecided, else the attractor's id), per attractor (id k at index k - 1) its
// fraction and interval, its legend_<id> attribute "pattern (type)", and the undecided share.
function drawBasins(a, arrays) {
  const c = $("basins-canvas"), ctx = c.getContext("2d"), s = c.width / a.n1, labels = arrays.labels.data;
  for (let i2 = 0; i2 < a.n2; ++i2)
    for (let i1 = 0; i1 < a.n1; ++i1) {
      ctx.fillStyle = BASIN_COLOURS[labels[i2 * a.n1 + i1] % BASIN_COLOURS.length];
      ctx.fillRect(i1 * s, (a.n2 - 1 - i2) * s, Math.ceil(s), Math.ceil(s));
    }
  const pct = (x) => (100 * x).toFixed(2);
  const rows = arrays.fraction.data.map((f, k) => `<tr><td style="color:${BASIN_COLOURS[(k + 1) % BASIN_COLOURS.length]}">` +
    `\u25a0</td><td>${a["legend_" + (k + 1)]}</td><td>${pct(f)}%</td>` +
    `<td>[${pct(arrays.ci_low.data[k])}, ${pct(arrays.ci_high.data[k])}]</td></tr>`);
  rows.push(`<tr><td style="color:${BASIN_COLOURS[0]}">\u25a0</td><td>undecided</td>` +
    `<td>${pct(a.undecided_fraction)}%</td><td>[${pct(a.undecided_ci_low)}, ${pct(a.undecided_ci_high)}]</td></tr>`);
  $("basins-table").innerHTML = rows.join("");
  $("basins-status").textContent = `r = ${a.r}: ${a.grid} (${a.measure}), 95% intervals`;
}
async function exportView() {
  const v = state.imageView;
  if (!v) return;
  const overlay = Object.keys(OVERLAY_STYLE).filter((k) => $("ov-" + k).checked)
    .map((k) => (k === "window_bounds" || k === "r_crit2" ? "windows" : k));
  const q = `${viewQuery(v)}&width=${v.width}&height=${plotSize().ih}&iterations=${v.iterations}&tail=${v.tail}` +
    `&overlay=${[...new Set(overlay)].join(",")}`;
  $("export-status").textContent = "exporting...";
  const res = await fetch("api/export?" + q, { method: "POST" });
  const j = await res.json();
  $("export-status").textContent = res.ok ? `wrote ${j.scene} and ${j.png} in ${j.folder}/ (btob run ${j.scene})`
    : "error: " + j.error;
  $("export-status").dataset.scene = res.ok ? j.scene : "";
}

function init() {
  const ov = $("overlay-canvas");
  ov.addEventListener("mousedown", onDown);
  window.addEventListener("mousemove", onMove);
  window.addEventListener("mouseup", onUp);
  ov.addEventListener("wheel", onWheel, { passive: false });
  ov.addEventListener("dblclick", () => { clearTimeout(pickTimer); setView(defaultView(state.view.coord), true); });
  for (const k of Object.keys(OVERLAY_STYLE)) $("ov-" + k).addEventListener("change", drawOverlay);
  const go = () => setView(clampView(viewFromInputs()), true);
  $("go-button").addEventListener("click", go);
  for (const id of ["r-min-input", "r-max-input", "lo-input", "hi-input"])
    $(id).addEventListener("keydown", (e) => { if (e.key === "Enter") go(); });
  $("coord-select").addEventListener("change", go);
  $("reset-button").addEventListener("click", () => setView(defaultView(state.view.coord), true));
  $("export-button").addEventListener("click", exportView);
  $("basins-button").addEventListener("click", basins);
  window.addEventListener("popstate", () => setView(viewFromURL(), false));
  let resizeTimer = null;
  window.addEventListener("resize", () => { clearTimeout(resizeTimer); resizeTimer = setTimeout(render, 200); });
  setView(viewFromURL(), false);
}
init();
