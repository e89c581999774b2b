#!/usr/bin/python3
# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""CAD part suite with B-rep ground truth, for segmentation tests and benchmarks.

Every part is built with gmsh's OpenCASCADE kernel (Debian package python3-gmsh), meshed with
triangles and written as <out_dir>/<part>.ply (binary little-endian): vertices x y z (double), faces
with vertex_indices, `int brep_face` (the B-rep face the triangle lies on, numbered from 0 per part)
and `uchar surface_type` (0 plane, 1 cylinder, 2 cone, 3 sphere, 4 torus, 5 other / free-form, from
the type of the OpenCASCADE face). <out_dir>/parts.csv lists name, faces, vertices, B-rep faces and
bounding-box diagonal. The output is deterministic (one meshing thread, fixed options).

Usage: generate_cad_parts.py <out_dir> [--parts name,...]
"""
import argparse
import math
import os
import struct
import sys

import gmsh

SURFACE_TYPES = {"Plane": 0, "Cylinder": 1, "Cone": 2, "Sphere": 3, "Torus": 4}
occ = None  # gmsh.model.occ, set in main()


def edges_of(dim_tags):
    """Curve tags bounding the given volumes."""
    faces = gmsh.model.getBoundary(dim_tags, combined=False, oriented=False)
    curves = gmsh.model.getBoundary(faces, combined=False, oriented=False)
    return sorted({abs(t) for _, t in curves})


def curves_where(tags, keep):
    """Curves whose bounding box (xmin, ymin, zmin, xmax, ymax, zmax) satisfies keep(box)."""
    return [c for c in tags if keep(gmsh.model.getBoundingBox(1, c))]


def sync_edges(volumes):
    occ.synchronize()
    return edges_of([(3, v) for v in volumes])


def solid(result):
    """Volume tags of a fillet result or of a boolean's (dim_tags, map) result."""
    dim_tags = result[0] if isinstance(result, tuple) else result
    return [t for d, t in dim_tags if d == 3]


# ---- parts -------------------------------------------------------------------------------------
# Each builder creates one solid in the current model and returns nothing; sizes are in millimetres
# (bounding boxes of 40-120), the mesh size is set per part in PARTS.

def box_fillet(r):
    def build():
        b = occ.addBox(0, 0, 0, 60, 40, 30)
        occ.fillet([b], sync_edges([b]), [r])
    return build


def box_fillet_mixed():
    # vertical edges r = 8, the others r = 3: cylinders of two radii and non-spherical corner blends
    b = occ.addBox(0, 0, 0, 60, 40, 30)
    edges = sync_edges([b])
    vertical = curves_where(edges, lambda bb: bb[5] - bb[2] > 29)
    v = solid(occ.fillet([b], vertical, [8]))
    occ.fillet(v, curves_where(sync_edges(v), lambda bb: abs(bb[2] - bb[5]) < 1e-6), [3])


def top_fillet():
    # only the top edges filleted: four cylinders meeting the planes, rounded at the corners
    b = occ.addBox(0, 0, 0, 70, 50, 25)
    top = curves_where(sync_edges([b]), lambda bb: bb[2] > 24.9)
    occ.fillet([b], top, [6])


def chamfered_block():
    b = occ.addBox(0, 0, 0, 50, 40, 30)
    edges = sync_edges([b])
    top = curves_where(edges, lambda bb: bb[2] > 29.9)
    faces = gmsh.model.getBoundary([(3, b)], combined=False, oriented=False)
    top_face = [t for _, t in faces if gmsh.model.getBoundingBox(2, t)[2] > 29.9]
    occ.chamfer([b], top, top_face * len(top), [5] * len(top))


def chamfered_block_all():
    b = occ.addBox(0, 0, 0, 50, 40, 30)
    edges = sync_edges([b])
    chamfer_faces = []
    for c in edges:
        adjacent = gmsh.model.getAdjacencies(1, c)[0]
        chamfer_faces.append(min(adjacent))
    occ.chamfer([b], edges, chamfer_faces, [4] * len(edges))


def plate_holes():
    p = occ.addBox(0, 0, 0, 100, 60, 10)
    holes = [(occ.addCylinder(x, y, -1, 0, 0, 12, r), 3) for x, y, r in
             [(20, 20, 6), (80, 20, 6), (50, 40, 10), (20, 45, 4), (80, 45, 4)]]
    occ.cut([(3, p)], [(3, h) for h, _ in holes])


