// tiptap live: the console's page (docs/live.md). Served by tiptap itself; nothing
// else is loaded. Messages from the server are JSON objects with a "type"; the page
// sends text lines "set NAME = VALUE" (checked by the server as scene text).
"use strict";

const state = {
  frame: null, images: {}, tiers: [], scope: null, status: null, controls: [],
  scopes: 0, rows: 0, replies: 0, lastReply: null, ws: null, sent: 0,
  // the display: what each image shows (per image, kept across frames), the scope shown
  // (the newest, or the one held), the reference, the zoom and the cursor
  view: {}, shown: {}, lastLine: null, scopeShown: null, hold: false, reference: null,
  xmode: "position", zoom: null, cursor: null, scopeTextPx: 0,
};
window.tiptapLive = state; // for the browser test and the curious

const $ = (id) => document.getElementById(id);
const FONT_PX = 13; // the smallest text on the page: readable on a projector at 1024 x 768

function connect() {
  const ws = new WebSocket("ws://" + location.host + "/", "tiptap-live");
  state.ws = ws;
  ws.onopen = () => {
    $("conn").textContent = "connected"; $("conn").className = "ok";
    // a new connection gets the controls afresh; nothing sent before waits for a reply
    for (const el of document.querySelectorAll("#controls [data-name]")) el.dataset.pending = "";
  };
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
  if (state.ws && state.ws.readyState === 1) { state.ws.send(text); state.sent++; return true; }
  return false;
}

// ---- controls
// A field shows the value in force, except while it holds text the user typed and has
// not sent yet (edited since its last send, in focus): that text is never overwritten.
// A sent value waits for the server's reply; accepted, the controls message brings the
// value in force (another page's changes come the same way); refused, every field that
// holds no unsent text returns to the value in force.
const choices = {
  "noise": ["on", "off"], "scan.fast_axis": ["x", "y"],
  "solver.tier": ["averaged", "envelope", "every"],
};
const optionText = { "solver.tier": { every: "every (far slower than real time)" } };
const hints = {
  "solver.tier": "averaged: the slow flow of amplitude and phase; envelope: cycles integrated " +
    "only where needed; every: every drive cycle integrated, the reference, far slower than real time",
};
// units the server leaves blank: shown, never sent (a bare number is what the key takes)
const shownUnit = { "feedback.proportional_gain": "m/m" };
function inForce(name) {
  const c = state.controls.find((k) => k.name === name);
  return c ? c.value : null;
}
function restore(el) {
  const v = inForce(el.dataset.name);
  if (v != null) el.value = v;
  el.dataset.dirty = "";
  el.dataset.pending = "";
}
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
      if (hints[c.name]) span.title = (span.title ? span.title + "; " : "") + hints[c.name];
      el = document.createElement(opts ? "select" : "input");
      el.id = id;
      el.dataset.name = c.name;
      el.dataset.unit = c.unit;
      if (opts) for (const o of opts) {
        const op = document.createElement("option");
        op.value = o;
        op.textContent = (optionText[c.name] || {})[o] || o;
        el.appendChild(op);
      }
      else { el.type = "text"; el.inputMode = "decimal"; }
      el.addEventListener("input", () => { el.dataset.dirty = "1"; });
      el.addEventListener("change", () => setControl(el));
      el.addEventListener("keydown", (ev) => { if (ev.key === "Escape") restore(el); });
      // left without a change sent (typed, then put back): the value in force again
      el.addEventListener("blur", () => { if (el.dataset.dirty) restore(el); });
      const u = document.createElement("span");
      u.className = "unit"; u.textContent = c.unit || shownUnit[c.name] || "";
      lab.append(span, el, u);
      form.appendChild(lab);
    }
    // the lesson's hidden controls are not drawn; its locked ones shown, not editable
    // (the server refuses a change to them too)
    el.parentElement.hidden = !!c.hidden;
    el.disabled = !!c.locked;
    el.parentElement.classList.toggle("locked", !!c.locked);
    const editing = el.dataset.dirty && document.activeElement === el;
    if (!editing && !el.dataset.pending) { el.value = c.value; el.dataset.dirty = ""; }
  }
  const ls = m.lesson;
  $("lesson").hidden = !ls;
  if (ls) {
    $("lessontitle").textContent = ls.title;
    $("lessontext").textContent = ls.instructions;
    document.title = ls.title + ": tiptap live";
  }
  state.lesson = ls || null;
  state.controlsSeen = (state.controlsSeen || 0) + 1;
  drawLoop();
}
function setControl(el) {
  const v = el.value.trim();
  const unit = el.dataset.unit;
  // a bare number takes the control's unit; a value with its own unit goes as written
  const withUnit = unit && /^[-+0-9.eE]+$/.test(v) ? v + " " + unit : v;
  el.dataset.dirty = "";
  if (send("set " + el.dataset.name + " = " + withUnit)) el.dataset.pending = "1";
  else restore(el);
}
window.tiptapSet = (name, value) => {
  const el = document.querySelector('[data-name="' + name + '"]');
  if (el) { el.value = value; setControl(el); }
};

function reply(m) {
  state.replies++;
  state.lastReply = m;
  $("reply").textContent = m.ok ? "" : m.error;
  // a step the server refuses ends auto-tune (its gain would never come into force)
  if (!m.ok && loop.tune) { loop.tune = null; $("autotune").textContent = "auto-tune I"; loopLog("auto-tune stopped: " + m.error); }
  // replies may coalesce (the server keeps the newest), so one answers all that are pending
  for (const el of document.querySelectorAll("#controls [data-name]")) {
    if (m.ok) el.dataset.pending = "";
    else if (!(el.dataset.dirty && document.activeElement === el)) restore(el);
  }
  // accepted: the controls message that follows (the server sends it after the reply)
  // brings the value in force, as the server writes it
}

