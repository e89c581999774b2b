// The stateful exact geodesic solver: sources (vertices, surface points, face regions),
// bounded propagation, point queries, nearest-source labels and path trace-back.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H

#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Intrinsic_triangle_mesh.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Window_propagation.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

// Reads a weight given as a number, for the fast Euclidean special case.
template <class T>
bool is_number_equal_to(const T& value, double x)
{
  if constexpr(std::is_arithmetic<T>::value)
    return static_cast<double>(value) == x;
  else
    return false;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricRef
///
/// Exact geodesic distances on a triangle mesh in the isophotic metric
/// `ds² = w·ds_surface² + w'·ds_normal²`, by exact window propagation on the lifted mesh
/// `X(v) = (√w·p(v), √w'·n(v))` (no approximation: the lifted mesh is piecewise flat and its
/// polyhedral geodesics are computed exactly, up to floating-point rounding).
///
/// Usage: add sources, `propagate()` (optionally up to a distance bound), then query distances at
/// vertices or at any surface point, the nearest source, and the shortest path back to it.
/// A new source set starts with `clear_sources()`; the mesh and metric are kept.
///
/// Sources are numbered 0, 1, ... in the order they are added; that number is the label returned
/// by `nearest_source()` (a geodesic Voronoi partition when there are several sources).
///
/// Point queries and paths need the windows of the propagation; they are kept by default (about
/// 64 bytes per propagated window). With the named parameter `store_windows(false)` only vertex
/// distances and labels are available, and memory follows the wavefront: each window is forgotten
/// once it has crossed its face (this is what `compute_geodesic_distances()` uses).
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph` (e.g. `Surface_mesh`, `Polyhedron_3`)
/// \tparam Point_3 the type of the 3D points written by `trace_path_points()`
template <class TriangleMesh,
          class Point_3 = typename boost::property_traits<
            typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value_type>
class Geodesic_solver
{
public:
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;
  typedef typename Graph_traits::face_descriptor face_descriptor;
  /// A point on the surface: a face and barycentric coordinates w.r.t. `source(halfedge(f))`,
  /// `target(halfedge(f))`, `target(next(halfedge(f)))` (the convention of `Polygon_mesh_processing::locate()`).
  typedef CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, double> Face_location;
  /// The type of the 3D points written by `trace_path_points()`.
  typedef Point_3 Point;

  /// Returned by `nearest_source()` where nothing is reachable.
  static constexpr std::size_t no_source = static_cast<std::size_t>(-1);

  /// Prepares the solver for `tm` and the metric given by `np`: validates the mesh, computes the
  /// lifted embedding (or reads it from `lifted_embedding_map`) and the edge lengths.
  ///
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{vertex_point_map} \cgalParamDescription{the vertex positions}
  ///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`} \cgalParamNEnd
  ///   \cgalParamNBegin{euclidean_weight} \cgalParamDescription{`w`, a number or a per-vertex map}
  ///     \cgalParamDefault{`1`} \cgalParamNEnd
  ///   \cgalParamNBegin{isophotic_weight} \cgalParamDescription{`w'`, a number or a per-vertex map;
  ///     `0` gives the Euclidean geodesic distance scaled by `√w`} \cgalParamDefault{`1`} \cgalParamNEnd
  ///   \cgalParamNBegin{weight_length_scale} \cgalParamDescription{see `compute_lifted_embedding()`}
  ///     \cgalParamDefault{`1`} \cgalParamNEnd
  ///   \cgalParamNBegin{vertex_normal_map} \cgalParamDescription{see `compute_lifted_embedding()`}
  ///     \cgalParamDefault{computed} \cgalParamNEnd
  ///   \cgalParamNBegin{lifted_embedding_map} \cgalParamDescription{a precomputed lifted embedding
  ///     (`Lifted_point` per vertex); the weights are then ignored} \cgalParamDefault{computed} \cgalParamNEnd
  ///   \cgalParamNBegin{store_windows} \cgalParamDescription{keep the windows for point queries and paths}
  ///     \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  ///
  /// \throws Invalid_mesh_error for a mesh the package cannot process (see `validate_triangle_mesh()`)
  /// \throws Invalid_parameter_error for invalid weights
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Geodesic_solver(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
    : shared_(std::make_shared<Shared>(tm))
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    using parameters::is_default_parameter;

    validate_triangle_mesh(tm, np);
    Shared& data = *shared_;
    const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                      get_const_property_map(CGAL::vertex_point, tm));
    const auto w = choose_parameter(get_parameter(np, internal_np::euclidean_weight), 1.0);
    const auto w_prime = choose_parameter(get_parameter(np, internal_np::isophotic_weight), 1.0);
    const bool lifted_given = !is_default_parameter<NamedParameters, internal_np::lifted_embedding_t>::value;

    if(!lifted_given && internal::is_number_equal_to(w_prime, 0.0) && std::is_arithmetic<decltype(w)>::value)
    {
      // Euclidean special case: no normals needed.
      const double w_value = to_number(w);
      if(!(w_value > 0) || !std::isfinite(w_value))
        throw Invalid_parameter_error("euclidean_weight must be finite and positive when isophotic_weight is 0 (got " +
                                      std::to_string(w_value) + ")");
      const double scale = std::sqrt(w_value);
      internal::build_intrinsic_triangle_mesh(data.mesh, tm, [&](vertex_descriptor u, vertex_descriptor v) {
        const auto& a = get(vpm, u);
        const auto& b = get(vpm, v); // (std::hypot: no overflow or underflow at any scale)
        return scale * std::hypot(CGAL::to_double(a.x()) - CGAL::to_double(b.x()), CGAL::to_double(a.y()) - CGAL::to_double(b.y()),
                                  CGAL::to_double(a.z()) - CGAL::to_double(b.z()));
      }, data.vertices, data.faces, data.vertex_id, data.face_id);
    }
    else
    {
      auto lifted = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), tm);
      if constexpr(!is_default_parameter<NamedParameters, internal_np::lifted_embedding_t>::value)
      {
        const auto given = get_parameter(np, internal_np::lifted_embedding);
        for(vertex_descriptor v : vertices(tm))
          put(lifted, v, get(given, v));
      }
      else
        compute_lifted_embedding(tm, lifted, np);
      const auto lifted_length = internal::lifted_edge_length(tm, lifted, np); // (accurate for short edges)
      internal::build_intrinsic_triangle_mesh(data.mesh, tm, [&](vertex_descriptor u, vertex_descriptor v) {
        return lifted_given ? internal::distance(get(lifted, u), get(lifted, v)) : lifted_length(u, v);
      }, data.vertices, data.faces, data.vertex_id, data.face_id);
    }
    data.vertex_index_end = index_end(data.vertices);
    data.face_index_end = index_end(data.faces);
    data.points.reserve(data.vertices.size());
    for(vertex_descriptor v : data.vertices)
    {
      const auto& p = get(vpm, v);
      data.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
    engine_ = std::make_unique<internal::Window_propagation>(data.mesh);
    engine_->set_keep_windows(choose_parameter(get_parameter(np, internal_np::store_windows), true));
  }

  Geodesic_solver(Geodesic_solver&&) = default;
  Geodesic_solver& operator=(Geodesic_solver&&) = default;

  /// A solver on the same mesh and metric, sharing this one's precomputed geometry (read-only, so
  /// the two may run in different threads), with no sources.
  Geodesic_solver sibling() const { return Geodesic_solver(shared_, engine_->keeps_windows()); }

  /// Removes every source and result; the mesh and metric are kept.
  void clear_sources() { engine_->clear(); }

  /// Adds vertex `v` as a source and returns its label.
  /// \throws Invalid_source_error if `v` is not a vertex of the mesh
  std::size_t add_source(vertex_descriptor v) { return engine_->add_vertex_source(vertex_index(v)); }

  /// Adds a point of the surface as a source and returns its label.
  /// \throws Invalid_source_error if the face is not in the mesh or the coordinates are not barycentric
  std::size_t add_source(const Face_location& p) { return engine_->add_point_source(surface_point(p)); }

  /// Adds the union of the closed faces of `faces` as one source (distance 0 on it; exact distance
  /// to its boundary edges outside) and returns its label.
  /// \throws Invalid_source_error if a face is not in the mesh or the range is empty
  template <class FaceRange>
  std::size_t add_source_region(const FaceRange& faces)
  {
    std::vector<std::uint32_t> ids;
    for(face_descriptor f : faces)
      ids.push_back(face_index(f));
    if(ids.empty())
      throw Invalid_source_error("source region " + std::to_string(engine_->sources().size()) + " has no face");
    return engine_->add_region_source(ids);
  }

  std::size_t number_of_sources() const { return engine_->sources().size(); }

  /// Computes the exact distances from the sources, up to `max_distance`: vertices and points
  /// beyond it read +infinity, and the work done follows the explored area. Calling it again with
  /// a larger bound continues where the previous call stopped (same result as one call).
  /// `visitor(front_distance)` is called periodically; returning `false` cancels the computation
  /// (`Cancelled_error` is thrown; the solver must then be cleared).
  /// \throws Invalid_parameter_error if `max_distance` is negative or NaN
  /// \throws Invalid_source_error if there is no source
  void propagate(double max_distance = std::numeric_limits<double>::infinity(),
                 const std::function<bool(double)>& visitor = {})
  {
    if(!(max_distance >= 0))
      throw Invalid_parameter_error("max_distance must be non-negative (got " + std::to_string(max_distance) + ")");
    if(engine_->sources().empty())
      throw Invalid_source_error("propagate() called without any source");
    engine_->propagate(max_distance, visitor);
  }

  /// Exact distance of vertex `v` to the nearest source (+infinity if unreachable or beyond the bound).
  double distance(vertex_descriptor v) const { return engine_->vertex_distance(vertex_index(v)); }

  /// Exact distance of a surface point to the nearest source. Requires stored windows.
  double distance(const Face_location& p) const
  {
    require_windows("distance at a surface point");
    return engine_->point_value(surface_point(p)).distance;
  }

  /// Exact minimum of the distance over the segment between two points `a` and `b` of one face (an
  /// edge of the face, say: its two corners) and, in `*t_at_minimum`, where it is reached, as the
  /// fraction of the way from `a` to `b`. +infinity if no point of the segment is reached. Requires
  /// stored windows. Throws `Invalid_parameter_error` if `a` and `b` lie in different faces.
  double minimum_distance_on_segment(const Face_location& a, const Face_location& b, double* t_at_minimum = nullptr) const
  {
    require_windows("minimum distance on a segment");
    if(a.first != b.first)
      throw Invalid_parameter_error("minimum_distance_on_segment: the two points lie in different faces (" +
                                    internal::describe_element("face", a.first, face_index(a.first)) + " and " +
                                    internal::describe_element("face", b.first, face_index(b.first)) + ")");
    double t = 0;
    const double d = engine_->segment_minimum(surface_point(a), surface_point(b), t).distance;
    if(t_at_minimum != nullptr)
      *t_at_minimum = t;
    return d;
  }

  /// Label of the source nearest to vertex `v`, or `no_source`.
  std::size_t nearest_source(vertex_descriptor v) const { return to_label(engine_->vertex_label(vertex_index(v))); }

  /// Label of the source nearest to a surface point, or `no_source`. Requires stored windows.
  std::size_t nearest_source(const Face_location& p) const
  {
    require_windows("nearest source of a surface point");
    return to_label(engine_->point_value(surface_point(p)).label);
  }

  /// Writes the shortest path from `p` to its nearest source as `Face_location`s, `p` first, the
  /// source last (for a region source: the first point of the region). Consecutive points lie in a
  /// common face, so the path is a polyline on the surface. Returns the number of points written
  /// (0 when `p` is unreachable). Requires stored windows.
  template <class OutputIterator>
  std::size_t trace_path(const Face_location& p, OutputIterator out) const
  {
    require_windows("path trace-back");
    std::vector<internal::Surface_point> path;
    engine_->trace_back(surface_point(p), path);
    for(const internal::Surface_point& q : path)
      *out++ = Face_location(shared_->faces[q.face], q.barycentric);
    return path.size();
  }

  /// As `trace_path()`, writing 3D points of the surface (of type `Point_3`).
  template <class OutputIterator>
  std::size_t trace_path_points(const Face_location& p, OutputIterator out) const
  {
    require_windows("path trace-back");
    std::vector<internal::Surface_point> path;
    engine_->trace_back(surface_point(p), path);
    for(const internal::Surface_point& q : path)
      *out++ = point(q);
    return path.size();
  }

  /// The `Face_location` of vertex `v` (in one of its faces), to query or trace from a vertex.
  /// \throws Invalid_source_error if `v` has no incident face
  Face_location location(vertex_descriptor v) const
  {
    const std::uint32_t i = vertex_index(v);
    if(shared_->mesh.corners_begin(i) == shared_->mesh.corners_end(i))
      throw Invalid_source_error(internal::describe_element("vertex", v, i) + " is isolated (no incident face)");
    const internal::Surface_point p = engine_->vertex_point(i);
    return Face_location(shared_->faces[p.face], p.barycentric);
  }

  /// Writes the distance of every vertex into `distance` (a writable vertex property map).
  template <class VertexDistanceMap>
  void copy_distances(VertexDistanceMap distance) const
  {
    for(std::size_t i = 0; i < shared_->vertices.size(); ++i)
      put(distance, shared_->vertices[i], engine_->vertex_distance(static_cast<std::uint32_t>(i)));
  }

  /// Statistics of the last propagation (for benchmarks and tuning).
  std::size_t number_of_windows_created() const { return engine_->windows_created(); }
  std::size_t number_of_windows_propagated() const { return engine_->windows_propagated(); }

