// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The R^6 lift of a triangle mesh (Remark 1 of Pottmann et al. 2004): X(v) = (sqrt(w) p(v), sqrt(w') n(v)).
// The Euclidean metric of R^6 restricted to the lifted mesh is the isophotic metric of the mesh.
#ifndef CGAL_ISOPHOTIC_METRIC_COMPUTE_LIFTED_EMBEDDING_H
#define CGAL_ISOPHOTIC_METRIC_COMPUTE_LIFTED_EMBEDDING_H

#include <CGAL/Isophotic_metric/estimate_vertex_normals.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>
#include <CGAL/Isophotic_metric/internal/Element_number_map.h>
#include <CGAL/Isophotic_metric/internal/sphere_exact_vertex_normals.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricLift
/// A point of the lifted embedding in \f$ \mathbb{R}^6 \f$: three positional coordinates
/// \f$ \sqrt{w}\,p \f$ followed by three normal coordinates \f$ \sqrt{w'}\,n \f$.
typedef std::array<double, 6> Lifted_point;

namespace internal {

// A weight given either as a number (the same at every vertex) or as a per-vertex property map.
template <typename Weight, bool is_number = std::is_arithmetic<Weight>::value>
struct Vertex_weight
{
  static constexpr bool is_constant = true;
  Weight value;
  template <typename Vertex> double operator()(const Vertex&) const { return static_cast<double>(value); }
};

template <typename WeightMap>
struct Vertex_weight<WeightMap, false>
{
  static constexpr bool is_constant = false;
  WeightMap map;
  template <typename Vertex> double operator()(const Vertex& v) const { return CGAL::to_double(get(map, v)); }
};

template <typename Weight>
Vertex_weight<Weight> make_vertex_weight(const Weight& w) { return Vertex_weight<Weight>{w}; }

inline bool is_valid_weight(double w) { return std::isfinite(w) && w >= 0.; }

inline double squared_distance(const Lifted_point& a, const Lifted_point& b)
{
  double s = 0.;
  for(int i = 0; i < 6; ++i)
    s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

inline double squared_norm(const Lifted_point& a)
{
  double s = 0.;
  for(int i = 0; i < 6; ++i)
    s += a[i] * a[i];
  return s;
}

// Euclidean norm of a vector of R^N without overflow or underflow of its squares (models at
// 1e200 or 1e-200 have squared lengths beyond the double range): the components are divided by
// the largest one first.
template <std::size_t N>
double stable_norm(const std::array<double, N>& a)
{
  double largest = 0.;
  for(double x : a)
    largest = (std::max)(largest, std::abs(x));
  if(largest == 0. || !std::isfinite(largest))
    return largest;
  double s = 0.;
  if(largest > 1e-150 && largest < 1e150) // squares in range: the plain sum
  {
    for(double x : a)
      s += x * x;
    return std::sqrt(s);
  }
  const double inverse = 1. / largest; // (a power of two would be exact; this is one rounding)
  for(double x : a)
    s += (x * inverse) * (x * inverse);
  return largest * std::sqrt(s);
}

// Length of the lifted edge from `a` to `b`, for any scale of the model.
inline double distance(const Lifted_point& a, const Lifted_point& b)
{
  Lifted_point d;
  for(int i = 0; i < 6; ++i)
    d[i] = a[i] - b[i];
  return stable_norm(d);
}

// Where the positional part of the lift is taken from: the origin for a constant positional
// weight, the centroid of the vertices for a varying one (see compute_lifted_embedding()).
template <typename TriangleMesh, typename VertexPointMap, typename Weight>
std::array<double, 3> lift_center(const TriangleMesh& tm, const VertexPointMap& vpm, const Weight&)
{
  std::array<double, 3> center = {0., 0., 0.};
  if(Weight::is_constant)
    return center;
  std::size_t n = 0;
  for(auto v : vertices(tm))
  {
    const auto& p = get(vpm, v);
    center[0] += CGAL::to_double(p.x());
    center[1] += CGAL::to_double(p.y());
    center[2] += CGAL::to_double(p.z());
    ++n;
  }
  for(double& c : center)
    c /= (n > 0 ? double(n) : 1.);
  return center;
}

// The length of every lifted edge, as a function of its two vertices. The positional part is
// formed from p(u) - p(v), not as the difference of the lifted coordinates sqrt(w) p: that
// difference loses the digits of a short edge far from the origin (a needle of width 1e-12 a
// hundred edge lengths away: a few percent of its length, and a spurious zero-length error).
// sqrt(w_u)(p_u - c) - sqrt(w_v)(p_v - c) = sqrt(w_u)(p_u - p_v) + (sqrt(w_u) - sqrt(w_v))(p_v - c).
template <typename TriangleMesh, typename LiftedPointMap, typename NamedParameters>
auto lifted_edge_length(const TriangleMesh& tm, const LiftedPointMap& lifted, const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  const auto w = make_vertex_weight(choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.));
  typedef decltype(w) Weight;
  const std::array<double, 3> center = lift_center(tm, vpm, w);
  // (the square root of a constant weight once, not twice per edge)
  const double constant_sqrt_w =
    Weight::is_constant ? std::sqrt(w(typename boost::graph_traits<TriangleMesh>::vertex_descriptor())) : 0.;
  return [lifted, vpm, w, center, constant_sqrt_w](auto u, auto v) {
    const std::array<double, 3> pu = to_array(get(vpm, u)), pv = to_array(get(vpm, v));
    const double sw_u = Weight::is_constant ? constant_sqrt_w : std::sqrt(w(u));
    const double sw_v = Weight::is_constant ? constant_sqrt_w : std::sqrt(w(v));
    const Lifted_point& xu = get(lifted, u);
    const Lifted_point& xv = get(lifted, v);
    Lifted_point d;
    for(int i = 0; i < 3; ++i)
    {
      d[i] = sw_u * (pu[i] - pv[i]) + (sw_u - sw_v) * (pv[i] - center[i]);
      d[3 + i] = xu[3 + i] - xv[3 + i];
    }
    return stable_norm(d);
  };
}

} // namespace internal