def plate_bosses():
    p = occ.addBox(0, 0, 0, 100, 60, 10)
    bosses = [occ.addCylinder(x, y, 9, 0, 0, 16, r) for x, y, r in [(25, 30, 10), (70, 30, 14)]]
    v = solid(occ.fuse([(3, p)], [(3, b) for b in bosses]))
    # fillet the circles where the bosses meet the plate (torus blends)
    base = curves_where(sync_edges(v), lambda bb: abs(bb[2] - 10) < 1e-6 and abs(bb[5] - 10) < 1e-6
                        and bb[3] - bb[0] < 40)
    occ.fillet(v, base, [3])


def boss_on_cylinder():
    # a vertical boss on a horizontal cylinder, filleted: the saddle fillet is a free-form surface
    c = occ.addCylinder(0, 0, 0, 100, 0, 0, 20)
    b = occ.addCylinder(50, 0, 0, 0, 0, 35, 10)
    v = solid(occ.fuse([(3, c)], [(3, b)]))
    edges = sync_edges(v)
    saddle = curves_where(edges, lambda bb: bb[5] > 15 and bb[2] > 5 and bb[5] < 21)
    occ.fillet(v, saddle, [4])


def knob():
    # a shaft, a larger head, a torus blend between them and a rounded top rim
    shaft = occ.addCylinder(0, 0, 0, 0, 0, 30, 8)
    head = occ.addCylinder(0, 0, 30, 0, 0, 15, 20)
    v = solid(occ.fuse([(3, shaft)], [(3, head)]))
    edges = sync_edges(v)
    neck = curves_where(edges, lambda bb: abs(bb[2] - 30) < 1e-6 and abs(bb[5] - 30) < 1e-6 and bb[3] - bb[0] < 17)
    v = solid(occ.fillet(v, neck, [5]))
    rim = curves_where(sync_edges(v), lambda bb: abs(bb[2] - 45) < 1e-6 and abs(bb[5] - 45) < 1e-6)
    occ.fillet(v, rim, [4])


def pipe_elbow(bend_radius=30, tube_radius=8, length=40):
    def build():
        R, r = bend_radius, tube_radius
        t = occ.addTorus(0, 0, 0, R, r, angle=math.pi / 2)
        a = occ.addCylinder(R, -length, 0, 0, length, 0, r)
        b = occ.addCylinder(0, R, 0, -length, 0, 0, r)
        occ.fuse([(3, t)], [(3, a), (3, b)])
    return build


def pipe_straight():
    c = occ.addCylinder(0, 0, 0, 0, 0, 100, 10)
    h = occ.addCylinder(0, 0, -1, 0, 0, 102, 7)
    occ.cut([(3, c)], [(3, h)])


def tube_chamfered():
    c = occ.addCylinder(0, 0, 0, 0, 0, 60, 20)
    h = occ.addCylinder(0, 0, -1, 0, 0, 62, 12)
    v = solid(occ.cut([(3, c)], [(3, h)]))
    edges = sync_edges(v)
    outer = curves_where(edges, lambda bb: bb[3] - bb[0] > 39)
    faces = gmsh.model.getBoundary([(3, t) for t in v], combined=False, oriented=False)
    caps = [t for _, t in faces if gmsh.model.getType(2, t) == "Plane"]
    chamfer_faces = [next(f for f in caps if c in [abs(e) for _, e in gmsh.model.getBoundary([(2, f)])])
                     for c in outer]
    occ.chamfer(v, outer, chamfer_faces, [3] * len(outer))


def cone_frustum():
    occ.addCone(0, 0, 0, 0, 0, 50, 25, 10)


def pencil():
    c = occ.addCylinder(0, 0, 0, 0, 0, 70, 8)
    k = occ.addCone(0, 0, 70, 0, 0, 20, 8, 0.5)
    occ.fuse([(3, c)], [(3, k)])


def cone_on_block():
    b = occ.addBox(-30, -30, -15, 60, 60, 15)
    k = occ.addCone(0, 0, 0, 0, 0, 30, 20, 8)
    v = solid(occ.fuse([(3, b)], [(3, k)]))
    base = curves_where(sync_edges(v), lambda bb: abs(bb[2]) < 1e-6 and abs(bb[5]) < 1e-6 and bb[3] - bb[0] < 41)
    occ.fillet(v, base, [3])


def capsule():
    c = occ.addCylinder(0, 0, 0, 0, 0, 60, 12)
    s1 = occ.addSphere(0, 0, 0, 12)
    s2 = occ.addSphere(0, 0, 60, 12)
    occ.fuse([(3, c)], [(3, s1), (3, s2)])


