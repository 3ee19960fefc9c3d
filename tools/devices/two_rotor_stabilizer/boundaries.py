#!/usr/bin/env python3
"""Stability boundaries in gain space (k1, k2) of the two-rotor stabilizers (docs/models/two-rotor-stabilizer.md).

Prints the markdown table of the docs page: along rays k2 = k1 tan(theta), the largest stable k1 (Routh-Hurwitz on
the closed loop's characteristic polynomial) of
  - the two-rotor two-axis stabilizer, counter-rotating (sigma = -1) and co-rotating (sigma = +1): the sextic
    P6 of det(M l^2 + C l + K) = l^2 P6(l) (sim/models/two_rotor_two_axis.hpp), expanded here independently of
    firmware/control/two_rotor_stabilizer_law.hpp;
  - the single-rotor two-axis stabilizer (14.23) with the same A, B, H and frame damping d + dK (Magnus (14.25)).
Plain Python (no numpy). Usage: boundaries.py [A B J H d1 d2 c dK]  (defaults: sim/scenes/two-rotor-two-axis.toml).
"""
import itertools
import math
import sys


def pmul(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def det_poly(m):
    """Determinant of a 4x4 matrix of polynomials (coefficient lists, ascending), by Leibniz."""
    total = [0.0] * 9
    for perm in itertools.permutations(range(4)):
        inv = sum(1 for i in range(4) for j in range(i + 1, 4) if perm[i] > perm[j])
        prod = [1.0]
        for r in range(4):
            prod = pmul(prod, m[r][perm[r]])
        for i, x in enumerate(prod):
            total[i] += (-1) ** inv * x
    return total


def sextic(A, B, J, H, d1, d2, c, s, k1, k2, dK1, dK2):
    m = [[[0, d1 + dK1, A], [0, (1 + s) * H, 0], [k1, H, 0], [0, 0, J]],
         [[0, -(1 + s) * H, 0], [0, d2 + dK2, B], [0, 0, J], [-s * k2, -s * H, 0]],
         [[0, -H, 0], [0, 0, J], [0, c, J], [0, 0, 0]],
         [[0, 0, J], [0, s * H, 0], [0, 0, 0], [0, c, J]]]
    d = det_poly(m)
    assert abs(d[0]) + abs(d[1]) <= 1e-9 * max(abs(x) for x in d), "the l^2 factor"
    return d[2:]


def routh_stable(a):
    """a ascending; True iff all roots in the open left half-plane."""
    a = list(a)
    while a and a[-1] == 0.0:
        a.pop()
    n = len(a) - 1
    if a[n] <= 0:
        return False
    r0 = [a[n - 2 * i] for i in range(n // 2 + 1)] + [0.0] * 4
    r1 = [a[n - 2 * i - 1] for i in range((n + 1) // 2)] + [0.0] * 4
    for _ in range(n):
        if r1[0] <= 0:
            return False
        nxt = [r0[i + 1] - r0[0] * r1[i + 1] / r1[0] for i in range(len(r1) - 1)] + [0.0]
        r0, r1 = r1, nxt
        if all(abs(x) == 0.0 for x in r1):
            return True
    return True


def boundary(stable, u, v):
    lo, hi = 0.0, 1.0
    while stable(hi * u, hi * v):
        lo, hi = hi, 2 * hi
        if hi > 1e9:
            return math.inf
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if stable(mid * u, mid * v):
            lo = mid
        else:
            hi = mid
    return lo


def main():
    A, B, J, H, d1, d2, c, dK = [float(x) for x in sys.argv[1:9]] or [4.0, 3.0, 0.5, 100.0, 0.0, 0.0, 2.0, 10.0]
    two = lambda s: (lambda k1, k2: routh_stable(sextic(A, B, J, H, d1, d2, c, s, k1, k2, dK, dK)))
    D1, D2 = d1 + dK, d2 + dK
    single = lambda k1, k2: k1 > 0 and k2 > 0 and routh_stable(
        [k1 * k2, H * (k1 + k2), H * H + D1 * D2, A * D2 + B * D1, A * B])
    print(f"A = {A}, B = {B}, J = {J}, H = {H}, d1 = {d1}, d2 = {d2}, c = {c}, dK1 = dK2 = {dK}\n")
    print("| ray k2/k1 | two-rotor, counter-rotating | two-rotor, co-rotating | single rotor (14.23) |")
    print("|---|---|---|---|")
    for deg in (0, 15, 30, 45, 60, 75, 90):
        th = math.radians(deg)
        u, v = math.cos(th), math.sin(th)
        if deg == 0:
            v = 1e-9
        if deg == 90:
            u = 1e-9
        cells = []
        for f in (two(-1), two(1), single):
            r = boundary(f, u, v)
            cells.append("stable to 1e9" if math.isinf(r) else f"k1 = {r * u:.1f}, k2 = {r * v:.1f}")
        ratio = "0 (k2 → 0)" if deg == 0 else ("∞ (k1 → 0)" if deg == 90 else f"{math.tan(th):.3f}")
        print(f"| {ratio} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