namespace internal {

// Whether a lifted edge of length `length` between lifted points `a` and `b` counts as of zero
// length (up to rounding), which would make lifted triangles degenerate. (A positive w gives every
// edge of non-zero length a positive lifted length; with w = 0 at both ends the normal part is
// compared with the rounding of the normals.)
inline bool is_zero_lifted_length(double length, bool no_positional_weight, const Lifted_point& a, const Lifted_point& b)
{
  const double rounding = 64. * std::numeric_limits<double>::epsilon();
  return length == 0. ||
         (no_positional_weight && length <= rounding * (std::max)(internal::stable_norm(a), internal::stable_norm(b)));
}

// A read-only map from the vertices to their lifted points, stored in the order of vertices(tm).
template <typename TriangleMesh>
struct Lifted_point_vector_map
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor key_type;
  typedef Lifted_point value_type;
  typedef const Lifted_point& reference;
  typedef boost::readable_property_map_tag category;

  const Huge_page_vector<Lifted_point>* points;
  const Vertex_number_map<TriangleMesh>* position; // of a vertex in vertices(tm)

  friend const Lifted_point& get(const Lifted_point_vector_map& m, key_type v) { return (*m.points)[get(*m.position, v)]; }
};

// Throws for the first edge of edges(tm) whose lifted length is zero (up to rounding), if any.
template <typename TriangleMesh, typename LiftedPointMap, typename NamedParameters>
void check_lifted_edge_lengths(const TriangleMesh& tm, const LiftedPointMap& lifted, const NamedParameters& np)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const auto vidx = CGAL::get_initialized_vertex_index_map(tm);
  const auto w = make_vertex_weight(choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.));
  const auto lifted_length = internal::lifted_edge_length(tm, lifted, np);
  for(auto e : edges(tm))
  {
    const auto a = source(e, tm), b = target(e, tm);
    if(is_zero_lifted_length(lifted_length(a, b), w(a) == 0. && w(b) == 0., get(lifted, a), get(lifted, b)))
      throw Invalid_mesh_error(message("edge (", get(vidx, a), ", ", get(vidx, b),
                                       ") has zero length in the lifted embedding (for example w = 0 on a "
                                       "flat region, or w = 0 at both vertices with equal normals)"));
  }
}