def dome_on_plate():
    p = occ.addBox(-40, -40, -10, 80, 80, 10)
    s = occ.addSphere(0, 0, -10, 28)
    cut = occ.addBox(-50, -50, -60, 100, 100, 50)
    d = solid(occ.cut([(3, s)], [(3, cut)]))
    v = solid(occ.fuse([(3, p)], [(3, t) for t in d]))
    rim = curves_where(sync_edges(v), lambda bb: abs(bb[2]) < 1e-6 and abs(bb[5]) < 1e-6 and bb[3] - bb[0] < 60)
    occ.fillet(v, rim, [4])


def revolved_profile():
    # a turned part: profile of lines (planes, cylinders, cones) and an arc (torus), revolved
    pts = [(0, 0), (25, 0), (25, 10), (18, 16), (18, 30), (12, 30), (12, 45), (0, 45)]
    tags = [occ.addPoint(x, 0, z) for x, z in pts]
    lines = [occ.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
    s = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    v = solid(occ.revolve([(2, s)], 0, 0, 0, 0, 0, 1, 2 * math.pi))
    step = curves_where(sync_edges(v), lambda bb: abs(bb[2] - 30) < 1e-6 and abs(bb[5] - 30) < 1e-6
                        and bb[3] - bb[0] > 30)
    occ.fillet(v, step, [3])


def vase():
    # a revolved spline profile: free-form surface of revolution between two flat ends
    pts = [(15, 0), (22, 15), (14, 35), (10, 50), (16, 65)]
    tags = [occ.addPoint(x, 0, z) for x, z in pts]
    spline = occ.addSpline(tags)
    top = occ.addPoint(0, 0, 65)
    bottom = occ.addPoint(0, 0, 0)
    lines = [spline, occ.addLine(tags[-1], top), occ.addLine(top, bottom), occ.addLine(bottom, tags[0])]
    s = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    occ.revolve([(2, s)], 0, 0, 0, 0, 0, 1, 2 * math.pi)


def l_bracket():
    # an extruded L profile, its inner edge filleted, a hole through each leg
    pts = [(0, 0), (80, 0), (80, 10), (10, 10), (10, 60), (0, 60)]
    tags = [occ.addPoint(x, 0, z) for x, z in pts]
    lines = [occ.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
    s = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    v = solid(occ.extrude([(2, s)], 0, 40, 0))
    inner = curves_where(sync_edges(v), lambda bb: abs(bb[0] - 10) < 1e-6 and abs(bb[2] - 10) < 1e-6
                         and abs(bb[3] - 10) < 1e-6 and abs(bb[5] - 10) < 1e-6)
    v = solid(occ.fillet(v, inner, [6]))
    holes = [occ.addCylinder(55, 20, -1, 0, 0, 12, 6), occ.addCylinder(-1, 20, 40, 12, 0, 0, 6)]
    occ.cut([(3, t) for t in v], [(3, h) for h in holes])


def slotted_block():
    b = occ.addBox(0, 0, 0, 80, 40, 20)
    slot = occ.addBox(20, 14, 10, 40, 12, 11)
    e1 = occ.addCylinder(20, 20, 10, 0, 0, 11, 6)
    e2 = occ.addCylinder(60, 20, 10, 0, 0, 11, 6)
    tool = occ.fuse([(3, slot)], [(3, e1), (3, e2)])
    v = solid(occ.cut([(3, b)], tool[0]))
    outer = curves_where(sync_edges(v), lambda bb: (bb[5] - bb[2] > 19.9))
    occ.fillet(v, outer, [5])


def flange():
    disc = occ.addCylinder(0, 0, 0, 0, 0, 10, 40)
    hub = occ.addCylinder(0, 0, 10, 0, 0, 25, 18)
    v = solid(occ.fuse([(3, disc)], [(3, hub)]))
    holes = [occ.addCylinder(30 * math.cos(a), 30 * math.sin(a), -1, 0, 0, 12, 4)
             for a in [k * math.pi / 3 for k in range(6)]]
    bore = occ.addCylinder(0, 0, -1, 0, 0, 40, 10)
    v = solid(occ.cut([(3, t) for t in v], [(3, h) for h in holes + [bore]]))
    neck = curves_where(sync_edges(v), lambda bb: abs(bb[2] - 10) < 1e-6 and abs(bb[5] - 10) < 1e-6
                        and 30 < bb[3] - bb[0] < 40)
    occ.fillet(v, neck, [4])


def sphere_cut():
    s = occ.addSphere(0, 0, 0, 30)
    b = occ.addBox(-40, -40, 12, 80, 80, 40)
    c = occ.addCylinder(0, 0, -40, 0, 0, 80, 8)
    occ.cut([(3, s)], [(3, b), (3, c)])


def torus_ring():
    t = occ.addTorus(0, 0, 0, 30, 8)
    b = occ.addBox(-50, -50, 4, 100, 100, 20)
    occ.cut([(3, t)], [(3, b)])


def block_with_pocket():
    b = occ.addBox(0, 0, 0, 80, 60, 25)
    p = occ.addBox(15, 15, 10, 50, 30, 20)
    v = solid(occ.cut([(3, b)], [(3, p)]))
    pocket = curves_where(sync_edges(v), lambda bb: bb[0] > 14.9 and bb[3] < 65.1 and bb[1] > 14.9
                          and bb[4] < 45.1 and bb[5] < 25.1)
    occ.fillet(v, pocket, [4])


# name -> (builder, mesh size, curvature resolution: elements per 2 pi)
PARTS = {
    "box_fillet_r2": (box_fillet(2), 2.0, 16),
    "box_fillet_r4": (box_fillet(4), 2.0, 16),
    "box_fillet_r8": (box_fillet(8), 2.5, 16),
    "box_fillet_r4_fine": (box_fillet(4), 1.0, 24),
    "box_fillet_mixed": (box_fillet_mixed, 2.0, 16),
    "top_fillet": (top_fillet, 2.5, 16),
    "chamfered_block": (chamfered_block, 2.5, 16),
    "chamfered_block_all": (chamfered_block_all, 2.0, 16),
    "plate_holes": (plate_holes, 2.5, 16),
    "plate_bosses": (plate_bosses, 2.5, 16),
    "boss_on_cylinder": (boss_on_cylinder, 2.5, 16),
    "knob": (knob, 2.0, 16),
    "pipe_elbow": (pipe_elbow(), 2.5, 16),
    "pipe_elbow_fine": (pipe_elbow(), 1.2, 24),
    "pipe_elbow_tight": (pipe_elbow(16, 8, 30), 2.0, 16),
    "pipe_straight": (pipe_straight, 2.5, 16),
    "tube_chamfered": (tube_chamfered, 2.0, 16),
    "cone_frustum": (cone_frustum, 2.0, 16),
    "pencil": (pencil, 2.0, 16),
    "cone_on_block": (cone_on_block, 2.5, 16),
    "capsule": (capsule, 2.0, 16),
    "dome_on_plate": (dome_on_plate, 2.5, 16),
    "revolved_profile": (revolved_profile, 2.0, 16),
    "vase": (vase, 2.0, 16),
    "l_bracket": (l_bracket, 2.5, 16),
    "slotted_block": (slotted_block, 2.0, 16),
    "flange": (flange, 2.5, 16),
    "sphere_cut": (sphere_cut, 2.0, 16),
    "torus_ring": (torus_ring, 2.0, 16),
    "block_with_pocket": (block_with_pocket, 2.5, 16),
    "box_fillet_r4_coarse": (box_fillet(4), 4.0, 12),
    "flange_fine": (flange, 0.65, 24),
}


# ---- meshing and output ------------------------------------------------------------------------

def mesh_part(name):
    builder, size, per_circle = PARTS[name]
    gmsh.clear()
    gmsh.model.add(name)
    builder()
    occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", size / 4)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", per_circle)
    gmsh.model.mesh.generate(2)

    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    position = {int(t): (coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]) for i, t in enumerate(node_tags)}
    triangles, brep, types = [], [], []
    # the faces of the solid (a revolved or extruded profile stays in the model beside the solid)
    solid_faces = sorted({abs(t) for _, t in gmsh.model.getBoundary(gmsh.model.getEntities(3), combined=False,
                                                                    oriented=False)})
    for face_id, surface in enumerate(solid_faces):
        surface_type = SURFACE_TYPES.get(gmsh.model.getType(2, surface), 5)
        element_types, _, element_nodes = gmsh.model.mesh.getElements(2, surface)
        for et, nodes in zip(element_types, element_nodes):
            if et != 2:  # 3-node triangles only
                raise RuntimeError(f"{name}: unexpected element type {et}")
            for k in range(0, len(nodes), 3):
                triangles.append([int(nodes[k]), int(nodes[k + 1]), int(nodes[k + 2])])
                brep.append(face_id)
                types.append(surface_type)
    # weld coincident nodes (a profile revolved about an axis it touches leaves copies on the axis),
    # drop the triangles this collapses, number vertices in order of first use
    scale = 1e-7 * max(1.0, max(abs(c) for c in coords))
    welded = {t: tuple(round(c / scale) for c in p) for t, p in position.items()}
    index, vertices, kept = {}, [], []
    for tri, b, s in zip(triangles, brep, types):
        keys = [welded[t] for t in tri]
        if len(set(keys)) < 3:
            continue
        for j, (t, key) in enumerate(zip(tri, keys)):
            if key not in index:
                index[key] = len(vertices)
                vertices.append(position[t])
            tri[j] = index[key]
        kept.append((tri, b, s))
    # B-rep faces numbered from 0 in order of their surface tags, skipping faces without triangles
    # (a degenerate face of revolution on the axis)
    face_number = {b: i for i, b in enumerate(sorted({b for _, b, _ in kept}))}
    triangles = [t for t, _, _ in kept]
    brep = [face_number[b] for _, b, _ in kept]
    types = [s for _, _, s in kept]
    n_faces = len(face_number)
    orient_outward(vertices, triangles)
    return vertices, triangles, brep, types, n_faces


