// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One-shot exact shortest path between two vertices in the isophotic metric.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_PATH_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_PATH_H

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricGeodesicsRef
///
/// Writes the exact shortest path from `source` to `target` in the isophotic metric as 3D points
/// on the surface (first = source, last = target) and returns its isophotic length. Returns
/// +infinity and writes nothing when `target` is not reachable from `source`.
///
/// Named parameters: the metric, as for `Geodesic_solver` (`euclidean_weight`, `isophotic_weight`, ...).
///
/// \throws Invalid_mesh_error, Invalid_parameter_error, Invalid_source_error on bad input
template <class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
double compute_geodesic_path(typename boost::graph_traits<TriangleMesh>::vertex_descriptor source,
                             typename boost::graph_traits<TriangleMesh>::vertex_descriptor target,
                             const TriangleMesh& tm,
                             OutputIterator points,
                             const NamedParameters& np = parameters::default_values())
{
  typedef Geodesic_solver<TriangleMesh> Solver;
  Solver solver(tm, parameters::combine(np, parameters::store_windows(true)));
  solver.add_source(source);
  const typename Solver::Face_location end = solver.location(target); // also checks `target`
  solver.propagate();
  const double length = solver.distance(target);
  if(length == std::numeric_limits<double>::infinity())
    return length;
  std::vector<typename Solver::Point> path;
  solver.trace_path_points(end, std::back_inserter(path));
  std::copy(path.rbegin(), path.rend(), points);
  return length;
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_PATH_H
