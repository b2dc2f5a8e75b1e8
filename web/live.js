// tiptap live: the console's page (docs/live.md). Served by tiptap itself; nothing
// else is loaded. Messages from the server are JSON objects with a "type"; the page
// sends text lines "set NAME = VALUE" (checked by the server as scene text).
"use strict";

const state = {
  frame: null, images: {}, tiers: [], scope: null, status: null, controls: [],
  scopes: 0, rows: 0, replies: 0, lastReply: null, ws: null, sent: 0,
};
window.tiptapLive = state; // for the browser test and the curious

const $ = (id) => document.getElementById(id);

function connect() {
  const ws = new WebSocket("ws://" + location.host + "/", "tiptap-live");
  state.ws = ws;
  ws.onopen = () => { $("conn").textContent = "connected"; $("conn").className = "ok"; };
  ws.onclose = () => {
    $("conn").textContent = "disconnected: retrying"; $("conn").className = "bad";
    setTimeout(connect, 1000);
  };
  ws.onmessage = (ev) => {
    let m;
    try { m = JSON.parse(ev.data); } catch (e) { return; }
    const handle = { controls, frame, row, scope, status, reply }[m.type];
    if (handle) handle(m);
  };
}

function send(text) {
  if (state.ws && state.ws.readyState === 1) { state.ws.send(text); state.sent++; }
}

// ---- controls
const choices = {
  "noise": ["on", "off"], "scan.fast_axis": ["x", "y"],
  "solver.tier": ["averaged", "envelope", "every"],
};
function controls(m) {
  state.controls = m.controls;
  const form = $("controls");
  for (const c of m.controls) {
    const id = "c-" + c.name.replace(/\./g, "-");
    let el = $(id);
    const opts = c.name === "sample" ? m.samples : choices[c.name];
    if (!el) {
      const lab = document.createElement("label");
      const span = document.createElement("span");
      span.textContent = c.label;
      if (c.restarts) { span.className = "restarts"; span.title = "a change starts a new frame"; }
      el = document.createElement(opts ? "select" : "input");
      el.id = id;
      el.dataset.name = c.name;
      el.dataset.unit = c.unit;
      if (opts) for (const o of opts) { const op = document.createElement("option"); op.value = op.textContent = o; el.appendChild(op); }
      else { el.type = "text"; el.inputMode = "decimal"; }
      el.addEventListener("change", () => setControl(el));
      const u = document.createElement("span");
      u.className = "unit"; u.textContent = c.unit;
      lab.append(span, el, u);
      form.appendChild(lab);
    }
    if (document.activeElement !== el) el.value = c.value;
  }
}
function setControl(el) {
  const v = el.value.trim();
  const unit = el.dataset.unit;
  // a bare number takes the control's unit; a value with its own unit goes as written
  const withUnit = unit && /^[-+0-9.eE]+$/.test(v) ? v + " " + unit : v;
  send("set " + el.dataset.name + " = " + withUnit);
}
window.tiptapSet = (name, value) => {
  const el = document.querySelector('[data-name="' + name + '"]');
  if (el) { el.value = value; setControl(el); }
};

function reply(m) {
  state.replies++;
  state.lastReply = m;
  $("reply").textContent = m.ok ? "" : m.error;
}

// ---- status, warning
function status(m) {
  state.status = m;
  const rt = m.realtime ? m.realtime.toFixed(2) + "x real time (" + m.realtime_cpu.toFixed(2) + "x per CPU second)" : "";
  const lat = m.preview_ms != null ? ", last change: " + m.preview_ms.toFixed(0) + " ms (preview), " +
    (m.accurate_ms != null ? m.accurate_ms.toFixed(0) + " ms (" + m.tier + ")" : "") : "";
  $("status").textContent = "frame " + m.frame + ", line " + m.line + ", " + m.tier + " tier, " + rt + lat +
    (m.clients > 1 ? ", " + m.clients + " pages" : "") + (m.note ? " | " + m.note : "");
  const w = $("warning");
  w.hidden = !m.oscillating;
  $("goodloop").hidden = m.oscillating;
  if (m.oscillating) {
    $("ringtext").textContent = " at " + fmt(m.ring_hz, "Hz") + ", " + fmt(m.ring_m * 1e9, "nm") +
      " peak to peak in z: the pixel means hide it.";
    const b = $("usegain");
    b.hidden = !(m.suggest_ki > 0);
    b.textContent = "use the suggested I gain, " + fmt(m.suggest_ki, "Hz");
    b.onclick = () => window.tiptapSet("feedback.integral_gain", Math.round(m.suggest_ki).toString());
  }
  if (state.frame) {
    $("reproduce").textContent = m.reproducible ?
      "A whole frame ran at the current settings: tiptap scan scene.ini writes these files byte for byte." :
      "Line " + m.line + " of " + state.frame.lines + (m.first_line_as_set > 0 ? "; lines from " + m.first_line_as_set +
        " at the current settings" : "") + ": an export holds the image as it stands; scene.ini is the current settings, " +
      "which tiptap scan reproduces once a whole frame has run at them.";
  }
}
function fmt(x, unit) {
  if (x == null || !isFinite(x)) return "?";
  const a = Math.abs(x);
  if (unit === "Hz" && a >= 1000) return (x / 1000).toPrecision(3) + " kHz";
  return x.toPrecision(3) + " " + unit;
}

