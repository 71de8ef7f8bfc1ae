"""The peer for the HSLM sweep: EN 1991-2's 810 cases (A1-A10 at 40-120 m/s every 1 m/s) on
the 15 m bridge of `studies/hslm-15m.yaml`, as a railway engineer writes them in numpy.

The bridge is an Euler-Bernoulli beam, simply supported, its modes sin(n pi x / L) up to
EN 1991-2's cutoff max(30 Hz, 1.5 f1, f3), Rayleigh damping at zeta = 1.85 % on the first
two. Each mode's force from the axles on the span is P sin(n pi (v t - d_k) / L) summed over
them: between two of the axles' entries and exits it is one sinusoid, whose response is
taken in closed form (steady state plus the free motion from the segment's start), carried
from event to event, and sampled 20 times a period of the highest mode kept (or as many as
the second argument says), through the train's crossing and 0.5 s after it. At 20 a case's
largest acceleration is read up to 2.2e-3 below its own at 1000 samples, at 40 within 6e-4:
to compare at the accuracy rollbeam holds, run it at 40.

    python benches/hslm_peer.py [OUT.csv [SAMPLES_PER_PERIOD]]

prints the wall time of the sweep (the CSV written after it) and writes, per case, the
midspan's least and largest deflection and largest |acceleration|: the columns
`rollbeam sweep` writes as mid.w_min, mid.w_max, mid.a_max.
"""

import sys
import time

import numpy as np

L = 15.0
E, I, RHO, A = 35.0e9, 0.219830886, 2500.0, 6.0
ZETA = 0.0185
FREE_AFTER = 0.5
SAMPLES_PER_PERIOD = int(sys.argv[2]) if len(sys.argv) > 2 else 20

HSLM_A = [
    (18, 18.0, 2.0, 170.0e3),
    (17, 19.0, 3.5, 200.0e3),
    (16, 20.0, 2.0, 180.0e3),
    (15, 21.0, 3.0, 190.0e3),
    (14, 22.0, 2.0, 170.0e3),
    (13, 23.0, 2.0, 180.0e3),
    (13, 24.0, 2.0, 190.0e3),
    (12, 25.0, 2.5, 190.0e3),
    (11, 26.0, 2.0, 210.0e3),
    (11, 27.0, 2.0, 210.0e3),
]


def hslm(k):
    """Axle distances behind the first, and the axle force, of HSLM-Ak (EN 1991-2 Annex E)."""
    n, coach, bogie, force = HSLM_A[k - 1]
    power = [0.0, 3.0, 14.0, 17.0]
    axles = list(power)
    first = power[3] + 3.525
    for b in range(n + 3):
        start = first + b * coach
        axles += [start, start + bogie]
    rear = axles[-1] + 3.525
    axles += [rear + x for x in power]
    return np.array(axles), force


def modes():
    m = RHO * A
    n = np.arange(1, 40)
    omega = (n * np.pi / L) ** 2 * np.sqrt(E * I / m)
    f = omega / (2 * np.pi)
    cutoff = max(30.0, 1.5 * f[0], f[2])
    keep = f <= cutoff
    w1, w2 = omega[0], omega[1]
    beta = 2 * ZETA / (w1 + w2)
    alpha = beta * w1 * w2
    zeta = alpha / (2 * omega[keep]) + beta * omega[keep] / 2
    return n[keep], omega[keep], zeta, m