// ---- status, warning
function status(m) {
  state.status = m;
  const rt = m.realtime ? m.realtime.toFixed(2) + "x real time (" + m.realtime_cpu.toFixed(2) + "x per CPU second)" : "";
  // latencies only once there has been a change (the server sends 0 or null before)
  const parts = [];
  if (m.preview_ms > 0) parts.push(m.preview_ms.toFixed(0) + " ms (preview)");
  if (m.accurate_ms > 0) parts.push(m.accurate_ms.toFixed(0) + " ms (" + m.tier + ")");
  const lat = parts.length ? ", last change: " + parts.join(", ") : "";
  $("status").textContent = "frame " + m.frame + ", line " + m.line + ", " + m.tier + " tier, " + rt + lat +
    (m.clients > 1 ? ", " + m.clients + " pages" : "") + (m.note ? " | " + m.note : "");
  const w = $("warning");
  w.hidden = !m.oscillating;
  const g = $("goodloop");
  g.hidden = m.oscillating;
  // steady only once a line was judged and z follows the surface (the server's rule:
  // z strays from it by at most 0.35 of its relief; docs/live.md)
  const jl = m.judged_line != null ? " (line " + m.judged_line + ")" : "";
  g.className = "good" + (!(m.judged > 0) ? " unjudged" : m.lagging ? " lagging" : "");
  g.textContent = !(m.judged > 0) ? "The loop is not judged yet: no line has run." :
    m.lagging ? "The loop lags" + jl + ": z strays from the surface by " + fmt(m.track_rms * 1e9, "nm") +
      " rms over a relief of " + fmt(m.surface_range * 1e9, "nm") + "; raise the I gain." :
      "The loop is steady" + jl + ".";
  if (state.firstLoopText == null) state.firstLoopText = g.textContent; // for the browser test
  $("runstate").textContent = m.idle ? "waiting for a page" : m.paused ? "paused at line " + m.line : "";
  const pb = $("pause");
  pb.textContent = m.paused ? "resume" : "pause";
  pb.setAttribute("aria-pressed", m.paused ? "true" : "false");
  if (m.oscillating) {
    // the pixel means hide the ring only where the judged line's height pixels spread
    // beyond the true surface's relief by less than half its z peak to peak (docs/live.md)
    const excess = m.height_range - (isFinite(m.surface_range) ? m.surface_range : 0);
    const hidden = !(excess >= 0.5 * m.ring_m);
    $("ringtext").textContent = " on line " + m.judged_line + ": at " + fmt(m.ring_hz, "Hz") + ", " +
      fmt(m.ring_m * 1e9, "nm") + " peak to peak in z" +
      (hidden ? ": the pixel means hide it." : ", in plain view in the image (its pixels span " +
        fmt(m.height_range * 1e9, "nm") + " over a relief of " + fmt(m.surface_range * 1e9, "nm") + ").");
    const b = $("usegain");
    b.hidden = !(m.suggest_ki >= 1); // under 1 Hz: no I helps, the P suggestion below does
    b.textContent = "use the suggested I gain, " + fmt(m.suggest_ki, "Hz");
    b.onclick = () => window.tiptapSet("feedback.integral_gain", Math.round(m.suggest_ki).toString());
    // P as the cause: the model with I as suggested and P as set still short of 45 deg,
    // or P alone (I near 0) short of it: P and I together for 60 deg (the loop panel's)
    const kp = parseFloat(inForce("feedback.proportional_gain")) || 0;
    const pmI = m.suggest_ki > 0 ? phaseMargin(loopParams(kp, m.suggest_ki)) : NaN;
    const pmP = phaseMargin(loopParams(kp, 1e-3));
    const r = loop.now;
    const pCause = kp > 0 && (!(pmI >= 45) || !(pmP >= 45)) && r && r.kp60pi >= 0 && r.kp60pi < kp;
    const pb2 = $("usepgain");
    pb2.hidden = !pCause;
    if (pCause) {
      pb2.textContent = "P is too high for the model: use P " + r.kp60pi.toFixed(2) + ", I " + fmt(r.ki60pi, "Hz");
      pb2.onclick = () => {
        window.tiptapSet("feedback.proportional_gain", r.kp60pi.toFixed(2));
        window.tiptapSet("feedback.integral_gain", Math.round(r.ki60pi).toString());
      };
    }
  }
  if (state.frame) {
    $("reproduce").textContent = m.reproducible ?
      "A whole frame ran at the current settings: tiptap scan scene.ini writes these files byte for byte." :
      "Line " + m.line + " of " + state.frame.lines + (m.first_line_as_set > 0 ? "; lines from " + m.first_line_as_set +
        " at the current settings" : "") + ": an export holds the image as it stands; scene.ini is the current settings, " +
      "which tiptap scan reproduces once a whole frame has run at them.";
  }
  drawLoop();
  // auto-tune counts the lines on the scan's own tier (the oscillation check's), not previews
  if (loop.lastScopes !== state.scopes && state.scope && state.scope.tier === m.tier) {
    loop.lastScopes = state.scopes; tuneLine(m);
  }
}
function fmt(x, unit) {
  if (x == null || !isFinite(x)) return "?";
  const a = Math.abs(x);
  if (unit === "Hz" && a >= 1000) return (x / 1000).toPrecision(3) + " kHz";
  return x.toPrecision(3) + " " + unit;
}

// ---- axes: ticks at 1, 2 or 5 times a power of ten, about n of them between lo and hi
function ticks(lo, hi, n) {
  if (!(hi > lo) || !isFinite(lo) || !isFinite(hi)) return { step: 1, at: [] };
  const raw = (hi - lo) / Math.max(1, n);
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const steps = [10, 5, 2, 1, 0.5].map((k) => k * p);
  // the nice step nearest to the raw one (on a log scale), smaller where it gives one tick only
  let j = 0;
  for (let k = 1; k < steps.length; k++) if (Math.abs(Math.log(steps[k] / raw)) < Math.abs(Math.log(steps[j] / raw))) j = k;
  for (;; j++) {
    const step = steps[j], at = [];
    for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9 && at.length < 50; k++) at.push(k * step);
    if (at.length >= 2 || j === steps.length - 1) return { step, at };
  }
}
// ticks whose labels (about 8 px a character at 13 px) fit side by side in width px
function fitTicks(lo, hi, width) {
  let t = { step: 1, at: [] };
  for (let n = Math.max(2, Math.floor(width / 60)); n >= 1; n--) {
    t = ticks(lo, hi, n);
    const widest = Math.max(...t.at.map((x) => tickText(x, t.step).length)) * 8 + 12;
    if (t.at.length * widest <= width) return t;
  }
  return t;
}
function tickText(t, step) {
  const d = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return (Math.abs(t) < step * 1e-6 ? 0 : t).toFixed(d);
}

