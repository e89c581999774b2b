// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// One-shot exact geodesic distance field from a set of source vertices.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_DISTANCES_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_DISTANCES_H

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>

#include <cmath>
#include <iterator>
#include <limits>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricGeodesicsRef
///
/// Computes the exact geodesic distance, in the isophotic metric, from the nearest vertex of
/// `sources` to every vertex of `tm`, and writes it into `distance`. Vertices that are
/// unreachable (another connected component) or beyond `max_distance` get
/// `std::numeric_limits<double>::infinity()`.
///
/// `euclidean_weight(1).isophotic_weight(0)` gives the plain Euclidean polyhedral geodesic distance.
/// For repeated queries, point sources, regions, paths or labels use `Geodesic_solver`.
///
/// \tparam VertexRange a range of `boost::graph_traits<TriangleMesh>::vertex_descriptor`
/// \tparam VertexDistanceMap a model of `WritablePropertyMap` with vertex keys and `double` values
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_point_map,
///     vertex_normal_map, lifted_embedding_map} \cgalParamDescription{the metric; see `Geodesic_solver`}
///     \cgalParamDefault{`w = w' = 1`, `L` = the bounding-box diagonal} \cgalParamNEnd
///   \cgalParamNBegin{metric_mesh} \cgalParamDescription{a `Metric_mesh` of `tm` prepared once: no set-up
///     (the metric parameters above are then those it was built with)} \cgalParamDefault{prepared by the call} \cgalParamNEnd
///   \cgalParamNBegin{max_distance} \cgalParamDescription{stop the propagation at this distance}
///     \cgalParamType{`double`} \cgalParamDefault{+infinity} \cgalParamNEnd
///   \cgalParamNBegin{propagation_threads} \cgalParamDescription{threads of the propagation; see
///     `Geodesic_solver` (the distances are the same for every number of threads)}
///     \cgalParamType{an integer in [0, 256]} \cgalParamDefault{`0`: serial} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// With a finite `max_distance` on a `Surface_mesh` (and a metric of constant weights, \f$ w > 0 \f$),
/// only the part of the mesh that distance can reach is prepared and validated: a defect beyond it is
/// not reported (see \ref IsophoticMetricReach).
///
/// \throws Invalid_mesh_error, Invalid_parameter_error, Invalid_source_error on bad input
template <class VertexRange, class TriangleMesh, class VertexDistanceMap,
          class NamedParameters = parameters::Default_named_parameters>
void compute_geodesic_distances(const VertexRange& sources, const TriangleMesh& tm, VertexDistanceMap distance,
                                const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const double max_distance = choose_parameter(get_parameter(np, internal_np::max_distance), std::numeric_limits<double>::infinity());
  const auto solver_options = parameters::store_windows(false).propagation_threads(
      choose_parameter(get_parameter(np, internal_np::propagation_threads), 0));
  // A bounded call prepares only what its bound can reach (when it may: see run_on_reach_region()).
  internal::Reach_sources<TriangleMesh> reach_sources;
  if(std::isfinite(max_distance))
    reach_sources.vertices.assign(std::begin(sources), std::end(sources));
  if(std::isfinite(max_distance) && !reach_sources.vertices.empty() &&
     internal::run_on_reach_region(tm, np, reach_sources, max_distance, [&](const Metric_mesh<TriangleMesh>& region) {
       Geodesic_solver<TriangleMesh> solver(region, solver_options);
       for(auto v : reach_sources.vertices)
         solver.add_source(v);
       solver.propagate(max_distance);
       for(auto v : vertices(tm)) // (beyond the region: beyond the bound)
         put(distance, v, std::numeric_limits<double>::infinity());
       solver.copy_distances(distance);
     }))
    return;
  auto make_solver = [&] {
    if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::metric_mesh_t>::value)
    {
      const Metric_mesh<TriangleMesh>& mesh = get_parameter(np, internal_np::metric_mesh);
      if(&mesh.mesh() != &tm)
        throw Invalid_parameter_error("metric_mesh must be a Metric_mesh built on the same mesh");
      return Geodesic_solver<TriangleMesh>(mesh, solver_options);
    }
    else
      return Geodesic_solver<TriangleMesh>(tm, parameters::combine(np, solver_options));
  };
  Geodesic_solver<TriangleMesh> solver = make_solver();
  for(auto v : sources)
    solver.add_source(v);
  solver.propagate(max_distance);
  solver.copy_distances(distance);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_COMPUTE_GEODESIC_DISTANCES_H
