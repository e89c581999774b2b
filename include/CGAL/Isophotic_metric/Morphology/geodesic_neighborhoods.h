// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geodesic neighbourhoods (the structuring elements of the paper): the faces or vertices within a
// metric radius of a face, a vertex or a surface point, one at a time or for every element in parallel.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#include <CGAL/Isophotic_metric/internal/for_each_index.h>

#include <CGAL/tags.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricMorphology
/// A face of a geodesic neighbourhood.
template <class FaceDescriptor>
struct Neighborhood_face
{
  FaceDescriptor face;     ///< the face
  double min_distance;     ///< the smallest distance found on the closed face: at most the radius, the minimum itself
                           ///< when it lies at a vertex (the search stops at the first point within the radius)
  double covered_fraction; ///< fraction of its area within the radius; `-1` unless `area_fraction` > 0
};

/// \ingroup PkgIsophoticMetricMorphology
/// A vertex of a geodesic neighbourhood.
template <class VertexDescriptor>
struct Neighborhood_vertex
{
  VertexDescriptor vertex; ///< the vertex
  double distance;         ///< its exact distance to the centre
};

/// \ingroup PkgIsophoticMetricMorphology
/// Where a neighbourhood is centred: on a closed face, a vertex or a surface point.
enum class Neighborhood_center { FACE, FACE_CENTROID, VERTEX };

namespace internal {

template <class TriangleMesh>
void add_center(Face_band_solver<TriangleMesh>& band, Neighborhood_center center, std::uint32_t index)
{
  band.clear_sources();
  switch(center)
  {
    case Neighborhood_center::FACE: band.add_source_region(std::array<typename Face_band_solver<TriangleMesh>::face_descriptor, 1>{{band.metric_mesh().face(index)}}); break;
    case Neighborhood_center::FACE_CENTROID:
      band.add_source(typename Face_band_solver<TriangleMesh>::Face_location(band.metric_mesh().face(index), {{1.0 / 3, 1.0 / 3, 1.0 / 3}}));
      break;
    case Neighborhood_center::VERTEX: band.add_source(band.metric_mesh().vertex(index)); break;
  }
}

// Faces (indices) of the neighbourhood of the current sources, with minimum distance and fraction.
template <class TriangleMesh>
void band_faces(Face_band_solver<TriangleMesh>& band, double radius, double fraction, bool exact_minimum,
                std::vector<std::pair<std::uint32_t, std::array<double, 2>>>& result)
{
  result.clear();
  band.visit_band(radius, fraction > 0, exact_minimum, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    if(fraction == 0 || v.covered_fraction >= fraction)
      result.push_back({v.face_index, {v.min_distance, v.covered_fraction}});
  });
}

// Vertices (indices) within the radius of the current sources, with their distances.
template <class TriangleMesh>
void band_vertices(Face_band_solver<TriangleMesh>& band, double radius, std::vector<std::pair<std::uint32_t, double>>& result,
                   std::vector<char>& seen)
{
  result.clear();
  seen.resize(band.metric_mesh().number_of_vertices(), 0);
  std::vector<std::uint32_t> touched;
  band.visit_band(radius, false, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    for(std::uint32_t c : band.metric_mesh().corners(v.face_index))
      if(!seen[c])
      {
        seen[c] = 1;
        touched.push_back(c);
        const double d = band.distance(band.metric_mesh().vertex(c));
        if(d <= radius)
          result.push_back({c, d});
      }
  });
  for(std::uint32_t c : touched)
    seen[c] = 0;
}

