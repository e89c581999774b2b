# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of the typed segmentation in Python: fits of exactly sampled surfaces against their closed
forms, segmentation of a generated CAD part equal to the C++ API's face for face, errors."""
import os
import subprocess

import numpy as np
import pytest

import isophotic_metric as im
from meshes import cylinder

PART = os.path.join(os.environ.get("IM_CAD_PARTS_DIR", ""), "box_fillet_r8.ply")
FANDISK = os.path.join(os.environ.get("IM_CGAL_DATA_DIR", ""), "meshes", "fandisk.off")
TYPES = ["plane", "cylinder", "cone", "sphere", "torus", "free-form"]  # the numbering of Surface_type
PARAMETERS = {"plane": {"center", "axis"}, "cylinder": {"center", "axis", "radius"},
              "cone": {"center", "axis", "half_angle"}, "sphere": {"center", "radius"},
              "torus": {"center", "axis", "radius", "minor_radius"}, "free-form": set()}


def unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def cylinder_samples(rng, center, axis, radius, n=200):
    """Points on the cylinder (random angles and heights) and their outward normals."""
    axis = unit(axis)
    u = unit(np.cross(axis, [1.0, 0.0, 0.0]))
    v = np.cross(axis, u)
    angle, height = rng.uniform(0, 2 * np.pi, n), rng.uniform(-2, 3, n)
    normals = np.outer(np.cos(angle), u) + np.outer(np.sin(angle), v)
    return center + np.outer(height, axis) + radius * normals, normals


def test_fitting_an_exact_cylinder_recovers_its_axis_and_radius():
    rng = np.random.default_rng(1)
    center, axis, radius = np.array([1.0, -2.0, 0.5]), unit([1.0, 2.0, 2.0]), 0.75
    points, normals = cylinder_samples(rng, center, axis, radius)
    fit = im.fit_fundamental_surface("cylinder", points, normals)
    assert fit["type"] == "cylinder" and fit["outward"]
    assert fit["radius"] == pytest.approx(radius, rel=1e-12)
    assert abs(fit["axis"] @ axis) == pytest.approx(1, abs=1e-12)
    offset = fit["center"] - center  # a point of the axis: along the axis from the true one
    assert np.linalg.norm(offset - (offset @ axis) * axis) < 1e-12
    assert fit["residual"] < 1e-12
    # a hole: normals towards the axis
    assert not im.fit_fundamental_surface("cylinder", points, -normals)["outward"]


