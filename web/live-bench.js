// tiptap live: the benches (docs/live.md, "Force curve and thermal tune"): a force curve
// and a thermal tune run by the server at the page's request ("force", "tune"), on the
// instrument's scene, their results drawn here. Uses live-loop.js's plot helpers.
"use strict";

const bench = { force: null, tune: null, forces: 0, tunes: 0, whole: false };
state.bench = bench; // for the browser test

const LEG_COLOUR = ["#1565c0", "#888", "#c62828"]; // approach, dwell, retract

// a lesson that hides every knob of a bench hides its panel (the server refuses its run)
window.benchShow = (shown) => {
  $("forcepanel").hidden = shown.force === false;
  $("tunepanel").hidden = shown.tune === false;
};

function benchState(kind, m) {
  $(kind + "state").textContent = m.state === "running" ? "running..." :
    m.state === "failed" ? "failed: " + m.error : "";
  $(kind === "force" ? "runforce" : "runtune").disabled = m.state === "running";
}

function range(xs) {
  let lo = Infinity, hi = -Infinity;
  for (const x of xs) if (x != null && isFinite(x)) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
  if (!(hi > lo)) { lo -= 1; hi += 1; }
  return [lo, hi];
}

// one panel of the force curve: force (nN) against xs (nm), the legs coloured, two marks;
// up close (not bench.whole) from the deepest point to three times as far past the
// jump-in, forces up to eight adhesions (the contact part runs off the top)
function drawForce(id, m, xs, xlabel, marks) {
  const { ctx, W, H } = canvasCtx($(id));
  const box = { x: 52, y: 6, w: W - 52 - 10, h: H - 6 - 40 };
  const x = xs.map((v) => v * 1e9), f = m.force.map((v) => v == null ? NaN : v * 1e9);
  let [xl, xh] = range(x), [fl, fh] = range(f);
  const jx = marks[0][0] * 1e9, ad = m.adhesion * 1e9;
  if (!bench.whole && isFinite(jx) && jx > xl) xh = Math.min(xh, jx + 3 * (jx - xl));
  if (!bench.whole && ad > 0) fh = Math.min(fh, 8 * ad);
  const pad = 0.05 * (fh - fl), below = bench.whole ? pad : 0.2 * (fh - fl); // room for the pull-off's label
  const xt = ticks(xl, xh, Math.max(2, Math.floor(box.w / 60)));
  const a = plotFrame(ctx, box, xl, xh, fl - below, fh + pad, false, xlabel, "force (nN)",
    xt.at.map((v) => [v, tickText(v, xt.step)]));
  ctx.save(); ctx.beginPath(); ctx.rect(box.x, box.y, box.w, box.h); ctx.clip();
  polyline(ctx, [[box.x, a.Y(0)], [box.x + box.w, a.Y(0)]], "#666", 1, [4, 3]);
  for (const leg of [2, 1, 0]) { // the approach drawn last, over the retract it meets
    const pts = x.map((v, i) => [a.X(v), m.leg[i] === leg ? a.Y(f[i]) : NaN]);
    polyline(ctx, pts, LEG_COLOUR[leg], 1.6);
  }
  // the jump-in's label above its mark, the pull-off's below (they lie close together)
  marks.forEach(([mx, mf, colour, label], i) => {
    if (mx == null || mf == null) return;
    const px = a.X(mx * 1e9), py = a.Y(mf * 1e9);
    ctx.fillStyle = colour; ctx.beginPath(); ctx.arc(px, py, 5, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = "#222"; ctx.font = FONT_PX + "px DejaVu Sans, sans-serif";
    ctx.textAlign = px > box.x + box.w * 0.6 ? "right" : "left"; ctx.textBaseline = i ? "top" : "bottom";
    ctx.fillText(label, px + (ctx.textAlign === "right" ? -8 : 8), py + (i ? 6 : -6));
  });
  ctx.restore();
}

// a bench's message: its state by its button; its result kept (bench.force, bench.forces
// counting them) and drawn
function benchHandler(kind, draw) {
  return (m) => {
    benchState(kind, m);
    if (m.state !== "done") return;
    bench[kind] = m;
    bench[kind + "s"]++;
    draw(m);
  };
}
function drawForces(m) {
  const jl = "jump-in " + fmt(m.jumpin_force * 1e9, "nN"), pl = "pull-off " + fmt(m.pulloff_force * 1e9, "nN");
  drawForce("forcez", m, m.z, "z, the rest separation (nm)",
    [[m.jumpin_z, m.jumpin_force, "#2e7d32", jl], [m.pulloff_z, m.pulloff_force, "#ef6c00", pl]]);
  drawForce("forcesep", m, m.separation, "separation (nm; below 0: indentation)",
    [[m.jumpin_separation, m.jumpin_force, "#2e7d32", jl], [m.pulloff_separation, m.pulloff_force, "#ef6c00", pl]]);
  $("forceinfo").textContent = "on " + (m.material || "the first material") + ", k = " + fmt(m.k, "N/m") +
    ", " + fmt(m.speed * 1e6, "um/s");
  $("forceread").textContent = "jump-in at z = " + fmt(m.jumpin_z * 1e9, "nm") + " (separation " +
    fmt(m.jumpin_separation * 1e9, "nm") + "): " + fmt(m.jumpin_force * 1e9, "nN") + "; pull-off at z = " +
    fmt(m.pulloff_z * 1e9, "nm") + ": " + fmt(m.pulloff_force * 1e9, "nN") + "; adhesion " +
    fmt(m.adhesion * 1e9, "nN") + "; contact slope " + fmt(m.slope, "N/m") + "; largest force " +
    fmt(m.max_force * 1e9, "nN") + ", indentation " + fmt(m.indentation * 1e9, "nm") + ".";
}

// a value and its standard error at the error's first significant digit or two
function withErr(x, err, unit, scale) {
  if (!isFinite(x)) return "?";
  const d = isFinite(err) && err > 0 ? Math.max(0, 1 - Math.floor(Math.log10(err / scale))) : 3;
  return (x / scale).toFixed(Math.min(d, 8)) + " \u00b1 " + (isFinite(err) ? (err / scale).toFixed(Math.min(d, 8)) : "?") +
    (unit ? " " + unit : "");
}

// a frequency's tick label
function hz(f) {
  return f >= 1e6 ? f / 1e6 + " MHz" : f >= 1e3 ? f / 1e3 + " kHz" : f + " Hz";
}

// each mode's colour: its window's shade, its resonance's mark, its figures' text
const MODE_COLOUR = ["#2e7d32", "#6a1b9a", "#ef6c00"];
function shade(colour) {
  const n = parseInt(colour.slice(1), 16);
  return "rgba(" + (n >> 16) + "," + ((n >> 8) & 255) + "," + (n & 255) + ",0.09)";
}

// the spectrum (blue) and the fit (red) on log-log axes between f0 and f1, each of
// modes' resonances marked and its fit's window shaded in its colour (the mode's number
// by its mark when there are several); ticks at 1..9 times the decades, the decades named
function drawSpectrum(id, modes, fs, psd, fit, xlabel, several) {
  const { ctx, W, H } = canvasCtx($(id));
  const box = { x: 52, y: 6, w: W - 52 - 10, h: H - 6 - 40 };
  const lp = psd.map((v) => v > 0 ? Math.log10(v) : NaN), lq = fit.map((v) => v > 0 ? Math.log10(v) : NaN);
  const f0 = fs[0], f1 = fs[fs.length - 1];
  const [yl, yh] = range(lp.concat(lq));
  let xt = [];
  if (f1 / f0 < 3) { // the resonance: linear ticks in kHz (log and linear alike over it)
    const t = ticks(f0 / 1e3, f1 / 1e3, Math.max(2, Math.floor(box.w / 90)));
    // no label so near the right end that it would be cut
    xt = t.at.map((v) => [v * 1e3, v * 1e3 < f1 - 0.08 * (f1 - f0) ? tickText(v, t.step) + " kHz" : ""]);
  } else {
    for (let d = Math.pow(10, Math.floor(Math.log10(f0))); d <= f1; d *= 10)
      for (let k = 1; k < 10; k++) if (k * d >= f0 && k * d <= f1) xt.push([k * d, k === 1 && k * d < f1 / 1.4 ? hz(k * d) : ""]); // none cut at the right
  }
  const a = plotFrame(ctx, box, f0, f1, Math.floor(yl * 2) / 2, Math.ceil(yh * 2) / 2, true, xlabel,
    "log10 PSD (m\u00b2/Hz)", xt);
  ctx.save(); ctx.beginPath(); ctx.rect(box.x, box.y, box.w, box.h); ctx.clip();
  for (const md of modes) {
    const wl = a.X(Math.max(md.fit_low, f0)), wh = a.X(Math.min(md.fit_high, f1));
    ctx.fillStyle = shade(md.colour);
    if (wh > wl) ctx.fillRect(wl, box.y, wh - wl, box.h);
  }
  polyline(ctx, fs.map((f, i) => [a.X(f), a.Y(lp[i])]), "#1565c0", 1.4);
  polyline(ctx, fs.map((f, i) => [a.X(f), a.Y(lq[i])]), "#c62828", 1.8);
  for (const md of modes) {
    polyline(ctx, [[a.X(md.f0), box.y], [a.X(md.f0), box.y + box.h]], md.colour, 1, [3, 2]);
    if (!several) continue;
    // one row each (marks may lie close on a log axis), left of a mark near the right edge
    const px = a.X(md.f0), right = px > box.x + 0.7 * box.w;
    ctx.fillStyle = md.colour; ctx.font = FONT_PX + "px DejaVu Sans, sans-serif";
    ctx.textAlign = right ? "right" : "left"; ctx.textBaseline = "top";
    ctx.fillText("mode " + md.n, px + (right ? -4 : 4), box.y + 4 + (md.n - 1) * (FONT_PX + 4));
  }
  ctx.restore();
}

// the zoom canvases, one a mode (tunezoom: mode 1's; the others made here, after it)
function zoomCanvas(n) {
  const id = n === 1 ? "tunezoom" : "tunezoom" + n;
  if (!$(id)) {
    const c = document.createElement("canvas");
    c.id = id;
    c.title = "mode " + n + "'s resonance bin by bin, f0 +- 12 f0/Q, and the fit";
    $("tuneplots").appendChild(c);
  }
  return id;
}

function drawTune(m) {
  const modes = m.modes.map((md, i) => Object.assign({ n: i + 1, colour: MODE_COLOUR[i % MODE_COLOUR.length] }, md));
  const several = modes.length > 1;
  drawSpectrum("tuneplot", modes, m.f, m.psd, m.fit, "frequency (the whole record's spectrum)", several);
  for (let n = 2; $("tunezoom" + n); n++) $("tunezoom" + n).hidden = n > modes.length; // a scene with fewer modes since
  for (const md of modes)
    if (md.zoom_f.length > 1)
      drawSpectrum(zoomCanvas(md.n), [md], md.zoom_f, md.zoom_psd, md.zoom_fit,
        "frequency (" + (several ? "mode " + md.n + "'s" : "the") + " resonance, bin by bin)", false);
  $("tuneinfo").textContent = "at " + fmt(m.temperature, "K") + ", " + m.averages.toFixed(1) + " averages, bins of " +
    fmt(m.bin_width, "Hz") + (several ? ", " + modes.length + " modes" : "");
  $("tuneread").innerHTML = "";
  for (const md of modes) {
    const sig = Math.abs(md.k - md.k_scene) / md.k_err;
    const line = document.createElement("span");
    line.className = "tunemode";
    line.style.color = md.colour;
    line.textContent = (several ? "mode " + md.n + ": " : "") + "f = " + withErr(md.f0, md.f0_err, "kHz", 1e3) +
      "; Q = " + withErr(md.Q, md.Q_err, "", 1) + "; k = " + withErr(md.k, md.k_err, "N/m", 1) + " (the scene's " +
      fmt(md.k_scene, "N/m") + ": " + (isFinite(sig) ? sig.toFixed(1) : "?") + " standard errors off)" +
      (several ? ", chi = " + md.chi.toFixed(4) : "") + ". ";
    $("tuneread").appendChild(line);
  }
  const note = document.createElement("span");
  note.className = "small";
  note.textContent = "spectrum (blue) and the damped oscillator" + (several ? "s" : "") + " fitted to it (red) over the shaded window" +
    (several ? "s, each mode's peak on its own window over the others' fits and the floor" : "") +
    "; k by equipartition, " + (several ? "each mode's chi its slope at the tip against the end load's" : "chi = " + m.chi) +
    ", fit chi\u00b2/dof " + modes.map((md) => md.chi2_dof != null ? md.chi2_dof.toFixed(2) : "?").join(", ") + ".";
  $("tuneread").appendChild(note);
}

window.benchHandlers = { force: benchHandler("force", drawForces), tune: benchHandler("tune", drawTune) };
$("runforce").onclick = () => send("force");
$("runtune").onclick = () => send("tune");
$("forcewhole").onclick = () => {
  bench.whole = !bench.whole;
  $("forcewhole").setAttribute("aria-pressed", bench.whole ? "true" : "false");
  if (bench.force) drawForces(bench.force);
};
