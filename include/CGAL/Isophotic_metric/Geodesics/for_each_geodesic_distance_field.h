// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Many independent single-source distance fields on one mesh, in parallel when TBB is available.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_FOR_EACH_GEODESIC_DISTANCE_FIELD_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_FOR_EACH_GEODESIC_DISTANCE_FIELD_H

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/internal/for_each_index.h>

#include <CGAL/tags.h>

#include <limits>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricGeodesicsRef
///
/// For every element `sources[i]` (a vertex, or a face taken as a closed region source), computes
/// the exact single-source distance field (bounded by `max_distance`) and calls
/// `callback(i, solver)`, where `solver` is a `Geodesic_solver` holding that field (query its
/// distances, labels, and, with `store_windows(true)`, point values and paths).
///
/// With `ConcurrencyTag = CGAL::Parallel_tag` (the default `CGAL::Parallel_if_available_tag` picks it
/// when `CGAL_LINKED_WITH_TBB` is defined) the fields are computed in parallel with TBB, one solver
/// per thread, all sharing one `Metric_mesh`; with `CGAL::Sequential_tag` one after the other. Each
/// field is the same either way. `callback` may then run concurrently for different `i`: it must only
/// write to data of its own `i`.
///
/// Named parameters: those of `Geodesic_solver` (the metric; `store_windows` defaults to `false`
/// here), and `max_distance` (default +infinity) — for geodesic discs, set it to the radius so each
/// field costs what its disc covers.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class SourceRange, class TriangleMesh,
          class Callback, class NamedParameters = parameters::Default_named_parameters>
void for_each_geodesic_distance_field(const SourceRange& sources, const TriangleMesh& tm, Callback callback,
                                      const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef Geodesic_solver<TriangleMesh> Solver;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;

  const bool store = choose_parameter(get_parameter(np, internal_np::store_windows), false);
  const double max_distance =
    choose_parameter(get_parameter(np, internal_np::max_distance), std::numeric_limits<double>::infinity());
  const Solver prototype(tm, parameters::combine(np, parameters::store_windows(store)));
  const std::vector<typename SourceRange::value_type> all(sources.begin(), sources.end());

  // grain 1: every field is a whole propagation, long enough to be a task of its own
  internal::for_each_index<ConcurrencyTag>(all.size(), 1, [&] { return prototype.sibling(); },
                                           [&](Solver& solver, std::size_t i) {
    solver.clear_sources();
    if constexpr(std::is_same<typename SourceRange::value_type, face_descriptor>::value)
    {
      const face_descriptor f[1] = {all[i]};
      solver.add_source_region(f);
    }
    else
      solver.add_source(all[i]);
    solver.propagate(max_distance);
    callback(i, static_cast<const Solver&>(solver));
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_FOR_EACH_GEODESIC_DISTANCE_FIELD_H