// The lifted point of every vertex of `range` (`count` of them: vertices(tm), or those of a region),
// in its order, on a mesh that already passed validate_triangle_mesh() (around those vertices),
// after checking the weights and normals (not the lifted edges: see check_lifted_edge_lengths()).
// The prepared mesh validates once and lifts without a second pass over the mesh.
template <typename TriangleMesh, typename NamedParameters, typename VertexRange>
Huge_page_vector<Lifted_point> lift_vertices(const TriangleMesh& tm, const NamedParameters& np, const VertexRange& range,
                                             std::size_t count)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::is_default_parameter;
  using internal::message;

  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;

  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  const auto vidx = CGAL::get_initialized_vertex_index_map(tm);

  const auto w = internal::make_vertex_weight(
    choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.));
  const auto w_iso = internal::make_vertex_weight(
    choose_parameter(get_parameter(np, internal_np::isophotic_weight), 1.));
  // Default length scale: the bounding-box diagonal, so that the weights do not depend on the units.
  double L = 1.;
  if constexpr(is_default_parameter<NamedParameters, internal_np::weight_length_scale_t>::value)
  {
    const double diagonal = suggested_weight_length_scale(tm, np);
    if(diagonal > 0.)
      L = diagonal;
  }
  else
    L = CGAL::to_double(get_parameter(np, internal_np::weight_length_scale));

  if(!(std::isfinite(L) && L > 0.))
    throw Invalid_parameter_error(message("weight_length_scale is ", L, "; it must be finite and positive"));

  // Constant weights are checked once, naming the parameter; weight maps per vertex, below.
  if(decltype(w)::is_constant && !internal::is_valid_weight(w(vertex_descriptor())))
    throw Invalid_parameter_error(message("euclidean_weight is ", w(vertex_descriptor()),
                                          "; it must be finite and non-negative"));
  if(decltype(w_iso)::is_constant && !internal::is_valid_weight(w_iso(vertex_descriptor())))
    throw Invalid_parameter_error(message("isophotic_weight is ", w_iso(vertex_descriptor()),
                                          "; it must be finite and non-negative"));
  if(decltype(w)::is_constant && decltype(w_iso)::is_constant &&
     w(vertex_descriptor()) == 0. && w_iso(vertex_descriptor()) == 0.)
    throw Invalid_parameter_error("euclidean_weight and isophotic_weight are both zero; "
                                  "at least one must be positive");

  // Normals: the user's, or Max's weighted sum of face normals (exact on spheres, see
  // internal/sphere_exact_vertex_normals.h for why not PMP::compute_vertex_normals).
  constexpr bool normals_given = !is_default_parameter<NamedParameters, CGAL::internal_np::vertex_normal_map_t>::value;
  const auto user_normals = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_normal_map), 0);
  // Noisy meshes: normals filtered at a scale (estimate_vertex_normals.h); 0 keeps Max's normals.
  const double smoothing = CGAL::to_double(choose_parameter(get_parameter(np, internal_np::normal_smoothing_scale), 0.));
  static_assert(!normals_given || is_default_parameter<NamedParameters, internal_np::normal_smoothing_scale_t>::value,
                "normal_smoothing_scale computes the normals: it cannot be combined with vertex_normal_map");
  if(!(std::isfinite(smoothing) && smoothing >= 0.))
    throw Invalid_parameter_error(message("normal_smoothing_scale is ", smoothing, "; it must be finite and non-negative"));
  typedef typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<std::array<double, 3>>>::const_type
    Smoothed_normal_map;
  std::optional<Smoothed_normal_map> smoothed_normals; // (a property only when smoothing)
  if(smoothing > 0.)
  {
    smoothed_normals = get(CGAL::dynamic_vertex_property_t<std::array<double, 3>>(), tm);
    // on all threads when TBB is linked: the normals do not depend on it, bit for bit
    internal::estimate_vertex_normals<CGAL::Parallel_if_available_tag>(tm, smoothing, *smoothed_normals, np,
                                                                       false); // tm is validated
  }
  auto normal_of = [&](vertex_descriptor v) -> std::array<double, 3> {
    if constexpr(normals_given)
    {
      const auto& n = get(user_normals, v);
      return {CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z())};
    }
    else if(smoothing > 0.)
      return get(*smoothed_normals, v);
    else
      return internal::sphere_exact_vertex_normal(v, tm, vpm);
  };

  // Varying positional weight: lift relative to the centroid, so lengths do not depend on the origin.
  const std::array<double, 3> center = internal::lift_center(tm, vpm, w);

  Huge_page_vector<Lifted_point> lifted;
  lifted.reserve(count);
  for(vertex_descriptor v : range)
  {
    const double wv = w(v), wv_iso = w_iso(v);
    if(!internal::is_valid_weight(wv))
      throw Invalid_parameter_error(message("euclidean_weight at vertex ", get(vidx, v), " is ", wv,
                                            "; it must be finite and non-negative"));
    if(!internal::is_valid_weight(wv_iso))
      throw Invalid_parameter_error(message("isophotic_weight at vertex ", get(vidx, v), " is ", wv_iso,
                                            "; it must be finite and non-negative"));
    if(wv == 0. && wv_iso == 0.)
      throw Invalid_parameter_error(message("euclidean_weight and isophotic_weight are both zero at vertex ",
                                            get(vidx, v), "; at least one must be positive"));

    std::array<double, 3> unit_normal = {0., 0., 0.};
    if(halfedge(v, tm) != Graph_traits::null_halfedge()) // isolated vertices keep a zero normal part
    {
      const std::array<double, 3> nv = normal_of(v);
      const double nx = nv[0], ny = nv[1], nz = nv[2];
      const double length = internal::stable_norm(nv);
      if(!std::isfinite(length))
        throw Invalid_mesh_error(message("vertex ", get(vidx, v), " has a non-finite normal (",
                                         nx, ", ", ny, ", ", nz, ")"));
      if(length == 0.)
        throw Invalid_mesh_error(message("vertex ", get(vidx, v), " has a zero normal",
                                         normals_given ? std::string()
                                                       : std::string(" (its incident faces are degenerate: ") +
                                                           internal::scan_repair_hint + ")"));
      unit_normal = {nx / length, ny / length, nz / length};
    }

    const auto& p = get(vpm, v);
    const double sw = std::sqrt(wv), sn = std::sqrt(wv_iso) * L;
    lifted.push_back(Lifted_point{sw * (CGAL::to_double(p.x()) - center[0]),
                                  sw * (CGAL::to_double(p.y()) - center[1]),
                                  sw * (CGAL::to_double(p.z()) - center[2]),
                                  sn * unit_normal[0], sn * unit_normal[1], sn * unit_normal[2]});
  }
  return lifted;
}

