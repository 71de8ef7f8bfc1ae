#!/usr/bin/env python3
"""How far runs lie from a reference in the probes' windowed means, and in their extremes.

REPORT.md, "A windowed mean reaches 10⁻⁶ on the sudden loads": each probe's deflection w is
averaged over equal windows of the run with a Hann weight, whose leakage falls as the cube of
a mode's frequency, so the fast modes whose phase decides the extremes are filtered out. The
integral is the trapezoidal rule on the history's own rows, so the history must be written on
a grid finer than the fastest mode that carries deflection (`output.interval: 1.0e-5` on the
sudden loads): on their 2 ms grid those kHz modes alias into the means.

Usage: windowed_means.py [--windows N] REFERENCE/history.csv RUN/history.csv...
Each error is relative to the largest |w| of the reference, as `rollbeam tradeoff` scores.
Only the standard library, so that it runs wherever the binary does.
"""

import argparse
import csv
import math


def read(path):
    """The output times and the probes' deflections (every column named `<probe>.w`)."""
    with open(path, newline="") as f:
        rows = csv.reader(f)
        header = next(rows)
        columns = [i for i, name in enumerate(header) if name.endswith(".w")]
        if header[0] != "t" or not columns:
            raise SystemExit(f"{path}: not a history with a time column and probes' w")
        t, w = [], []
        for row in rows:
            t.append(float(row[0]))
            w.append([float(row[i]) for i in columns])
    return t, w


def windowed_means(t, w, windows):
    """Per probe and window, the Hann-weighted mean of w over [k T/N, (k+1) T/N]."""
    length = t[-1] / windows
    probes = len(w[0])
    sums = [[0.0] * windows for _ in range(probes)]
    weights = [0.0] * windows
    for i in range(1, len(t)):
        k = int(0.5 * (t[i - 1] + t[i]) / length)
        if k >= windows:
            continue
        start, dt = k * length, t[i] - t[i - 1]
        hann = [math.sin(math.pi * (s - start) / length) ** 2 for s in (t[i - 1], t[i])]
        weights[k] += 0.5 * dt * (hann[0] + hann[1])
        for p in range(probes):
            sums[p][k] += 0.5 * dt * (hann[0] * w[i - 1][p] + hann[1] * w[i][p])
    return [s / weights[k] for row in sums for k, s in enumerate(row)]


def extremes(w):
    return [f(row[p] for row in w) for f in (min, max) for p in range(len(w[0]))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--windows", type=int, default=10)
    parser.add_argument("reference")
    parser.add_argument("runs", nargs="+")
    args = parser.parse_args()
    t, w = read(args.reference)
    scale = max(abs(x) for row in w for x in row)
    means, peaks = windowed_means(t, w, args.windows), extremes(w)
    for path in args.runs:
        rt, rw = read(path)
        if abs(rt[-1] - t[-1]) > 1e-9 * t[-1]:
            raise SystemExit(f"{path}: ends at t = {rt[-1]}, the reference at {t[-1]}")
        m = max(abs(a - b) for a, b in zip(windowed_means(rt, rw, args.windows), means))
        e = max(abs(a - b) for a, b in zip(extremes(rw), peaks))
        print(f"{path}: windowed means {m / scale:.2e}, extremes {e / scale:.2e}")


if __name__ == "__main__":
    main()
