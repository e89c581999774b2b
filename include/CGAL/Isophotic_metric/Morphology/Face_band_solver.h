// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The faces within a metric radius of sources (regions, vertices, surface points), with the exact
// "closed face meets the disc" test and area fractions; the building block of every morphological
// operator of the package.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/Metric_mesh.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/internal/Progress_callback.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

namespace internal {

inline void check_radius(double radius, const char* name = "radius")
{
  if(!(radius >= 0) || !std::isfinite(radius))
    throw Invalid_parameter_error(std::string(name) + " must be finite and non-negative (got " +
                                  std::to_string(radius) + ")");
}

inline void check_area_fraction(double fraction)
{
  if(!(fraction >= 0 && fraction <= 1))
    throw Invalid_parameter_error("area_fraction must lie in [0,1] (got " + std::to_string(fraction) + ")");
}

// The one default of `area_fraction` in the package: 0, a face joins when it meets the disc.
template <class NamedParameters>
double read_area_fraction(const NamedParameters& np)
{
  const double a = parameters::choose_parameter(parameters::get_parameter(np, internal_np::area_fraction), 0.0);
  check_area_fraction(a);
  return a;
}

inline void check_area_resolution(int n)
{
  if(n < 1 || n > 64)
    throw Invalid_parameter_error("area_resolution must lie in [1,64] (got " + std::to_string(n) + ")");
}

// Fraction of a triangle where the linear interpolant of the corner values f is <= r.
inline double linear_fraction_below(std::array<double, 3> f, double r)
{
  std::sort(f.begin(), f.end());
  if(f[2] <= r)
    return 1.0;
  if(f[0] > r)
    return 0.0;
  if(f[1] <= r) // two corners inside: remove the corner triangle around f[2]
    return 1.0 - ((f[2] - r) / (f[2] - f[0])) * ((f[2] - r) / (f[2] - f[1]));
  return ((r - f[0]) / (f[1] - f[0])) * ((r - f[0]) / (f[2] - f[0])); // one corner inside
}

} // namespace internal

/// \ingroup PkgIsophoticMetricMorphology
///
/// Finds the faces of a triangle mesh that come within a radius of a set of sources in the isophotic
/// metric, with one bounded exact propagation of `Geodesic_solver` whose cost follows the band found.
/// All morphological operators of the package are built on it; use it directly to run many operations
/// on one mesh without recomputing anything. It runs on a `Metric_mesh` (its own, or one shared with
/// other solvers); its API takes and reports descriptors, and the index-level view of the mesh
/// (corners, metric edge lengths, incidence) is that of `metric_mesh()`.
///
/// A face *meets* the disc of radius `r` when the minimum of the exact distance field over the closed
/// face is at most `r`. Without point sources inside a face the distance field has no interior
/// minimum in a face (in the unfolding of a face it is a minimum of distances to pseudo-sources lying
/// outside the face and of linear line waves), so the minimum lies on the face's boundary: at a
/// vertex, or inside an edge where a geodesic arrives perpendicularly, possibly in a narrow dip between
/// the values at its ends. Vertex values are exact, and so is the minimum along an edge
/// (`Geodesic_solver::minimum_distance_on_segment()`: each window's distance along the edge is convex,
/// or linear, on the part of the edge it covers, and is minimised in closed form). Most edges are
/// decided without that query: they are discarded when \f$ (d(a)+d(b)-\ell)/2 > r \f$ (the distance is
/// 1-Lipschitz along an edge of metric length \f$ \ell \f$) or when a vertex is within `r`.
///
/// The *covered area fraction* of a face is the fraction of its area where the distance is at most `r`,
/// computed from the exact distances at the nodes of a regular subdivision of the face into `n²`
/// congruent sub-triangles (`n` = `area_resolution`, default 4), interpolated linearly on each
/// sub-triangle, whose sub-level set area is then exact. The error is that of linear interpolation at
/// resolution `n`: the fraction is exact when the distance is linear on the sub-triangles.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
template <class TriangleMesh>
class Face_band_solver
{
public:
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;
  typedef typename Graph_traits::face_descriptor face_descriptor;
  typedef Geodesic_solver<TriangleMesh> Solver;
  typedef typename Solver::Face_location Face_location;

