#!/usr/bin/python3
"""The console's thermal tune of a lever of several modes in headless Chromium at
1024 x 768 (tests/cli_live_bench.sh): the tune's message carries every mode of the scene,
each mode's f, Q and k equal `tiptap tune`'s on the same scene (the same seed: the same
run), each k lies within two of its standard errors of the scene's k_n (the band that
holds 95 % of seeds), the whole spectrum marks every mode, each mode has its zoom shown
and its figures read out. With a shots folder, docs/live-tune.png.

usage: live_bench_modes.py CHROMIUM URL SHOTS_DIR CLI_FIGURES (tiptap tune's stdout)"""
import sys

from live_cdp import run, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]
cli = dict(line.split(" = ", 1) for line in open(sys.argv[4]).read().splitlines() if " = " in line)


def close(a, b, rel=1e-5):
    return a is not None and abs(a - b) <= rel * abs(b)


def expected(n):
    """tiptap tune's f, Q, k and the scene's k of mode n (1 ..)."""
    if n == 1:
        return float(cli["f0_Hz"]), float(cli["Q"]), float(cli["k_N_per_m"]), None
    p = "mode%d_" % n
    return (float(cli[p + "f_Hz"]), float(cli[p + "Q"]), float(cli[p + "k_N_per_m"]),
            float(cli[p + "k_scene_N_per_m"]))


def main(b):
    modes = int(cli["modes"])
    b.eval("document.getElementById('runtune').click()")
    wait_for(b, "tiptapLive.bench.tunes > 0", "the thermal tune")
    t = b.eval("tiptapLive.bench.tune")
    assert len(t["modes"]) == modes, "%d modes sent, the scene has %d" % (len(t["modes"]), modes)
    read = b.eval("document.getElementById('tuneread').textContent")
    for n, md in enumerate(t["modes"], 1):
        f, q, k, ks = expected(n)
        assert close(md["f0"], f, 1e-6) and close(md["Q"], q) and close(md["k"], k), \
            "mode %d: f %s Q %s k %s, tiptap tune's %s %s %s" % (n, md["f0"], md["Q"], md["k"], f, q, k)
        if ks is not None:
            assert close(md["k_scene"], ks), "mode %d's scene k %s, tiptap tune's %s" % (n, md["k_scene"], ks)
        off = abs(md["k"] - md["k_scene"]) / md["k_err"]
        assert off <= 2, "mode %d: k = %s +- %s, %.2f standard errors from the scene's %s" % (
            n, md["k"], md["k_err"], off, md["k_scene"])
        assert md["fit_low"] < md["f0"] < md["fit_high"] and len(md["zoom_f"]) > 10, md["fit_low"]
        zoom = "tunezoom" if n == 1 else "tunezoom%d" % n
        assert b.eval("!!document.getElementById('%s') && !!document.getElementById('%s').offsetParent"
                      % (zoom, zoom)), zoom + " is not shown"
        assert ("mode %d: f = " % n) in read, read
        print("ok mode %d: f = %.8g Hz, Q = %.4g, k = %.4g +- %.2g N/m equal tiptap tune's; %.2f standard "
              "errors from the scene's %.6g N/m; its zoom shown" % (n, md["f0"], md["Q"], md["k"], md["k_err"],
                                                                  off, md["k_scene"]))
    # each window ends below the next mode's peak and starts above the last's
    for lo, hi in zip(t["modes"], t["modes"][1:]):
        assert lo["fit_high"] < hi["f0"] and hi["fit_low"] > lo["f0"], (lo["fit_high"], hi["fit_low"])
    print("ok read out: %s" % read)
    b.eval("document.getElementById('tunepanel').scrollIntoView()")
    shot(b, shots, "live-tune.png")


run(main, chromium, url, 1024, 768)
