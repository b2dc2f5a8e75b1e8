// tiptap live: the console's page (docs/live.md). Served by tiptap itself; nothing
// else is loaded. Messages from the server are JSON objects with a "type"; the page
// sends text lines "set NAME = VALUE" (checked by the server as scene text). The scope is
// in live-scope.js, the loop panel and the start in live-loop.js (loaded after this one).
"use strict";

const state = {
  frame: null, images: {}, tiers: [], tierTable: [], previewRows: 0, scope: null, status: null, controls: [],
  scopes: 0, rows: 0, replies: 0, lastReply: null, ws: null, sent: 0,
  // the display: what each image shows (per image, kept across frames), the scope shown
  // (the newest, or the one held), the reference, the zoom and the cursor
  view: {}, shown: {}, lastLine: null, scopeShown: null, hold: false, reference: null,
  xmode: "position", zoom: null, cursor: null, scopeTextPx: 0,
};
window.tiptapLive = state; // for the browser test and the curious

const $ = (id) => document.getElementById(id);
const FONT_PX = 13; // the smallest text on the page: readable on a projector at 1024 x 768

// Each page (tab) drives an instrument of its own; its number, kept for the tab's life
// (sessionStorage), asks for the same one again after a reload or a reconnection.
function instrumentNumber() {
  try { return parseInt(sessionStorage.getItem("tiptap-instrument"), 10) || 0; } catch (e) { return 0; }
}
function exportPath(name) {
  return "/export/" + (state.instrument ? state.instrument + "/" : "") + name;
}
// the Page Visibility API: a tab put behind another (or minimised, where the browser
// says so) idles its instrument; shown again, it runs on
document.addEventListener("visibilitychange", () => {
  if (state.ws && state.ws.readyState === 1) state.ws.send(document.hidden ? "hidden" : "visible");
});
function connect() {
  const n = instrumentNumber();
  const ws = new WebSocket("ws://" + location.host + "/" + (n ? n : ""), "tiptap-live");
  state.ws = ws;
  ws.onopen = () => {
    $("conn").textContent = "connected"; $("conn").className = "ok";
    // a new connection gets the controls afresh; nothing sent before waits for a reply
    for (const el of document.querySelectorAll(".knobs [data-name]")) el.dataset.pending = "";
    // a hidden tab does not look: its instrument idles until it is shown (the server
    // counts a new connection as looking)
    if (document.hidden) ws.send("hidden");
  };
  ws.onclose = () => {
    $("conn").textContent = "disconnected: retrying"; $("conn").className = "bad";
    setTimeout(connect, 1000);
  };
  ws.onmessage = (ev) => {
    let m;
    try { m = JSON.parse(ev.data); } catch (e) { return; }
    // the benches' messages (force, tune) are live-bench.js's
    const handle = { controls, frame, row, scope, status, reply }[m.type] || (window.benchHandlers || {})[m.type];
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
// the tier menu is the server's table of tiers (m.tiers: name and hint, the solver's order)
const choices = { "noise": ["on", "off"], "scan.fast_axis": ["x", "y"] };
// an option's hint: its tooltip, and the line under its menu for the one in force (the
// closed menu shows the name only: the column is too narrow for the hint)
const optionHint = {};
const hints = {};
// a read-out beside a field: its value in force in another unit (the setpoint, in % of
// the free amplitude as the scene writes it, in nm)
const derivedHint = {
  "feedback.setpoint": () => {
    const sp = parseFloat(inForce("feedback.setpoint")), a0 = parseFloat(inForce("cantilever.free_amplitude"));
    return sp > 0 && a0 > 0 ? "= " + (sp * a0 / 100).toPrecision(3) + " nm" : "";
  },
};
const derivedTitle = { "feedback.setpoint": "the setpoint in nm: its % of the free amplitude in force (a value typed in nm is taken as such)" };
function tierTable(tiers) {
  if (!tiers || !tiers.length) return;
  state.tierTable = tiers;
  choices["solver.tier"] = tiers.map((t) => t.name);
  optionHint["solver.tier"] = {};
  for (const t of tiers) optionHint["solver.tier"][t.name] = t.hint;
  hints["solver.tier"] = tiers.map((t) => t.name + ": " + t.hint).join("; ");
}
// units the server leaves blank: shown, never sent (a bare number is what the key takes)
const shownUnit = { "feedback.proportional_gain": "m/m" };
function inForce(name) {
  const c = state.controls.find((k) => k.name === name);
  return c ? c.value : null;
}
function restore(el) {
  const v = inForce(el.dataset.name);
  if (v != null) { el.value = v; el.dataset.was = v; }
  el.classList.remove("stale"); el.title = "";
  el.dataset.dirty = "";
  el.dataset.pending = "";
}
function controls(m) {
  state.controls = m.controls;
  tierTable(m.tiers);
  if (m.instrument && m.instrument !== state.instrument) {
    state.instrument = m.instrument;
    try { sessionStorage.setItem("tiptap-instrument", String(m.instrument)); } catch (e) { /* none kept */ }
    for (const a of document.querySelectorAll("#exports a")) a.href = exportPath(a.download);
    loadScene();
  }
  $("conn").textContent = "connected: instrument " + m.instrument + " of " + m.instruments;
  for (const c of m.controls) {
    // a bench's knobs in its own panel (live-bench.js), the scan's here
    const form = $(c.panel ? c.panel + "controls" : "controls");
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
        op.textContent = o;
        op.title = (optionHint[c.name] || {})[o] || "";
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
      if (optionHint[c.name] || derivedHint[c.name]) {
        const h = document.createElement("span");
        h.className = derivedHint[c.name] ? "beside" : "hint"; h.id = id + "-hint";
        if (derivedHint[c.name]) { lab.classList.add("withbeside"); h.title = derivedTitle[c.name] || ""; }
        lab.append(h);
      }
      form.appendChild(lab);
    }
    if (optionHint[c.name]) $(id + "-hint").textContent = c.value + ": " + (optionHint[c.name][c.value] || "");
    // the lesson's hidden controls are not drawn; its locked ones shown, not editable
    // (the server refuses a change to them too)
    el.parentElement.hidden = !!c.hidden;
    el.disabled = !!c.locked;
    el.parentElement.classList.toggle("locked", !!c.locked);
    const editing = el.dataset.dirty && document.activeElement === el;
    if (!editing && !el.dataset.pending) { el.value = c.value; el.dataset.dirty = ""; }
    // unsent text kept: marked stale when the value in force is not the one it was typed over
    el.classList.toggle("stale", !!editing && c.value !== el.dataset.was);
    el.title = el.classList.contains("stale") ? "in force now: " + c.value + " (Escape puts it back)" : "";
    if (!editing) el.dataset.was = c.value;
  }
  // once every value in force is known
  for (const name in derivedHint) {
    const h = $("c-" + name.replace(/\./g, "-") + "-hint");
    if (h) h.textContent = derivedHint[name]();
  }
  const ls = m.lesson;
  $("lesson").hidden = !ls;
  if (ls) {
    $("lessontitle").textContent = ls.title;
    $("lessontext").textContent = ls.instructions;
    document.title = ls.title + ": tiptap live";
  }
  state.lesson = ls || null;
  if (window.benchShow) window.benchShow(m.benches || {});
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
  for (const el of document.querySelectorAll(".knobs [data-name]")) {
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
  runWarnings(m);
  $("runstate").textContent = m.idle ? (document.hidden ? "idle: this tab is hidden" : "waiting for a page") : m.paused ? "paused at line " + m.line : "";
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
// the run's warnings, as tiptap scan prints them of the same scene (the run layer's):
// an earlier frame's marked as such
function runWarnings(m) {
  const ws = m.warnings || [];
  $("runwarnings").hidden = !ws.length;
  const ul = $("runwarninglist");
  ul.textContent = "";
  for (const w of ws) {
    const li = document.createElement("li");
    li.textContent = (w.frame !== m.frame ? "(frame " + w.frame + ") " : "") + w.text;
    li.dataset.category = w.category;
    ul.appendChild(li);
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
  amplitude_2: [[0, 0, 4], [81, 18, 124], [183, 55, 121], [252, 137, 97], [252, 253, 191]],
  phase_2: [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]],
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
    a.href = exportPath(n); a.textContent = n; a.download = n;
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
  if (m.preview) state.previewRows++;
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
      (ln != null && state.tiers[ln] === "preview" ? "; line " + ln + " from the averaged preview" : "");
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
