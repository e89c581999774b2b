// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The metric radius that dilates a face selection to a given share of the area, or to a given
// number of faces: radii stated by what they select, whatever the model's units and the metric.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_RADIUS_FOR_AREA_SHARE_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_RADIUS_FOR_AREA_SHARE_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// The smallest radius whose dilation of `selection` (the selection included) reaches `target` by
// the measure `weight` summed over its faces. The measure grows with the radius in steps (a face
// joins at one radius), so the answer is bracketed by doubling and then bisected until the bracket
// is 1e-12 of the radius (or of a median edge, for radii near 0): the faces selected at the returned
// radius are those of the step.
template <class TriangleMesh, class NamedParameters, class FaceWeight>
double radius_for_measure(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& selection,
                          double target, const NamedParameters& np, FaceWeight&& weight, const std::string& what)
{
  if(selection.empty())
    throw Invalid_source_error("the selection to dilate is empty");
  const double fraction = read_area_fraction(np);
  const Metric_mesh<TriangleMesh>& mesh = band.metric_mesh();
  std::vector<char> in_selection(mesh.number_of_faces(), 0);
  double selected = 0;
  for(std::uint32_t f : selection)
    if(!in_selection[f])
    {
      in_selection[f] = 1;
      selected += weight(f);
    }

  // One source for the whole search: each radius continues the propagation of the previous ones
  // or reuses it, and the faces joining are those of dilate_face_selection() at that radius.
  band.clear_sources();
  add_source_region_by_index(band, selection);
  auto measure_at = [&](double radius) {
    double m = selected;
    band.visit_band(radius, fraction > 0, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
      if(!in_selection[v.face_index] && (fraction == 0 || v.covered_fraction >= fraction))
        m += weight(v.face_index);
    });
    return m;
  };
  if(selected >= target || measure_at(0.) >= target)
    return 0.;

  // No finite geodesic distance exceeds the sum of all lifted edge lengths: beyond it, the target
  // lies in parts of the mesh the selection cannot reach.
  double edge_sum = 0;
  for(std::uint32_t f = 0; f < mesh.number_of_faces(); ++f)
    for(int k = 0; k < 3; ++k)
      edge_sum += mesh.edge_length(f, k);
  const double median_edge = mesh.median_edge_length();
  double low = 0., high = median_edge; // the first guess
  while(measure_at(high) < target)
  {
    if(high > edge_sum)
      throw Invalid_parameter_error(message("no radius dilates the selection to ", what,
                                            ": the faces connected to the selection hold less"));
    low = high;
    high *= 2;
  }
  while(high - low > 1e-12 * (std::max)(high, median_edge))
  {
    const double mid = 0.5 * (low + high);
    if(measure_at(mid) < target)
      low = mid;
    else
      high = mid;
  }
  return high;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief returns the smallest metric radius whose dilation of `selection` (by
/// `dilate_face_selection()` with the same named parameters) covers at least the share `share` of
/// the area of `tm`, the selection included.
///
/// A radius stated as a share of the area means the same on any model, in any units and in any
/// metric: "dilate to 5 % of the surface". The dilated area grows with the radius in steps (each
/// face joins at one radius); the radius is found by doubling, then bisection until it is known to
/// a relative 1e-12, so the dilation at the returned radius selects the faces of that step. Each
/// step of the search is one bounded propagation: pass a prepared `face_band_solver` to reuse the
/// geometry across calls.
///
/// \tparam FaceRange a range of `boost::graph_traits<TriangleMesh>::%face_descriptor`
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
///
/// \param selection the selected faces
/// \param tm the mesh
/// \param share the share of the total area to reach, in (0, 1]
/// \param np the metric and the joining rule, as for `dilate_face_selection()` (`area_fraction`,
///        `area_resolution`, the metric parameters or `face_band_solver`; `vertex_point_map` also
///        gives the positions the areas are measured with)
///
/// \returns the radius, `0` when the selection alone covers the share
/// \throws Invalid_parameter_error when `share` is outside (0, 1] or the faces the selection can
///         reach (its connected components) hold less than the share
/// \throws Invalid_source_error when `selection` is empty or a face of it is not a face of `tm`
///
/// \sa `radius_for_face_count()`
template <class FaceRange, class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
double radius_for_area_share(const FaceRange& selection, const TriangleMesh& tm, double share,
                             const NamedParameters& np = parameters::default_values())
{
  if(!(share > 0 && share <= 1))
    throw Invalid_parameter_error(internal::message("area share is ", share, "; it must be in (0, 1]"));
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    const Metric_mesh<TriangleMesh>& mesh = band.metric_mesh();
    std::vector<double> area(mesh.number_of_faces());
    double total = 0;
    for(std::uint32_t f = 0; f < mesh.number_of_faces(); ++f)
      total += area[f] = CGAL::to_double(CGAL::Polygon_mesh_processing::face_area(mesh.face(f), tm, parameters::cgal_np(np)));
    // a target a little below the share asked, so that rounding in the sums of the areas cannot
    // turn "the whole surface" into an unreachable target
    const double target = share * total * (1 - 1e-12);
    return internal::radius_for_measure(band, internal::face_indices(band, selection), target, np,
                                        [&](std::uint32_t f) { return area[f]; },
                                        internal::message(100 * share, " % of the area"));
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief returns the smallest metric radius whose dilation of `selection` (by
/// `dilate_face_selection()` with the same named parameters) holds at least `number_of_faces`
/// faces, the selection included.
///
/// Same search as `radius_for_area_share()`; the dilation may hold more faces than asked when
/// several join at the same radius.
///
/// \returns the radius, `0` when the selection alone has enough faces
/// \throws Invalid_parameter_error when the faces the selection can reach are fewer than `number_of_faces`
/// \throws Invalid_source_error when `selection` is empty or a face of it is not a face of `tm`
///
/// \sa `radius_for_area_share()`
template <class FaceRange, class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
double radius_for_face_count(const FaceRange& selection, const TriangleMesh& tm, std::size_t number_of_faces,
                             const NamedParameters& np = parameters::default_values())
{
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    return internal::radius_for_measure(band, internal::face_indices(band, selection), double(number_of_faces), np,
                                        [](std::uint32_t) { return 1.; },
                                        internal::message(number_of_faces, " faces"));
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_RADIUS_FOR_AREA_SHARE_H
