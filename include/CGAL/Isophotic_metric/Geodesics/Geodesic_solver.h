// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The stateful exact geodesic solver: sources (vertices, surface points, face regions),
// bounded propagation, point queries, nearest-source labels and path trace-back.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H

#include <CGAL/Isophotic_metric/Metric_mesh.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Window_propagation.h>

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

/// \ingroup PkgIsophoticMetricGeodesicsRef
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
/// 5 bytes per propagated window, see `number_of_windows_stored()`: most are kept as a 2-byte link
/// to the window they were made from and rebuilt when a query needs them, see the named parameter
/// `full_window_every`). With the named parameter `store_windows(false)` only vertex
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
  /// A surface point whose barycentric coordinates have the number type `FT` (e.g. the result of
  /// `Polygon_mesh_processing::locate()` with an exact kernel). Every member function taking a
  /// `Face_location` also takes one of these; its coordinates are converted with `CGAL::to_double()`.
  template <class FT>
  using Face_location_of = CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, FT>;
  /// The type of the 3D points written by `trace_path_points()`.
  typedef Point_3 Point;

  /// Returned by `nearest_source()` where nothing is reachable.
  static constexpr std::size_t no_source = static_cast<std::size_t>(-1);

  /// Prepares the solver for `tm` and the metric given by `np`: builds its `Metric_mesh` (which
  /// validates the mesh and computes the metric's edge lengths).
  ///
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{edge_length_map, lifted_embedding_map, euclidean_weight, isophotic_weight,
  ///     weight_length_scale, vertex_normal_map, vertex_point_map} \cgalParamDescription{the metric,
  ///     see `Metric_mesh`} \cgalParamDefault{`w = w' = 1`, `L` = the bounding-box diagonal} \cgalParamNEnd
  ///   \cgalParamNBegin{store_windows} \cgalParamDescription{keep the windows for point queries and paths}
  ///     \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
  ///   \cgalParamNBegin{full_window_every} \cgalParamDescription{with stored windows: one window in
  ///     `k` of each line of descent is kept in full (48 bytes), the others as a 2-byte link to the
  ///     window they were made from, rebuilt when a query needs them (at most `k - 1` rebuilds). `1`
  ///     keeps every window in full: the fastest point queries, in about 5 times the memory of the
  ///     default; a larger `k` takes less memory and makes point queries and segment minima slower.
  ///     The answers are the same, bit for bit, for every `k`.}
  ///     \cgalParamType{an integer in [1, 255]} \cgalParamDefault{`16`} \cgalParamNEnd
  ///   \cgalParamNBegin{propagation_threads} \cgalParamDescription{`0`: the serial propagation.
  ///     `n >= 1`: the propagation advances in bands of the front on `n` threads (see
  ///     \ref IMGeoParallel); distances, labels and window counts are then the same, bit for bit,
  ///     for every `n` with the same partitions (`1` runs the order of `2` on the calling thread
  ///     alone), and the distances and labels were those of the serial propagation on every mesh
  ///     tested. Needs `store_windows(false)`.}
  ///     \cgalParamType{an integer in [0, 256]} \cgalParamDefault{`0`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  ///
  /// \throws Invalid_mesh_error for a mesh the package cannot process (see `validate_triangle_mesh()`)
  /// \throws Invalid_parameter_error for invalid weights, an invalid `full_window_every` or
  ///   `propagation_threads`, or threads with stored windows
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Geodesic_solver(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
    : Geodesic_solver(Metric_mesh<TriangleMesh>(tm, np), np)
  {}

  /// A solver on a prepared mesh, sharing it (no set-up beyond the solver's own buffers).
  /// Named parameters: `store_windows`, `full_window_every` and `propagation_threads`, as above.
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Geodesic_solver(const Metric_mesh<TriangleMesh>& mesh, const NamedParameters& np = parameters::default_values())
    : mesh_(mesh), engine_(std::make_unique<internal::Window_propagation>(mesh_.intrinsic()))
  {
    const auto every = parameters::choose_parameter(parameters::get_parameter(np, internal_np::full_window_every),
                                                    internal::Window_propagation::default_full_record_every);
    if(!(every >= 1 && every <= 255))
      throw Invalid_parameter_error("full_window_every must be an integer in [1, 255] (got " + std::to_string(every) + ")");
    const bool store_windows = parameters::choose_parameter(parameters::get_parameter(np, internal_np::store_windows), true);
    const auto threads = parameters::choose_parameter(parameters::get_parameter(np, internal_np::propagation_threads), 0);
    if(!(threads >= 0 && threads <= 256))
      throw Invalid_parameter_error("propagation_threads must be an integer in [0, 256] (got " + std::to_string(threads) + ")");
    if(threads > 0 && store_windows)
      throw Invalid_parameter_error("propagation_threads(" + std::to_string(threads) +
                                    ") keeps no windows: add store_windows(false), or use propagation_threads(0)");
    engine_->set_keep_windows(store_windows, static_cast<std::uint8_t>(every));
    engine_->set_propagation_threads(static_cast<unsigned>(threads));
  }

  Geodesic_solver(Geodesic_solver&&) = default;
  Geodesic_solver& operator=(Geodesic_solver&&) = default;

  /// A solver on the same prepared mesh (shared, read-only, so the two may run in different
  /// threads), with no sources, storing windows and using threads as this one does.
  Geodesic_solver sibling() const
  {
    return Geodesic_solver(mesh_, parameters::store_windows(engine_->keeps_windows())
                                      .full_window_every(int(engine_->full_record_every()))
                                      .propagation_threads(int(engine_->propagation_threads())));
  }

  /// The prepared mesh the solver runs on.
  const Metric_mesh<TriangleMesh>& metric_mesh() const { return mesh_; }

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
      *out++ = Face_location(mesh_.face(q.face), q.barycentric);
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
    if(mesh_.incident_faces(i).empty())
      throw Invalid_source_error(internal::describe_element("vertex", v, i) + " is isolated (no incident face)");
    const internal::Surface_point p = engine_->vertex_point(i);
    return Face_location(mesh_.face(p.face), p.barycentric);
  }

  /// Writes the distance of every vertex into `distance` (a writable vertex property map).
  template <class VertexDistanceMap>
  void copy_distances(VertexDistanceMap distance) const
  {
    for(std::uint32_t i = 0; i < mesh_.number_of_vertices(); ++i)
      put(distance, mesh_.vertex(i), engine_->vertex_distance(i));
  }

  /// \name Surface points of any number type
  /// As the functions of the same name above, for a `Face_location_of<FT>`.
  /// @{
  template <class FT>
  std::size_t add_source(const Face_location_of<FT>& p) { return add_source(to_double_location(p)); }
  template <class FT>
  double distance(const Face_location_of<FT>& p) const { return distance(to_double_location(p)); }
  template <class FT>
  double minimum_distance_on_segment(const Face_location_of<FT>& a, const Face_location_of<FT>& b,
                                     double* t_at_minimum = nullptr) const
  {
    return minimum_distance_on_segment(to_double_location(a), to_double_location(b), t_at_minimum);
  }
  template <class FT>
  std::size_t nearest_source(const Face_location_of<FT>& p) const { return nearest_source(to_double_location(p)); }
  template <class FT, class OutputIterator>
  std::size_t trace_path(const Face_location_of<FT>& p, OutputIterator out) const { return trace_path(to_double_location(p), out); }
  template <class FT, class OutputIterator>
  std::size_t trace_path_points(const Face_location_of<FT>& p, OutputIterator out) const
  {
    return trace_path_points(to_double_location(p), out);
  }
  /// The same point with `double` coordinates.
  template <class FT>
  static Face_location to_double_location(const Face_location_of<FT>& p)
  {
    return Face_location(p.first, {{CGAL::to_double(p.second[0]), CGAL::to_double(p.second[1]), CGAL::to_double(p.second[2])}});
  }
  /// @}

  /// Statistics of the last propagation (for benchmarks and tuning).
  std::size_t number_of_windows_created() const { return engine_->windows_created(); }
  std::size_t number_of_windows_propagated() const { return engine_->windows_propagated(); }
  /// The windows kept for point queries and paths (0 with `store_windows(false)`).
  std::size_t number_of_windows_stored() const { return engine_->stored_windows(); }

private:
  static std::size_t to_label(std::uint32_t l) { return l == internal::Window_propagation::none ? no_source : l; }

  void require_windows(const char* what) const
  {
    if(!engine_->keeps_windows())
      throw Error(std::string(what) + " needs the propagation's windows: construct the solver with store_windows(true)");
  }

  std::uint32_t vertex_index(vertex_descriptor v) const { return mesh_.vertex_index(v); }
  std::uint32_t face_index(face_descriptor f) const { return mesh_.face_index(f); }

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
      const std::array<double, 3>& p = mesh_.point(mesh_.corner(q.face, c));
      for(int i = 0; i < 3; ++i)
        x[i] += q.barycentric[c] * p[i];
    }
    return Point_3(x[0], x[1], x[2]);
  }

  Metric_mesh<TriangleMesh> mesh_; // before engine_, which refers to it
  std::unique_ptr<internal::Window_propagation> engine_;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_GEODESICS_GEODESIC_SOLVER_H