def test_fitting_an_exact_sphere_recovers_its_centre_and_radius_and_weights_select_samples():
    rng = np.random.default_rng(2)
    center, radius = np.array([0.3, 4.0, -1.0]), 2.5
    normals = rng.normal(size=(300, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    points = center + radius * normals
    fit = im.fit_fundamental_surface("sphere", points, normals)
    assert fit["type"] == "sphere" and set(fit) == PARAMETERS["sphere"] | {"type", "outward", "residual"}
    np.testing.assert_allclose(fit["center"], center, rtol=0, atol=1e-12)
    assert fit["radius"] == pytest.approx(radius, rel=1e-12)
    # samples of weight zero do not count: outliers with weight 0 leave the fit exact
    outliers = center + 3 * radius * normals[:20]
    weights = np.r_[np.ones(len(points)), np.zeros(20)]
    fit = im.fit_fundamental_surface("sphere", np.r_[points, outliers], np.r_[normals, normals[:20]], weights)
    assert fit["radius"] == pytest.approx(radius, rel=1e-12)
    # too few samples: no surface
    fit = im.fit_fundamental_surface("sphere", points[:2], normals[:2])
    assert fit["type"] == "free-form" and fit["residual"] == np.inf


@pytest.fixture(scope="module")
def part():
    if not os.path.exists(PART):
        pytest.skip("CAD part suite not found (IM_CAD_PARTS_DIR)")
    return im.Mesh(PART)


def test_segmentation_of_a_cad_part_equals_the_cpp_api(part, tmp_path):
    program = os.environ.get("IM_CPP_REFERENCE")
    if not program or not os.path.exists(FANDISK):
        pytest.skip("IM_CPP_REFERENCE or the CGAL data set not set (run through ctest)")
    subprocess.run([program, FANDISK, str(tmp_path), PART], check=True)
    diagonal = im.suggested_weight_length_scale(part)
    options = dict(distance_tolerance=0.004 * diagonal, angle_tolerance=12.0, seed_spacing=0.08 * diagonal,
                   minimum_segment_faces=12, euclidean_weight=0.4, isophotic_weight=0.6,
                   weight_length_scale=0.5 * diagonal)
    for suffix, kw in (("", {}), ("_options", options)):
        ids, segments = im.segment_fundamental_surfaces(part, **kw)
        reference = np.fromfile(tmp_path / f"fundamental{suffix}.i64", dtype="<i8")
        assert ids.shape == (part.number_of_faces,) and ids.dtype == np.int64
        np.testing.assert_array_equal(ids, reference)
        rows = np.fromfile(tmp_path / f"surfaces{suffix}.f64", dtype="<f8").reshape(-1, 13)
        assert len(segments) == len(rows) == ids.max() + 1
        np.testing.assert_array_equal([s["number_of_faces"] for s in segments], np.bincount(ids))
        for s, row in zip(segments, rows):
            kind = TYPES[int(row[0])]
            assert s["type"] == kind
            assert s["number_of_faces"] == row[12]
            # the same fits of the same faces, up to the rounding of differently compiled code
            expected = {"center": row[1:4], "axis": row[4:7], "radius": row[7], "minor_radius": row[8],
                        "half_angle": row[9], "residual": row[10], "area": row[11]}
            for key, value in expected.items():
                if key in s:
                    np.testing.assert_allclose(s[key], value, rtol=1e-10, atol=1e-10 * diagonal, err_msg=key)
            described = {"type", "residual", "area", "number_of_faces"} | ({"outward"} if kind != "free-form" else set())
            assert set(s) == described | PARAMETERS[kind]
    # the options change the result: the comparison above saw them arrive
    assert not np.array_equal(np.fromfile(tmp_path / "fundamental.i64", dtype="<i8"),
                              np.fromfile(tmp_path / "fundamental_options.i64", dtype="<i8"))


def test_segmentation_reports_progress_and_cancels(part):
    heard = []
    ids, _ = im.segment_fundamental_surfaces(part, progress=lambda a: heard.append(a) or True)
    assert heard == sorted(heard) and heard[0] >= 0 and heard[-1] <= 1 and len(heard) >= 6
    np.testing.assert_array_equal(ids, im.segment_fundamental_surfaces(part)[0])
    with pytest.raises(im.CancelledError, match="segment_fundamental_surfaces cancelled by its callback"):
        im.segment_fundamental_surfaces(part, progress=lambda a: a < 0.7)


def test_segmentation_and_fit_errors_name_the_offending_argument():
    mesh = im.Mesh(*cylinder(24, 6))
    with pytest.raises(TypeError, match="incompatible function arguments"):
        im.segment_fundamental_surfaces(mesh, distance_tolerence=0.1)
    with pytest.raises(im.InvalidParameterError, match="distance_tolerance must be positive and finite"):
        im.segment_fundamental_surfaces(mesh, distance_tolerance=-1.0)
    with pytest.raises(im.InvalidParameterError, match="seed_spacing must be positive and finite"):
        im.segment_fundamental_surfaces(mesh, seed_spacing=float("nan"))
    with pytest.raises(im.InvalidParameterError, match="angle_tolerance must be positive"):
        im.segment_fundamental_surfaces(mesh, angle_tolerance=0.0)
    with pytest.raises(im.InvalidParameterError, match="minimum_segment_faces must be 0 or more"):
        im.segment_fundamental_surfaces(mesh, minimum_segment_faces=-3)
    with pytest.raises(im.InvalidParameterError, match="euclidean_weight"):
        im.segment_fundamental_surfaces(mesh, euclidean_weight=-1.0)
    points, normals = cylinder_samples(np.random.default_rng(3), np.zeros(3), [0, 0, 1], 1.0, n=50)
    with pytest.raises(ValueError, match="unknown surface type 'cylindre'"):
        im.fit_fundamental_surface("cylindre", points, normals)
    with pytest.raises(im.InvalidParameterError, match="free-form surface has no parameters"):
        im.fit_fundamental_surface("free-form", points, normals)
    with pytest.raises(ValueError, match=r"normals must have shape \(50, 3\)"):
        im.fit_fundamental_surface("cylinder", points, normals[:49])
    with pytest.raises(ValueError, match=r"weights must have shape \(50,\)"):
        im.fit_fundamental_surface("cylinder", points, normals, np.ones(3))
