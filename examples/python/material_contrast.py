"""The material-contrast study of examples/material-contrast (docs/sweeps.md) from
Python: disk minus matrix apparent height, phase and dissipation of the polymer blend
against setpoint, for four free amplitudes (docs/python.md).

    PYTHONPATH=python TIPTAP_LIBRARY=build/libtiptap.so /usr/bin/python3 examples/python/material_contrast.py
"""
import os

import tiptap

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = [os.path.join(HERE, "..", "..", "surfaces", "polymer-blend.ini"),
         os.path.join(HERE, "..", "material-contrast", "scene.ini")]


def study(amplitudes="10nm,20nm,40nm,80nm", setpoints="10%:95%:18", **run):
    """The sweep, and its disk - matrix differences as arrays (free amplitude, setpoint)."""
    t = tiptap.sweep(SCENE, {"cantilever.free_amplitude": amplitudes,
                             "approach.material": "matrix,disk",
                             "feedback.setpoint": setpoints}, run="setpoint", **run)
    grid = (len(amplitudes.split(",")), 2, -1)
    z, phase, loss = (t[k].reshape(grid) for k in ("z", "phase", "dissipated"))
    # apparent height: the feedback retracts the sample where the setpoint needs a larger gap
    return t, {"height": z[:, 1] - z[:, 0], "phase": phase[:, 1] - phase[:, 0],
               "dissipation": loss[:, 1] - loss[:, 0]}


if __name__ == "__main__":
    t, d = study()
    setpoint = t["feedback.setpoint"].reshape(4, 2, -1)[0, 0]
    print("setpoint  " + "  ".join(f"{a:>8}" for a in ("10 nm", "20 nm", "40 nm", "80 nm")))
    for j, s in enumerate(setpoint):
        print(f"{s * 100:6.1f} %  " + "  ".join(f"{h * 1e9:+8.2f}" for h in d["height"][:, j]))
    print("(disk - matrix apparent height, nm, for each free amplitude)")
