// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Umbrella header of the Isophotic_metric package: includes every public header.
#ifndef CGAL_ISOPHOTIC_METRIC_H
#define CGAL_ISOPHOTIC_METRIC_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/repair_scanned_mesh.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/estimate_vertex_normals.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Isophotic_metric/isophotic_length.h>
#include <CGAL/Isophotic_metric/Metric_mesh.h>
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_path.h>
#include <CGAL/Isophotic_metric/Geodesics/for_each_geodesic_distance_field.h>
#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>
#include <CGAL/Isophotic_metric/Morphology/label_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/grey_level_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/radius_for_area_share.h>
#include <CGAL/Isophotic_metric/Segmentation/region_growing.h>
// Continuous side: parametric and implicit surfaces, fast sweeping, continuous morphology.
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_metric.h>
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_distance.h>
#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_2.h>
#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_3.h>
#include <CGAL/Isophotic_metric/Continuous/Implicit_surface_metric.h>
#include <CGAL/Isophotic_metric/Continuous/Implicit_surface_distance.h>
#include <CGAL/Isophotic_metric/Continuous/signed_distance_grid.h>
#include <CGAL/Isophotic_metric/Continuous/level_set_morphology.h>

#endif // CGAL_ISOPHOTIC_METRIC_H
