// Geodesic neighbourhoods (the structuring elements of the paper): the faces or vertices within a
// metric radius of a face, a vertex or a surface point, one at a time or for every element in parallel.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#endif

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
    case Neighborhood_center::FACE: band.add_source_region(std::vector<std::uint32_t>{index}); break;
    case Neighborhood_center::FACE_CENTROID:
      band.add_source(typename Face_band_solver<TriangleMesh>::Face_location(band.face(index), {{1.0 / 3, 1.0 / 3, 1.0 / 3}}));
      break;
    case Neighborhood_center::VERTEX: band.add_source(band.vertex(index)); break;
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
      result.push_back({v.face, {v.min_distance, v.covered_fraction}});
  });
}

// Vertices (indices) within the radius of the current sources, with their distances.
template <class TriangleMesh>
void band_vertices(Face_band_solver<TriangleMesh>& band, double radius, std::vector<std::pair<std::uint32_t, double>>& result,
                   std::vector<char>& seen)
{
  result.clear();
  seen.resize(band.number_of_vertices(), 0);
  std::vector<std::uint32_t> touched;
  band.visit_band(radius, false, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    for(std::uint32_t c : band.corners(v.face))
      if(!seen[c])
      {
        seen[c] = 1;
        touched.push_back(c);
        const double d = band.vertex_distance(c);
        if(d <= radius)
          result.push_back({c, d});
      }
  });
  for(std::uint32_t c : touched)
    seen[c] = 0;
}

// Runs task(band, element) for every element in [0, n), with a sibling solver per thread.
template <class TriangleMesh, class Task>
void for_each_element(Face_band_solver<TriangleMesh>& band, std::size_t n, bool parallel, Task&& task)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel)
  {
    tbb::enumerable_thread_specific<std::unique_ptr<Face_band_solver<TriangleMesh>>> solvers;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16), [&](const tbb::blocked_range<std::size_t>& range) {
      auto& local = solvers.local();
      if(!local)
        local = std::make_unique<Face_band_solver<TriangleMesh>>(band.sibling());
      for(std::size_t i = range.begin(); i != range.end(); ++i)
        task(*local, i);
    });
    return;
  }
#else
  (void)parallel;
#endif
  for(std::size_t i = 0; i < n; ++i)
    task(band, i);
}

template <class NamedParameters>
bool read_parallel(const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  return choose_parameter(get_parameter(np, internal_np::parallel_execution), true);
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
///   \cgalParamNBegin{face_band_solver} \cgalParamDescription{see `dilate_face_selection()`} \cgalParamNEnd
/// \cgalNamedParamsEnd
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
  const double fraction = parameters::choose_parameter(parameters::get_parameter(np, internal_np::area_fraction), 0.0);
  internal::check_area_fraction(fraction);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    band.clear_sources();
    if constexpr(std::is_same<Center, face_descriptor>::value)
      band.add_source_region(std::vector<std::uint32_t>{band.face_index(center)});
    else if constexpr(std::is_same<Center, vertex_descriptor>::value)
      band.add_source(center);
    else
      band.add_source(center);
    std::vector<std::pair<std::uint32_t, std::array<double, 2>>> faces;
    internal::band_faces(band, radius, fraction, false, faces);
    for(const auto& f : faces)
      *out++ = Neighborhood_face<face_descriptor>{band.face(f.first), f.second[0], f.second[1]};
    return out;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief writes the vertices within `radius` of a vertex, with their exact distances.
/// \tparam OutputIterator an output iterator accepting `Neighborhood_vertex<vertex_descriptor>`
/// Named parameters: the metric and `face_band_solver`, as `geodesic_neighborhood()`.
template <class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
OutputIterator geodesic_vertex_neighborhood(typename boost::graph_traits<TriangleMesh>::vertex_descriptor center,
                                            const TriangleMesh& tm, double radius, OutputIterator out,
                                            const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  internal::check_radius(radius);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    band.clear_sources();
    band.add_source(center);
    std::vector<std::pair<std::uint32_t, double>> vs;
    std::vector<char> seen;
    internal::band_vertices(band, radius, vs, seen);
    for(const auto& v : vs)
      *out++ = Neighborhood_vertex<vertex_descriptor>{band.vertex(v.first), v.second};
    return out;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the neighbourhood of every face, as lists of face indices (positions in `faces(tm)`)
/// with the smallest distance found on them (see `Neighborhood_face`): entry `i` lists the faces meeting the disc of radius `radius` centred
/// at face `i` (`Neighborhood_center::FACE`: the closed face; `FACE_CENTROID`: its centroid).
///
/// One bounded propagation per face, run in parallel with TBB (one sibling solver per thread) when
/// `CGAL_LINKED_WITH_TBB` is defined and `parallel_execution` is `true` (default); the results do not
/// depend on it.
///
/// Named parameters: those of `geodesic_neighborhood()`, plus `parallel_execution` (`bool`).
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::vector<std::vector<std::pair<std::uint32_t, double>>>
all_face_neighborhoods(const TriangleMesh& tm, double radius, Neighborhood_center center = Neighborhood_center::FACE,
                       const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const double fraction = parameters::choose_parameter(parameters::get_parameter(np, internal_np::area_fraction), 0.0);
  internal::check_area_fraction(fraction);
  if(center == Neighborhood_center::VERTEX)
    throw Invalid_parameter_error("all_face_neighborhoods: the centre must be a face or a face centroid");
  const bool parallel = internal::read_parallel(np);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    std::vector<std::vector<std::pair<std::uint32_t, double>>> result(band.number_of_faces());
    internal::for_each_element(band, band.number_of_faces(), parallel, [&](Face_band_solver<TriangleMesh>& local, std::size_t i) {
      internal::add_center(local, center, static_cast<std::uint32_t>(i));
      std::vector<std::pair<std::uint32_t, std::array<double, 2>>> faces;
      internal::band_faces(local, radius, fraction, false, faces);
      result[i].reserve(faces.size());
      for(const auto& f : faces)
        result[i].push_back({f.first, f.second[0]});
    });
    return result;
  });
}

/// \ingroup PkgIsophoticMetricMorphology
///
/// \brief the vertices within `radius` of every vertex, as lists of vertex indices (positions in
/// `vertices(tm)`) with their exact distances; parallel as `all_face_neighborhoods()`.
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::vector<std::vector<std::pair<std::uint32_t, double>>>
all_vertex_neighborhoods(const TriangleMesh& tm, double radius, const NamedParameters& np = parameters::default_values())
{
  internal::check_radius(radius);
  const bool parallel = internal::read_parallel(np);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    std::vector<std::vector<std::pair<std::uint32_t, double>>> result(band.number_of_vertices());
#ifdef CGAL_LINKED_WITH_TBB
    tbb::enumerable_thread_specific<std::vector<char>> seen_per_thread;
#endif
    std::vector<char> seen_serial;
    internal::for_each_element(band, band.number_of_vertices(), parallel, [&](Face_band_solver<TriangleMesh>& local, std::size_t i) {
      auto range = local.incident_faces(static_cast<std::uint32_t>(i));
      if(range.first == range.second)
        return; // isolated vertex: only itself
#ifdef CGAL_LINKED_WITH_TBB
      std::vector<char>& seen = parallel ? seen_per_thread.local() : seen_serial;
#else
      std::vector<char>& seen = seen_serial;
#endif
      internal::add_center(local, Neighborhood_center::VERTEX, static_cast<std::uint32_t>(i));
      internal::band_vertices(local, radius, result[i], seen);
    });
    return result;
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_GEODESIC_NEIGHBORHOODS_H
