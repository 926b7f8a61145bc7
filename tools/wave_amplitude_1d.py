#!/usr/bin/env python3
"""A 1D model of the step on a plane wave (docs/theory.md §2.4, "Amplitude of a plane wave").

    wave_amplitude_1d.py [CELLS]

Nodes i = 0..N along the wave, stress points at the cell centres, h = 0.75 dx (each sees its two
corners), no hourglass filter. Node 0 is a piston (v = V0), node N free (sigma = 0 after its
projection); both are boundary nodes with the half-step values of step 1b (§2.2) and the adjoint
momentum closure (eq. 5.2). The nodal stress is advanced either with the compact gradient of the
stress points' half-step velocities (half step, eq. 2.3) or with the lumped average of the cells'
gradients of (v^n + v^{n+1})/2 (mean velocity, eq. 2.5). Prints the tension plateau error over
2.75-2.95 L/c after the free-face and piston reflections, and the same window on a front that met no
face (a bar 3 L long, read 2.5 L from the piston), for C in 0.1, 0.25, 0.5 and the limit, with and
without the artificial viscosity (eq. of §2.7). Standard library only.
"""

import math
import sys

RHO, C_P, V0 = 2000.0, 300.0, 0.3


def run(cells, courant, update, alpha=0.0, length_factor=1, probe=0.5):
    dx = 1.0 / cells
    n = cells * length_factor
    modulus, dt = RHO * C_P * C_P, courant * dx / C_P
    v, s = [0.0] * (n + 1), [0.0] * (n + 1)
    v[0] = V0
    mid = round(cells * probe)
    transit = 1.0 / C_P
    first = math.ceil(2.75 * transit / dt - 1e-9)
    last = math.floor(2.95 * transit / dt + 1e-9)
    total = 0.0
    for step in range(1, last + 1):
        # Step 1: the stress points, half a step from the interpolated level n.
        vp = [0.5 * (v[i] + v[i + 1]) + 0.5 * dt * (s[i + 1] - s[i]) / (RHO * dx) for i in range(n)]
        sp = [0.5 * (s[i] + s[i + 1]) + 0.5 * dt * modulus * (v[i + 1] - v[i]) / dx for i in range(n)]
        if alpha > 0.0:
            for i in range(n):
                sp[i] += alpha * RHO * C_P * dx * (v[i + 1] - v[i]) / dx
        # Step 1b: the boundary nodes (collocated gradient); the free face keeps sigma = 0.
        v0_half = V0
        vn_half, sn_half = v[n] + 0.5 * dt * (s[n] - s[n - 1]) / (RHO * dx), 0.0
        # Step 2: momentum (the free node with the adjoint closure, half a cell).
        w = v[:]
        for i in range(1, n):
            w[i] = v[i] + dt * (sp[i] - sp[i - 1]) / (RHO * dx)
        w[n] = v[n] + dt * 2.0 * (sn_half - sp[n - 1]) / (RHO * dx)
        t = s[:]
        if update == "half_step":
            t[0] = s[0] + dt * modulus * (vp[0] - v0_half) / (0.5 * dx)
            for i in range(1, n):
                t[i] = s[i] + dt * modulus * (vp[i] - vp[i - 1]) / dx
        else:
            mean = [0.5 * (a + b) for a, b in zip(v, w)]
            g = [(mean[i + 1] - mean[i]) / dx for i in range(n)]
            t[0] = s[0] + dt * modulus * g[0]
            for i in range(1, n):
                t[i] = s[i] + dt * modulus * 0.5 * (g[i - 1] + g[i])
        t[n] = 0.0
        v, s = w, t
        if step >= first:
            total += s[mid]
    plateau = total / (last - first + 1)
    exact = (1.0 if length_factor == 1 else -1.0) * RHO * C_P * V0
    return plateau / exact - 1.0


def main():
    cells = int(sys.argv[1]) if len(sys.argv) > 1 else 60
    print(f"{cells} cells; errors of the plateau: reflected / no face")
    for alpha in (0.0, 0.25):
        for courant in (0.1, 0.25, 0.5, math.sqrt(1.0 + alpha * alpha) - alpha):
            row = []
            for update in ("half_step", "mean_velocity"):
                reflected = run(cells, courant, update, alpha)
                unreflected = run(cells, courant, update, alpha, length_factor=3, probe=2.5)
                row.append(f"{update} {100 * reflected:+.3f} % / {100 * unreflected:+.3f} %")
            print(f"alpha {alpha:.2f} C {courant:.4f}: " + "   ".join(row))


if __name__ == "__main__":
    main()
