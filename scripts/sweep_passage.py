#!/usr/bin/env python3
"""Passage of one mode through its critical speed under a linear speed ramp (docs/validation.md, "The reference rotor
on linear bearings"; docs/ball-bearing.md, "The resonances").

A one-degree-of-freedom oscillator, natural frequency w_n and damping ratio zeta, forced like an unbalance,
x'' + 2 zeta w_n x' + w_n^2 x = W(t)^2 cos(phi(t)) with W = a t and phi = a t^2 / 2, is run up from rest at the ramp
rate a (rad/s^2) to twice w_n (classical RK4, 400 steps per period). Printed: where the response peaks, as a speed
ratio W / w_n, and how large the peak is against the steady resonance 1 / (2 zeta) (the static deflection of
the unit unbalance being 1 here). The ramp enters only through lambda = a / w_n^2, so

    scripts/sweep_passage.py LAMBDA ZETA

with lambda = (dn/dt) / (2 pi f_n^2) for a ramp of dn/dt Hz per second through a critical of f_n Hz: the paper's
2,500 Hz in 4 s through 700 Hz gives lambda = 625 / (2 pi 700^2) = 2.03e-4. On a rotor whose natural frequency
moves with the speed (Campbell slope s = d f_n / d f_d) the ramp sweeps the mode's detuning at (1 - s) times the
speed's rate: use lambda (1 - s), and the rotor speed at the peak is the critical's times 1 + (ratio - 1) / (1 - s).
`turbodyn modal` does this for every 1x critical at the model's own ramp (model/rotor/modal.h, ramp_passage). The
classical study of this passage is F. M. Lewis, "Vibration during acceleration
through a critical speed", Trans. ASME 54 (1932) 253-261.
"""
import math
import sys


def passage(lam, zeta):
    a = lam  # w_n = 1: W = a t, the ramp rate in units of w_n^2
    t_end = 2.0 / a
    steps = int(t_end / (2.0 * math.pi) * 400) + 1
    dt = t_end / steps

    def rhs(t, x, v):
        w = a * t
        return v, w * w * math.cos(0.5 * a * t * t) - 2.0 * zeta * v - x

    t = x = v = 0.0
    peak, at = 0.0, 0.0
    for _ in range(steps):
        k1 = rhs(t, x, v)
        k2 = rhs(t + dt / 2, x + dt / 2 * k1[0], v + dt / 2 * k1[1])
        k3 = rhs(t + dt / 2, x + dt / 2 * k2[0], v + dt / 2 * k2[1])
        k4 = rhs(t + dt, x + dt * k3[0], v + dt * k3[1])
        x += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += dt
        if a * t > 0.5 and abs(x) > peak:
            peak, at = abs(x), a * t
    return peak, at


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    try:
        lam, zeta = float(sys.argv[1]), float(sys.argv[2])
    except ValueError:
        sys.exit("sweep_passage.py: LAMBDA and ZETA must be numbers")
    if not (0.0 < lam < 0.1) or not (0.0 <= zeta < 0.5):
        sys.exit("sweep_passage.py: needs 0 < LAMBDA < 0.1 (a slow ramp) and 0 <= ZETA < 0.5")
    peak, at = passage(lam, zeta)
    steady = 1.0 / (2.0 * zeta * math.sqrt(1.0 - zeta * zeta)) if zeta > 0.0 else math.inf
    print(f"lambda {lam:g}, zeta {zeta:g}: the run-up peaks at {at:.4f} of the critical speed "
          f"({100.0 * (at - 1.0):+.2f} %), {peak:.4g} times the static deflection, "
          f"{peak / steady:.3f} of the steady resonance ({steady:.4g})")


if __name__ == "__main__":
    main()
