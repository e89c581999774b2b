# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Test meshes with known geodesics, built with numpy: plane, sphere, open cylinder, folded sheet."""
import numpy as np


def grid(nx, ny, size=1.0):
    """A planar square [0, size]^2 in z = 0, (nx+1) x (ny+1) vertices, diagonals alternating."""
    x, y = np.meshgrid(np.linspace(0, size, nx + 1), np.linspace(0, size, ny + 1), indexing="ij")
    V = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    F = []
    for i in range(nx):
        for j in range(ny):
            a, b, c, d = i * (ny + 1) + j, (i + 1) * (ny + 1) + j, (i + 1) * (ny + 1) + j + 1, i * (ny + 1) + j + 1
            F += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    return V, np.array(F, dtype=np.int64)


def icosphere(levels, radius=1.0):
    """An icosahedron subdivided `levels` times, vertices projected on the sphere."""
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    for _ in range(levels):
        midpoint = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                midpoint[key] = len(V) - 1
            return midpoint[key]

        F = [f for a, b, c in F for f in ((a, middle(a, b), middle(c, a)), (b, middle(b, c), middle(a, b)),
                                          (c, middle(c, a), middle(b, c)),
                                          (middle(a, b), middle(b, c), middle(c, a)))]
    return radius * np.array(V), np.array(F, dtype=np.int64)


def cylinder(n_around, n_along, radius=1.0, height=2.0):
    """An open cylinder around the z axis: vertex (i, j) at angle 2 pi i / n_around, height j."""
    angle = 2 * np.pi * np.arange(n_around) / n_around
    z = np.linspace(0, height, n_along + 1)
    V = np.array([(radius * np.cos(a), radius * np.sin(a), h) for h in z for a in angle])
    F = []
    for j in range(n_along):
        for i in range(n_around):
            a, b = j * n_around + i, j * n_around + (i + 1) % n_around
            c, d = b + n_around, a + n_around
            F += [(a, b, c), (a, c, d)]
    return V, np.array(F, dtype=np.int64)


def folded_sheet(n, angle_degrees=90.0):
    """Two unit squares meeting at a sharp edge along the y axis: the plane z = 0 for x <= 0 and,
    for x >= 0, the square turned up by the given angle. Returns V, F and the side (0, 1) of every face."""
    V, F = grid(2 * n, n, size=2.0)
    V[:, 0] -= 1.0
    side = (V[F].mean(axis=1)[:, 0] > 0).astype(np.int64)  # before folding
    a = np.radians(angle_degrees)
    right = V[:, 0] > 0
    x = V[right, 0].copy()
    V[right, 0], V[right, 2] = x * np.cos(a), x * np.sin(a)
    return V, F, side