  static constexpr std::size_t no_source = Solver::no_source;
  static constexpr double infinity = std::numeric_limits<double>::infinity();

  /// What the band search reports for every face that meets the disc.
  struct Face_visit
  {
    face_descriptor face;     ///< the face
    std::uint32_t face_index; ///< its index in `metric_mesh()`
    double min_distance;      ///< an upper bound of the minimum distance over the face, exact when requested
    double covered_fraction;  ///< fraction of the area within the radius, `-1` when not requested
    std::size_t label;        ///< nearest source at the closest point found, when requested
  };

  /// Prepares `tm` for the metric given by `np` (builds its `Metric_mesh`; the named parameters
  /// of `Metric_mesh`, plus `area_resolution`).
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Face_band_solver(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
    : Face_band_solver(Metric_mesh<TriangleMesh>(tm, np), np)
  {}

  /// A solver on a prepared mesh, sharing it. Named parameters: `area_resolution`, and `callback`
  /// (CGAL's: a callable `bool(double)`, told of the advancement in [0, 1] of every propagation and
  /// of the loops of the operations that use this solver, at least once each; returning `false`
  /// stops them with a `Cancelled_error`, and the solver must then have its sources cleared).
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Face_band_solver(const Metric_mesh<TriangleMesh>& mesh, const NamedParameters& np = parameters::default_values())
    // Point queries and segment minima need the windows. The band's propagations are bounded, so
    // their windows take little memory, and nearly every face they reach is queried: every window
    // is kept in full, none is rebuilt from its parent.
    : solver_(mesh, parameters::store_windows(true).full_window_every(1)),
      area_resolution_(parameters::choose_parameter(parameters::get_parameter(np, internal_np::area_resolution), 4)),
      progress_(internal::Progress_callback::of(np)),
      stamp_(mesh.number_of_faces(), 0)
  {
    internal::check_area_resolution(area_resolution_);
  }

  /// The callback given at construction (none by default).
  const internal::Progress_callback& progress_callback() const { return progress_; }
  void set_progress_callback(const internal::Progress_callback& progress) { progress_ = progress; }

  /// A solver on the same prepared mesh (shared, read-only), with no sources and no callback; the
  /// two may run in different threads.
  Face_band_solver sibling() const
  {
    return Face_band_solver(metric_mesh(), parameters::area_resolution(area_resolution_));
  }

  const TriangleMesh& mesh() const { return metric_mesh().mesh(); }
  /// The prepared mesh (numbering, corners, metric edge lengths, incidence).
  const Metric_mesh<TriangleMesh>& metric_mesh() const { return solver_.metric_mesh(); }
  /// The underlying exact geodesic solver (its sources are the ones added here).
  const Solver& geodesic_solver() const { return solver_; }
  int area_resolution() const { return area_resolution_; }

  /// \cond SKIP_IN_MANUAL
  // How far beyond the radius `visit_band()` propagates (default: the median edge). Any positive
  // margin gives the same faces, minima and vertex distances (see there); a one-shot call on a
  // region sets the one its region was gathered for.
  void set_propagation_margin(double margin) { margin_ = margin; }
  /// \endcond

  /// Removes every source.
  void clear_sources()
  {
    solver_.clear_sources();
    seeds_.clear();
    bound_ = -1;
    point_sources_.clear();
  }

  /// Adds the union of the closed faces of `faces` (face descriptors) as one source; returns its label.
  /// \throws Invalid_source_error if a face is not in the mesh or the range is empty
  template <class FaceRange>
  std::size_t add_source_region(const FaceRange& faces)
  {
    const std::size_t label = solver_.add_source_region(faces);
    for(face_descriptor f : faces)
      seeds_.push_back(metric_mesh().face_index(f));
    return label;
  }

  /// Adds vertex `v` as a source; returns its label.
  std::size_t add_source(vertex_descriptor v)
  {
    const std::size_t label = solver_.add_source(v);
    for(std::uint32_t f : metric_mesh().incident_faces(metric_mesh().vertex_index(v)))
      seeds_.push_back(f);
    return label;
  }

  /// Adds a surface point as a source; returns its label.
  std::size_t add_source(const Face_location& p)
  {
    const std::size_t label = solver_.add_source(p);
    const std::uint32_t f = metric_mesh().face_index(p.first);
    seeds_.push_back(f);
    point_sources_.push_back({f, p.second});
    return label;
  }

  /// As above, for a surface point whose coordinates have any number type (see `Geodesic_solver::Face_location_of`).
  template <class FT>
  std::size_t add_source(const CGAL::Polygon_mesh_processing::Face_location<TriangleMesh, FT>& p)
  {
    return add_source(Solver::to_double_location(p));
  }

  /// Exact distance at vertex `v` (+infinity beyond the propagated bound).
  double distance(vertex_descriptor v) const { return solver_.distance(v); }

  /// Exact distance at a surface point (+infinity beyond the propagated bound).
  double distance(const Face_location& p) const { return solver_.distance(p); }

  /// Makes distances exact up to `bound` (continues the propagation).
  void propagate_to(double bound)
  {
    if(bound > bound_)
    {
      if(progress_)
      {
        progress_.report(0, "propagation");
        solver_.propagate(bound, [&](double front) {
          progress_.report(front / bound, "propagation");
          return true;
        });
      }
      else
        solver_.propagate(bound);
      bound_ = bound;
    }
  }

  /// Visits every face that meets the closed disc of radius `radius` around the sources, once,
  /// in breadth-first order from the sources: `visit(const Face_visit&)`. The covered fraction is
  /// computed when `with_fraction`, the exact minimum and nearest label when `with_label`.
  template <class Visitor>
  void visit_band(double radius, bool with_fraction, bool with_label, Visitor&& visit)
  {
    internal::check_radius(radius);
    if(seeds_.empty())
      return;
    const Metric_mesh<TriangleMesh>& mesh = metric_mesh();
    // Distances are made exact up to radius + margin; beyond the bound a value is unknown and taken
    // as the bound, so the margin must be positive (it is: the input checks reject edges of length 0).
    // It trades propagation for edge queries: an edge with both ends beyond the bound can still dip
    // within the radius and is then queried. One median edge: most edges are then decided by their
    // ends, and the propagation (whose windows grow faster than the area reached) stops as close to
    // the radius as that allows. Any positive margin gives the same answer: a face's minimum is
    // decided exactly (a vertex within the radius, or the exact minimum of the first edge, in corner
    // order, that dips within it; the lower bounds that skip edges only skip edges that do not), and
    // a distance within the bound does not depend on how far beyond it the front went.
    propagate_to(radius + (margin_ > 0 ? margin_ : mesh.median_edge_length()));
    if(++current_stamp_ == 0)
    {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      current_stamp_ = 1;
    }
    std::vector<std::uint32_t> queue;
    for(std::uint32_t f : seeds_)
      if(stamp_[f] != current_stamp_)
      {
        stamp_[f] = current_stamp_;
        queue.push_back(f);
      }
    for(std::size_t next_face = 0; next_face < queue.size(); ++next_face)
    {
      const std::uint32_t f = queue[next_face];
      Face_visit v{mesh.face(f), f, infinity, -1, no_source};
      std::array<double, 3> closest{1, 0, 0};
      if(!face_min(f, radius, with_label, v.min_distance, closest))
        continue;
      if(with_fraction)
        v.covered_fraction = covered_fraction_of(f, radius);
      if(with_label)
        v.label = solver_.nearest_source(Face_location(v.face, closest));
      visit(static_cast<const Face_visit&>(v));
      for(std::uint32_t c : mesh.corners(f))
        for(std::uint32_t g : mesh.incident_faces(c))
          if(stamp_[g] != current_stamp_)
          {
            stamp_[g] = current_stamp_;
            queue.push_back(g);
          }
    }
  }

  /// Fraction of the area of face `f` within distance `radius` of the sources (see the class
  /// documentation for the rule); continues the propagation as far as it needs.
  double covered_fraction(face_descriptor f, double radius) { return covered_fraction_of(metric_mesh().face_index(f), radius); }

private:
  double vertex_distance(std::uint32_t v) const { return solver_.distance(metric_mesh().vertex(v)); }

  double covered_fraction_of(std::uint32_t f, double radius)
  {
    propagate_to(radius + metric_mesh().max_edge_length(f));
    const int n = area_resolution_;
    // node (i,j): barycentric (1 - (i+j)/n, i/n, j/n)
    std::vector<double> value((n + 1) * (n + 2) / 2);
    auto node = [n](int i, int j) { return j * (n + 1) - j * (j - 1) / 2 + i; };
    const auto c = metric_mesh().corners(f);
    const face_descriptor fd = metric_mesh().face(f);
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i + j <= n; ++i)
      {
        double d;
        if(i == 0 && j == 0) d = vertex_distance(c[0]);
        else if(i == n) d = vertex_distance(c[1]);
        else if(j == n) d = vertex_distance(c[2]);
        else d = solver_.distance(Face_location(fd, {{1.0 - double(i + j) / n, double(i) / n, double(j) / n}}));
        value[node(i, j)] = d;
      }
    double sum = 0;
    for(int j = 0; j < n; ++j)
      for(int i = 0; i + j < n; ++i)
      {
        sum += internal::linear_fraction_below({value[node(i, j)], value[node(i + 1, j)], value[node(i, j + 1)]}, radius);
        if(i + j + 1 < n)
          sum += internal::linear_fraction_below({value[node(i + 1, j)], value[node(i + 1, j + 1)], value[node(i, j + 1)]}, radius);
      }
    return sum / double(n * n);
  }

