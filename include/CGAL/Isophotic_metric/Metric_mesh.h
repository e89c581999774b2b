// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The prepared mesh: a triangle mesh numbered once, validated once, with the metric's edge lengths
// computed once (from the R^6 lift, from 3D positions, or given by the user), shared by every
// solver of the package.
#ifndef CGAL_ISOPHOTIC_METRIC_METRIC_MESH_H
#define CGAL_ISOPHOTIC_METRIC_METRIC_MESH_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/internal/Element_number_map.h>
#include <CGAL/Isophotic_metric/internal/Reach_region.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Intrinsic_triangle_mesh.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// Whether a weight is given as a number equal to x (the Euclidean special case needs no normals).
template <class T>
bool is_number_equal_to(const T& value, double x)
{
  if constexpr(std::is_arithmetic<T>::value)
    return static_cast<double>(value) == x;
  else
    return false;
}

// Length of the edge from u to v read from a user's map keyed by halfedges or by edges.
template <class TriangleMesh, class EdgeLengthMap>
double read_edge_length(const EdgeLengthMap& lengths, typename boost::graph_traits<TriangleMesh>::vertex_descriptor u,
                        typename boost::graph_traits<TriangleMesh>::vertex_descriptor v, const TriangleMesh& tm)
{
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::property_traits<EdgeLengthMap>::key_type Key;
  const halfedge_descriptor h = halfedge(u, v, tm).first;
  if constexpr(std::is_same<Key, halfedge_descriptor>::value)
    return CGAL::to_double(get(lengths, h));
  else
    return CGAL::to_double(get(lengths, edge(h, tm)));
}

// A halfedge-keyed length map must give both halfedges of an inner edge the same length.
template <class TriangleMesh, class EdgeLengthMap>
void check_halfedge_lengths_agree(const EdgeLengthMap& lengths, const TriangleMesh& tm)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  if constexpr(std::is_same<typename boost::property_traits<EdgeLengthMap>::key_type,
                            typename GT::halfedge_descriptor>::value)
  {
    const auto vidx = CGAL::get_initialized_vertex_index_map(tm);
    for(typename GT::edge_descriptor e : edges(tm))
    {
      const typename GT::halfedge_descriptor h = halfedge(e, tm), o = opposite(h, tm);
      if(is_border(h, tm) || is_border(o, tm))
        continue;
      const double a = CGAL::to_double(get(lengths, h)), b = CGAL::to_double(get(lengths, o));
      if(!(a == b))
        throw Invalid_parameter_error(message("edge_length_map gives the two halfedges of edge (", get(vidx, source(h, tm)),
                                              ", ", get(vidx, target(h, tm)), ") different lengths (", a, " and ", b,
                                              "); an edge has one length"));
    }
  }
}

} // namespace internal

/// \ingroup PkgIsophoticMetricRef
///
/// \brief a triangle mesh prepared for the package: validated once, its vertices and faces numbered
/// once, and the metric's length of every edge computed once.
///
/// Every solver of the package runs on a `Metric_mesh`: `Geodesic_solver`, `Face_band_solver` and,
/// through them, the neighbourhoods, the morphology and the region growing. Building one is the whole
/// set-up cost of those solvers; build it once and pass it to each of them (or to the free functions,
/// as named parameter `metric_mesh`) to pay it once. A `Metric_mesh` is a handle: copies share the same
/// read-only data, so solvers built on copies may run in different threads. The mesh `tm` must
/// outlive every copy and must not be modified meanwhile.
///
/// The length of an edge is, in this order of precedence:
/// - the value of the user's `edge_length_map` (any intrinsic metric: geodesics on a piecewise-flat
///   surface depend on its edge lengths only; the vertex positions are then used for nothing but
///   the 3D points of `Geodesic_solver::trace_path_points()`),
/// - the distance of the two ends in the user's `lifted_embedding_map`,
/// - \f$ \sqrt{w}\,\|p_u - p_v\| \f$ when `isophotic_weight` is the number 0,
/// - the distance of the two ends in the lifted embedding computed by `compute_lifted_embedding()`.
///
/// Vertices keep the order of `vertices(tm)`; faces are numbered so that neighbouring faces get
/// near numbers (which makes propagations walk through memory nearly in order), not in the order of
/// `faces(tm)`. Corner `k` of a face is the `k`-th vertex from `source(halfedge(f))` (the order of
/// `Face_location`), and its edge `k` joins corners `k` and `k+1 (mod 3)`.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
template <class TriangleMesh>
class Metric_mesh
{
public:
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;
  typedef typename Graph_traits::halfedge_descriptor halfedge_descriptor;
  typedef typename Graph_traits::face_descriptor face_descriptor;