def orient_outward(vertices, triangles):
    """Consistent orientation across edges (breadth-first), then outward (positive volume)."""
    edge_faces = {}
    for f, (a, b, c) in enumerate(triangles):
        for u, v in ((a, b), (b, c), (c, a)):
            edge_faces.setdefault((min(u, v), max(u, v)), []).append(f)
    done = [False] * len(triangles)
    for start in range(len(triangles)):
        if done[start]:
            continue
        done[start] = True
        component, queue = [start], [start]
        while queue:
            f = queue.pop()
            a, b, c = triangles[f]
            for u, v in ((a, b), (b, c), (c, a)):
                for g in edge_faces[(min(u, v), max(u, v))]:
                    if g == f or done[g]:
                        continue
                    # g must traverse the shared edge as v -> u
                    ga, gb, gc = triangles[g]
                    if (u, v) in ((ga, gb), (gb, gc), (gc, ga)):
                        triangles[g] = [ga, gc, gb]
                    done[g] = True
                    component.append(g)
                    queue.append(g)
        volume = 0.0
        for f in component:
            p, q, r = (vertices[i] for i in triangles[f])
            volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0])
                       + p[2] * (q[0] * r[1] - q[1] * r[0]))
        if volume < 0:
            for f in component:
                a, b, c = triangles[f]
                triangles[f] = [a, c, b]