  // Minimum of the distance over the closed face f. Returns whether it is <= radius. Stops at the
  // first point found within the radius unless `exact`; `closest` receives that point.
  bool face_min(std::uint32_t f, double radius, bool exact, double& minimum, std::array<double, 3>& closest)
  {
    const auto c = metric_mesh().corners(f);
    std::array<double, 3> dv;
    minimum = infinity;
    for(int k = 0; k < 3; ++k)
    {
      dv[k] = vertex_distance(c[k]);
      if(dv[k] < minimum)
      {
        minimum = dv[k];
        closest = {0, 0, 0};
        closest[k] = 1;
      }
    }
    if(minimum <= radius && !exact)
      return true;
    // a point source inside the face is an interior minimum (distance 0) that no boundary point sees
    for(const auto& s : point_sources_)
      if(s.first == f)
      {
        minimum = 0;
        closest = s.second;
        return true;
      }
    for(int k = 0; k < 3; ++k)
    {
      // beyond the propagated bound a distance is unknown but at least the bound: a valid lower value
      const double a = std::min(dv[k], bound_), b = std::min(dv[(k + 1) % 3], bound_), len = metric_mesh().edge_length(f, k);
      const double lower = std::max(0.0, 0.5 * (a + b - len));
      if(exact ? lower >= minimum : lower > radius)
        continue;
      double t_best;
      const double m = edge_min(f, k, t_best);
      if(m < minimum)
      {
        minimum = m;
        closest = {0, 0, 0};
        closest[k] = 1 - t_best;
        closest[(k + 1) % 3] = t_best;
      }
      if(minimum <= radius && !exact)
        return true;
    }
    return minimum <= radius;
  }