// The centre of the neighbourhoods of all_face_neighborhoods(), from the named parameters.
template <class NamedParameters>
Neighborhood_center read_face_center(const NamedParameters& np)
{
  const Neighborhood_center center = parameters::choose_parameter(
    parameters::get_parameter(np, internal_np::neighborhood_center), Neighborhood_center::FACE);
  if(center == Neighborhood_center::VERTEX)
    throw Invalid_parameter_error("all_face_neighborhoods: neighborhood_center must be FACE or FACE_CENTROID");
  return center;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief writes the faces within `radius` of a closed face, a vertex or a surface point: the
/// geodesic disc used as structuring element.
///
/// A face belongs to the neighbourhood when the minimum distance over the closed face is at most
/// `radius` and, with `area_fraction` \f$ a > 0 \f$, when at least the fraction \f$ a \f$ of its area
/// lies within `radius` (see `Face_band_solver` for how both are computed).
///
/// \tparam Center `boost::graph_traits<TriangleMesh>::%face_descriptor` (the closed face),
///   `%vertex_descriptor`, or `Geodesic_solver<TriangleMesh>::%Face_location` (a surface point)
/// \tparam OutputIterator an output iterator accepting `Neighborhood_face<face_descriptor>`
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{area_fraction} \cgalParamDescription{see `dilate_face_selection()`} \cgalParamDefault{`0`} \cgalParamNEnd
///   \cgalParamNBegin{area_resolution} \cgalParamDescription{see `dilate_face_selection()`} \cgalParamDefault{`4`} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_point_map, vertex_normal_map, lifted_embedding_map}
///     \cgalParamDescription{the metric, see `Geodesic_solver`} \cgalParamNEnd
///   \cgalParamNBegin{face_band_solver, callback} \cgalParamDescription{see `dilate_face_selection()`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// With `area_fraction` 0, on a `Surface_mesh` and a metric of constant weights, only the part of the
/// mesh within reach of the radius is prepared and validated (see \ref IsophoticMetricReach); so for
/// `geodesic_vertex_neighborhood()`.
///
/// \throws Invalid_parameter_error for a negative or non-finite radius, an area fraction outside [0,1]
/// \throws Invalid_source_error when the centre is not an element of `tm`
template <class Center, class TriangleMesh, class OutputIterator,
          class NamedParameters = parameters::Default_named_parameters>
OutputIterator geodesic_neighborhood(const Center& center, const TriangleMesh& tm, double radius, OutputIterator out,
                                     const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  internal::Reach_sources<TriangleMesh> sources;
  if constexpr(std::is_same<Center, face_descriptor>::value)
    sources.faces.push_back(center);
  else if constexpr(std::is_same<Center, vertex_descriptor>::value)
    sources.vertices.push_back(center);
  else
    sources.faces.push_back(center.first); // (a surface point: its face)
  return internal::with_band_solver(tm, np, sources, radius, fraction, [&](Face_band_solver<TriangleMesh>& band) {
    band.clear_sources();
    if constexpr(std::is_same<Center, face_descriptor>::value)
      band.add_source_region(std::array<face_descriptor, 1>{{center}});
    else if constexpr(std::is_same<Center, vertex_descriptor>::value)
      band.add_source(center);
    else
      band.add_source(center);
    std::vector<std::pair<std::uint32_t, std::array<double, 2>>> faces;
    internal::band_faces(band, radius, fraction, false, faces);
    for(const auto& f : faces)
      *out++ = Neighborhood_face<face_descriptor>{band.metric_mesh().face(f.first), f.second[0], f.second[1]};
    return out;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief writes the vertices within `radius` of a vertex, with their exact distances.
/// \tparam OutputIterator an output iterator accepting `Neighborhood_vertex<vertex_descriptor>`
/// Named parameters: the metric, `face_band_solver` and `callback`, as `geodesic_neighborhood()`.
template <class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
OutputIterator geodesic_vertex_neighborhood(typename boost::graph_traits<TriangleMesh>::vertex_descriptor center,
                                            const TriangleMesh& tm, double radius, OutputIterator out,
                                            const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  internal::check_radius(radius);
  internal::Reach_sources<TriangleMesh> sources;
  sources.vertices.push_back(center);
  return internal::with_band_solver(tm, np, sources, radius, 0., [&](Face_band_solver<TriangleMesh>& band) {
    band.clear_sources();
    band.add_source(center);
    std::vector<std::pair<std::uint32_t, double>> vs;
    std::vector<char> seen;
    internal::band_vertices(band, radius, vs, seen);
    for(const auto& v : vs)
      *out++ = Neighborhood_vertex<vertex_descriptor>{band.metric_mesh().vertex(v.first), v.second};
    return out;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the neighbourhood of every face: `neighborhoods[f]` receives the faces meeting the disc of
/// radius `radius` centred at face `f` (on the closed face, or at its centroid, see
/// `neighborhood_center`), with the smallest distance found on them (see `Neighborhood_face`).
///
/// One bounded propagation per face. With `ConcurrencyTag` = `CGAL::Parallel_tag` (what the default
/// `CGAL::Parallel_if_available_tag` is when `CGAL_LINKED_WITH_TBB` is defined) they run on TBB's
/// threads, one solver per thread sharing the prepared mesh; with `CGAL::Sequential_tag` one after the
/// other. The results do not depend on it.
///
/// \tparam FaceNeighborhoodMap a model of `WritablePropertyMap` with face descriptors as key and
///   `std::vector<Neighborhood_face<face_descriptor>>` as value
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{neighborhood_center} \cgalParamDescription{where the disc of a face is centred}
///     \cgalParamType{`Neighborhood_center::FACE` (the closed face) or `Neighborhood_center::FACE_CENTROID`}
///     \cgalParamDefault{`Neighborhood_center::FACE`} \cgalParamNEnd
///   \cgalParamNBegin{area_fraction, area_resolution, face_band_solver, callback} \cgalParamDescription{see
///     `geodesic_neighborhood()`} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_point_map, vertex_normal_map, lifted_embedding_map}
///     \cgalParamDescription{the metric, see `Geodesic_solver`} \cgalParamNEnd
/// \cgalNamedParamsEnd
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class FaceNeighborhoodMap,
          class NamedParameters = parameters::Default_named_parameters>
void all_face_neighborhoods(const TriangleMesh& tm, double radius, FaceNeighborhoodMap neighborhoods,
                            const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_area_fraction(np);
  const Neighborhood_center center = internal::read_face_center(np);
  internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    std::vector<std::vector<Neighborhood_face<face_descriptor>>> result(band.metric_mesh().number_of_faces());
    internal::for_each_index<ConcurrencyTag>(band.metric_mesh().number_of_faces(), 16, [&] { return band.sibling(); },
                                             [&](Face_band_solver<TriangleMesh>& local, std::size_t i) {
      internal::add_center(local, center, static_cast<std::uint32_t>(i));
      std::vector<std::pair<std::uint32_t, std::array<double, 2>>> faces;
      internal::band_faces(local, radius, fraction, false, faces);
      result[i].reserve(faces.size());
      for(const auto& f : faces)
        result[i].push_back({local.metric_mesh().face(f.first), f.second[0], f.second[1]});
    }, band.progress_callback(), "all_face_neighborhoods");
    // written here, not in the loop: a property map need not accept concurrent writes
    for(std::size_t i = 0; i < result.size(); ++i)
      put(neighborhoods, band.metric_mesh().face(i), std::move(result[i]));
    return 0;
  });
}

namespace internal {

// The vertices within `radius` of every vertex, by vertex index, with their exact distances.
template <class ConcurrencyTag, class TriangleMesh>
std::vector<std::vector<std::pair<std::uint32_t, double>>>
vertex_neighborhoods_by_index(Face_band_solver<TriangleMesh>& band, double radius)
{
  struct Local
  {
    Face_band_solver<TriangleMesh> band;
    std::vector<char> seen; // scratch of band_vertices()
  };
  std::vector<std::vector<std::pair<std::uint32_t, double>>> result(band.metric_mesh().number_of_vertices());
  for_each_index<ConcurrencyTag>(band.metric_mesh().number_of_vertices(), 16, [&] { return Local{band.sibling(), {}}; },
                                 [&](Local& local, std::size_t i) {
    if(local.band.metric_mesh().incident_faces(static_cast<std::uint32_t>(i)).empty())
      return; // isolated vertex: only itself
    add_center(local.band, Neighborhood_center::VERTEX, static_cast<std::uint32_t>(i));
    band_vertices(local.band, radius, result[i], local.seen);
  }, band.progress_callback(), "vertex neighbourhoods");
  return result;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the vertices within `radius` of every vertex, with their exact distances:
/// `neighborhoods[v]` receives those of `v` (an isolated vertex gets none); parallel as
/// `all_face_neighborhoods()`.
///
/// \tparam VertexNeighborhoodMap a model of `WritablePropertyMap` with vertex descriptors as key and
///   `std::vector<Neighborhood_vertex<vertex_descriptor>>` as value
///
/// Named parameters: the metric, `face_band_solver` and `callback`, as `geodesic_neighborhood()`.
template <class ConcurrencyTag = CGAL::Parallel_if_available_tag, class TriangleMesh, class VertexNeighborhoodMap,
          class NamedParameters = parameters::Default_named_parameters>
void all_vertex_neighborhoods(const TriangleMesh& tm, double radius, VertexNeighborhoodMap neighborhoods,
                              const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  internal::check_radius(radius);
  internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    const auto by_index = internal::vertex_neighborhoods_by_index<ConcurrencyTag>(band, radius);
    for(std::size_t i = 0; i < by_index.size(); ++i)
    {
      std::vector<Neighborhood_vertex<vertex_descriptor>> n;
      n.reserve(by_index[i].size());
      for(const auto& v : by_index[i])
        n.push_back({band.metric_mesh().vertex(v.first), v.second});
      put(neighborhoods, band.metric_mesh().vertex(i), std::move(n));
    }
    return 0;
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H
