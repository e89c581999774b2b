// The faces within a metric radius of sources (regions, vertices, surface points), with the exact
// "closed face meets the disc" test and area fractions; the building block of every morphological
// operator of the package.
#ifndef CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H
#define CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H

#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Intrinsic_triangle_mesh.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
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
/// on one mesh without recomputing its geometry.
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
    std::uint32_t face;       ///< index of the face (see `face()`)
    double min_distance;      ///< an upper bound of the minimum distance over the face, exact when requested
    double covered_fraction;  ///< fraction of the area within the radius, `-1` when not requested
    std::size_t label;        ///< nearest source at the closest point found, when requested
  };

  /// Prepares the geometry of `tm` for the metric given by `np` (the named parameters of
  /// `Geodesic_solver`, plus `area_resolution`).
  template <class NamedParameters = parameters::Default_named_parameters>
  explicit Face_band_solver(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
    : solver_(tm, np), shared_(std::make_shared<Shared>(tm))
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    using parameters::is_default_parameter;

    area_resolution_ = choose_parameter(get_parameter(np, internal_np::area_resolution), 4);
    internal::check_area_resolution(area_resolution_);

    Shared& s = *shared_;
    auto lifted = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), tm);
    if constexpr(!is_default_parameter<NamedParameters, internal_np::lifted_embedding_t>::value)
    {
      const auto given = get_parameter(np, internal_np::lifted_embedding);
      for(vertex_descriptor v : vertices(tm))
        put(lifted, v, get(given, v));
    }
    else
      compute_lifted_embedding(tm, lifted, np);

    std::uint32_t i = 0;
    for(vertex_descriptor v : vertices(tm))
    {
      put(s.vertex_id, v, i++);
      s.vertices.push_back(v);
      if constexpr(std::is_convertible<vertex_descriptor, std::size_t>::value)
        s.vertex_index_end = std::max<std::size_t>(s.vertex_index_end, static_cast<std::size_t>(v) + 1);
    }
    i = 0;
    for(face_descriptor f : faces(tm))
    {
      put(s.face_id, f, i++);
      s.faces.push_back(f);
      if constexpr(std::is_convertible<face_descriptor, std::size_t>::value)
        s.face_index_end = std::max<std::size_t>(s.face_index_end, static_cast<std::size_t>(f) + 1);
      std::array<std::uint32_t, 3> c;
      auto h = halfedge(f, tm);
      for(int k = 0; k < 3; ++k, h = next(h, tm))
        c[k] = get(s.vertex_id, source(h, tm));
      s.corners.push_back(c);
      std::array<double, 3> len;
      for(int k = 0; k < 3; ++k)
        len[k] = std::sqrt(internal::squared_distance(get(lifted, s.vertices[c[k]]), get(lifted, s.vertices[c[(k + 1) % 3]])));
      s.edge_length.push_back(len);
    }
    s.median_edge_length = median_edge_length(s.edge_length);
    // incident faces of every vertex, compressed rows
    s.first_face.assign(s.vertices.size() + 1, 0);
    for(const auto& c : s.corners)
      for(std::uint32_t v : c)
        ++s.first_face[v + 1];
    for(std::size_t v = 0; v < s.vertices.size(); ++v)
      s.first_face[v + 1] += s.first_face[v];
    s.incident_faces.resize(s.first_face.back());
    std::vector<std::uint32_t> fill(s.first_face.begin(), s.first_face.end() - 1);
    for(std::uint32_t f = 0; f < s.corners.size(); ++f)
      for(std::uint32_t v : s.corners[f])
        s.incident_faces[fill[v]++] = f;
    stamp_.assign(s.faces.size(), 0);
  }

  /// A solver on the same mesh and metric sharing this one's geometry (read-only), with no sources;
  /// the two may run in different threads.
  Face_band_solver sibling() const { return Face_band_solver(*this, 0); }

  const TriangleMesh& mesh() const { return shared_->tm; }
  /// The underlying exact geodesic solver (its sources are the ones added here).
  const Solver& geodesic_solver() const { return solver_; }
  std::size_t number_of_faces() const { return shared_->faces.size(); }
  std::size_t number_of_vertices() const { return shared_->vertices.size(); }
  face_descriptor face(std::size_t i) const { return shared_->faces[i]; }
  vertex_descriptor vertex(std::size_t i) const { return shared_->vertices[i]; }
  int area_resolution() const { return area_resolution_; }

  /// Index of face `f`; throws `Invalid_source_error` naming `f` when it is not a face of the mesh.
  std::uint32_t face_index(face_descriptor f) const { return checked(f, shared_->faces, shared_->face_id, "face", shared_->face_index_end); }
  /// Index of vertex `v`; throws `Invalid_source_error` naming `v` when it is not a vertex of the mesh.
  std::uint32_t vertex_index(vertex_descriptor v) const { return checked(v, shared_->vertices, shared_->vertex_id, "vertex", shared_->vertex_index_end); }

  /// The three corner vertex indices of face `f` (in `Face_location` order).
  const std::array<std::uint32_t, 3>& corners(std::uint32_t f) const { return shared_->corners[f]; }
  /// Metric length of the edge from corner `k` to corner `k+1` of face `f`.
  double edge_length(std::uint32_t f, int k) const { return shared_->edge_length[f][k]; }
  /// Faces incident to vertex `v` (indices).
  std::pair<const std::uint32_t*, const std::uint32_t*> incident_faces(std::uint32_t v) const
  {
    const Shared& s = *shared_;
    return {s.incident_faces.data() + s.first_face[v], s.incident_faces.data() + s.first_face[v + 1]};
  }

  /// Removes every source.
  void clear_sources()
  {
    solver_.clear_sources();
    seeds_.clear();
    bound_ = -1;
    point_sources_.clear();
  }

  /// Adds the union of the closed faces `face_indices` as one source; returns its label.
  std::size_t add_source_region(const std::vector<std::uint32_t>& face_indices)
  {
    std::vector<face_descriptor> fs;
    fs.reserve(face_indices.size());
    for(std::uint32_t f : face_indices)
      fs.push_back(shared_->faces[f]);
    const std::size_t label = solver_.add_source_region(fs);
    seeds_.insert(seeds_.end(), face_indices.begin(), face_indices.end());
    return label;
  }

  /// Adds vertex `v` as a source; returns its label.
  std::size_t add_source(vertex_descriptor v)
  {
    const std::uint32_t i = vertex_index(v);
    const std::size_t label = solver_.add_source(v);
    auto range = incident_faces(i);
    seeds_.insert(seeds_.end(), range.first, range.second);
    return label;
  }

  /// Adds a surface point as a source; returns its label.
  std::size_t add_source(const Face_location& p)
  {
    const std::uint32_t f = face_index(p.first);
    const std::size_t label = solver_.add_source(p);
    seeds_.push_back(f);
    point_sources_.push_back({f, p.second});
    return label;
  }

  /// Exact distance at vertex index `v` (+infinity beyond the propagated bound).
  double vertex_distance(std::uint32_t v) const { return solver_.distance(shared_->vertices[v]); }

  /// Exact distance at the point of face `f` with barycentric coordinates `b`.
  double point_distance(std::uint32_t f, const std::array<double, 3>& b) const
  {
    return solver_.distance(Face_location(shared_->faces[f], b));
  }

  /// Makes distances exact up to `bound` (continues the propagation).
  void propagate_to(double bound)
  {
    if(bound > bound_)
    {
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
    // Distances are made exact up to radius + margin; beyond the bound a value is unknown and taken
    // as the bound, so the margin must be positive. It trades propagation for edge queries: an edge
    // with both ends beyond the bound can still dip within the radius and is then queried. One
    // median edge: most edges are then decided by their ends, and the propagation (whose windows
    // grow faster than the area reached) stops as close to the radius as that allows.
    propagate_to(radius + shared_->median_edge_length);
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
      Face_visit v{f, infinity, -1, no_source};
      std::array<double, 3> closest{1, 0, 0};
      if(!face_min(f, radius, with_label, v.min_distance, closest))
        continue;
      if(with_fraction)
        v.covered_fraction = covered_fraction(f, radius);
      if(with_label)
        v.label = solver_.nearest_source(Face_location(shared_->faces[f], closest));
      visit(static_cast<const Face_visit&>(v));
      for(std::uint32_t c : shared_->corners[f])
      {
        auto range = incident_faces(c);
        for(const std::uint32_t* g = range.first; g != range.second; ++g)
          if(stamp_[*g] != current_stamp_)
          {
            stamp_[*g] = current_stamp_;
            queue.push_back(*g);
          }
      }
    }
  }

  /// Fraction of the area of face `f` within distance `radius` of the sources (see the class
  /// documentation for the rule). Requires a previous `visit_band()` or `propagate_to()` with a
  /// bound of at least `radius` plus the longest edge of `f`.
  double covered_fraction(std::uint32_t f, double radius)
  {
    propagate_to(radius + max_edge(f));
    const int n = area_resolution_;
    // node (i,j): barycentric (1 - (i+j)/n, i/n, j/n)
    std::vector<double> value((n + 1) * (n + 2) / 2);
    auto node = [n](int i, int j) { return j * (n + 1) - j * (j - 1) / 2 + i; };
    const auto& c = shared_->corners[f];
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i + j <= n; ++i)
      {
        double d;
        if(i == 0 && j == 0) d = vertex_distance(c[0]);
        else if(i == n) d = vertex_distance(c[1]);
        else if(j == n) d = vertex_distance(c[2]);
        else d = point_distance(f, {1.0 - double(i + j) / n, double(i) / n, double(j) / n});
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

  /// Longest metric edge of face `f`.
  double max_edge(std::uint32_t f) const
  {
    const auto& l = shared_->edge_length[f];
    return std::max({l[0], l[1], l[2]});
  }

private:
  struct Shared
  {
    explicit Shared(const TriangleMesh& m)
      : tm(m), vertex_id(get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), m)),
        face_id(get(CGAL::dynamic_face_property_t<std::uint32_t>(), m))
    {}
    const TriangleMesh& tm;
    typename boost::property_map<TriangleMesh, CGAL::dynamic_vertex_property_t<std::uint32_t>>::const_type vertex_id;
    typename boost::property_map<TriangleMesh, CGAL::dynamic_face_property_t<std::uint32_t>>::const_type face_id;
    std::vector<vertex_descriptor> vertices;
    std::vector<face_descriptor> faces;
    std::vector<std::array<std::uint32_t, 3>> corners;
    std::vector<std::array<double, 3>> edge_length;
    std::vector<std::uint32_t> first_face, incident_faces;
    std::size_t face_index_end = 0, vertex_index_end = 0; // for index-based descriptors: one past the largest
    double median_edge_length = 0;
  };

  // The median, not the mean: in the isophotic metric the few edges across sharp features are
  // long (the normal jumps), and on CAD parts they raise the mean several-fold. It is positive, as
  // the margin must be: the input checks reject edges of length 0 in the lifted embedding.
  static double median_edge_length(const std::vector<std::array<double, 3>>& edge_length)
  {
    std::vector<double> all;
    all.reserve(3 * edge_length.size());
    for(const auto& len : edge_length)
      all.insert(all.end(), len.begin(), len.end());
    if(all.empty())
      return 0;
    std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
    return all[all.size() / 2];
  }

  Face_band_solver(const Face_band_solver& other, int)
    : solver_(other.solver_.sibling()), shared_(other.shared_), area_resolution_(other.area_resolution_),
      stamp_(other.shared_->faces.size(), 0)
  {}

  template <class Descriptor, class IdMap>
  static std::uint32_t checked(const Descriptor& d, const std::vector<Descriptor>& all, const IdMap& ids, const char* kind,
                               std::size_t index_end)
  {
    bool ok = !(d == Descriptor());
    std::uint32_t i = 0;
    if constexpr(std::is_convertible<Descriptor, std::size_t>::value)
      ok = ok && static_cast<std::size_t>(d) < index_end;
    if(ok)
    {
      i = get(ids, d);
      ok = i < all.size() && all[i] == d;
    }
    if(!ok)
      throw Invalid_source_error(internal::describe_element(kind, d, i) + " is not an element of the mesh");
    return i;
  }

  // Minimum of the distance over the closed face f. Returns whether it is <= radius. Stops at the
  // first point found within the radius unless `exact`; `closest` receives that point.
  bool face_min(std::uint32_t f, double radius, bool exact, double& minimum, std::array<double, 3>& closest)
  {
    const auto& c = shared_->corners[f];
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
      const double a = std::min(dv[k], bound_), b = std::min(dv[(k + 1) % 3], bound_), len = shared_->edge_length[f][k];
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
    const double m = solver_.minimum_distance_on_segment(Face_location(shared_->faces[f], from),
                                                         Face_location(shared_->faces[f], to), &t_best);
    return std::min(m, bound_);
  }

private:
  Solver solver_;
  std::shared_ptr<Shared> shared_;
  int area_resolution_ = 4;
  std::vector<std::uint32_t> seeds_;
  std::vector<std::pair<std::uint32_t, std::array<double, 3>>> point_sources_;
  double bound_ = -1;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t current_stamp_ = 0;
};

namespace internal {

// Runs `task(band_solver)` with the solver passed as named parameter `face_band_solver` (a pointer),
// or with a new one built from the metric parameters of `np`.
template <class TriangleMesh, class NamedParameters, class Task>
decltype(auto) with_band_solver(const TriangleMesh& tm, const NamedParameters& np, Task&& task)
{
  using parameters::get_parameter;
  if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::face_band_solver_t>::value)
  {
    Face_band_solver<TriangleMesh>* solver = get_parameter(np, internal_np::face_band_solver);
    if(solver == nullptr || &solver->mesh() != &tm)
      throw Invalid_parameter_error("face_band_solver must point to a Face_band_solver built on the same mesh");
    return task(*solver);
  }
  else
  {
    Face_band_solver<TriangleMesh> solver(tm, np);
    return task(solver);
  }
}

} // namespace internal

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_MORPHOLOGY_FACE_BAND_SOLVER_H
