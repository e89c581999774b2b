// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Named parameters added by the package Isophotic_metric (X-macro file).
// Intentionally no include guard: included several times with different definitions of
// CGAL_add_named_parameter, exactly like <CGAL/STL_Extension/internal/parameters_interface.h>.
//
// CGAL_add_named_parameter(tag_type, tag_value, function_name)
CGAL_add_named_parameter(euclidean_weight_t, euclidean_weight, euclidean_weight)
CGAL_add_named_parameter(isophotic_weight_t, isophotic_weight, isophotic_weight)
CGAL_add_named_parameter(weight_length_scale_t, weight_length_scale, weight_length_scale)
CGAL_add_named_parameter(lifted_embedding_t, lifted_embedding, lifted_embedding_map)
CGAL_add_named_parameter(max_distance_t, max_distance, max_distance)
CGAL_add_named_parameter(area_fraction_t, area_fraction, area_fraction)
CGAL_add_named_parameter(store_windows_t, store_windows, store_windows)
CGAL_add_named_parameter(full_window_every_t, full_window_every, full_window_every)
CGAL_add_named_parameter(propagation_threads_t, propagation_threads, propagation_threads)
CGAL_add_named_parameter(fast_sweeping_options_t, fast_sweeping_options, fast_sweeping_options)
CGAL_add_named_parameter(narrow_band_width_t, narrow_band_width, narrow_band_width)
CGAL_add_named_parameter(area_resolution_t, area_resolution, area_resolution)
CGAL_add_named_parameter(face_band_solver_t, face_band_solver, face_band_solver)
CGAL_add_named_parameter(neighborhood_center_t, neighborhood_center, neighborhood_center)
CGAL_add_named_parameter(edge_length_map_t, edge_length_map, edge_length_map)
CGAL_add_named_parameter(metric_mesh_t, metric_mesh, metric_mesh)
CGAL_add_named_parameter(structuring_function_t, structuring_function, structuring_function)
CGAL_add_named_parameter(face_predicate_t, face_predicate, face_predicate)
CGAL_add_named_parameter(merge_tolerance_t, merge_tolerance, merge_tolerance)
CGAL_add_named_parameter(distance_tolerance_t, distance_tolerance, distance_tolerance)
CGAL_add_named_parameter(angle_tolerance_t, angle_tolerance, angle_tolerance)
CGAL_add_named_parameter(seed_spacing_t, seed_spacing, seed_spacing)
CGAL_add_named_parameter(minimum_segment_faces_t, minimum_segment_faces, minimum_segment_faces)
CGAL_add_named_parameter(normal_smoothing_scale_t, normal_smoothing_scale, normal_smoothing_scale)
CGAL_add_named_parameter(normal_range_t, normal_range, normal_range)
CGAL_add_named_parameter(max_hole_size_t, max_hole_size, max_hole_size)
CGAL_add_named_parameter(min_component_fraction_t, min_component_fraction, min_component_fraction)
CGAL_add_named_parameter(use_patch_guidance_t, use_patch_guidance, use_patch_guidance)
CGAL_add_named_parameter(number_of_vertex_updates_t, number_of_vertex_updates, number_of_vertex_updates)
