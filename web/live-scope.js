// tiptap live: the console's page, the scope: its panels, axes, cursor, zoom, hold and reference (docs/live.md); loaded after live.js,
// whose state and helpers it shares (classic scripts: one global scope).
"use strict";

// ---- scope
const panels = [
  { key: "z", label: "height z", unit: "nm", scale: 1e9, surface: true },
  { key: "error", label: "error", unit: "nm", scale: 1e9 },
  { key: "amplitude", label: "amplitude", unit: "nm", scale: 1e9 },
  { key: "phase", label: "phase", unit: "deg", scale: 1 },
];
const colours = { trace: "#1565c0", retrace: "#c62828", surface: "#888", reftrace: "#ef6c00", refretrace: "#2e7d32" };
function scope(m) {
  // the gains the line ran with (the server's), for a reference's legend: a line under way
  // when a change came arrives after the change is in force
  const g = (x) => (x == null ? "?" : Number(x.toPrecision(6)));
  m.gains = "I gain " + g(m.ki) + " Hz, P gain " + g(m.kp);
  state.scope = m;
  state.scopes++;
  // the block's delay is the record's point spacing
  if (m.rate > 0 && loop.p.fd > 0) { const P = Math.round(loop.p.fd / m.rate); if (P >= 1 && P !== loop.p.P) { loop.p.P = P; loop.sig = ""; } }
  if (state.hold && state.scopeShown) return;
  state.scopeShown = m;
  drawScope();
}
// One direction's abscissa as drawn: the tip's position in nm, or the instrument time in
// ms from the trace's start (the decimated points spaced evenly between the ends' times).
function xsOf(m, dir) {
  const d = m[dir];
  if (state.xmode === "position") return d.position.map((v) => (v == null ? null : v * 1e9));
  const n = d.position.length, t0 = m.trace.t0;
  return d.position.map((_, i) => 1e3 * (d.t0 + (n > 1 ? (d.t1 - d.t0) * i / (n - 1) : 0) - t0));
}
function seriesOf(m, ref) {
  const out = [];
  for (const dir of ["trace", "retrace"]) {
    if (!m[dir] || !m[dir].position.length) continue;
    out.push({ dir, ref, xs: xsOf(m, dir), d: m[dir], colour: colours[(ref ? "ref" : "") + dir] });
  }
  return out;
}
function geometry() {
  const cv = $("scope");
  const W = cv.clientWidth, H = cv.clientHeight;
  const left = 64, right = 12, top = 6, bottom = 40, gap = 10;
  const ph = (H - top - bottom - gap * (panels.length - 1)) / panels.length;
  return { W, H, left, right, top, bottom, gap, ph, pw: W - left - right };
}
function drawScope() {
  const cv = $("scope"), dpr = window.devicePixelRatio || 1;
  const g = geometry();
  // the canvas's pixels are the screen's: its text is drawn at the size it is read
  const BW = Math.round(g.W * dpr), BH = Math.round(g.H * dpr);
  if (cv.width !== BW || cv.height !== BH) { cv.width = BW; cv.height = BH; }
  const ctx = cv.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, g.W, g.H);
  ctx.font = FONT_PX + "px DejaVu Sans, sans-serif";
  state.scopeTextPx = FONT_PX * (cv.clientWidth / (cv.width / dpr));
  const m = state.scopeShown;
  if (!m) return;
  const series = seriesOf(m, false);
  const refs = state.reference ? seriesOf(state.reference, true) : [];
  let x0 = Infinity, x1 = -Infinity;
  for (const s of series) for (const v of s.xs) if (v != null) { x0 = Math.min(x0, v); x1 = Math.max(x1, v); }
  if (!(x1 > x0)) return;
  if (state.zoom) { x0 = Math.max(x0, state.zoom[0]); x1 = Math.min(x1, state.zoom[1]); if (!(x1 > x0)) { state.zoom = null; return drawScope(); } }
  const X = (x) => g.left + (x - x0) / (x1 - x0) * g.pw;
  const xt = fitTicks(x0, x1, g.pw);
  const geo = { x0, x1, g, panels: [], xticks: xt.at, xstep: xt.step };
  panels.forEach((p, k) => {
    const y0 = g.top + k * (g.ph + g.gap);
    // the y range of what is in view, the reference's too
    let lo = Infinity, hi = -Infinity;
    const look = (xs, ys) => {
      for (let i = 0; i < ys.length; i++) {
        if (ys[i] == null || xs[i] == null || xs[i] < x0 || xs[i] > x1) continue;
        const v = ys[i] * p.scale; if (v < lo) lo = v; if (v > hi) hi = v;
      }
    };
    for (const s of series.concat(refs)) { look(s.xs, s.d[p.key]); if (p.surface && !s.ref) look(s.xs, s.d.surface); }
    if (!(hi > lo)) { hi = (isFinite(hi) ? hi : 0) + 1; lo = hi - 2; }
    const pad = 0.06 * (hi - lo); lo -= pad; hi += pad;
    const Y = (v) => y0 + g.ph - (v - lo) / (hi - lo) * g.ph;
    // grid and ticks
    ctx.strokeStyle = "#e3e3e3"; ctx.lineWidth = 1; ctx.fillStyle = "#222";
    ctx.textAlign = "right"; ctx.textBaseline = "middle";
    const yt = ticks(lo, hi, Math.max(3, Math.floor(g.ph / 24)));
    geo.panels.push({ y0, lo, hi, yticks: yt.at, ystep: yt.step });
    for (const t of yt.at) {
      const y = Math.round(Y(t)) + 0.5;
      ctx.beginPath(); ctx.moveTo(g.left, y); ctx.lineTo(g.left + g.pw, y); ctx.stroke();
      ctx.fillText(tickText(t, yt.step), g.left - 5, y);
    }
    for (const t of xt.at) {
      const x = Math.round(X(t)) + 0.5;
      ctx.beginPath(); ctx.moveTo(x, y0); ctx.lineTo(x, y0 + g.ph); ctx.stroke();
    }
    ctx.strokeStyle = "#999"; ctx.strokeRect(g.left + 0.5, y0 + 0.5, g.pw, g.ph);
    ctx.save();
    ctx.beginPath(); ctx.rect(g.left, y0, g.pw, g.ph); ctx.clip();
    const line = (xs, ys, col, width, dash) => {
      ctx.strokeStyle = col; ctx.lineWidth = width; ctx.setLineDash(dash);
      ctx.beginPath();
      let pen = false;
      for (let i = 0; i < ys.length; i++) {
        if (ys[i] == null || xs[i] == null) { pen = false; continue; }
        const px = X(xs[i]), py = Y(ys[i] * p.scale);
        if (pen) ctx.lineTo(px, py); else ctx.moveTo(px, py);
        pen = true;
      }
      ctx.stroke();
    };
    for (const s of refs) line(s.xs, s.d[p.key], s.colour, 1.5, []);
    if (p.surface) for (const s of series) line(s.xs, s.d.surface, colours.surface, 1, [4, 3]);
    for (const s of series) line(s.xs, s.d[p.key], s.colour, 1.3, []);
    ctx.setLineDash([]);
    ctx.restore();
    // the panel's name and unit, on a white ground at its top left
    const name = p.label + " (" + p.unit + ")";
    ctx.textAlign = "left"; ctx.textBaseline = "top";
    const tw = ctx.measureText(name).width;
    ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(g.left + 2, y0 + 2, tw + 6, FONT_PX + 4);
    ctx.fillStyle = "#222"; ctx.fillText(name, g.left + 5, y0 + 3);
  });
  // the x axis under the last panel
  const yb = g.top + panels.length * (g.ph + g.gap) - g.gap;
  ctx.fillStyle = "#222"; ctx.textAlign = "center"; ctx.textBaseline = "top";
  for (const t of xt.at) ctx.fillText(tickText(t, xt.step), X(t), yb + 3);
  ctx.fillText(state.xmode === "position" ? "position along the fast axis (nm)" :
    "time from the trace's start (ms): trace, then retrace", g.left + g.pw / 2, yb + 4 + FONT_PX + 4);
  // the cursor: a vertical line and each line's point under it
  if (state.cursor != null && state.cursor >= x0 && state.cursor <= x1) {
    const cx = Math.round(X(state.cursor)) + 0.5;
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1; ctx.setLineDash([2, 2]);
    ctx.beginPath(); ctx.moveTo(cx, g.top); ctx.lineTo(cx, yb); ctx.stroke();
    ctx.setLineDash([]);
  }
  // a drag in progress: the span it would zoom to
  if (state.drag && state.drag.to != null) {
    ctx.fillStyle = "rgba(21,101,192,0.15)";
    const a = Math.min(state.drag.from, state.drag.to), b = Math.max(state.drag.from, state.drag.to);
    ctx.fillRect(a, g.top, b - a, yb - g.top);
  }
  state.scopeGeom = geo;
  const held = state.hold ? "held: " : "";
  $("scopeinfo").textContent = held + "line " + m.line + " (" + m.tier + " tier), " +
    (m.rate ? (m.rate / 1000).toFixed(1) + " kHz record" : "") +
    (state.zoom ? ", zoomed: " + tickText(x0, xt.step / 10) + " to " + tickText(x1, xt.step / 10) +
      (state.xmode === "position" ? " nm" : " ms") : "");
  readout();
}
// The values under the cursor: each line's point nearest to it along x.
function nearest(xs, x) {
  let best = -1, bd = Infinity;
  for (let i = 0; i < xs.length; i++) if (xs[i] != null) { const d = Math.abs(xs[i] - x); if (d < bd) { bd = d; best = i; } }
  return best;
}
function readout() {
  const tab = $("readout");
  tab.textContent = "";
  const m = state.scopeShown;
  const x = state.cursor;
  const head = tab.insertRow();
  const u = state.xmode === "position" ? "nm" : "ms";
  const h0 = document.createElement("th");
  h0.textContent = x == null ? "cursor: point at the scope" : "at " + x.toPrecision(4) + " " + u;
  head.appendChild(h0);
  for (const p of panels.map((q) => q.label + " (" + q.unit + ")").concat([state.xmode === "position" ? "time (ms)" : "position (nm)"])) {
    const th = document.createElement("th"); th.textContent = p; head.appendChild(th);
  }
  const values = [];
  if (m && x != null) {
    const rows = seriesOf(m, false).concat(state.reference ? seriesOf(state.reference, true) : []);
    for (const s of rows) {
      const i = nearest(s.xs, x);
      if (i < 0) continue;
      const r = tab.insertRow();
      r.className = (s.ref ? "ref" : "") + s.dir;
      const c0 = r.insertCell(); c0.textContent = (s.ref ? "reference " : "") + s.dir;
      const vals = { series: (s.ref ? "ref" : "") + s.dir, index: i };
      for (const p of panels) {
        const v = s.d[p.key][i];
        vals[p.key] = v == null ? null : v * p.scale;
        r.insertCell().textContent = v == null ? "-" : (v * p.scale).toFixed(p.key === "phase" ? 2 : 3);
      }
      const n = s.d.position.length;
      const t = 1e3 * (s.d.t0 + (n > 1 ? (s.d.t1 - s.d.t0) * i / (n - 1) : 0) - (s.ref ? state.reference : m).trace.t0);
      vals.time_ms = t;
      vals.position_nm = s.d.position[i] == null ? null : s.d.position[i] * 1e9;
      r.insertCell().textContent = state.xmode === "position" ? t.toFixed(2) : (vals.position_nm == null ? "-" : vals.position_nm.toFixed(1));
      values.push(vals);
    }
  }
  state.cursorValues = values;
}
// pointer x on the canvas (CSS px) to the scope's x, or null outside the plot
function xAt(px) {
  const geo = state.scopeGeom;
  if (!geo || px < geo.g.left || px > geo.g.left + geo.g.pw) return null;
  return geo.x0 + (px - geo.g.left) / geo.g.pw * (geo.x1 - geo.x0);
}
function zoomBy(f) {
  const geo = state.scopeGeom;
  if (!geo) return;
  const c = (geo.x0 + geo.x1) / 2, h = (geo.x1 - geo.x0) / 2 / f;
  state.zoom = f < 1 && state.zoom && h * 2 >= fullSpan() ? null : [c - h, c + h];
  drawScope();
}
function fullSpan() {
  const m = state.scopeShown;
  if (!m) return 0;
  let a = Infinity, b = -Infinity;
  for (const s of seriesOf(m, false)) for (const v of s.xs) if (v != null) { a = Math.min(a, v); b = Math.max(b, v); }
  return b - a;
}
function scopeUi() {
  const cv = $("scope");
  const px = (ev) => ev.clientX - cv.getBoundingClientRect().left;
  cv.addEventListener("mousedown", (ev) => { if (ev.button === 0) state.drag = { from: px(ev), to: null }; });
  cv.addEventListener("mousemove", (ev) => {
    const p = px(ev);
    if (state.drag && (ev.buttons & 1)) state.drag.to = p;
    const x = xAt(p);
    if (x != null) state.cursor = x;
    drawScope();
  });
  window.addEventListener("mouseup", (ev) => {
    const d = state.drag;
    state.drag = null;
    if (!d) return;
    const to = px(ev);
    if (Math.abs(to - d.from) >= 6 && state.scopeGeom) {
      const geo = state.scopeGeom, g = geo.g;
      const clamp = (q) => Math.min(g.left + g.pw, Math.max(g.left, q));
      const a = xAt(clamp(Math.min(d.from, to))), b = xAt(clamp(Math.max(d.from, to)));
      if (b > a) state.zoom = [a, b];
    }
    drawScope();
  });
  cv.addEventListener("dblclick", () => { state.zoom = null; drawScope(); });
  $("zoomin").onclick = () => zoomBy(2);
  // the scan's own buttons: pause or resume, one line, the frame again
  $("pause").onclick = () => send(state.status && state.status.paused ? "resume" : "pause");
  $("stepline").onclick = () => send("step");
  $("restart").onclick = () => send("restart");
  $("zoomout").onclick = () => zoomBy(0.5);
  $("zoomreset").onclick = () => { state.zoom = null; drawScope(); };
  $("xmode").onchange = () => { state.xmode = $("xmode").value; state.zoom = null; state.cursor = null; drawScope(); };
  $("hold").onclick = () => {
    state.hold = !state.hold;
    $("hold").setAttribute("aria-pressed", state.hold ? "true" : "false");
    $("hold").textContent = state.hold ? "release" : "hold";
    if (!state.hold && state.scope) state.scopeShown = state.scope;
    drawScope();
  };
  $("storeref").onclick = () => {
    if (!state.scopeShown) return;
    state.reference = state.scopeShown;
    state.referenceNote = "reference: line " + state.reference.line + ", " + state.reference.gains;
    $("refinfo").textContent = state.referenceNote;
    for (const s of document.querySelectorAll(".reftrace, .refretrace, #clearref")) s.hidden = false;
    drawScope();
  };
  $("clearref").onclick = () => {
    state.reference = null;
    $("refinfo").textContent = "";
    for (const s of document.querySelectorAll(".reftrace, .refretrace, #clearref")) s.hidden = true;
    drawScope();
  };
  if (window.ResizeObserver) new ResizeObserver(() => { drawScope(); if (state.frame) { for (const t of document.querySelectorAll(".cbar-ticks")) t.dataset.sig = ""; drawImages(); } }).observe($("right"));
}