// ---- frame and image
const cmaps = {
  height: [[0, 0, 0], [120, 60, 10], [230, 170, 60], [255, 250, 220]],
  error: [[30, 60, 160], [245, 245, 245], [180, 30, 30]],
  phase: [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]],
  amplitude: [[0, 0, 4], [81, 18, 124], [183, 55, 121], [252, 137, 97], [252, 253, 191]],
  peak_force: [[13, 8, 135], [126, 3, 168], [204, 71, 120], [248, 149, 64], [240, 249, 33]],
};
function colour(map, t) {
  t = Math.min(1, Math.max(0, t)) * (map.length - 1);
  const i = Math.min(map.length - 2, Math.floor(t)), f = t - i;
  return map[i].map((a, k) => a + (map[i + 1][k] - a) * f);
}
const ranges = [["lines", "typical lines"], ["pct", "1 to 99 %"], ["frame", "frame min to max"],
  ["line", "last line"], ["manual", "manual"]];
const flattens = [["none", "none"], ["offset", "offset per line"], ["slope", "slope per line"]];
// a channel's display unit: heights in nm, forces in nN, angles in deg
function unitOf(c) {
  return c.unit === "m" ? { unit: "nm", sc: 1e9 } : c.unit === "N" ? { unit: "nN", sc: 1e9 } : { unit: c.unit, sc: 1 };
}
function dirs(f) { return f.retrace ? ["trace", "retrace"] : ["trace"]; }
function select(options, value, onchange) {
  const s = document.createElement("select");
  for (const [v, t] of options) { const o = document.createElement("option"); o.value = v; o.textContent = t; s.appendChild(o); }
  s.value = value;
  s.addEventListener("change", () => onchange(s.value));
  return s;
}
function frame(m) {
  state.frame = m;
  state.images = {};
  state.shown = {};
  state.lastLine = null;
  state.tiers = new Array(m.lines).fill(null);
  const box = $("images");
  box.textContent = "";
  // a row of channels for the trace, one for the retrace
  for (const dir of dirs(m)) for (const c of m.channels) {
    const key = c.name + "_" + dir;
    state.images[key] = new Float64Array(m.pixels * m.lines).fill(NaN);
    const v = state.view[key] || (state.view[key] = { range: "lines", flatten: "none", min: null, max: null });
    const id = c.name + "-" + dir;
    const fig = document.createElement("figure");
    const cv = document.createElement("canvas");
    cv.id = "img-" + id;
    cv.width = m.pixels; cv.height = m.lines;
    // drawn in the scan's own proportions, as an instrument shows a frame
    cv.style.aspectRatio = (m.fast_y ? m.size_slow / m.size_fast : m.size_fast / m.size_slow).toString();
    const bar = document.createElement("div");
    bar.className = "cbar"; bar.id = "cbar-" + id;
    const grad = document.createElement("div");
    grad.className = "cbar-grad";
    const map = cmaps[c.name] || cmaps.phase;
    grad.style.background = "linear-gradient(to right, " +
      map.map((rgb, k) => "rgb(" + rgb.join(",") + ") " + (100 * k / (map.length - 1)).toFixed(1) + "%").join(", ") + ")";
    const tk = document.createElement("div");
    tk.className = "cbar-ticks"; tk.id = "ticks-" + id;
    bar.append(grad, tk);
    const cap = document.createElement("figcaption");
    cap.id = "cap-" + id;
    cap.textContent = c.name + " (" + dir + ")";
    const u = unitOf(c);
    const ctl = document.createElement("div");
    ctl.className = "imgctl";
    const lr = document.createElement("label");
    const man = document.createElement("span");
    man.className = "manual"; man.id = "man-" + id;
    const min = document.createElement("input"), max = document.createElement("input");
    min.id = "min-" + id; max.id = "max-" + id;
    for (const inp of [min, max]) {
      inp.type = "text"; inp.inputMode = "decimal";
      inp.addEventListener("change", () => {
        const a = parseFloat(min.value), b = parseFloat(max.value);
        const ok = isFinite(a) && isFinite(b) && b > a;
        min.classList.toggle("invalid", !ok); max.classList.toggle("invalid", !ok);
        if (ok) { v.min = a / u.sc; v.max = b / u.sc; drawImages(); }
      });
    }
    const rsel = select(ranges, v.range, (r) => {
      if (r === "manual" && v.min == null) {
        const s = state.shown[key];
        if (s && isFinite(s.lo)) { v.min = s.lo; v.max = s.hi; }
      }
      v.range = r;
      drawImages();
    });
    rsel.id = "range-" + id;
    lr.append("colour ", rsel);
    man.append(min, " to ", max, " " + u.unit);
    const lf = document.createElement("label");
    const fsel = select(flattens, v.flatten, (x) => { v.flatten = x; drawImages(); });
    fsel.id = "flatten-" + id;
    lf.append("flatten ", fsel);
    ctl.append(lr, man, lf);
    fig.append(cv, bar, cap, ctl);
    box.appendChild(fig);
  }
  box.style.gridTemplateColumns = "repeat(" + m.channels.length + ", minmax(0, 1fr))";
  $("imageinfo").textContent = m.pixels + " x " + m.lines + " pixels, " + fmt(m.size_fast * 1e9, "nm") +
    (m.fast_y ? " along y (fast)" : " along x (fast)");
  const ex = $("exports");
  ex.textContent = "";
  const names = ["scan.gwy", "scene.ini", "lesson.ini"];
  for (const c of m.channels) for (const d of dirs(m))
    names.push(c.file + "_" + d + ".gsf");
  for (const n of names) {
    const a = document.createElement("a");
    a.href = "/export/" + n; a.textContent = n; a.download = n;
    ex.appendChild(a);
  }
  drawImages();
  loadScene();
}

function row(m) {
  if (!state.frame || m.frame !== state.frame.frame) return;
  state.rows++;
  const f = state.frame;
  let k = 0;
  for (const c of f.channels) for (const dir of dirs(f)) {
    const img = state.images[c.name + "_" + dir], d = m.data[k++];
    if (!img || !d) continue;
    for (let i = 0; i < f.pixels; i++) img[m.line * f.pixels + i] = d[i] == null ? NaN : d[i];
  }
  // only the preview's rows are captioned as such (a scan on the averaged tier is not one)
  state.tiers[m.line] = m.preview ? "preview" : m.tier;
  state.lastLine = m.line;
  drawImages(m.line);
}

