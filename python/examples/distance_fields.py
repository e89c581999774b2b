# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Euclidean and isophotic distance fields and a dilation on a CGAL data mesh, drawn with matplotlib.

    python3 distance_fields.py [mesh.off] [output.png]

Default mesh: fandisk from CGAL's data set (CGAL_DATA_DIR or build/cgal_data/data). The isophotic
level sets crowd where the normal turns (at the fandisk's fillets and sharp edges), the Euclidean
ones do not; the isophotic dilation of a face spreads along the features and stops at them.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import isophotic_metric as im


def default_mesh():
    data = os.environ.get("CGAL_DATA_DIR", os.path.join(os.path.dirname(__file__), "../../build/cgal_data/data"))
    return os.path.join(data, "meshes", "fandisk.off")


def draw(ax, V, F, face_colours, title):
    """The mesh with flat shading (light from the viewer's upper left), one colour per face."""
    normals = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    light = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])
    shade = 0.55 + 0.45 * np.abs(normals @ light)
    ax.add_collection3d(Poly3DCollection(V[F], facecolors=face_colours[:, :3] * shade[:, None], edgecolor="none"))
    low, high = V.min(axis=0), V.max(axis=0)
    centre, half = (low + high) / 2, (high - low).max() / 2
    for axis, c in zip("xyz", centre):
        getattr(ax, f"set_{axis}lim")(c - half, c + half)
    ax.view_init(elev=30, azim=35)
    ax.set_axis_off()
    ax.set_title(title, fontsize=10)


def level_set_colours(distance, F, period):
    """A colour ramp with dark stripes every `period`: the level sets of the field."""
    d = distance[F].mean(axis=1)
    colours = plt.get_cmap("viridis")(d / d[np.isfinite(d)].max())
    stripes = np.abs((d / period + 0.5) % 1.0 - 0.5) < 0.08
    colours[stripes, :3] *= 0.25
    return colours


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else default_mesh()
    output = sys.argv[2] if len(sys.argv) > 2 else "distance_fields.png"
    mesh = im.Mesh(path)
    V, F = mesh.vertices, mesh.faces

    # [python distance fields]
    L = im.suggested_weight_length_scale(mesh)       # makes the weights dimensionless
    source = int(np.argmin(np.linalg.norm(V - [0.7, 0.5, 0.15], axis=1)))
    euclidean = im.compute_geodesic_distances(mesh, [source], isophotic_weight=0.0)
    isophotic = im.compute_geodesic_distances(mesh, [source], euclidean_weight=0.5, isophotic_weight=0.5,
                                              weight_length_scale=L)
    seed = int(np.argmin(np.linalg.norm(V[F].mean(axis=1) - V[source], axis=1)))
    dilation = im.dilate_face_selection(mesh, [seed], 0.4 * L, euclidean_weight=0.2, isophotic_weight=0.8,
                                        weight_length_scale=L)
    # [python distance fields]

    period = np.nanmax(euclidean[np.isfinite(euclidean)]) / 20
    dilation_colours = np.tile([0.85, 0.85, 0.85, 1.0], (len(F), 1))
    dilation_colours[dilation] = [0.85, 0.15, 0.1, 1.0]
    figure = plt.figure(figsize=(15, 5.5))
    panels = [(level_set_colours(euclidean, F, period), "Euclidean geodesic distance (w = 1, w' = 0)"),
              (level_set_colours(isophotic, F, np.sqrt(0.5) * period), "isophotic distance (w = w' = 0.5)"),
              (dilation_colours, f"isophotic dilation of one face ({dilation.sum()} faces)")]
    for k, (colours, title) in enumerate(panels):
        draw(figure.add_subplot(1, 3, k + 1, projection="3d"), V, F, colours, title)
    figure.tight_layout()
    figure.savefig(output, dpi=110)
    print(f"{os.path.basename(path)}: {len(V)} vertices, farthest vertex {np.max(euclidean):.4f} (Euclidean), "
          f"{np.max(isophotic):.4f} (isophotic); dilation {dilation.sum()} of {len(F)} faces; wrote {output}")


if __name__ == "__main__":
    main()
