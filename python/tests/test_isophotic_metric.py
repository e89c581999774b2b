# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of the Python module isophotic_metric: closed forms (plane, sphere, cylinder), equality
with the C++ API on a CGAL data mesh, numpy dtypes and shapes, errors, memory, GIL and Ctrl-C."""
import os
import signal
import subprocess
import threading
import time
import tracemalloc

import numpy as np
import pytest

import isophotic_metric as im
from meshes import cylinder, folded_sheet, grid, icosphere

DATA = os.environ.get("IM_CGAL_DATA_DIR", "")
FANDISK = os.path.join(DATA, "meshes", "fandisk.off")


@pytest.fixture(scope="module")
def plane():
    return im.Mesh(*grid(20, 20))


@pytest.fixture(scope="module")
def fandisk():
    if not os.path.exists(FANDISK):
        pytest.skip("CGAL data set not found (IM_CGAL_DATA_DIR)")
    return im.Mesh(FANDISK)


# ------------------------------------------------------------------ closed forms

def test_plane_distance_is_sqrt_w_times_the_straight_line(plane):
    V = plane.vertices
    source = 220  # the centre (10, 10) of the 21 x 21 grid
    for w, w_prime in [(1.0, 0.0), (0.3, 2.0)]:
        d = im.compute_geodesic_distances(plane, [source], euclidean_weight=w, isophotic_weight=w_prime,
                                          weight_length_scale=1.0)
        exact = np.sqrt(w) * np.linalg.norm(V - V[source], axis=1)
        np.testing.assert_allclose(d, exact, rtol=1e-12, atol=1e-14)


def test_sphere_is_a_scaled_copy_of_the_euclidean_one():
    R, w, w_prime, L = 2.0, 0.4, 1.5, 3.0
    sphere = im.Mesh(*icosphere(3, R))
    V = sphere.vertices
    d_euclidean = im.compute_geodesic_distances(sphere, [0], isophotic_weight=0.0)
    d = im.compute_geodesic_distances(sphere, [0], euclidean_weight=w, isophotic_weight=w_prime,
                                      weight_length_scale=L)
    # The lift of a sphere, X = (sqrt(w) p, sqrt(w') L p / R), is the sphere scaled by this factor.
    scale = np.sqrt(w + w_prime * L * L / (R * R))
    np.testing.assert_allclose(d, scale * d_euclidean, rtol=1e-11, atol=1e-13)
    # d = sqrt(w + w'/R^2) R theta up to the polyhedral approximation (shorter than the sphere).
    theta = np.arccos(np.clip(V @ V[0] / (R * R), -1, 1))
    far = theta > 0.3
    ratio = d[far] / (scale * R * theta[far])
    assert ratio.max() <= 1.0 and ratio.min() > 0.985


def test_cylinder_unrolls_to_a_flat_strip():
    n_around, n_along, R, H = 48, 24, 1.0, 2.0
    V, F = cylinder(n_around, n_along, R, H)
    mesh = im.Mesh(V, F)
    normals = V * np.array([1.0, 1.0, 0.0]) / R
    w, w_prime, L = 0.5, 2.0, 1.0
    source = 12 * n_around  # angle 0, half height
    d = im.compute_geodesic_distances(mesh, [source], euclidean_weight=w, isophotic_weight=w_prime,
                                      weight_length_scale=L, normals=normals)
    c = w + w_prime * L * L / (R * R)
    steps = np.abs(np.arange(len(V)) % n_around)
    steps = np.minimum(steps, n_around - steps)
    t = V[:, 2] - V[source, 2]
    # The polyhedral cylinder is developable; its lift is a polyhedral cylinder of radius sqrt(c) R.
    chord = 2 * R * np.sin(np.pi / n_around)
    np.testing.assert_allclose(d, np.sqrt(c * (steps * chord) ** 2 + w * t * t), rtol=1e-11, atol=1e-13)
    # The continuous closed form d = sqrt((w + w'/R^2) s^2 + w t^2), s the arc length around.
    s = R * 2 * np.pi * steps / n_around
    np.testing.assert_allclose(d, np.sqrt(c * s * s + w * t * t), rtol=2e-3)


def test_point_queries_and_paths_on_the_plane(plane):
    V, F = plane.vertices, plane.faces
    solver = im.Geodesic_solver(plane, isophotic_weight=0.0)
    assert solver.add_source(0) == 0
    solver.propagate()
    rng = np.random.default_rng(1)
    faces = rng.integers(0, plane.number_of_faces, 50)
    b = rng.random((50, 3))
    b /= b.sum(axis=1, keepdims=True)
    points = np.einsum("kc,kcx->kx", b, V[F[faces]])
    np.testing.assert_allclose(solver.distance_at(faces, b), np.linalg.norm(points - V[0], axis=1), rtol=1e-12)
    for f, bary, p in zip(faces[:5], b[:5], points[:5]):
        path = solver.trace_path_points(f, bary)
        np.testing.assert_allclose(path[0], p, atol=1e-14)
        np.testing.assert_allclose(path[-1], V[0], atol=1e-14)
        # on a plane the path is the straight segment: every point lies on it
        direction = (p - V[0]) / np.linalg.norm(p - V[0])
        offsets = path - V[0]
        np.testing.assert_allclose(offsets - np.outer(offsets @ direction, direction), 0, atol=1e-12)
        path_faces, path_bary = solver.trace_path(f, bary)
        assert path_faces.dtype == np.int64 and path_bary.shape == (len(path_faces), 3)
        assert im.polyline_isophotic_length(plane, path_faces, path_bary, isophotic_weight=0.0) == \
            pytest.approx(solver.distance_at(f, bary), rel=1e-12)


def test_sources_bound_and_labels(plane):
    V = plane.vertices
    solver = im.Geodesic_solver(plane, euclidean_weight=4.0, isophotic_weight=0.0)
    np.testing.assert_array_equal(solver.add_sources([0, 440]), [0, 1])
    solver.propagate(max_distance=1.0)
    d = solver.distances()
    exact = 2.0 * np.minimum(np.linalg.norm(V - V[0], axis=1), np.linalg.norm(V - V[440], axis=1))
    inside = exact <= 1.0 - 1e-9
    np.testing.assert_allclose(d[inside], exact[inside], rtol=1e-12, atol=1e-14)
    assert np.all(np.isinf(d[exact > 1.0 + 1e-9]))
    labels = solver.nearest_sources()
    nearer_first = np.linalg.norm(V - V[0], axis=1) < np.linalg.norm(V - V[440], axis=1) - 1e-9
    assert np.all(labels[inside & nearer_first] == 0) and np.all(labels[inside & ~nearer_first & (exact > 0)] >= 0)
    assert np.all(labels[exact > 1.0 + 1e-9] == -1)
    # a larger bound continues the same propagation
    solver.propagate()
    np.testing.assert_allclose(solver.distances(), exact, rtol=1e-12, atol=1e-14)
    # region and point sources
    solver.clear_sources()
    region = np.zeros(plane.number_of_faces, bool)
    region[:2] = True
    assert solver.add_source_region(region) == 0
    assert solver.add_source_point(100, [0.2, 0.3, 0.5]) == 1
    solver.propagate()
    assert solver.distances()[0] == 0.0 and solver.number_of_sources == 2


def test_neighbourhood_and_dilation_on_the_plane_follow_triangle_distances(plane):
    V, F = plane.vertices, plane.faces
    r = 0.17

    def segment_distance(p, a, b):
        t = np.clip(np.dot(p - a, b - a) / np.dot(b - a, b - a), 0, 1)
        return np.linalg.norm(p - (a + t * (b - a)))

    def triangle_distance(s, t):  # planar, disjoint or touching triangles
        return min(min(segment_distance(p, q[i], q[(i + 1) % 3]) for p in P for i in range(3))
                   for P, q in ((s, t), (t, s)))

    seed = 400
    expected = np.array([triangle_distance(V[F[seed]], V[F[f]]) <= r for f in range(len(F))])
    dilated = im.dilate_face_selection(plane, [seed], r, isophotic_weight=0.0)
    assert dilated.dtype == np.bool_ and dilated.shape == (len(F),)
    np.testing.assert_array_equal(dilated, expected)
    faces, distance, fraction = im.geodesic_neighborhood(plane, seed, r, isophotic_weight=0.0)
    np.testing.assert_array_equal(np.sort(faces), np.flatnonzero(expected))
    assert np.all(distance <= r) and np.all(fraction == -1)
    # erosion is the complement of the dilation of the complement
    selection = np.linalg.norm(V[F].mean(axis=1) - 0.5, axis=1) < 0.3
    eroded = im.erode_face_selection(plane, selection, 0.05, isophotic_weight=0.0)
    np.testing.assert_array_equal(eroded, ~im.dilate_face_selection(plane, ~selection, 0.05, isophotic_weight=0.0))
    closed = im.close_face_selection(plane, selection, 0.05, isophotic_weight=0.0)
    opened = im.open_face_selection(plane, selection, 0.05, isophotic_weight=0.0)
    assert np.all(closed >= selection) and np.all(opened <= selection)


def test_vertex_neighbourhoods_and_grey_level_dilation_on_the_plane(plane):
    V = plane.vertices
    r = 0.12
    offsets, vertices, distances = im.all_vertex_neighborhoods(plane, r, isophotic_weight=0.0)
    assert offsets.shape == (len(V) + 1,) and offsets[-1] == len(vertices)
    for i in (0, 220, 300):
        near = vertices[offsets[i]:offsets[i + 1]]
        exact = np.linalg.norm(V - V[i], axis=1)
        np.testing.assert_array_equal(np.sort(near), np.flatnonzero(exact <= r))
        np.testing.assert_allclose(distances[offsets[i]:offsets[i + 1]], exact[near], rtol=1e-12, atol=1e-15)
    spike = np.zeros(len(V))
    spike[220] = 1.0
    grey = im.Grey_level_morphology(plane, r, isophotic_weight=0.0)
    np.testing.assert_array_equal(grey.dilate(spike), (np.linalg.norm(V - V[220], axis=1) <= r).astype(float))
    np.testing.assert_array_equal(grey.open(spike), np.zeros(len(V)))
    cone = im.Grey_level_morphology(plane, r, isophotic_weight=0.0, structuring_function=lambda d: -d)
    np.testing.assert_allclose(cone.dilate(spike), np.maximum(0, 1 - np.linalg.norm(V - V[220], axis=1)) *
                               (np.linalg.norm(V - V[220], axis=1) <= r), atol=1e-12)


def test_labels_grow_to_the_nearer_seed(plane):
    V, F = plane.vertices, plane.faces
    labels = np.full(len(F), -1)
    labels[0], labels[len(F) - 1] = 3, 7
    grown = im.dilate_face_labels(plane, labels, 2.0, isophotic_weight=0.0)
    assert labels[1] == -1  # the input is not modified
    c = V[F].mean(axis=1)
    to_first, to_last = np.linalg.norm(c - c[0], axis=1), np.linalg.norm(c - c[-1], axis=1)
    clear = np.abs(to_first - to_last) > 0.1
    np.testing.assert_array_equal(grown[clear], np.where(to_first < to_last, 3, 7)[clear])
    closed = im.series_close_face_labels(plane, grown, [0.01, 0.02], isophotic_weight=0.0)
    assert closed.shape == (len(F),) and closed.dtype == np.int64


def test_region_growing_and_segmentation_stop_at_a_sharp_edge():
    V, F, side = folded_sheet(8)
    mesh = im.Mesh(V, F)
    metric = dict(euclidean_weight=0.2, isophotic_weight=0.8, weight_length_scale=2.0)
    region = im.grow_region(mesh, [0], 3.0, **metric)
    # the faces touching the crease see its averaged vertex normals: the first row across may join
    on_crease = np.all(np.abs(V[:, [0, 2]]) < 1e-12, axis=1)
    first_row = on_crease[F].any(axis=1) & (side != side[0])
    assert np.all(region[side == side[0]]) and not np.any(region[(side != side[0]) & ~first_row])
    patches = im.segment_by_region_growing(mesh, 0.5, **metric)
    # away from the rows along the crease (whose lift smears the jump of the normal) the patches
    # are the two sides
    crease_rows = on_crease[F].any(axis=1)
    away = patches[~crease_rows]
    assert len(np.unique(away)) == 2
    np.testing.assert_array_equal(away == patches[0], side[~crease_rows] == side[0])
    voronoi = im.partition_by_nearest_seed(mesh, [[0], [len(F) - 1]], **metric)
    np.testing.assert_array_equal(voronoi, np.where(side == side[0], 0, 1))


def test_a_metric_mesh_serves_every_call_with_the_same_results(fandisk):
    L = im.suggested_weight_length_scale(fandisk)
    metric = dict(euclidean_weight=0.5, isophotic_weight=0.5, weight_length_scale=L)
    prepared = im.Metric_mesh(fandisk, **metric)
    assert prepared.number_of_faces == fandisk.number_of_faces
    np.testing.assert_array_equal(im.compute_geodesic_distances(prepared, [5]),
                                  im.compute_geodesic_distances(fandisk, [5], **metric))
    np.testing.assert_array_equal(im.dilate_face_selection(prepared, [7], 0.05 * L),
                                  im.dilate_face_selection(fandisk, [7], 0.05 * L, **metric))
    solver = im.Geodesic_solver(prepared)
    solver.add_source(5)
    solver.propagate()
    np.testing.assert_array_equal(solver.distances(), im.compute_geodesic_distances(prepared, [5]))
    with pytest.raises(ValueError, match="a Metric_mesh has its metric"):
        im.compute_geodesic_distances(prepared, [5], isophotic_weight=0.0)


def test_windows_kept_as_links_give_the_answers_of_windows_kept_in_full(fandisk):
    # full_window_every=1 keeps every window in full: the reference the rebuilt windows must equal
    rng = np.random.default_rng(3)
    faces = rng.integers(0, fandisk.number_of_faces, 200)
    bary = rng.dirichlet(np.ones(3), 200)
    answers = []
    for k in (1, 16, 255):
        solver = im.Geodesic_solver(fandisk, euclidean_weight=0.5, isophotic_weight=0.5, full_window_every=k)
        solver.add_source(5)
        solver.propagate()
        answers.append((solver.distance_at(faces, bary), solver.trace_path_points(int(faces[0]), bary[0])))
    for values, path in answers[1:]:
        np.testing.assert_array_equal(values, answers[0][0])
        np.testing.assert_array_equal(path, answers[0][1])
    assert np.all(np.isfinite(answers[0][0]))
    for bad in (0, 256):
        with pytest.raises(im.InvalidParameterError, match="full_window_every"):
            im.Geodesic_solver(fandisk, full_window_every=bad)


# ------------------------------------------------------------------ the same results as C++

def test_equal_to_the_cpp_api_on_fandisk(fandisk, tmp_path):
    program = os.environ.get("IM_CPP_REFERENCE")
    if not program:
        pytest.skip("IM_CPP_REFERENCE not set (run through ctest)")
    subprocess.run([program, FANDISK, str(tmp_path)], check=True)

    def read(name, dtype):
        return np.fromfile(tmp_path / name, dtype=dtype)

    L = im.suggested_weight_length_scale(fandisk)
    metric = dict(euclidean_weight=0.5, isophotic_weight=0.5, weight_length_scale=L)
    n, m = fandisk.number_of_vertices, fandisk.number_of_faces
    np.testing.assert_array_equal(im.compute_lifted_embedding(fandisk, **metric), read("lift.f64", "<f8").reshape(n, 6))
    # The two programs inline and contract floating-point operations differently: distances agree
    # to rounding (the engine's own agreement with exact methods is 1e-14).
    np.testing.assert_allclose(im.compute_geodesic_distances(fandisk, [0], isophotic_weight=0.0),
                               read("euclidean.f64", "<f8"), rtol=1e-14, atol=0)
    np.testing.assert_allclose(im.compute_geodesic_distances(fandisk, [0], **metric), read("isophotic.f64", "<f8"),
                               rtol=1e-14, atol=0)
    np.testing.assert_array_equal(im.dilate_face_selection(fandisk, [0], 0.1 * L, **metric),
                                  read("dilation.u8", np.uint8).astype(bool))
    np.testing.assert_array_equal(im.segment_by_region_growing(fandisk, 0.05 * L, **metric), read("patches.i64", "<i8"))
    assert m == len(read("patches.i64", "<i8"))
    h = im.estimate_mesh_noise(fandisk)[0]
    np.testing.assert_array_equal(im.estimate_vertex_normals(fandisk, 2 * h), read("robust_normals.f64", "<f8").reshape(n, 3))


# ------------------------------------------------------------------ scans: robust normals

def test_robust_normals_of_a_noisy_plane():
    # A planar 30 x 30 grid of unit squares with noise of 0.2 edges along its normal. In the plane the
    # normals are constant and the isophotic distance is sqrt(w) times the straight one (the noise
    # lengthens the surface by a few per cent): raw normals make it over twice that, robust ones
    # bring it back close.
    V, F = grid(30, 30, size=30.0)
    V[:, 2] = np.random.default_rng(3).normal(0.0, 0.2, len(V))
    mesh = im.Mesh(V, F)
    h, noise = im.estimate_mesh_noise(mesh)
    E = mesh.edges
    assert h == pytest.approx(np.linalg.norm(V[E[:, 0]] - V[E[:, 1]], axis=1).mean(), rel=1e-12)
    assert noise == pytest.approx(0.2, rel=0.15)
    s = im.suggested_normal_smoothing_scale(mesh)
    assert s == pytest.approx(2 * h)
    normals = im.estimate_vertex_normals(mesh, s)
    assert normals.shape == (len(V), 3) and normals.dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12)
    angles = np.degrees(np.arccos(np.abs(normals[:, 2])))
    assert np.median(angles) < 2.0
    far = 30 * 31 + 30
    metric = dict(euclidean_weight=0.5, isophotic_weight=0.5)
    plane = np.sqrt(0.5) * np.hypot(30.0, 30.0)
    raw = im.compute_geodesic_distances(mesh, [0], **metric)[far]
    robust = im.compute_geodesic_distances(mesh, [0], normals=normals, **metric)[far]
    assert raw > 2 * plane
    assert plane < robust < 1.25 * plane
    prepared = im.Metric_mesh(mesh, normals=normals, **metric)
    assert im.compute_geodesic_distances(prepared, [0])[far] == robust


def test_robust_normals_keep_a_clean_mesh_and_check_the_scale(fandisk):
    assert im.suggested_normal_smoothing_scale(fandisk) == 0.0  # no noise found: the exact normals
    for scale in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(im.InvalidParameterError, match="normal smoothing scale"):
            im.estimate_vertex_normals(fandisk, scale)


# ------------------------------------------------------------------ arrays, dtypes and errors

def test_dtypes_shapes_and_views(plane):
    V, F = grid(4, 4)
    mesh = im.Mesh(V.astype(np.float32), F.astype(np.int32))  # converted on the way in
    np.testing.assert_array_equal(mesh.vertices, V.astype(np.float32).astype(float))
    np.testing.assert_array_equal(mesh.faces, F)
    assert mesh.vertices.dtype == np.float64 and not mesh.vertices.flags.writeable
    assert mesh.edges.shape == (mesh.edges.shape[0], 2)
    lift = im.compute_lifted_embedding(plane, isophotic_weight=0.5, weight_length_scale=1.0)
    assert lift.shape == (plane.number_of_vertices, 6) and lift.dtype == np.float64
    np.testing.assert_allclose(lift[:, :3], plane.vertices)
    np.testing.assert_allclose(lift[:, 3:], np.tile([0, 0, np.sqrt(0.5)], (len(lift), 1)))
    assert type(lift.base).__name__ == "PyCapsule"  # handed over from C++, not copied
    lengths = im.edge_isophotic_lengths(plane, isophotic_weight=0.0)
    E = plane.edges
    np.testing.assert_allclose(lengths, np.linalg.norm(plane.vertices[E[:, 0]] - plane.vertices[E[:, 1]], axis=1))
    assert im.purely_isophotic_distance([0, 0, 1], [0, 2, 0]) == pytest.approx(np.pi / 2)
    np.testing.assert_allclose(im.purely_isophotic_distance(np.eye(3), -np.eye(3)), np.pi)


def test_every_function_class_and_method_has_a_docstring():
    missing = []
    for name, obj in vars(im).items():
        if name.startswith("_"):
            continue
        if not (obj.__doc__ or "").strip():
            missing.append(name)
        if isinstance(obj, type) and not issubclass(obj, BaseException):
            missing += [f"{name}.{m}" for m, member in vars(obj).items()
                        if not m.startswith("_") and not (getattr(member, "__doc__", None) or "").strip()]
    assert missing == []


def test_errors_name_the_offending_element(plane):
    V, F = grid(3, 3)
    with pytest.raises(ValueError, match=r"V must have shape \(n, 3\) \(got \(16, 2\)\)"):
        im.Mesh(V[:, :2], F)
    with pytest.raises(TypeError, match="F must be an integer array"):
        im.Mesh(V, F.astype(float))
    bad = F.copy()
    bad[5, 1] = 99
    with pytest.raises(im.InvalidMeshError, match="face 5 .* refers to vertex 99; the mesh has 16 vertices"):
        im.Mesh(V, bad)
    nan = V.copy()
    nan[7, 2] = np.nan
    with pytest.raises(im.InvalidMeshError, match="7"):
        im.Mesh(nan, F)
    with pytest.raises(im.InvalidSourceError, match=r"sources\[1\] = 999 is not a vertex of the mesh"):
        im.compute_geodesic_distances(plane, [0, 999])
    with pytest.raises(im.InvalidSourceError, match="-1 is not a vertex"):
        im.Geodesic_solver(plane).add_source(-1)
    with pytest.raises(im.InvalidParameterError, match="euclidean_weight is -1; it must be finite and non-negative"):
        im.compute_geodesic_distances(plane, [0], euclidean_weight=-1.0)
    with pytest.raises(ValueError, match=r"isophotic_weight must have shape \(441,\)"):
        im.compute_geodesic_distances(plane, [0], isophotic_weight=np.ones(5))
    with pytest.raises(im.InvalidParameterError, match="isophotic_weight"):
        im.compute_lifted_embedding(plane, isophotic_weight=np.full(441, np.nan))
    with pytest.raises(im.InvalidParameterError, match="radius"):
        im.dilate_face_selection(plane, [0], -1.0)
    with pytest.raises(im.InvalidSourceError, match="barycentric"):
        s = im.Geodesic_solver(plane)
        s.add_source_point(0, [0.5, 0.6, 0.1])
    with pytest.raises(TypeError, match="integer indices"):
        im.compute_geodesic_distances(plane, [0.5])
    with pytest.raises(ValueError, match="cannot open mesh file"):
        im.Mesh("/nonexistent/mesh.off")
    assert issubclass(im.InvalidMeshError, im.Error) and issubclass(im.CancelledError, im.Error)


def test_per_vertex_weights_and_inputs_of_the_right_dtype_are_not_copied():
    mesh = im.Mesh(*grid(150, 150))  # 22801 vertices
    n = mesh.number_of_vertices
    w_prime = np.full(n, 0.5)
    # constant arrays give the lift of constant weights (the positions relative to the centroid)
    np.testing.assert_allclose(im.edge_isophotic_lengths(mesh, isophotic_weight=w_prime, weight_length_scale=1.0),
                               im.edge_isophotic_lengths(mesh, isophotic_weight=0.5, weight_length_scale=1.0))

    def peak_of(call):
        tracemalloc.start()
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        call()
        peak = tracemalloc.get_traced_memory()[1] - base
        tracemalloc.stop()
        return peak

    # the lift is handed over from C++ (not traced): what the call allocates through numpy is a copy
    lift = lambda weights: im.compute_lifted_embedding(mesh, isophotic_weight=weights, weight_length_scale=1.0)
    assert peak_of(lambda: lift(w_prime)) < n * 8 // 4
    # float32 weights are converted (the measure can see a copy): n float32 and n float64
    assert peak_of(lambda: lift(w_prime.astype(np.float32))) >= n * 12
    solver = im.Geodesic_solver(mesh, isophotic_weight=0.0)
    solver.add_source(0)
    solver.propagate()
    # distances() allocates its result once and fills it: no second array of n doubles
    assert peak_of(solver.distances) < n * 8 * 1.5
    d = solver.distances()
    assert d.flags.owndata and d.flags.c_contiguous and d.dtype == np.float64


# ------------------------------------------------------------------ GIL and Ctrl-C

@pytest.fixture(scope="module")
def large_mesh():
    return im.Mesh(*grid(300, 300))  # 180k faces


def test_propagation_releases_the_gil(large_mesh):
    solver = im.Geodesic_solver(large_mesh, store_windows=False)
    solver.add_source(0)
    ticks, done = [0], threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.0005)

    counter = threading.Thread(target=count)
    counter.start()
    time.sleep(0.01)
    before = ticks[0]
    start = time.perf_counter()
    solver.propagate()
    elapsed = time.perf_counter() - start
    during = ticks[0] - before
    done.set()
    counter.join()
    assert elapsed > 0.02, "the propagation is too short to tell"
    assert during >= 5  # a thread holding the GIL for the whole call would leave the counter at ~0


def test_ctrl_c_cancels_the_propagation(large_mesh):
    solver = im.Geodesic_solver(large_mesh)
    solver.add_source(0)
    running = threading.Event()

    def press_ctrl_c():
        running.wait()
        os.kill(os.getpid(), signal.SIGINT)

    presser = threading.Thread(target=press_ctrl_c)
    presser.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        solver.propagate(progress=lambda front: running.set() or True)  # the first report starts the timer
    presser.join()
    interrupted_after = time.perf_counter() - start
    assert solver.number_of_sources == 0  # cleared: ready for new sources
    solver.add_source(0)
    start = time.perf_counter()
    solver.propagate()
    assert interrupted_after < time.perf_counter() - start  # it stopped before the end


def test_progress_callback_cancels(large_mesh):
    fronts = []
    solver = im.Geodesic_solver(large_mesh, store_windows=False)
    solver.add_source(0)
    with pytest.raises(im.CancelledError, match="cancelled by its visitor"):
        solver.propagate(progress=lambda front: fronts.append(front) or len(fronts) < 3)
    assert len(fronts) == 3 and fronts == sorted(fronts)


def test_morphology_reports_progress_and_cancels():
    mesh = im.Mesh(*grid(60, 60))
    heard = []
    offsets, faces, distances = im.all_face_neighborhoods(mesh, 0.05, isophotic_weight=0,
                                                          progress=lambda a: heard.append(a) or True)
    assert len(heard) >= 1000 and all(0 <= a <= 1 for a in heard)  # about a thousand reports per loop
    assert np.array_equal(offsets, im.all_face_neighborhoods(mesh, 0.05, isophotic_weight=0)[0])
    with pytest.raises(im.CancelledError, match="cancelled by its callback"):
        im.all_face_neighborhoods(mesh, 0.05, isophotic_weight=0, progress=lambda a: a < 0.3)
    heard.clear()
    mask = im.dilate_face_selection(mesh, [0], 0.5, isophotic_weight=0, progress=lambda a: heard.append(a) or True)
    assert heard and mask.sum() > 100
    with pytest.raises(im.CancelledError):
        im.dilate_face_selection(mesh, [0], 0.5, isophotic_weight=0, progress=lambda a: False)
    with pytest.raises(im.CancelledError):
        im.Grey_level_morphology(mesh, 0.05, isophotic_weight=0, progress=lambda a: False)
    with pytest.raises(im.CancelledError):
        im.segment_by_region_growing(mesh, 0.1, isophotic_weight=0, progress=lambda a: False)


def test_ctrl_c_interrupts_morphology():
    mesh = im.Mesh(*grid(60, 60))
    running, heard = threading.Event(), []

    def press_ctrl_c():
        running.wait()
        os.kill(os.getpid(), signal.SIGINT)

    presser = threading.Thread(target=press_ctrl_c)
    presser.start()
    with pytest.raises(KeyboardInterrupt):
        im.all_face_neighborhoods(mesh, 0.05, isophotic_weight=0,
                                  progress=lambda a: heard.append(a) or running.set() or True)
    presser.join()
    assert len(heard) < 500  # stopped well before the end (a whole loop reports about a thousand times)


# ------------------------------------------------------------------ continuous solvers

def test_fast_sweeping_2_on_a_constant_metric():
    nu, nv = 81, 61
    M = np.array([[4.0, 1.0], [1.0, 1.0]])  # anisotropic, not aligned with the grid
    solver = im.Fast_sweeping_2(np.broadcast_to(M, (nu, nv, 2, 2)), (0, 1), (0, 0.75))
    assert solver.add_point_source(0.5, 0.4) == 0
    field = solver.solve()
    u, v = np.meshgrid(np.linspace(0, 1, nu), np.linspace(0, 0.75, nv), indexing="ij")
    offset = np.stack([u - 0.5, v - 0.4], axis=-1)
    exact = np.sqrt(np.einsum("...i,ij,...j", offset, M, offset))  # d = sqrt(x^T M x)
    assert field.distance.shape == (nu, nv) and field.converged
    assert np.abs(field.distance - exact).max() < 0.01 * exact.max()
    assert field.distance.base is not None and not field.distance.flags.writeable  # a view of the result
    assert np.all(field.nearest_source == 0)
    points, reached = solver.trace_back(field, 0.9, 0.7)
    assert reached and np.allclose(points[-1], [0.5, 0.4], atol=0.02)
    with pytest.raises(ValueError, match=r"metric must have shape \(nu, nv, 2, 2\)"):
        im.Fast_sweeping_2(np.zeros((nu, nv, 3, 3)))
    bad = np.array(np.broadcast_to(M, (nu, nv, 2, 2)))
    bad[3, 4] = [[1, 0], [0, -1]]
    with pytest.raises(im.InvalidParameterError, match=r"\(3,4\)|3, 4"):
        im.Fast_sweeping_2(bad)


def test_fast_sweeping_3_on_a_constant_metric():
    n, h = 21, 0.05
    M = np.diag([1.0, 4.0, 9.0])
    active = np.ones((n, n, n), bool)
    active[0] = False
    solver = im.Fast_sweeping_3(np.broadcast_to(M, (n, n, n, 3, 3)), active, (0, 0, 0), h)
    solver.add_point_source(0.5, 0.5, 0.5)
    field = solver.solve()
    x = np.stack(np.meshgrid(*[np.arange(n) * h] * 3, indexing="ij"), axis=-1) - 0.5
    exact = np.sqrt(np.einsum("...i,ij,...j", x, M, x))
    assert field.distance.shape == (n, n, n)
    assert np.all(np.isinf(field.distance[0]))  # inactive nodes
    assert np.abs(field.distance[1:] - exact[1:]).max() < 0.01 * exact.max()