// compute_lifted_embedding() on a mesh that already passed validate_triangle_mesh().
template <typename TriangleMesh, typename LiftedPointMap, typename NamedParameters>
void lift_validated_mesh(const TriangleMesh& tm, LiftedPointMap lifted, const NamedParameters& np)
{
  // Lifted points are written to `lifted` only once every check passed.
  const Huge_page_vector<Lifted_point> points = lift_vertices(tm, np, vertices(tm), static_cast<std::size_t>(num_vertices(tm)));
  Vertex_number_map<TriangleMesh> position(tm);
  std::uint32_t i = 0;
  for(auto v : vertices(tm))
    put(position, v, i++);
  check_lifted_edge_lengths(tm, Lifted_point_vector_map<TriangleMesh>{&points, &position}, np);
  i = 0;
  for(auto v : vertices(tm))
    put(lifted, v, points[i++]);
}

} // namespace internal

/// \ingroup PkgIsophoticMetricLift
///
/// \brief computes the lifted embedding of a triangle mesh: every vertex `v` with position `p` and
/// unit normal `n` goes to the point \f$ X(v) = (\sqrt{w}\,p,\ \sqrt{w'}\,L\,n) \in \mathbb{R}^6 \f$.
///
/// The Euclidean metric of \f$ \mathbb{R}^6 \f$ restricted to the lifted surface is the
/// regularized isophotic metric \f$ ds_i^2 = w\,ds^2 + w'\,ds^{*2} \f$ (Remark 1 of the paper):
/// `ds` is arc length on the surface and `ds*` arc length of its Gaussian image.
/// Every lifted triangle is flat (it spans a 2-plane of \f$ \mathbb{R}^6 \f$), so the lifted mesh is a
/// polyhedral surface whose exact geodesics depend only on its edge lengths
/// \f$ \ell(uv) = \sqrt{w\,\|p_u-p_v\|^2 + w' L^2 \|n_u-n_v\|^2} \f$. Along an edge the normal part
/// measures the chord \f$ \|n_u-n_v\| = 2\sin(\theta/2) \f$ of the angle \f$ \theta \f$ between the
/// normals, which tends to the great-circle arc \f$ \theta \f$ of the continuous metric under refinement.
///
/// <b>Weights.</b> In the paper `w` multiplies a squared length and `w'` a squared angle, so their
/// balance depends on the size of the model. Here the normal part is multiplied by a length `L`,
/// by default the diagonal of the bounding box (`suggested_weight_length_scale()`): `w` and `w'` are
/// then dimensionless and mean the same whatever the model's units (scaling a model by `s` scales
/// every lifted distance by `s`). `weight_length_scale(1)` gives the paper's raw metric.
///
/// <b>Spatially varying weights.</b> `w` and `w'` may be per-vertex property maps (functions on the
/// surface, as the paper allows). The lift stays per vertex, with the weights of that vertex, so every
/// lifted triangle is still flat and distances are those of the lifted polyhedron. The positional part is
/// then taken relative to the centroid `c` of the vertices, \f$ \sqrt{w(v)}\,(p-c) \f$, so that lifted
/// distances do not depend on where the model sits in space. This discretises the metric
/// \f$ \|d(\sqrt{w}\,(x-c))\|^2 + L^2\|d(\sqrt{w'}\,n)\|^2 \f$, which equals \f$ w\,ds^2 + w'L^2\,ds^{*2} \f$
/// plus terms in the derivatives of \f$ \sqrt{w} \f$ and \f$ \sqrt{w'} \f$: close to the isophotic
/// metric where the weights vary slowly over the size of the model, exact for constant weights.
/// With constant weights `c` is the origin, and the lift is literally the formula above.
///
/// Isolated vertices have no normal: their normal part is zero (no edge uses them).
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam LiftedPointMap a model of `WritablePropertyMap` with
///         `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and `Lifted_point` as
///         value type, for example `get(CGAL::dynamic_vertex_property_t<Lifted_point>(), tm)`
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the triangle mesh; see `validate_triangle_mesh()` for what it may and may not contain
/// \param lifted the property map receiving the lifted point of every vertex
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a class model of `ReadablePropertyMap` with
///                    `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    `%Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_normal_map}
///     \cgalParamDescription{a property map associating a normal to every vertex of `tm`;
///                           the normals are normalized before use}
///     \cgalParamType{a class model of `ReadablePropertyMap` with
///                    `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    `%Vector_3` as value type}
///     \cgalParamDefault{the weighted sum of the incident face normals of Max (1999), with the
///                       weight \f$ \sin\alpha / (\|e_1\|\,\|e_2\|) \f$ per face (\f$ \alpha \f$
///                       the angle at the vertex between the edges \f$ e_1, e_2 \f$): exact when the
///                       vertex and its neighbours lie on a common sphere, second-order accurate on
///                       smooth surfaces. `CGAL::Polygon_mesh_processing::compute_vertex_normals()`
///                       is not used by default because its error does not decrease under refinement;
///                       pass its result here to use it.}
///   \cgalParamNEnd
///   \cgalParamNBegin{normal_smoothing_scale}
///     \cgalParamDescription{for noisy meshes (scans): the scale \f$ \rho \f$ of the default vertex
///                           normals, computed by `estimate_vertex_normals()` at that scale
///                           (its `normal_range`, `number_of_iterations`, `use_patch_guidance` and `number_of_vertex_updates` are read from `np`),
///                           with `CGAL::Parallel_if_available_tag`: on TBB's threads when
///                           `CGAL_LINKED_WITH_TBB` is defined, the same normals bit for bit as on one;
///                           `0` keeps the normals of a clean mesh described above}
///     \cgalParamType{a number}
///     \cgalParamDefault{`0`}
///     \cgalParamExtra{Must be finite and non-negative. Cannot be combined with `vertex_normal_map`.
///                     See `suggested_normal_smoothing_scale()`.}
///   \cgalParamNEnd
///   \cgalParamNBegin{euclidean_weight}
///     \cgalParamDescription{the weight `w` of the squared surface arc length}
///     \cgalParamType{a number (any arithmetic type), or a class model of `ReadablePropertyMap`
///                    with `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    a number as value type}
///     \cgalParamDefault{`1`}
///     \cgalParamExtra{Must be finite and non-negative.}
///   \cgalParamNEnd
///   \cgalParamNBegin{isophotic_weight}
///     \cgalParamDescription{the weight `w'` of the squared arc length of the Gaussian image}
///     \cgalParamType{as for `euclidean_weight`}
///     \cgalParamDefault{`1`}
///     \cgalParamExtra{Must be finite and non-negative; `w` and `w'` must not both vanish at a vertex.}
///   \cgalParamNEnd
///   \cgalParamNBegin{weight_length_scale}
///     \cgalParamDescription{the length `L` that makes the weights dimensionless}
///     \cgalParamType{a number}
///     \cgalParamDefault{`suggested_weight_length_scale(tm)`, the bounding-box diagonal (`1` when
///                       it is zero: a mesh without extent)}
///     \cgalParamExtra{Must be finite and positive. `1` gives the weights of the paper.}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_mesh_error if `tm` fails `validate_triangle_mesh()`, if a normal is not finite or
///         zero, or if a lifted edge has zero length (for example a flat region with `w = 0`).
/// \throws Invalid_parameter_error if a weight is negative or not finite, if `w = w' = 0`, or if
///         `L` is not finite and positive.
///
/// \sa `edge_isophotic_length()`, `polyline_isophotic_length()`
template <typename TriangleMesh, typename LiftedPointMap,
          typename NamedParameters = parameters::Default_named_parameters>
void compute_lifted_embedding(const TriangleMesh& tm,
                              LiftedPointMap lifted,
                              const NamedParameters& np = parameters::default_values())
{
  validate_triangle_mesh(tm, np);
  internal::lift_validated_mesh(tm, lifted, np);
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_COMPUTE_LIFTED_EMBEDDING_H
