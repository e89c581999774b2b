// A scale for the robust normals of a scanned mesh (see normal_smoothing_scale), from the mesh alone:
// its mean edge length and an estimate of its noise.
#ifndef CGAL_ISOPHOTIC_METRIC_SUGGESTED_NORMAL_SMOOTHING_SCALE_H
#define CGAL_ISOPHOTIC_METRIC_SUGGESTED_NORMAL_SMOOTHING_SCALE_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/internal/sphere_exact_vertex_normals.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricLift
/// The noise of a mesh and its mean edge length, as estimated by `estimate_mesh_noise()`.
struct Mesh_noise_estimate
{
  /// the mean length of the edges
  double mean_edge_length = 0.;
  /// the estimated standard deviation of the noise along the normal, a length
  double noise = 0.;
};

/// \ingroup PkgIsophoticMetricLift
///
/// \brief estimates the noise of `tm` along its normals.
///
/// At every interior vertex `v` with neighbours \f$ q_1 \dots q_k \f$, the offset
/// \f$ \delta(v) = n \cdot (p(v) - \frac{1}{k}\sum q_i) \f$ of the vertex from the centroid of its
/// neighbours along its normal `n` is, for independent Gaussian noise of deviation \f$ \sigma \f$ along the
/// normal, Gaussian of deviation \f$ \sigma\sqrt{1 + 1/k} \f$; on a clean surface it is of the order of
/// \f$ h^2\kappa \f$ (`h` the edge length, \f$ \kappa \f$ the curvature), and large only at the few vertices of
/// features. The estimate is the robust one, \f$ \hat\sigma = \mathrm{median}|\delta| / (0.6745\,\sqrt{1+1/k}) \f$,
/// which the vertices of features do not move as long as they are fewer than half.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the mesh
/// \param np an optional sequence of named parameters: `vertex_point_map` (as for `compute_lifted_embedding()`)
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Mesh_noise_estimate estimate_mesh_noise(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef boost::graph_traits<TriangleMesh> Graph_traits;

  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  Mesh_noise_estimate result;
  std::size_t nb_edges = 0;
  for(const auto e : edges(tm))
  {
    const std::array<double, 3> d = internal::difference(internal::to_array(get(vpm, source(e, tm))),
                                                         internal::to_array(get(vpm, target(e, tm))));
    result.mean_edge_length += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    ++nb_edges;
  }
  if(nb_edges == 0)
    return result;
  result.mean_edge_length /= double(nb_edges);

  std::vector<double> offsets;
  for(const auto v : vertices(tm))
  {
    const auto h0 = halfedge(v, tm);
    if(h0 == Graph_traits::null_halfedge() || is_border(v, tm))
      continue;
    const std::array<double, 3> n = internal::sphere_exact_vertex_normal(v, tm, vpm);
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if(!(length > 0.) || !std::isfinite(length))
      continue;
    std::array<double, 3> centroid = {0., 0., 0.};
    double k = 0.;
    for(const auto h : CGAL::halfedges_around_target(h0, tm))
    {
      const std::array<double, 3> q = internal::to_array(get(vpm, source(h, tm)));
      for(int i = 0; i < 3; ++i)
        centroid[i] += q[i];
      k += 1.;
    }
    const std::array<double, 3> d = internal::difference(internal::to_array(get(vpm, v)),
                                                         {centroid[0] / k, centroid[1] / k, centroid[2] / k});
    offsets.push_back(std::abs(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / length / std::sqrt(1. + 1. / k));
  }
  if(offsets.empty())
    return result;
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  result.noise = offsets[offsets.size() / 2] / 0.6745;
  return result;
}

/// \ingroup PkgIsophoticMetricLift
///
/// \brief returns a scale for `normal_smoothing_scale` (the radius of `estimate_vertex_normals()`)
/// suited to `tm`: `0` (no smoothing, the exact normals of a clean mesh) when the estimated noise
/// (`estimate_mesh_noise()`) is below 5 % of the mean edge length `h`, and `2h` otherwise.
///
/// Why: below 5 % of `h` the noise turns the normals by less than about 5 degrees per triangle, about the
/// error of the vertex normals of a clean curved mesh, and the exact normals are kept. Above, the filter
/// must average enough faces to bring the noise of the normals well below the turn of the normals across
/// one edge in the smooth regions; a radius of `2h` averages some 50 faces with weights above one half,
/// which on CAD meshes with noise of 0.1 to 0.35 `h` brings the figure of merit of morphology back to
/// that of the clean mesh (see the manual, section "Scans"). The trade-off: features narrower than the
/// radius are lost, a fillet of radius below about `2h` becomes a sharp edge and a bump smaller than
/// `2h` is smoothed away; larger radii remove stronger noise at the cost of more of them, and the cost
/// of the filter grows with the square of the radius.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the mesh
/// \param np an optional sequence of named parameters: `vertex_point_map` (as for `compute_lifted_embedding()`)
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
double suggested_normal_smoothing_scale(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  const Mesh_noise_estimate estimate = estimate_mesh_noise(tm, np);
  return estimate.noise < 0.05 * estimate.mean_edge_length ? 0. : 2. * estimate.mean_edge_length;
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_SUGGESTED_NORMAL_SMOOTHING_SCALE_H