  /// The faces incident to a vertex, as a range of face indices.
  class Incident_faces
  {
  public:
    struct iterator
    {
      const std::uint32_t* corner;
      std::uint32_t operator*() const { return internal::Intrinsic_triangle_mesh::face(*corner); }
      iterator& operator++() { ++corner; return *this; }
      bool operator!=(const iterator& other) const { return corner != other.corner; }
      bool operator==(const iterator& other) const { return corner == other.corner; }
    };
    Incident_faces(const std::uint32_t* b, const std::uint32_t* e) : begin_{b}, end_{e} {}
    iterator begin() const { return begin_; }
    iterator end() const { return end_; }
    bool empty() const { return begin_.corner == end_.corner; }

  private:
    iterator begin_, end_;
  };

  /// Prepares `tm` for the metric given by `np`.
  ///
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{edge_length_map} \cgalParamDescription{the metric length of every edge, a model
  ///     of the concept `EdgeLengthMap` (keyed by halfedges or by edges); the other metric parameters
  ///     are then ignored} \cgalParamDefault{computed from the metric below} \cgalParamNEnd
  ///   \cgalParamNBegin{lifted_embedding_map} \cgalParamDescription{a precomputed lifted embedding
  ///     (`Lifted_point` per vertex); the weights are then ignored} \cgalParamDefault{computed} \cgalParamNEnd
  ///   \cgalParamNBegin{euclidean_weight, isophotic_weight, weight_length_scale, vertex_normal_map}
  ///     \cgalParamDescription{the metric, see `compute_lifted_embedding()`} \cgalParamDefault{`w = w' = 1`, `L` = the bounding-box diagonal} \cgalParamNEnd
  ///   \cgalParamNBegin{vertex_point_map} \cgalParamDescription{the vertex positions}
  ///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  ///
  /// \throws Invalid_mesh_error for a mesh the package cannot process (see `validate_triangle_mesh()`;
  ///   with `edge_length_map` only its connectivity is checked, and the lengths must be positive,
  ///   finite and satisfy the triangle inequality in every face)
  /// \throws Invalid_parameter_error for invalid weights, or two halfedges of an edge with different lengths
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Metric_mesh(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
  {
    auto data = std::make_shared<Data>(tm);
    data->build(np, nullptr);
    data_ = std::move(data);
  }

  /// \cond SKIP_IN_MANUAL
  // The prepared mesh of a region of `tm` alone (internal/Reach_region.h: found and checked by its
  // walk), for the metric given by `np` with constant weights: the faces of the region and their
  // corners, numbered among themselves, the region's border as the mesh's border. The lengths of its
  // edges are those of the whole mesh's `Metric_mesh`. (`Invalid_mesh_error` and
  // `Invalid_parameter_error` here only say that the region cannot be prepared alone.)
  template <class NamedParameters>
  Metric_mesh(const TriangleMesh& tm, const internal::Reach_region<TriangleMesh>& region, const NamedParameters& np)
  {
    auto data = std::make_shared<Data>(tm);
    data->build(np, &region);
    data_ = std::move(data);
  }
  /// \endcond

  /// The mesh.
  const TriangleMesh& mesh() const { return data_->tm; }

  std::size_t number_of_vertices() const { return data_->vertex_descriptors.size(); }
  std::size_t number_of_faces() const { return data_->face_descriptors.size(); }

  /// The vertex of index `i`.
  vertex_descriptor vertex(std::uint32_t i) const { return data_->vertex_descriptors[i]; }
  /// The face of index `i`.
  face_descriptor face(std::uint32_t i) const { return data_->face_descriptors[i]; }

  /// The index of vertex `v`.
  /// \throws Invalid_source_error naming `v` when it is not a vertex of the mesh
  std::uint32_t vertex_index(vertex_descriptor v) const
  {
    return lookup(v, data_->vertex_descriptors, data_->vertex_id, data_->vertex_index_end, "vertex");
  }
  /// The index of face `f`.
  /// \throws Invalid_source_error naming `f` when it is not a face of the mesh
  std::uint32_t face_index(face_descriptor f) const
  {
    return lookup(f, data_->face_descriptors, data_->face_id, data_->face_index_end, "face");
  }

  /// The index of corner `k` (0, 1, 2) of face `f`.
  std::uint32_t corner(std::uint32_t f, int k) const { return data_->intrinsic.source(3 * f + k); }
  /// The three corners of face `f`.
  std::array<std::uint32_t, 3> corners(std::uint32_t f) const { return {{corner(f, 0), corner(f, 1), corner(f, 2)}}; }
  /// The metric length of edge `k` of face `f` (from corner `k` to corner `k+1`).
  double edge_length(std::uint32_t f, int k) const
  {
    return data_->intrinsic.length(3 * f + k) * data_->intrinsic.length_unit(); // (exact: a power of two)
  }
  /// The longest metric edge of face `f`.
  double max_edge_length(std::uint32_t f) const
  {
    return std::max({edge_length(f, 0), edge_length(f, 1), edge_length(f, 2)});
  }
  /// The median metric edge length (0 for a mesh without faces). Computed on first use (thread-safe):
  /// only the band solver needs it.
  double median_edge_length() const
  {
    std::call_once(data_->median_once, [this] { data_->median_edge_length = compute_median_edge_length(); });
    return data_->median_edge_length;
  }
  /// The faces incident to vertex `v`.
  Incident_faces incident_faces(std::uint32_t v) const
  {
    return Incident_faces(data_->intrinsic.corners_begin(v), data_->intrinsic.corners_end(v));
  }
  /// The position of vertex `v` in space, in `double`.
  const std::array<double, 3>& point(std::uint32_t v) const { return data_->points[v]; }

  /// \cond SKIP_IN_MANUAL
  // The engine's structure (connectivity and lengths in the same numbering).
  const internal::Intrinsic_triangle_mesh& intrinsic() const { return data_->intrinsic; }
  /// \endcond

private:
  typedef internal::Vertex_number_map<TriangleMesh> Vertex_id_map;
  typedef internal::Face_number_map<TriangleMesh> Face_id_map;

  struct Data
  {
    explicit Data(const TriangleMesh& m)
      : tm(m), vertex_id(m), face_id(m)
    {}

    template <class NamedParameters>
    void build(const NamedParameters& np, const internal::Reach_region<TriangleMesh>* region);

    const TriangleMesh& tm;
    internal::Intrinsic_triangle_mesh intrinsic;
    // (arrays from a mapping kept for reuse: see Huge_page_chunk.h)
    internal::Huge_page_vector<vertex_descriptor> vertex_descriptors;
    internal::Huge_page_vector<face_descriptor> face_descriptors;
    internal::Huge_page_vector<std::array<double, 3>> points;
    Vertex_id_map vertex_id;
    Face_id_map face_id;
    std::size_t vertex_index_end = 0, face_index_end = 0;
    mutable std::once_flag median_once;
    mutable double median_edge_length = 0;
  };

  // The median, not the mean (the margin of Face_band_solver): in the isophotic metric the few
  // edges across sharp features are long (the normal jumps), and on CAD parts they raise the mean
  // several-fold.
  double compute_median_edge_length() const
  {
    internal::Huge_page_vector<double> all(data_->intrinsic.number_of_corners());
    if(all.empty())
      return 0;
    for(std::size_t h = 0; h < all.size(); ++h)
      all[h] = data_->intrinsic.length(static_cast<std::uint32_t>(h));
    // (engine units differ by a power of two: the same order, the same median)
    return internal::kth_smallest_positive(all.data(), all.size(), all.size() / 2) * data_->intrinsic.length_unit();
  }

  // Index of a descriptor, checking that it belongs to the mesh.
  template <class Descriptor, class IdMap>
  static std::uint32_t lookup(const Descriptor& d, const internal::Huge_page_vector<Descriptor>& all, const IdMap& ids,
                              std::size_t index_end, const char* kind)
  {
    bool valid = !(d == Descriptor());
    if constexpr(std::is_convertible<Descriptor, std::size_t>::value)
      valid = valid && static_cast<std::size_t>(d) < index_end; // before reading the map
    const std::uint32_t index = valid ? get(ids, d) : 0;
    if(!valid || index >= all.size() || !(all[index] == d))
      throw Invalid_source_error(internal::describe_element(kind, d, index) + " is not an element of the mesh");
    return index;
  }

  // One past the largest index of index-based descriptors (Surface_mesh indices may exceed the
  // element count when elements were removed but not collected).
  template <class Descriptor>
  static std::size_t index_end(const internal::Huge_page_vector<Descriptor>& all)
  {
    std::size_t end = 0;
    if constexpr(std::is_convertible<Descriptor, std::size_t>::value)
      for(const Descriptor& d : all)
        end = std::max<std::size_t>(end, static_cast<std::size_t>(d) + 1);
    return end;
  }

  std::shared_ptr<const Data> data_;
};

template <class TriangleMesh>
template <class NamedParameters>
void Metric_mesh<TriangleMesh>::Data::build(const NamedParameters& np, const internal::Reach_region<TriangleMesh>* region)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::is_default_parameter;

  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  auto build_from = [&](auto&& length_of_edge) {
    if(region != nullptr)
      internal::build_intrinsic_triangle_mesh_of_region(intrinsic, tm, *region, length_of_edge, vertex_descriptors, face_descriptors,
                                                        vertex_id, face_id);
    else
      internal::build_intrinsic_triangle_mesh(intrinsic, tm, length_of_edge, vertex_descriptors, face_descriptors, vertex_id, face_id);
  };

  if constexpr(!is_default_parameter<NamedParameters, internal_np::edge_length_map_t>::value)
  {
    CGAL_precondition(region == nullptr); // (lengths of any metric: no ball holds its paths)
    // the user's intrinsic metric: the positions play no part, only the connectivity is checked
    internal::validate_triangle_mesh_connectivity(tm);
    const auto lengths = get_parameter(np, internal_np::edge_length_map);
    internal::check_halfedge_lengths_agree(lengths, tm);
    build_from([&](vertex_descriptor u, vertex_descriptor v) { return internal::read_edge_length(lengths, u, v, tm); });
  }
  else
  {
    if(region == nullptr) // (a region was checked by its walk; its lengths are checked below)
      validate_triangle_mesh(tm, np);
    const auto w = choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.0);
    const auto w_prime = choose_parameter(get_parameter(np, internal_np::isophotic_weight), 1.0);
    constexpr bool lifted_given = !is_default_parameter<NamedParameters, internal_np::lifted_embedding_t>::value;
    bool built = false;
    if constexpr(!lifted_given && std::is_arithmetic<std::decay_t<decltype(w)>>::value)
    {
      if(internal::is_number_equal_to(w_prime, 0.0))
      {
        // Euclidean special case: no normals needed
        const double w_value = static_cast<double>(w);
        if(!(w_value > 0) || !std::isfinite(w_value))
          throw Invalid_parameter_error("euclidean_weight must be finite and positive when isophotic_weight is 0 (got " +
                                        std::to_string(w_value) + ")");
        const double scale = std::sqrt(w_value);
        build_from([&](vertex_descriptor u, vertex_descriptor v) {
          const auto& p = get(vpm, u);
          const auto& q = get(vpm, v);
          const double dx = CGAL::to_double(p.x()) - CGAL::to_double(q.x()), dy = CGAL::to_double(p.y()) - CGAL::to_double(q.y()),
                       dz = CGAL::to_double(p.z()) - CGAL::to_double(q.z());
          return scale * internal::stable_norm(std::array<double, 3>{dx, dy, dz}); // (any scale)
        });
        built = true;
      }
    }
    if(!built)
    {
      if constexpr(lifted_given)
      {
        const auto given = get_parameter(np, internal_np::lifted_embedding);
        build_from([&](vertex_descriptor u, vertex_descriptor v) {
          return internal::distance(Lifted_point(get(given, u)), Lifted_point(get(given, v)));
        });
      }
      else
      {
        // Lifted points in the order of vertices(tm) (of the region), which is the order of the
        // vertex indices (assigned by the build before it asks for lengths).
        const internal::Huge_page_vector<Lifted_point> points =
          region != nullptr ? internal::lift_vertices(tm, np, region->vertices, region->vertices.size())
                            : internal::lift_vertices(tm, np, vertices(tm), static_cast<std::size_t>(num_vertices(tm)));
        const internal::Lifted_point_vector_map<TriangleMesh> lifted{&points, &vertex_id};
        const auto lifted_length = internal::lifted_edge_length(tm, lifted, np); // (accurate for short edges)
        const auto w_of = internal::make_vertex_weight(w);
        build_from([&](vertex_descriptor u, vertex_descriptor v) {
          const double length = lifted_length(u, v);
          if(internal::is_zero_lifted_length(length, w_of(u) == 0. && w_of(v) == 0., get(lifted, u), get(lifted, v)))
          {
            if(region != nullptr)
              throw Invalid_mesh_error("an edge of the region has zero lifted length");
            internal::check_lifted_edge_lengths(tm, lifted, np); // throws, naming the first such edge of edges(tm)
          }
          return length;
        });
      }
    }
  }