  // Minimum of the distance over the edge from corner k to corner k+1 of face f, exact up to the
  // propagated bound (beyond it the value is unknown but at least the bound, which is returned).
  double edge_min(std::uint32_t f, int k, double& t_best) const
  {
    std::array<double, 3> from{0, 0, 0}, to{0, 0, 0};
    from[k] = 1;
    to[(k + 1) % 3] = 1;
    const face_descriptor fd = metric_mesh().face(f);
    const double m = solver_.minimum_distance_on_segment(Face_location(fd, from), Face_location(fd, to), &t_best);
    return std::min(m, bound_);
  }

  Solver solver_;
  int area_resolution_ = 4;
  double margin_ = 0; // (0: the median edge)
  internal::Progress_callback progress_;
  std::vector<std::uint32_t> seeds_;
  std::vector<std::pair<std::uint32_t, std::array<double, 3>>> point_sources_;
  double bound_ = -1;
  internal::Huge_page_vector<std::uint32_t> stamp_; // (from a mapping kept for reuse)
  std::uint32_t current_stamp_ = 0;
};

namespace internal {

// Adds the faces of indices `ids` (of the band's prepared mesh) as one region source.
template <class TriangleMesh>
std::size_t add_source_region_by_index(Face_band_solver<TriangleMesh>& band, const std::vector<std::uint32_t>& ids)
{
  std::vector<typename Face_band_solver<TriangleMesh>::face_descriptor> faces;
  faces.reserve(ids.size());
  for(std::uint32_t f : ids)
    faces.push_back(band.metric_mesh().face(f));
  return band.add_source_region(faces);
}

// Runs `task(band_solver)` with the solver passed as named parameter `face_band_solver` (a pointer),
// or with a new one on the prepared mesh passed as `metric_mesh`, or on a new prepared mesh built
// from the metric parameters of `np`. A `callback` of `np` is the solver's during the task.
template <class TriangleMesh, class NamedParameters, class Task>
decltype(auto) with_band_solver(const TriangleMesh& tm, const NamedParameters& np, Task&& task)
{
  using parameters::get_parameter;
  if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::face_band_solver_t>::value)
  {
    Face_band_solver<TriangleMesh>* solver = get_parameter(np, internal_np::face_band_solver);
    if(solver == nullptr || &solver->mesh() != &tm)
      throw Invalid_parameter_error("face_band_solver must point to a Face_band_solver built on the same mesh");
    if constexpr(parameters::is_default_parameter<NamedParameters, CGAL::internal_np::callback_t>::value)
      return task(*solver);
    else
    {
      struct Restore // the solver's own callback, also when the task throws
      {
        Face_band_solver<TriangleMesh>& solver;
        Progress_callback own;
        ~Restore() { solver.set_progress_callback(own); }
      } restore{*solver, solver->progress_callback()};
      solver->set_progress_callback(Progress_callback::of(np));
      return task(*solver);
    }
  }
  else if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::metric_mesh_t>::value)
  {
    const Metric_mesh<TriangleMesh>& mesh = get_parameter(np, internal_np::metric_mesh);
    if(&mesh.mesh() != &tm)
      throw Invalid_parameter_error("metric_mesh must be a Metric_mesh built on the same mesh");
    Face_band_solver<TriangleMesh> solver(mesh, np);
    return task(solver);
  }
  else
  {
    Face_band_solver<TriangleMesh> solver(tm, np);
    return task(solver);
  }
}