def write_ply(path, vertices, triangles, brep, types):
    with open(path, "wb") as out:
        out.write((
            "ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(vertices)}\nproperty double x\nproperty double y\nproperty double z\n"
            f"element face {len(triangles)}\nproperty list uchar int vertex_indices\n"
            "property int brep_face\nproperty uchar surface_type\nend_header\n").encode("ascii"))
        out.write(b"".join(struct.pack("<3d", *p) for p in vertices))
        out.write(b"".join(struct.pack("<B3iiB", 3, *t, b, s) for t, b, s in zip(triangles, brep, types)))


def bbox_diagonal(vertices):
    lo = [min(p[k] for p in vertices) for k in range(3)]
    hi = [max(p[k] for p in vertices) for k in range(3)]
    return math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))


def main():
    global occ
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir")
    parser.add_argument("--parts", help="comma-separated names (default: all): " + ",".join(PARTS))
    args = parser.parse_args()
    names = args.parts.split(",") if args.parts else list(PARTS)
    unknown = [n for n in names if n not in PARTS]
    if unknown:
        sys.exit(f"unknown part(s): {', '.join(unknown)}; known: {', '.join(PARTS)}")
    os.makedirs(args.out_dir, exist_ok=True)

    gmsh.initialize(["generate_cad_parts", "-nt", "1"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.RandomSeed", 1)
    occ = gmsh.model.occ
    rows = []
    for name in names:
        vertices, triangles, brep, types, n_faces = mesh_part(name)
        write_ply(os.path.join(args.out_dir, name + ".ply"), vertices, triangles, brep, types)
        rows.append(f"{name},{len(triangles)},{len(vertices)},{n_faces},{bbox_diagonal(vertices):.6g}")
        print(rows[-1])
    gmsh.finalize()
    with open(os.path.join(args.out_dir, "parts.csv"), "w") as csv:
        csv.write("name,faces,vertices,brep_faces,bbox_diagonal\n" + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