// ---- frame and image
const cmaps = {
  height: [[0, 0, 0], [120, 60, 10], [230, 170, 60], [255, 250, 220]],
  error: [[30, 60, 160], [245, 245, 245], [180, 30, 30]],
  phase: [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]],
};
function colour(map, t) {
  t = Math.min(1, Math.max(0, t)) * (map.length - 1);
  const i = Math.min(map.length - 2, Math.floor(t)), f = t - i;
  return map[i].map((a, k) => a + (map[i + 1][k] - a) * f);
}
function frame(m) {
  state.frame = m;
  state.images = {};
  state.tiers = new Array(m.lines).fill(null);
  const box = $("images");
  box.textContent = "";
  // a row of channels for the trace, one for the retrace
  for (const dir of m.retrace ? ["trace", "retrace"] : ["trace"]) for (const c of m.channels) {
    state.images[c.name + "_" + dir] = new Float64Array(m.pixels * m.lines).fill(NaN);
    const fig = document.createElement("figure");
    const cv = document.createElement("canvas");
    cv.id = "img-" + c.name + "-" + dir;
    cv.width = m.pixels; cv.height = m.lines;
    // drawn in the scan's own proportions, as an instrument shows a frame
    cv.style.aspectRatio = (m.fast_y ? m.size_slow / m.size_fast : m.size_fast / m.size_slow).toString();
    const cap = document.createElement("figcaption");
    cap.id = "cap-" + c.name + "-" + dir;
    cap.textContent = c.name + " (" + dir + ")";
    fig.append(cv, cap);
    box.appendChild(fig);
  }
  box.style.gridTemplateColumns = "repeat(" + m.channels.length + ", minmax(0, 1fr))";
  $("imageinfo").textContent = m.pixels + " x " + m.lines + " pixels, " + fmt(m.size_fast * 1e9, "nm") +
    (m.fast_y ? " along y (fast)" : " along x (fast)");
  const ex = $("exports");
  ex.textContent = "";
  const names = ["scan.gwy", "scene.ini"];
  for (const c of m.channels) for (const d of m.retrace ? ["trace", "retrace"] : ["trace"])
    names.push(c.file + "_" + d + ".gsf");
  for (const n of names) {
    const a = document.createElement("a");
    a.href = "/export/" + n; a.textContent = n; a.download = n;
    ex.appendChild(a);
  }
}