  vertex_index_end = index_end(vertex_descriptors);
  face_index_end = index_end(face_descriptors);
  points.reserve(vertex_descriptors.size());
  for(vertex_descriptor v : vertex_descriptors)
  {
    const auto& p = get(vpm, v);
    points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
}

namespace internal {

// The largest share of a mesh's faces that a one-shot call prepares alone: beyond it the walk
// gives up and the whole mesh is prepared (see benchmark/README.md, "Bounded one-shot calls
// prepare their reach").
constexpr double reach_region_max_share = 1. / 3;

// Whether a one-shot call on `TriangleMesh` with the named parameters `NamedParameters` may prepare
// only the region its bound can reach: a Surface_mesh (internal/Reach_region.h), and a metric
// computed here with constant weights (no edge lengths or lifted embedding given: what bounds their
// paths is not known from the weights), nothing prepared given. (Smoothed normals are decided at run
// time: see run_on_reach_region().)
template <class TriangleMesh, class NamedParameters>
constexpr bool may_prepare_reach_only()
{
  using parameters::is_default_parameter;
  typedef std::decay_t<decltype(parameters::choose_parameter(
    parameters::get_parameter(std::declval<NamedParameters>(), internal_np::euclidean_weight), 1.0))> W;
  typedef std::decay_t<decltype(parameters::choose_parameter(
    parameters::get_parameter(std::declval<NamedParameters>(), internal_np::isophotic_weight), 1.0))> W_prime;
  return Has_reach_region<TriangleMesh>::value && std::is_arithmetic<W>::value && std::is_arithmetic<W_prime>::value &&
         is_default_parameter<NamedParameters, internal_np::edge_length_map_t>::value &&
         is_default_parameter<NamedParameters, internal_np::lifted_embedding_t>::value &&
         is_default_parameter<NamedParameters, internal_np::metric_mesh_t>::value &&
         is_default_parameter<NamedParameters, internal_np::face_band_solver_t>::value;
}

// sqrt(w) of a metric for which may_prepare_reach_only() holds: a metric length is at least that
// times the length in space. 0 when w is not positive and finite (no ball then holds the paths).
template <class NamedParameters>
double reach_scale(const NamedParameters& np)
{
  const double w = static_cast<double>(parameters::choose_parameter(parameters::get_parameter(np, internal_np::euclidean_weight), 1.0));
  return w > 0 && std::isfinite(w) ? std::sqrt(w) : 0.;
}

template <class TriangleMesh, class NamedParameters>
auto reach_vertex_point_map(const TriangleMesh& tm, const NamedParameters& np)
{
  return parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                      get_const_property_map(CGAL::vertex_point, tm));
}

// The longest edge in space of the source faces (see Reach_region_walk), 0 when a source is unusable.
template <class TriangleMesh, class NamedParameters>
double longest_source_edge(const TriangleMesh& tm, const NamedParameters& np, const Reach_sources<TriangleMesh>& sources)
{
  const auto vpm = reach_vertex_point_map(tm, np);
  return Reach_region_walk<typename TriangleMesh::Point, decltype(vpm)>(tm, vpm).longest_source_edge(sources);
}

// The one place where a one-shot call chooses its set-up. Runs `task(mesh)`, `mesh` the prepared
// mesh of the region of `tm` that the paths of metric length at most `reach` from `sources` can touch,
// and returns true; or returns false without running it, when may_prepare_reach_only() does not
// hold, when the normals are smoothed (normal_smoothing_scale not 0), when w is not positive, when
// the region would hold more than reach_region_max_share of the faces (the whole set-up is then the
// cheaper), and when the walk's checks or the region's set-up fail (the whole mesh's validation then
// names the problem). On the region, every distance up to `reach` is the one the whole mesh gives, bit
// for bit (the region holds every face those paths cross, with the same lengths; see
// internal/Reach_region.h); beyond it the region knows nothing.
template <class TriangleMesh, class NamedParameters, class Task>
bool run_on_reach_region(const TriangleMesh& tm, const NamedParameters& np, const Reach_sources<TriangleMesh>& sources,
                         double reach, Task&& task)
{
  if constexpr(!may_prepare_reach_only<TriangleMesh, NamedParameters>())
    return false;
  else
  {
    const double scale = reach_scale(np);
    // Normals smoothed at a scale are filtered over the whole mesh, which the filter needs validated
    // (it assumes triangles): the whole set-up then. A smoothing scale of 0 (the exact normals) is as if
    // none were given.
    const double smoothing =
      CGAL::to_double(parameters::choose_parameter(parameters::get_parameter(np, internal_np::normal_smoothing_scale), 0.));
    if(smoothing != 0 || !(scale > 0) || !(reach >= 0) || !std::isfinite(reach / scale) ||
       !(longest_source_edge(tm, np, sources) > 0)) // (the sources are elements of the mesh)
      return false;
    const auto vpm = reach_vertex_point_map(tm, np);
    Reach_region<TriangleMesh> region;
    const std::size_t max_faces = static_cast<std::size_t>(reach_region_max_share * static_cast<double>(num_faces(tm)));
    if(!Reach_region_walk<typename TriangleMesh::Point, decltype(vpm)>(tm, vpm).gather(sources, reach / scale, max_faces, region))
      return false;
    std::optional<Metric_mesh<TriangleMesh>> mesh;
    try
    {
      mesh.emplace(tm, region, np);
    }
    catch(const Invalid_mesh_error&)
    {
      return false;
    }
    catch(const Invalid_parameter_error&)
    {
      return false;
    }
    task(*mesh);
    return true;
  }
}

} // namespace internal

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_METRIC_MESH_H
