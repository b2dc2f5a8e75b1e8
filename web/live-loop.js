// tiptap live: the console's page, the loop's model and panel, auto-tune; and the page's start (docs/live.md); loaded after live.js,
// whose state and helpers it shares (classic scripts: one global scope).
"use strict";

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
  fetch(exportPath("scene.ini")).then((r) => (r.ok ? r.text() : "")).then((text) => {
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
