#!/usr/bin/env python3
"""Fit the outside air's six radiation channels (Source/Physics/OutsideAir.h) to the air box.

The reduced drum (the cavity with outside air) and the drum in the air box are measured alike by
build/Lab/airbox_figures (modes / modes-model): the heads' (0,1) pair in phase and
anti-phase and each head's (1,1) mode, frequency and decay rate, lossless heads, snares off. This
script takes the air box's eight figures (from `airbox_figures modes SIDE`) and moves the four
channel pairs (mass M, resistance R: monopole, dipole, tilt sum, tilt difference) by damped
Gauss-Newton steps on the logarithms until the reduced drum gives the same figures; it prints
each step and the values to put into OutsideAirSpec (Source/Physics/OutsideAirSpec.h).

usage: calibrate_outside_air.py F_IN D_IN F_ANTI D_ANTI F_B11 D_B11 F_C11 D_C11
                                [--start Mm Rm Md Rd Ms Rs Mt Rt] [--steps N] [--modes-up-to HZ]
"""

import argparse
import math
import re
import subprocess
import sys

import numpy as np

TOOL = "build/Lab/airbox_figures"
NAMES = ["in phase", "anti-phase", "batter (1,1)", "carry (1,1)"]


def measure(params, anti_near, modes_up_to=0.0):
    out = subprocess.run([TOOL, "modes-model", *[f"{p:.9g}" for p in params], f"{anti_near:.6g}", f"{modes_up_to:.6g}"],
                         capture_output=True, text=True, check=True).stdout
    figures = []
    for name in NAMES:
        m = re.search(re.escape(name) + r"\s+([-\d.naninf]+) Hz\s+([-\d.naninf]+) dB/s", out)
        figures += [float(m.group(1)), float(m.group(2))]
    return np.array(figures)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("target", type=float, nargs=8)
    ap.add_argument("--start", type=float, nargs=8, default=[1.25, 5e4, 2.0, 1.4e4, 225.0, 4e6, 225.0, 4e6])
    ap.add_argument("--steps", type=int, default=8)
    ap.add_argument("--modes-up-to", type=float, default=0.0,
                    help="the cavity's own modes up to this frequency (Hz) in the reduced drum (CavitySpec::modesUpTo_Hz)")
    a = ap.parse_args()
    target = np.log(np.array(a.target))
    x = np.log(np.array(a.start))
    # volume parameters move the pair, tilt parameters the (1,1) modes: two 4 x 4 blocks
    blocks = [(slice(0, 4), slice(0, 4)), (slice(4, 8), slice(4, 8))]
    for step in range(a.steps):
        f = measure(np.exp(x), a.target[2], a.modes_up_to)
        if not np.all(np.isfinite(f)) or np.any(f <= 0):
            sys.exit(f"a figure was not found at {np.exp(x)}: {f}")
        r = np.log(f) - target
        print(f"step {step}: " + "; ".join(f"{NAMES[i]} {f[2*i]:.2f} Hz {f[2*i+1]:.1f} dB/s" for i in range(4))
              + f"  (worst: freq {100*np.max(np.abs(np.expm1(r[0::2]))):.2f} %, decay {100*np.max(np.abs(np.expm1(r[1::2]))):.1f} %)",
              flush=True)
        if np.max(np.abs(r[0::2])) < 0.002 and np.max(np.abs(r[1::2])) < 0.02:
            break
        J = np.zeros((8, 8))
        eps = 0.05
        for j in range(8):
            xj = x.copy()
            xj[j] += eps
            J[:, j] = (np.log(measure(np.exp(xj), a.target[2], a.modes_up_to)) - np.log(f)) / eps
        dx = np.zeros(8)
        for rows, cols in blocks:
            dx[cols] = np.linalg.lstsq(J[rows, cols], -r[rows], rcond=None)[0]
        dx = np.clip(dx, -0.7, 0.7)
        x = x + dx
        print("  params " + " ".join(f"{v:.5g}" for v in np.exp(x)), flush=True)
    print("OutsideAirSpec: monopole {%.4g, %.4g}, dipole {%.4g, %.4g}, tiltSum {%.4g, %.4g}, tiltDiff {%.4g, %.4g}" % tuple(np.exp(x)))


if __name__ == "__main__":
    main()