// A line flattened as consoles do while scanning: its mean (offset) or its least-squares
// straight line (slope) taken off, each line on its own.
function flattenLine(src, dst, n, how) {
  let s = 0, sx = 0, sxx = 0, sy = 0, sxy = 0;
  for (let i = 0; i < n; i++) if (isFinite(src[i])) { s++; sx += i; sxx += i * i; sy += src[i]; sxy += i * src[i]; }
  let a = 0, b = 0;
  if (how !== "none" && s > 0) {
    a = sy / s;
    const den = s * sxx - sx * sx;
    if (how === "slope" && s > 1 && den > 0) { b = (s * sxy - sx * sy) / den; a = (sy - b * sx) / s; }
  }
  for (let i = 0; i < n; i++) dst[i] = src[i] - a - b * i;
}
function percentile(sorted, q) {
  const x = q * (sorted.length - 1), i = Math.floor(x), f = x - i;
  return i + 1 < sorted.length ? sorted[i] + (sorted[i + 1] - sorted[i]) * f : sorted[i];
}
// The colour range of an image's data as shown: auto (typical lines: from the 20th
// percentile of the lines' lowest values to the 80th of their highest, which a band of
// ringing lines up to a fifth of the frame leaves alone, and which spans features along
// the slow axis too; the 1st to 99th percentile of the pixels; the frame's; the newest
// line's) or manual; the error's auto range symmetric about zero.
function rangeOf(c, v, data, f) {
  if (v.range === "manual" && v.min != null) return [v.min, v.max];
  let lo = Infinity, hi = -Infinity;
  if (v.range === "lines") {
    const los = [], his = [];
    for (let l = 0; l < f.lines; l++) {
      let a = Infinity, b = -Infinity;
      for (let i = l * f.pixels; i < (l + 1) * f.pixels; i++) { const x = data[i]; if (isFinite(x)) { if (x < a) a = x; if (x > b) b = x; } }
      if (a <= b) { los.push(a); his.push(b); }
    }
    if (los.length) {
      los.sort((a, b) => a - b); his.sort((a, b) => a - b);
      lo = percentile(los, 0.2); hi = percentile(his, 0.8);
    }
  } else if (v.range === "pct") {
    const fin = Array.from(data).filter(isFinite).sort((a, b) => a - b);
    if (fin.length) { lo = percentile(fin, 0.01); hi = percentile(fin, 0.99); }
  } else {
    const one = v.range === "line" && state.lastLine != null;
    const from = one ? state.lastLine * f.pixels : 0, to = one ? from + f.pixels : data.length;
    for (let i = from; i < to; i++) { const x = data[i]; if (isFinite(x)) { if (x < lo) lo = x; if (x > hi) hi = x; } }
  }
  if (c.name === "error" && isFinite(lo)) { const a = Math.max(Math.abs(lo), Math.abs(hi)); lo = -a; hi = a; }
  return [lo, hi];
}
function drawImages(line) {
  const f = state.frame;
  if (!f) return;
  for (const c of f.channels) for (const dir of dirs(f)) {
    const key = c.name + "_" + dir, id = c.name + "-" + dir;
    const img = state.images[key], v = state.view[key];
    const cv = $("img-" + id);
    if (!img || !cv) continue;
    const data = new Float64Array(img.length);
    for (let l = 0; l < f.lines; l++)
      flattenLine(img.subarray(l * f.pixels, (l + 1) * f.pixels), data.subarray(l * f.pixels, (l + 1) * f.pixels),
        f.pixels, v.flatten);
    const [lo, hi] = rangeOf(c, v, data, f);
    state.shown[key] = { lo, hi, data };
    // the sample's orientation: line l is row l with x fast, column l with y fast
    const W = f.fast_y ? f.lines : f.pixels, H = f.fast_y ? f.pixels : f.lines;
    if (cv.width !== W || cv.height !== H) { cv.width = W; cv.height = H; }
    const ctx = cv.getContext("2d");
    const out = ctx.createImageData(W, H);
    const map = cmaps[c.name] || cmaps.phase;
    for (let l = 0; l < f.lines; l++) for (let i = 0; i < f.pixels; i++) {
      const x = data[l * f.pixels + i];
      const o = 4 * ((f.fast_y ? i : l) * W + (f.fast_y ? l : i));
      if (!isFinite(x)) { out.data[o + 3] = 0; continue; }
      const rgb = colour(map, hi > lo ? (x - lo) / (hi - lo) : 0.5);
      out.data[o] = rgb[0]; out.data[o + 1] = rgb[1]; out.data[o + 2] = rgb[2]; out.data[o + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
    const u = unitOf(c);
    colourBar(id, lo * u.sc, hi * u.sc, u.unit);
    $("man-" + id).hidden = v.range !== "manual";
    const min = $("min-" + id), max = $("max-" + id);
    if (v.range === "manual" && document.activeElement !== min && document.activeElement !== max &&
        !min.classList.contains("invalid")) {
      min.value = (v.min * u.sc).toPrecision(3).replace(/\.?0+$/, "");
      max.value = (v.max * u.sc).toPrecision(3).replace(/\.?0+$/, "");
    }
    const ln = line != null ? line : state.lastLine;
    $("cap-" + id).textContent = c.name + " (" + dir + "), " + u.unit + (v.flatten !== "none" ? ", flattened" : "") +
      (ln != null && state.tiers[ln] === "averaged" ? "; line " + ln + " from the averaged preview" : "");
  }
}
// The colour bar under an image: the map from lo to hi, ticks in the display unit.
function colourBar(id, lo, hi, unit) {
  const tk = $("ticks-" + id);
  const sig = [lo, hi, unit].join();
  if (tk.dataset.sig === sig) return;
  tk.dataset.sig = sig;
  tk.textContent = "";
  if (!(hi > lo)) return;
  const w = tk.clientWidth || 200;
  const t = fitTicks(lo, hi, w);
  for (const x of t.at) {
    const s = document.createElement("span");
    s.className = "tick";
    const f = (x - lo) / (hi - lo);
    s.style.left = (100 * f).toFixed(2) + "%";
    // a label at either end is kept inside the bar, its tick mark at its own end
    if (f < 0.08) s.classList.add("first"); else if (f > 0.92) s.classList.add("last");
    s.textContent = tickText(x, t.step);
    tk.appendChild(s);
  }
  tk.dataset.lo = lo; tk.dataset.hi = hi;
}

// ---- scope
const panels = [
  { key: "z", label: "height z", unit: "nm", scale: 1e9, surface: true },
  { key: "error", label: "error", unit: "nm", scale: 1e9 },
  { key: "amplitude", label: "amplitude", unit: "nm", scale: 1e9 },
  { key: "phase", label: "phase", unit: "deg", scale: 1 },
];
const colours = { trace: "#1565c0", retrace: "#c62828", surface: "#888", reftrace: "#ef6c00", refretrace: "#2e7d32" };
function scope(m) {
  // the gains in force when the line arrived, for a reference's legend
  m.gains = "I gain " + inForce("feedback.integral_gain") + " Hz, P gain " + inForce("feedback.proportional_gain");
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
  const geo = { x0, x1, g, panels: [] };
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
    geo.panels.push({ y0, lo, hi });
    // grid and ticks
    ctx.strokeStyle = "#e3e3e3"; ctx.lineWidth = 1; ctx.fillStyle = "#222";
    ctx.textAlign = "right"; ctx.textBaseline = "middle";
    const yt = ticks(lo, hi, Math.max(3, Math.floor(g.ph / 24)));
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

// ---- the loop's model (docs/imaging.md, "Lock-in and feedback"; docs/live.md, "The
// loop"): the PI controller C(s) = kp + ki / s on the plant g e^(-s d) / ((1 + s tau_A)
// (1 + s tau_f)^n), g = 1 (hard tapping), tau_A = Q / (pi f0), as
// src/instrument/scan_oscillation.c computes it (tt_loop_phase_margin).
const loop = {
  // the standard cantilever and lock-in (scans/standard.ini) until scene.ini says otherwise
  p: { f0: 300e3, Q: 400, fd: 300e3, tau_f: 100e-6, n: 2, P: 4, g: 1, from: "defaults" },
  log: [], tune: null,
};
state.loop = loop;
function loopParams(kp, ki) {
  const p = loop.p;
  return { kp, ki, g: p.g, tauA: p.Q / (Math.PI * p.f0), tf: p.tau_f, n: p.n, d: p.P / p.fd };
}
// |L(i w)| and its phase in degrees, continuous from 0 down (each factor's own lag)
function loopMag(l, w) {
  let m = l.g * Math.hypot(l.kp, l.ki / w) / Math.hypot(1, w * l.tauA);
  if (l.tf > 0) m /= Math.pow(Math.hypot(1, w * l.tf), l.n);
  return m;
}
function loopPhase(l, w) {
  let ph = Math.atan2(-l.ki / w, l.kp) - Math.atan(w * l.tauA) - w * l.d;
  if (l.tf > 0) ph -= l.n * Math.atan(w * l.tf);
  return ph * 180 / Math.PI;
}
// the crossover |L(i w)| = 1 (rad/s), by bisection in log w: |L| falls with w
function crossover(l) {
  let lo = 1e-9, hi = 1e10;
  if (loopMag(l, hi) >= 1 || loopMag(l, lo) <= 1) return NaN;
  for (let i = 0; i < 200 && hi / lo > 1 + 1e-12; i++) {
    const w = Math.sqrt(lo * hi);
    if (loopMag(l, w) > 1) lo = w; else hi = w;
  }
  return Math.sqrt(lo * hi);
}
function phaseMargin(l) { const w = crossover(l); return isNaN(w) ? NaN : 180 + loopPhase(l, w); }
// the integral gain that gives margin pm (deg) with kp = kpOf(ki); NaN where none does
function kiForMargin(pm, kpOf) {
  const at = (k) => phaseMargin(loopParams(kpOf(k), k));
  let lo = 1, hi = 1e8;
  if (!(at(lo) > pm) || at(hi) > pm) return NaN;
  for (let i = 0; i < 200 && hi / lo > 1 + 1e-9; i++) {
    const k = Math.sqrt(lo * hi);
    if (at(k) > pm) lo = k; else hi = k;
  }
  return Math.sqrt(lo * hi);
}
// The closed loop's answer z(t) to a unit step of the surface: the lags integrated exactly
// over steps of dt (a fortieth of the shortest time constant), the delay as a queue.
function stepResponse(l, tEnd) {
  const dt = Math.min(l.tauA, l.tf > 0 ? l.tf : Infinity, l.d > 0 ? l.d : Infinity) / 40;
  const N = Math.min(200000, Math.ceil(tEnd / dt));
  const qa = Math.exp(-dt / l.tauA), qf = l.tf > 0 ? Math.exp(-dt / l.tf) : 0;
  const delay = new Float64Array(Math.max(1, Math.round(l.d / dt)));
  const f = new Float64Array(l.tf > 0 ? l.n : 0);
  let a = 0, integ = 0, z = 0, k = 0;
  const t = [], zs = [];
  const every = Math.max(1, Math.floor(N / 800));
  for (let i = 0; i <= N; i++) {
    if (i % every === 0) { t.push(i * dt); zs.push(z); }
    const u = delay[k]; delay[k] = 1 - z; k = (k + 1) % delay.length;
    a = u + (a - u) * qa;
    let y = a;
    for (let j = 0; j < f.length; j++) { f[j] = y + (f[j] - y) * qf; y = f[j]; }
    const e = l.g * y;
    integ += l.ki * e * dt;
    z = l.kp * e + integ;
    if (!isFinite(z) || Math.abs(z) > 1e6) break;
  }
  return { t, z: zs };
}
// A ring's frequency and damping ratio from a signal's swings about its final value: the
// extremes between crossings, their median spacing and ratio (as tt_scan_oscillation does).
function ringOf(t, x, final) {
  const peaks = [];
  let start = 0;
  for (let i = 1; i <= x.length; i++) {
    const cross = i === x.length || Math.sign(x[i] - final) !== Math.sign(x[start] - final);
    if (!cross) continue;
    let best = start;
    for (let j = start; j < i; j++) if (Math.abs(x[j] - final) > Math.abs(x[best] - final)) best = j;
    if (start > 0 && i < x.length) peaks.push({ t: t[best], a: Math.abs(x[best] - final) });
    start = i;
  }
  const big = peaks.filter((q) => q.a > 1e-3 * (peaks.length ? peaks[0].a : 0));
  if (big.length < 3) return null;
  const gaps = [], ratios = [];
  for (let i = 1; i < big.length; i++) { gaps.push(big[i].t - big[i - 1].t); ratios.push(big[i].a / big[i - 1].a); }
  const med = (v) => v.slice().sort((a, b) => a - b)[Math.floor(v.length / 2)];
  const r = Math.min(med(ratios.slice(0, 6)), 0.999999), lr = Math.log(r);
  return { hz: 1 / (2 * med(gaps.slice(0, 6))), damping: -lr / Math.sqrt(Math.PI * Math.PI + lr * lr), swings: big.length };
}
// The loop now: the gains in force, the margin, the crossover (the open loop's unity-gain
// bandwidth), the step response and its ring, and the suggestions.
function loopNow() {
  const kp = parseFloat(inForce("feedback.proportional_gain")) || 0;
  const ki = parseFloat(inForce("feedback.integral_gain"));
  if (!isFinite(ki)) return null;
  const l = loopParams(kp, ki);
  const wc = crossover(l);
  const r = {
    kp, ki, l, margin: phaseMargin(l), fc: wc / (2 * Math.PI),
    tauA: l.tauA,
    kiRule: Math.PI * loop.p.f0 / (2 * loop.p.Q),
    // I alone (P kept as set) for a 60 deg margin
    ki60: kiForMargin(60, () => kp),
  };
  // P and I together: the largest P is the one whose zero ki / kp cancels the amplitude's
  // lag (kp = ki tau_A, more P adds gain above it without phase), I then for 60 deg
  r.ki60pi = kiForMargin(60, (k) => k * l.tauA);
  r.kp60pi = r.ki60pi * l.tauA;
  // long enough to settle: a few crossover periods, more where the margin is small
  const r0 = phaseMargin(l);
  const tEnd = Math.min(0.05, Math.max(2e-3, isFinite(wc) ? (r0 > 45 ? 8 : 25) / wc : 12 / Math.max(ki, 50)));
  r.step = stepResponse(l, tEnd);
  r.ring = r.margin > 0 ? ringOf(r.step.t, r.step.z, 1) : null;
  let peak = 0;
  for (const z of r.step.z) peak = Math.max(peak, z);
  r.overshoot = peak - 1;
  return r;
}
// The cantilever's and the lock-in's numbers from the scene in force (the export, every
// key written): f0, Q, the drive, the filter and the block; the block's delay from the
// scope's record rate once a scope has come.
function siValue(text) {
  const m = /^\s*([-+0-9.eE]+)\s*([a-zA-Z\u00b5]*)/.exec(text || "");
  if (!m) return NaN;
  const pre = { p: 1e-12, n: 1e-9, u: 1e-6, "\u00b5": 1e-6, m: 1e-3, k: 1e3, M: 1e6, G: 1e9 };
  const u = m[2];
  const base = ["Hz", "s", "m"].find((b) => u.endsWith(b) && u.length === b.length + 1 && pre[u[0]]);
  return parseFloat(m[1]) * (base ? pre[u[0]] : 1);
}
function loadScene() {
  if (!window.fetch) return;
  fetch("/export/scene.ini").then((r) => (r.ok ? r.text() : "")).then((text) => {
    const keys = {};
    let sec = "";
    for (const line of text.split("\n")) {
      const s = /^\s*\[([^\]]+)\]/.exec(line);
      if (s) { sec = s[1].trim(); continue; }
      const kv = /^\s*([a-z_]+)\s*=\s*(.*)$/.exec(line);
      if (kv && !(sec + "." + kv[1] in keys)) keys[sec + "." + kv[1]] = kv[2];
    }
    const f0 = siValue(keys["cantilever.resonance_frequency"]), Q = siValue(keys["cantilever.quality_factor"]);
    if (!(f0 > 0 && Q > 0)) return;
    const fd = siValue(keys["cantilever.drive_frequency"]);
    const tf = siValue(keys["lockin.time_constant"]), n = parseInt(keys["lockin.filter_order"], 10);
    const P = parseInt(keys["lockin.periods_per_block"], 10);
    Object.assign(loop.p, { f0, Q, fd: fd > 0 ? fd : f0, from: "scene" });
    if (tf >= 0) loop.p.tau_f = tf;
    if (n >= 0) loop.p.n = n;
    if (P > 0) loop.p.P = P;
    loop.sig = "";
    drawLoop();
  }).catch(() => {});
}

// ---- the loop panel: Bode plot, step response, the ring against the model, suggestions
function plotFrame(ctx, box, xl, xh, yl, yh, logx, xlabel, ylabel, xTicks) {
  const X = (x) => box.x + (logx ? Math.log10(x / xl) / Math.log10(xh / xl) : (x - xl) / (xh - xl)) * box.w;
  const Y = (y) => box.y + box.h - (y - yl) / (yh - yl) * box.h;
  ctx.strokeStyle = "#e3e3e3"; ctx.lineWidth = 1; ctx.fillStyle = "#222";
  ctx.font = FONT_PX + "px DejaVu Sans, sans-serif";
  const yt = ticks(yl, yh, Math.max(2, Math.floor(box.h / 26)));
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (const t of yt.at) {
    const y = Math.round(Y(t)) + 0.5;
    ctx.beginPath(); ctx.moveTo(box.x, y); ctx.lineTo(box.x + box.w, y); ctx.stroke();
    ctx.fillText(tickText(t, yt.step), box.x - 4, y);
  }
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  for (const [t, label] of xTicks) {
    const x = Math.round(X(t)) + 0.5;
    ctx.beginPath(); ctx.moveTo(x, box.y); ctx.lineTo(x, box.y + box.h); ctx.stroke();
    if (label) ctx.fillText(label, x, box.y + box.h + 3);
  }
  ctx.strokeStyle = "#999"; ctx.strokeRect(box.x + 0.5, box.y + 0.5, box.w, box.h);
  if (xlabel) ctx.fillText(xlabel, box.x + box.w / 2, box.y + box.h + 4 + FONT_PX + 2);
  ctx.textAlign = "left";
  const tw = ctx.measureText(ylabel).width;
  ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(box.x + 2, box.y + 2, tw + 6, FONT_PX + 4);
  ctx.fillStyle = "#222"; ctx.fillText(ylabel, box.x + 5, box.y + 3);
  return { X, Y };
}
function canvasCtx(cv) {
  const dpr = window.devicePixelRatio || 1, W = cv.clientWidth, H = cv.clientHeight;
  if (cv.width !== Math.round(W * dpr) || cv.height !== Math.round(H * dpr)) { cv.width = Math.round(W * dpr); cv.height = Math.round(H * dpr); }
  const ctx = cv.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
  return { ctx, W, H };
}
function polyline(ctx, pts, colour, width, dash) {
  ctx.save(); ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.setLineDash(dash || []);
  ctx.beginPath();
  let pen = false;
  for (const [x, y] of pts) { if (!isFinite(y)) { pen = false; continue; } if (pen) ctx.lineTo(x, y); else ctx.moveTo(x, y); pen = true; }
  ctx.stroke(); ctx.restore();
}
function drawBode(r) {
  const { ctx, W, H } = canvasCtx($("bode"));
  const left = 48, right = 10, top = 6, gap = 16, bottom = 40;
  const ph = (H - top - bottom - gap) / 2;
  const f0 = 10, f1 = 1e5, n = 300;
  const fs = [];
  for (let i = 0; i <= n; i++) fs.push(f0 * Math.pow(f1 / f0, i / n));
  const mag = fs.map((f) => 20 * Math.log10(loopMag(r.l, 2 * Math.PI * f)));
  const pha = fs.map((f) => loopPhase(r.l, 2 * Math.PI * f));
  const xt = [];
  for (let f = 10; f <= 1e5; f *= 10) xt.push([f, f >= 1000 ? f / 1000 + "k" : String(f)]);
  for (let d = 10; d < 1e5; d *= 10) for (let k = 2; k < 10; k++) xt.push([k * d, ""]);
  const mb = { x: left, y: top, w: W - left - right, h: ph };
  const mlo = Math.max(-80, Math.min(...mag.filter(isFinite))), mhi = Math.min(80, Math.max(...mag.filter(isFinite)));
  const a = plotFrame(ctx, mb, f0, f1, Math.floor(mlo / 20) * 20, Math.ceil(mhi / 20) * 20, true, "", "|L| (dB)",
    xt.map(([f]) => [f, ""]));
  ctx.save(); ctx.beginPath(); ctx.rect(mb.x, mb.y, mb.w, mb.h); ctx.clip();
  polyline(ctx, [[mb.x, a.Y(0)], [mb.x + mb.w, a.Y(0)]], "#666", 1, [4, 3]);
  polyline(ctx, fs.map((f, i) => [a.X(f), a.Y(mag[i])]), "#1565c0", 1.6);
  ctx.restore();
  const pb = { x: left, y: top + ph + gap, w: mb.w, h: ph };
  const plo = Math.max(-360, Math.floor(Math.min(...pha) / 45) * 45), phi = 0;
  const b = plotFrame(ctx, pb, f0, f1, Math.min(plo, -225), phi, true, "frequency (Hz)", "phase of L (deg)", xt);
  ctx.save(); ctx.beginPath(); ctx.rect(pb.x, pb.y, pb.w, pb.h); ctx.clip();
  polyline(ctx, [[pb.x, b.Y(-180)], [pb.x + pb.w, b.Y(-180)]], "#666", 1, [4, 3]);
  polyline(ctx, fs.map((f, i) => [b.X(f), b.Y(pha[i])]), "#c62828", 1.6);
  ctx.restore();
  // the crossover (the bandwidth) through both panels, the margin as a bar up from -180
  if (isFinite(r.fc) && r.fc > f0 && r.fc < f1) {
    const x = Math.round(a.X(r.fc)) + 0.5;
    polyline(ctx, [[x, mb.y], [x, pb.y + pb.h]], "#2e7d32", 1.2, [3, 2]);
    const yp = b.Y(-180 + r.margin), y180 = b.Y(-180);
    ctx.save(); ctx.strokeStyle = r.margin >= 45 ? "#2e7d32" : r.margin > 0 ? "#ef6c00" : "#c62828"; ctx.lineWidth = 4;
    ctx.beginPath(); ctx.moveTo(x, y180); ctx.lineTo(x, yp); ctx.stroke(); ctx.restore();
    ctx.fillStyle = "#222"; ctx.font = FONT_PX + "px DejaVu Sans, sans-serif";
    const right = x > mb.x + mb.w * 0.6;
    ctx.textAlign = right ? "right" : "left"; ctx.textBaseline = "bottom";
    ctx.fillText("bandwidth " + fmt(r.fc, "Hz"), x + (right ? -5 : 5), a.Y(0) - 3);
    ctx.textBaseline = "top";
    ctx.fillText("margin " + r.margin.toFixed(1) + " deg", x + (right ? -5 : 5), Math.min(y180, yp) + 4);
  }
}
function drawStep(r) {
  const { ctx, W, H } = canvasCtx($("step"));
  const box = { x: 44, y: 6, w: W - 44 - 10, h: H - 6 - 40 };
  const t = r.step.t, z = r.step.z;
  const tEnd = t[t.length - 1] * 1e3;
  let hi = 1.2;
  for (const v of z) if (isFinite(v)) hi = Math.max(hi, Math.min(v, 3));
  const lo = Math.min(0, Math.max(-1, Math.min(...z)));
  const xt = ticks(0, tEnd, Math.max(2, Math.floor(box.w / 60)));
  const a = plotFrame(ctx, box, 0, tEnd, lo, hi * 1.05, false, "time after a step of the surface (ms)", "z / step",
    xt.at.map((x) => [x, tickText(x, xt.step)]));
  ctx.save(); ctx.beginPath(); ctx.rect(box.x, box.y, box.w, box.h); ctx.clip();
  polyline(ctx, [[box.x, a.Y(1)], [box.x + box.w, a.Y(1)]], "#666", 1, [4, 3]);
  polyline(ctx, t.map((x, i) => [a.X(x * 1e3), a.Y(z[i])]), "#1565c0", 1.6);
  ctx.restore();
}
function drawLoop() {
  const r = loopNow();
  if (!r) return;
  const st = state.status || {};
  const sig = [r.kp, r.ki, JSON.stringify(loop.p), $("bode").clientWidth, st.oscillating, st.ring_hz].join();
  if (sig === loop.sig) return;
  loop.sig = sig;
  loop.now = r;
  drawBode(r);
  drawStep(r);
  const pm = isFinite(r.margin) ? r.margin.toFixed(1) + " deg" : "none";
  $("loopinfo").textContent = "the model of docs/imaging.md: f0 " + fmt(loop.p.f0, "Hz") + ", Q " + loop.p.Q +
    ", lock-in " + loop.p.n + " x " + (loop.p.tau_f * 1e6).toFixed(0) + " us, block " + (loop.p.P / loop.p.fd * 1e6).toFixed(1) +
    " us" + (loop.p.from === "defaults" ? " (the standard cantilever's: scene not read)" : "");
  const unstable = !(r.margin > 0);
  $("loopsummary").textContent = "P " + r.kp + ", I " + fmt(r.ki, "Hz") + ": phase margin " + pm +
    (unstable ? " (the loop oscillates)" : "") + ", bandwidth (crossover) " + fmt(r.fc, "Hz") +
    (unstable ? "" : ", overshoot " + (100 * Math.max(0, r.overshoot)).toFixed(0) + " %") +
    "; tau_A = Q / (pi f0) = " + (r.tauA * 1e3).toFixed(2) + " ms, the rule pi f0 / (2 Q) = " + fmt(r.kiRule, "Hz") + ".";
  const model = unstable ? "the model grows without bound at " + fmt(r.fc, "Hz") + " or so" :
    r.ring ? "the model rings at " + fmt(r.ring.hz, "Hz") + ", damping ratio " + r.ring.damping.toFixed(2) :
      "the model does not ring (fewer than three swings)";
  const ring = st.oscillating && st.ring_hz > 0 ?
    "Measured: the loop rings at " + fmt(st.ring_hz, "Hz") + ", " + fmt(st.ring_m * 1e9, "nm") +
    " peak to peak in z" + (st.ring_damping > 0 ? ", damping ratio " + st.ring_damping.toFixed(2) : "") +
    " (the server's warning); " + model + " (in contact the amplitude answers faster than tau_A: docs/imaging.md)." :
    "No ring measured on the last line; " + model + ".";
  $("loopring").textContent = ring;
  $("loopsuggest").textContent = "For a 60 deg margin: I " + fmt(r.ki60, "Hz") + " with P as set (" + r.kp +
    "); or P " + r.kp60pi.toFixed(2) + " with I " + fmt(r.ki60pi, "Hz") +
    " (the largest useful P: kp = ki tau_A puts the PI zero on the amplitude's lag and cancels it; more P only raises the gain).";
  const u1 = $("usei60"), u2 = $("usepi60");
  u1.textContent = "use I " + fmt(r.ki60, "Hz"); u1.disabled = !(r.ki60 > 0);
  u1.onclick = () => window.tiptapSet("feedback.integral_gain", Math.round(r.ki60).toString());
  u2.textContent = "use P " + r.kp60pi.toFixed(2) + ", I " + fmt(r.ki60pi, "Hz"); u2.disabled = !(r.ki60pi > 0);
  u2.onclick = () => {
    window.tiptapSet("feedback.proportional_gain", r.kp60pi.toFixed(2));
    window.tiptapSet("feedback.integral_gain", Math.round(r.ki60pi).toString());
  };
}
function loopLog(text) {
  loop.log.push(text);
  const li = document.createElement("li");
  li.textContent = text;
  $("looplog").appendChild(li);
  $("looplog").scrollTop = 1e9;
}
// Auto-tune: I raised by half at a time, each step through the field's own message, kept
// for two lines on the scan's tier; it stops where the server warns of a ring or the
// model's margin falls below 20 deg, and backs off to the model's 60 deg margin.
const TUNE_STEP = 1.5, TUNE_STOP_DEG = 20, TUNE_MAX_STEPS = 16;
function autoTune() {
  if (loop.tune) { loop.tune = null; loopLog("auto-tune stopped by hand"); $("autotune").textContent = "auto-tune I"; return; }
  const ki = parseFloat(inForce("feedback.integral_gain"));
  if (!(ki > 0)) return;
  loop.tune = { steps: 0, ki, lines: 0 };
  $("autotune").textContent = "stop auto-tune";
  loopLog("auto-tune: from I " + fmt(ki, "Hz") + ", P " + (parseFloat(inForce("feedback.proportional_gain")) || 0) +
    ": I x " + TUNE_STEP + " each step, two lines each, until the loop rings or the model's margin is under " + TUNE_STOP_DEG + " deg");
  tuneNext();
}
function tuneNext() {
  const tu = loop.tune;
  if (!tu) return;
  tu.ki = tu.ki * TUNE_STEP;
  tu.steps++;
  tu.lines = -1; // counts the lines once the gain is in force
  window.tiptapSet("feedback.integral_gain", Math.round(tu.ki).toString());
}
function tuneFinish(why) {
  const tu = loop.tune;
  loop.tune = null;
  $("autotune").textContent = "auto-tune I";
  const kp = parseFloat(inForce("feedback.proportional_gain")) || 0;
  const k60 = kiForMargin(60, () => kp);
  const back = Math.round(k60);
  loopLog("step " + tu.steps + ": I " + fmt(tu.ki, "Hz") + " " + why + "; backed off to I " + fmt(back, "Hz") +
    ", the model's margin " + phaseMargin(loopParams(kp, back)).toFixed(1) + " deg");
  window.tiptapSet("feedback.integral_gain", back.toString());
  loop.tuned = back;
}
// each status after a new line's scope: the step's gain in force, two lines run, then judged
function tuneLine(st) {
  const tu = loop.tune;
  if (!tu) return;
  const ki = parseFloat(inForce("feedback.integral_gain"));
  if (Math.abs(ki - Math.round(tu.ki)) > 0.5) return;
  tu.lines++;
  const kp = parseFloat(inForce("feedback.proportional_gain")) || 0;
  const pm = phaseMargin(loopParams(kp, ki));
  if (st.oscillating && tu.lines >= 1) return tuneFinish("rings (the server's warning: " + fmt(st.ring_hz, "Hz") + ")");
  if (tu.lines < 2) return;
  if (!(pm >= TUNE_STOP_DEG)) return tuneFinish("leaves the model " + (isFinite(pm) ? pm.toFixed(1) + " deg" : "no margin") + " (under " + TUNE_STOP_DEG + ")");
  loopLog("step " + tu.steps + ": I " + fmt(ki, "Hz") + ", model margin " + pm.toFixed(1) + " deg, no ring in 2 lines");
  if (tu.steps >= TUNE_MAX_STEPS) return tuneFinish("is the last step allowed");
  tuneNext();
}
$("autotune").onclick = autoTune;

scopeUi();
drawScope();
connect();