// with_band_solver() for a one-shot call whose band (of radius `radius` around `sources`, faces
// joining when they meet it) is all it asks for: the solver then runs on a prepared mesh of the
// region the band's propagation can reach (see run_on_reach_region()), else as above. A covered
// fraction propagates up to a face's longest metric edge beyond the radius, unknown before the set-up:
// with `fraction` > 0 the whole mesh is prepared.
template <class TriangleMesh, class NamedParameters, class Task>
decltype(auto) with_band_solver(const TriangleMesh& tm, const NamedParameters& np, const Reach_sources<TriangleMesh>& sources,
                                double radius, double fraction, Task&& task)
{
  if constexpr(may_prepare_reach_only<TriangleMesh, NamedParameters>())
  {
    typedef decltype(task(std::declval<Face_band_solver<TriangleMesh>&>())) Result;
    // The margin beyond the radius (any positive one gives the same answer): half the longest edge
    // of the sources in space, times sqrt(w), below their metric length. (Measured on one-face calls at
    // 0.01 L: 10-15 % faster than the whole edge, 30-50 % faster than twice it, see benchmark/README.md.)
    const double margin = fraction == 0 ? 0.5 * reach_scale(np) * longest_source_edge(tm, np, sources) : 0.;
    std::optional<Result> result;
    if(margin > 0 && std::isfinite(radius + margin) &&
       run_on_reach_region(tm, np, sources, radius + margin, [&](const Metric_mesh<TriangleMesh>& mesh) {
         Face_band_solver<TriangleMesh> band(mesh, np);
         band.set_propagation_margin(margin);
         result.emplace(task(band));
       }))
      return Result(std::move(*result));
  }
  return with_band_solver(tm, np, std::forward<Task>(task));
}

} // namespace internal

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H
