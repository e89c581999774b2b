// Region growing in the isophotic metric: growth from seed faces that stops at features, geodesic
// Voronoi partition from several seeds, and a greedy segmentation built on them.
#ifndef CGAL_ISOPHOTIC_METRIC_REGION_GROWING_H
#define CGAL_ISOPHOTIC_METRIC_REGION_GROWING_H

#include <CGAL/Isophotic_metric/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/face_selection_morphology.h>

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// Faces reached from `seeds` (indices) within `radius`, passing `accept`, with at least `fraction` of
// their area within the radius, and connected to the seeds across edges through such faces.
template <class TriangleMesh, class Accept>
std::vector<std::uint32_t> grow_connected(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& seeds,
                                          double radius, double fraction, Accept&& accept)
{
  band.clear_sources();
  band.add_source_region(seeds);
  std::vector<char> reached(band.number_of_faces(), 0);
  std::vector<std::uint32_t> reached_list;
  band.visit_band(radius, fraction > 0, false, [&](const typename Face_band_solver<TriangleMesh>::Face_visit& v) {
    if((fraction == 0 || v.covered_fraction >= fraction) && accept(v.face))
    {
      reached[v.face] = 1;
      reached_list.push_back(v.face);
    }
  });
  for(std::uint32_t s : seeds)
    reached[s] = 1;
  // keep what is edge-connected to the seeds
  const TriangleMesh& tm = band.mesh();
  std::vector<char> kept(band.number_of_faces(), 0);
  std::vector<std::uint32_t> queue(seeds.begin(), seeds.end());
  for(std::uint32_t s : seeds)
    kept[s] = 1;
  for(std::size_t i = 0; i < queue.size(); ++i)
    for(auto h : CGAL::halfedges_around_face(halfedge(band.face(queue[i]), tm), tm))
    {
      const auto o = opposite(h, tm);
      if(is_border(o, tm))
        continue;
      const std::uint32_t g = band.face_index(face(o, tm));
      if(reached[g] && !kept[g])
      {
        kept[g] = 1;
        queue.push_back(g);
      }
    }
  for(std::uint32_t f : reached_list)
    reached[f] = 0;
  return queue;
}