def train(axles, force, speeds, n, omega, zeta, m):
    """Midspan (w_min, w_max, |a|_max) for one train at every speed: the axles enter and
    leave in one order whatever the speed, so the events are carried for all speeds at once."""
    wd = omega * np.sqrt(1 - zeta**2)
    v = speeds[:, None]
    big_omega = n * np.pi * v / L
    h = 1.0 / (omega**2 - big_omega**2 + 2j * zeta * omega * big_omega)
    at = np.concatenate([axles, axles + L])
    signs = np.concatenate([np.ones_like(axles), -np.ones_like(axles)])
    order = np.argsort(at, kind="stable")
    at, signs = at[order], signs[order]
    theta = np.outer(np.concatenate([axles, axles])[order], n * np.pi / L)
    # Per segment the force is scale (c sin(Omega t) - s cos(Omega t)), its complex amplitude
    # f with force = Re(f e^{i Omega t}).
    c = np.cumsum(signs[:, None] * np.cos(theta), axis=0)
    s = np.cumsum(signs[:, None] * np.sin(theta), axis=0)
    f = 2 * force / (m * L) * (-s - 1j * c)
    amp = h[None, :, :] * f[:, None, :]
    starts = at[:, None] / speeds[None, :]
    t_end = starts[-1] + FREE_AFTER
    x0 = np.zeros(amp.shape)
    v0 = np.zeros(amp.shape)
    x, xd = np.zeros(amp.shape[1:]), np.zeros(amp.shape[1:])
    for i in range(len(at)):
        x0[i], v0[i] = x, xd
        t1 = starts[i + 1] if i + 1 < len(at) else t_end
        x, xd = motion(amp[i], big_omega, omega, zeta, wd, starts[i][:, None], x, xd, t1[:, None])
    dt = 1.0 / (SAMPLES_PER_PERIOD * omega[-1] / (2 * np.pi))
    mid = np.sin(n * np.pi / 2)
    out = []
    for j in range(len(speeds)):
        t = np.arange(starts[0, j], t_end[j], dt)
        seg = np.searchsorted(starts[:, j], t, side="right") - 1
        tt = t[:, None]
        q, qd = motion(amp[seg, j], big_omega[j], omega, zeta, wd, starts[seg, j][:, None], x0[seg, j], v0[seg, j], tt)
        forcing = np.real(f[seg] * np.exp(1j * big_omega[j] * tt))
        qdd = forcing - 2 * zeta * omega * qd - omega**2 * q
        w = -(q @ mid)
        a = qdd @ mid
        out.append((w.min(), w.max(), np.abs(a).max()))
    return out


def motion(amp, big_omega, omega, zeta, wd, t0, x0, v0, t):
    """(q, q') at t of each mode under Re(amp e^{i Omega t}) from (x0, v0) at t0."""
    e0 = np.exp(1j * big_omega * t0)
    p0 = amp * e0
    e0_free = x0 - np.real(p0)
    e1_free = v0 - np.real(1j * big_omega * p0)
    tau = t - t0
    decay = np.exp(-zeta * omega * tau)
    cos, sin = np.cos(wd * tau), np.sin(wd * tau)
    b = (e1_free + zeta * omega * e0_free) / wd
    x_free = decay * (e0_free * cos + b * sin)
    v_free = -zeta * omega * x_free + decay * wd * (b * cos - e0_free * sin)
    p = amp * np.exp(1j * big_omega * t)
    return np.real(p) + x_free, np.real(1j * big_omega * p) + v_free


def main():
    n, omega, zeta, m = modes()
    speeds = np.linspace(40.0, 120.0, 81)
    trains = [hslm(k) for k in range(1, 11)]
    start = time.perf_counter()
    by_train = [train(axles, force, speeds, n, omega, zeta, m) for axles, force in trains]
    rows = [
        (v, f"A{k + 1}", *by_train[k][j]) for j, v in enumerate(speeds) for k in range(len(trains))
    ]
    wall = time.perf_counter() - start
    print(f"{len(rows)} cases, {len(n)} modes up to {omega[-1] / (2 * np.pi):.2f} Hz: {wall:.3f} s")
    if len(sys.argv) > 1:
        with open(sys.argv[1], "w") as out:
            out.write("train.speed,train.hslm,mid.w_min,mid.w_max,mid.a_max\n")
            for r in rows:
                out.write(f"{r[0]:g},{r[1]},{r[2]:.9e},{r[3]:.9e},{r[4]:.9e}\n")


if __name__ == "__main__":
    main()
