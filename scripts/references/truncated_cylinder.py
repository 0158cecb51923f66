"""Heave added mass and damping of a floating truncated vertical cylinder,
by matched eigenfunction expansions (R. W. Yeung, "Added mass and damping
of a vertical cylinder in finite-depth waters", Appl. Ocean Res. 3, 1981):
the reference `crates/soak-seakeeping/tests/cylinder.rs` holds the panel
method to.

The fluid is split at the cylinder's radius a. Beside it (r > a, water of
depth h) the potential is the outgoing wave H0(k0 r) cosh k0(z + h) plus
evanescent modes K0(k_m r) cos k_m(z + h); under it (r < a, between the
bottom at z = -d and the sea bed) a particular solution that moves with the
bottom plus I0(l_n r) cos l_n(z + h), l_n = n pi / (h - d). Continuity of
the potential under the cylinder and of the radial velocity (zero on its
wall) at r = a, each projected on its region's modes, gives the
coefficients; the force is the pressure integrated over the bottom.

Deep water is approached by a sea bed 80 radii down. The damping is checked
against the energy the outgoing wave carries away (the two agree to the
printed digits), and the results against twice as many terms and half the
depth (see `--check`).

    python3 -m venv venv && venv/bin/pip install numpy scipy
    venv/bin/python scripts/references/truncated_cylinder.py [--check]

prints `(Ka, A22 / (rho pi a^3), B22 / (rho omega pi a^3))` rows, K = omega^2 / g,
for radius = draft = 1.
"""

import sys

import numpy as np
from scipy import special as sp
from scipy.optimize import brentq


def wavenumbers(nu, h, count):
    """k0 tanh(k0 h) = nu, then k_m tan(k_m h) = -nu, m = 1..count."""
    ks = [brentq(lambda k: k * np.tanh(k * h) - nu, 1e-12, nu + 10.0 / h + 10.0)]
    for m in range(1, count + 1):
        lo, hi = (m - 0.5) * np.pi / h + 1e-12, m * np.pi / h - 1e-12
        ks.append(brentq(lambda k: k * np.tan(k * h) + nu, lo, hi))
    return np.array(ks)


def heave(ka, a=1.0, d=1.0, h=80.0, terms=12, rho=1000.0, g=9.81):
    """(A22, B22, omega, B22 from the far field) at K a = ka."""
    nu = ka / a
    b = h - d
    outer, inner = int(terms * h / a) + 20, int(terms * b / a) + 20
    k = wavenumbers(nu, h, outer)
    lam = np.arange(inner + 1) * np.pi / b

    def overlap(m, n):
        # Integral over s = z + h in [0, b] of Z_m(s) cos(lam_n s).
        l, kk = lam[n], k[m]
        if m == 0:
            return (kk * np.sinh(kk * b) * np.cos(l * b) + l * np.cosh(kk * b) * np.sin(l * b)) / (kk**2 + l**2)
        if abs(kk - l) < 1e-12:
            return b / 2 + np.sin(2 * kk * b) / (4 * kk)
        return 0.5 * (np.sin((kk - l) * b) / (kk - l) + np.sin((kk + l) * b) / (kk + l))

    def norm(m):
        kk = k[m]
        if m == 0:
            return h / 2 + np.sinh(2 * kk * h) / (4 * kk)
        return h / 2 + np.sin(2 * kk * h) / (4 * kk)

    # Radial derivatives at r = a over the values there.
    d_outer = np.zeros(outer + 1, complex)
    d_outer[0] = -k[0] * sp.hankel1(1, k[0] * a) / sp.hankel1(0, k[0] * a)
    d_outer[1:] = -k[1:] * sp.k1e(k[1:] * a) / sp.k0e(k[1:] * a)
    d_inner = np.zeros(inner + 1)
    d_inner[1:] = lam[1:] * sp.i1e(lam[1:] * a) / sp.i0e(lam[1:] * a)
    overlaps = np.array([[overlap(m, n) for n in range(inner + 1)] for m in range(outer + 1)])
    norms = np.array([norm(m) for m in range(outer + 1)])

    size = outer + 1 + inner + 1
    matrix = np.zeros((size, size), complex)
    rhs = np.zeros(size, complex)
    # Radial velocity, projected on Z_j over the whole depth.
    for j in range(outer + 1):
        matrix[j, j] = d_outer[j] * norms[j]
        matrix[j, outer + 2:] = -d_inner[1:] * overlaps[j, 1:]
        rhs[j] = -a / (2 * b) * overlaps[j, 0]
    # Potential, projected on cos(lam_i s) under the cylinder; the
    # particular solution is ((z + h)^2 - r^2 / 2) / (2 b).
    for i in range(inner + 1):
        row = outer + 1 + i
        matrix[row, : outer + 1] = overlaps[:, i]
        matrix[row, row] = -(b if i == 0 else b / 2)
        l = lam[i]
        rhs[row] = (b**3 / 3 - a * a / 2 * b) / (2 * b) if i == 0 else np.cos(l * b) / l**2
    x = np.linalg.solve(matrix, rhs)
    coefficients = x[outer + 1 :]
    # The potential integrated over the bottom.
    integral = 2 * np.pi * (b * b * a * a / 2 - a**4 / 8) / (2 * b) + coefficients[0] * np.pi * a * a
    n = np.arange(1, inner + 1)
    integral += np.sum(
        coefficients[1:] * (-1.0) ** n * 2 * np.pi * a * sp.i1e(lam[1:] * a) / (lam[1:] * sp.i0e(lam[1:] * a))
    )
    omega = np.sqrt(g * nu)
    far = 4 * rho * omega * abs(x[0]) ** 2 * norms[0] / abs(sp.hankel1(0, k[0] * a)) ** 2
    return rho * integral.real, omega * rho * integral.imag, omega, far


KAS = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0]

if __name__ == "__main__":
    scale = 1000.0 * np.pi
    for ka in KAS:
        a22, b22, omega, far = heave(ka)
        if "--check" in sys.argv:
            more = heave(ka, terms=24)
            shallower = heave(ka, h=40.0)
            print(
                f"Ka {ka}: B {b22 / (omega * scale):.5f}, far field {far / (omega * scale):.5f}; "
                f"A {a22 / scale:.5f}, twice the terms {more[0] / scale:.5f}, 40 radii deep {shallower[0] / scale:.5f}"
            )
        else:
            print(f"    ({ka}, {a22 / scale:.4f}, {b22 / (omega * scale):.5f}),")