template <class NamedParameters>
double read_region_fraction(const NamedParameters& np)
{
  const double a = parameters::choose_parameter(parameters::get_parameter(np, internal_np::area_fraction), 0.5);
  check_area_fraction(a);
  return a;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief grows a region from seed faces in the isophotic metric: the faces within `radius` of the
/// seeds that pass the optional predicate and are connected to the seeds across edges through such
/// faces. Because crossing a sharp edge or a fillet is long in the isophotic metric, the region spreads
/// along features and stops at them.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{face_predicate}
///     \cgalParamDescription{a callable `bool(face_descriptor)`: faces for which it is `false` never join
///       (e.g. a normal-deviation or curvature test)} \cgalParamDefault{every face may join} \cgalParamNEnd
///   \cgalParamNBegin{area_fraction} \cgalParamDescription{fraction of a face's area that must lie within
///     `radius`} \cgalParamDefault{`0.5`} \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, face_band_solver}
///     \cgalParamDescription{the metric, see `dilate_face_selection()`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \returns `out` after the faces of the region (the seeds first)
template <class FaceRange, class TriangleMesh, class OutputIterator, class NamedParameters = parameters::Default_named_parameters>
OutputIterator grow_region(const FaceRange& seeds, const TriangleMesh& tm, double radius, OutputIterator out,
                           const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_region_fraction(np);
  const std::function<bool(face_descriptor)> all = [](face_descriptor) { return true; };
  const auto predicate = parameters::choose_parameter(parameters::get_parameter(np, internal_np::face_predicate), all);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) {
    const std::vector<std::uint32_t> seed_ids = internal::face_indices(band, seeds);
    if(seed_ids.empty())
      return out;
    for(std::uint32_t f : internal::grow_connected(band, seed_ids, radius, fraction,
                                                   [&](std::uint32_t f) { return bool(predicate(band.face(f))); }))
      *out++ = band.face(f);
    return out;
  });
}

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief partitions the faces by their nearest seed in the isophotic metric (a geodesic Voronoi
/// partition): seed `i` (a range of faces, the `i`-th element of `seeds`) is source `i`, and every face
/// whose centroid is within `max_distance` (default: no bound) takes the index of the seed nearest to its
/// centroid. Faces beyond the bound, or unreachable, get `seeds.size()`. One propagation in all.
///
/// \tparam SeedRange a range of ranges of face descriptors
/// \tparam FacePatchMap a writable property map from faces to an integer type
/// \returns the number of faces assigned to a seed
template <class SeedRange, class TriangleMesh, class FacePatchMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t partition_by_nearest_seed(const SeedRange& seeds, const TriangleMesh& tm, FacePatchMap patch,
                                      const NamedParameters& np = parameters::default_values())
{
  const double max_distance = parameters::choose_parameter(parameters::get_parameter(np, internal_np::max_distance),
                                                           std::numeric_limits<double>::infinity());
  if(!(max_distance >= 0))
    throw Invalid_parameter_error("max_distance must be non-negative (got " + std::to_string(max_distance) + ")");
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    band.clear_sources();
    std::size_t n = 0;
    for(const auto& seed : seeds)
    {
      const std::vector<std::uint32_t> ids = internal::face_indices(band, seed);
      if(ids.empty())
        throw Invalid_source_error("seed " + std::to_string(n) + " has no face");
      band.add_source_region(ids);
      ++n;
    }
    std::size_t assigned = 0;
    if(n == 0)
      return 0;
    band.propagate_to(max_distance);
    for(std::uint32_t f = 0; f < band.number_of_faces(); ++f)
    {
      const typename Face_band_solver<TriangleMesh>::Face_location c(band.face(f), {{1.0 / 3, 1.0 / 3, 1.0 / 3}});
      const std::size_t label = band.geodesic_solver().nearest_source(c);
      const bool ok = label != Face_band_solver<TriangleMesh>::no_source && band.geodesic_solver().distance(c) <= max_distance;
      put(patch, band.face(f), ok ? label : n);
      assigned += ok;
    }
    return assigned;
  });
}

/// \ingroup PkgIsophoticMetricRegionGrowing
///
/// \brief segments the mesh greedily by region growing in the isophotic metric: the unassigned face of
/// largest area seeds a region grown by `grow_region()` with radius `radius` among the unassigned faces,
/// which becomes a patch; repeated until every face is assigned. Patch indices start at 0, in the order
/// of creation. Named parameters as `grow_region()`. Returns the number of patches.
template <class TriangleMesh, class FacePatchMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t segment_by_region_growing(const TriangleMesh& tm, double radius, FacePatchMap patch,
                                      const NamedParameters& np = parameters::default_values())
{
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  internal::check_radius(radius);
  const double fraction = internal::read_region_fraction(np);
  const std::function<bool(face_descriptor)> all = [](face_descriptor) { return true; };
  const auto predicate = parameters::choose_parameter(parameters::get_parameter(np, internal_np::face_predicate), all);
  return internal::with_band_solver(tm, np, [&](Face_band_solver<TriangleMesh>& band) -> std::size_t {
    const std::size_t nf = band.number_of_faces();
    std::vector<double> area(nf);
    for(std::uint32_t f = 0; f < nf; ++f)
      area[f] = CGAL::Polygon_mesh_processing::face_area(band.face(f), tm);
    std::vector<std::uint32_t> order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return area[a] > area[b]; });
    const std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::size_t> assigned(nf, none);
    std::size_t patches = 0;
    for(std::uint32_t seed : order)
    {
      if(assigned[seed] != none)
        continue;
      const std::vector<std::uint32_t> region = internal::grow_connected(band, {seed}, radius, fraction, [&](std::uint32_t f) {
        return assigned[f] == none && bool(predicate(band.face(f)));
      });
      for(std::uint32_t f : region)
        assigned[f] = patches;
      ++patches;
    }
    for(std::uint32_t f = 0; f < nf; ++f)
      put(patch, band.face(f), assigned[f]);
    return patches;
  });
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_REGION_GROWING_H