private:
  struct Shared
  {
    explicit Shared(const TriangleMesh& tm)
      : vertex_id(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm)),
        face_id(get(CGAL::dynamic_face_property_t<std::uint32_t>(), tm))
    {}
    internal::Intrinsic_triangle_mesh mesh;
    std::vector<vertex_descriptor> vertices;
    std::vector<face_descriptor> faces;
    std::vector<std::array<double, 3>> points;
    std::size_t vertex_index_end = 0, face_index_end = 0;
    typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<std::uint32_t>>::const_type vertex_id;
    typename boost::property_map<TriangleMesh, CGAL::dynamic_face_property_t<std::uint32_t>>::const_type face_id;
  };

  Geodesic_solver(std::shared_ptr<Shared> shared, bool keep_windows)
    : shared_(std::move(shared)), engine_(std::make_unique<internal::Window_propagation>(shared_->mesh))
  {
    engine_->set_keep_windows(keep_windows);
  }

  template <class W>
  static double to_number(const W& w)
  {
    if constexpr(std::is_arithmetic<W>::value)
      return static_cast<double>(w);
    else
      return 1.0;
  }

  static std::size_t to_label(std::uint32_t l) { return l == internal::Window_propagation::none ? no_source : l; }

  void require_windows(const char* what) const
  {
    if(!engine_->keeps_windows())
      throw Error(std::string(what) + " needs the propagation's windows: construct the solver with store_windows(true)");
  }

  // Index of a descriptor, checking that it belongs to the mesh.
  template <class Descriptor, class IdMap>
  static std::uint32_t lookup(const Descriptor& d, const std::vector<Descriptor>& all, const IdMap& ids,
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
  static std::size_t index_end(const std::vector<Descriptor>& all)
  {
    std::size_t end = 0;
    if constexpr(std::is_convertible<Descriptor, std::size_t>::value)
      for(const Descriptor& d : all)
        end = std::max<std::size_t>(end, static_cast<std::size_t>(d) + 1);
    return end;
  }

  std::uint32_t vertex_index(vertex_descriptor v) const
  {
    return lookup(v, shared_->vertices, shared_->vertex_id, shared_->vertex_index_end, "vertex");
  }
  std::uint32_t face_index(face_descriptor f) const
  {
    return lookup(f, shared_->faces, shared_->face_id, shared_->face_index_end, "face");
  }

  internal::Surface_point surface_point(const Face_location& p) const
  {
    internal::Surface_point q{face_index(p.first), {0, 0, 0}};
    double sum = 0;
    for(int i = 0; i < 3; ++i)
    {
      const double b = p.second[i];
      if(!std::isfinite(b) || b < -1e-12)
        throw Invalid_source_error("barycentric coordinate " + std::to_string(i) + " = " + std::to_string(b) +
                                   " in " + internal::describe_element("face", p.first, q.face) + " is negative or not finite");
      q.barycentric[i] = std::max(0.0, b);
      sum += q.barycentric[i];
    }
    if(std::abs(sum - 1.0) > 1e-9)
      throw Invalid_source_error("barycentric coordinates in " + internal::describe_element("face", p.first, q.face) +
                                 " sum to " + std::to_string(sum) + ", not 1");
    for(double& b : q.barycentric)
      b /= sum;
    return q;
  }

  Point_3 point(const internal::Surface_point& q) const
  {
    std::array<double, 3> x{0, 0, 0};
    for(int c = 0; c < 3; ++c)
    {
      const std::array<double, 3>& p = shared_->points[shared_->mesh.source(3 * q.face + c)];
      for(int i = 0; i < 3; ++i)
        x[i] += q.barycentric[c] * p[i];
    }
    return Point_3(x[0], x[1], x[2]);
  }

  std::shared_ptr<Shared> shared_;
  std::unique_ptr<internal::Window_propagation> engine_;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H