function row(m) {
  if (!state.frame || m.frame !== state.frame.frame) return;
  state.rows++;
  const f = state.frame;
  let k = 0;
  for (const c of f.channels) for (const dir of f.retrace ? ["trace", "retrace"] : ["trace"]) {
    const img = state.images[c.name + "_" + dir], d = m.data[k++];
    if (!img || !d) continue;
    for (let i = 0; i < f.pixels; i++) img[m.line * f.pixels + i] = d[i] == null ? NaN : d[i];
  }
  state.tiers[m.line] = m.tier;
  drawImages(m.line);
}
function drawImages(line) {
  const f = state.frame;
  for (const c of f.channels) for (const dir of f.retrace ? ["trace", "retrace"] : ["trace"]) {
    const img = state.images[c.name + "_" + dir];
    const cv = $("img-" + c.name + "-" + dir);
    if (!img || !cv) continue;
    let lo = Infinity, hi = -Infinity;
    for (const v of img) if (isFinite(v)) { if (v < lo) lo = v; if (v > hi) hi = v; }
    if (c.name === "error") { const a = Math.max(Math.abs(lo), Math.abs(hi)); lo = -a; hi = a; }
    // the sample's orientation: line l is row l with x fast, column l with y fast
    const W = f.fast_y ? f.lines : f.pixels, H = f.fast_y ? f.pixels : f.lines;
    if (cv.width !== W || cv.height !== H) { cv.width = W; cv.height = H; }
    const ctx = cv.getContext("2d");
    const data = ctx.createImageData(W, H);
    for (let l = 0; l < f.lines; l++) for (let i = 0; i < f.pixels; i++) {
      const v = img[l * f.pixels + i];
      const x = f.fast_y ? l : i, y = f.fast_y ? i : l;
      const o = 4 * (y * W + x);
      if (!isFinite(v)) { data.data[o + 3] = 0; continue; }
      const rgb = colour(cmaps[c.name] || cmaps.phase, hi > lo ? (v - lo) / (hi - lo) : 0.5);
      data.data[o] = rgb[0]; data.data[o + 1] = rgb[1]; data.data[o + 2] = rgb[2]; data.data[o + 3] = 255;
    }
    ctx.putImageData(data, 0, 0);
    const unit = c.unit === "m" ? "nm" : c.unit, sc = c.unit === "m" ? 1e9 : 1;
    $("cap-" + c.name + "-" + dir).textContent = c.name + " (" + dir + "): " +
      (isFinite(lo) ? (lo * sc).toPrecision(3) + " to " + (hi * sc).toPrecision(3) + " " + unit : "") +
      (line != null && state.tiers[line] === "averaged" ? "; line " + line + " from the averaged preview" : "");
  }
}

// ---- scope
const panels = [
  { key: "z", label: "height z (nm)", scale: 1e9, surface: true },
  { key: "error", label: "error (nm)", scale: 1e9 },
  { key: "amplitude", label: "amplitude (nm)", scale: 1e9 },
  { key: "phase", label: "phase (deg)", scale: 1 },
];
function scope(m) {
  state.scope = m;
  state.scopes++;
  $("scopeinfo").textContent = "line " + m.line + " (" + m.tier + " tier), " +
    (m.rate ? (m.rate / 1000).toFixed(1) + " kHz record" : "") + ", against the tip's position";
  drawScope();
}
function drawScope() {
  const m = state.scope, cv = $("scope"), ctx = cv.getContext("2d");
  const W = cv.width, H = cv.height, left = 70, right = 10, top = 8, gap = 22;
  const ph = (H - top - gap * panels.length) / panels.length;
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
  ctx.font = "12px DejaVu Sans, sans-serif";
  const pos = [m.trace.position, m.retrace.position];
  let x0 = Infinity, x1 = -Infinity;
  for (const p of pos) for (const v of p) if (v != null) { x0 = Math.min(x0, v); x1 = Math.max(x1, v); }
  if (!(x1 > x0)) return;
  panels.forEach((p, k) => {
    const y0 = top + k * (ph + gap);
    const series = [[m.trace[p.key], "#1565c0"], [m.retrace[p.key], "#c62828"]];
    if (p.surface) series.push([m.trace.surface, "#888"], [m.retrace.surface, "#888"]);
    let lo = Infinity, hi = -Infinity;
    for (const [s] of series) for (const v of s) if (v != null) { lo = Math.min(lo, v * p.scale); hi = Math.max(hi, v * p.scale); }
    if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
    const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
    ctx.strokeStyle = "#ccc"; ctx.strokeRect(left, y0, W - left - right, ph);
    ctx.fillStyle = "#222";
    ctx.fillText(p.label, 4, y0 + 12);
    ctx.fillText(hi.toPrecision(3), 4, y0 + 26);
    ctx.fillText(lo.toPrecision(3), 4, y0 + ph - 2);
    series.forEach(([s, col], j) => {
      const xs = pos[j % 2];
      ctx.strokeStyle = col; ctx.lineWidth = j >= 2 ? 1 : 1.2;
      ctx.setLineDash(j >= 2 ? [4, 3] : []);
      ctx.beginPath();
      let pen = false;
      for (let i = 0; i < s.length; i++) {
        if (s[i] == null || xs[i] == null) { pen = false; continue; }
        const X = left + (xs[i] - x0) / (x1 - x0) * (W - left - right);
        const Y = y0 + ph - (s[i] * p.scale - lo) / (hi - lo) * ph;
        if (pen) ctx.lineTo(X, Y); else ctx.moveTo(X, Y);
        pen = true;
      }
      ctx.stroke();
    });
    ctx.setLineDash([]);
  });
  ctx.fillStyle = "#222";
  ctx.fillText("position along the fast axis: 0 to " + ((x1 - x0) * 1e9).toPrecision(4) + " nm", left, H - 4);
}

connect();
