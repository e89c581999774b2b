// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Robustness of the exact geodesic engine on damaged and extreme input: isolated vertices, models
// at any scale of the double range, caps, needles and collapsed corners, several components,
// holes. Every distance is checked against bounds computed here, in long double, independently of
// the engine: never above the length of an explicit path on the surface (edge-graph Dijkstra,
// point sources joined straight to their face's corners), never below the straight chord in R^3 or
// R^6, |d(u) - d(v)| <= l(uv) on every edge, +inf exactly where nothing is connected to a source,
// a traced path as long as its distance, the field of point queries 1-Lipschitz along the edges of
// the faces (IM_ROBUSTNESS_FIELD_SAMPLES points an edge), and, in the Euclidean case, CGAL's exact
// Surface_mesh_shortest_path.
//
// The randomized campaign runs IM_ROBUSTNESS_CASES cases (default: a few, for CI) from the seed
// IM_ROBUSTNESS_SEED (default 1); e.g. IM_ROBUSTNESS_CASES=5000 for a long campaign. A failure
// names its case; IM_ROBUSTNESS_ONLY_CASE=i (same count and seed) checks that case alone, and
// IM_ROBUSTNESS_WRITE=file.off then writes its mesh. IM_ROBUSTNESS_DAMAGES=n (default 8) draws up
// to n - 1 damages per mesh instead of 7. The cases that failed in long campaigns are
// replayed by CasesThatFailedInLongCampaigns.
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/Face_filtered_graph.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <queue>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
typedef IM::Geodesic_solver<Mesh> Solver;
typedef Solver::Face_location Face_location;
typedef long double Real; // the bounds: 64-bit mantissa, exponents to 1e+-4932 (no overflow at any scale)
typedef std::array<Real, 6> Lifted;

namespace {

const double inf = std::numeric_limits<double>::infinity();

Mesh load(const std::string& name)
{
  Mesh m;
  if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path(name), m))
    throw std::runtime_error("cannot read " + name);
  return m;
}

bool is_isolated(vertex_descriptor v, const Mesh& m) { return halfedge(v, m) == Mesh::null_halfedge(); }

Real distance(const Lifted& a, const Lifted& b)
{
  Real s = 0;
  for(int i = 0; i < 6; ++i)
    s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

Lifted combination(const std::array<Lifted, 3>& corners, const std::array<double, 3>& b)
{
  Lifted x{};
  for(int c = 0; c < 3; ++c)
    for(int i = 0; i < 6; ++i)
      x[i] += b[c] * corners[c][i];
  return x;
}

// Distance from x to the segment ab, and to the triangle abc (all in R^6).
Real segment_distance(const Lifted& x, const Lifted& a, const Lifted& b)
{
  Real ab2 = 0, t = 0;
  for(int i = 0; i < 6; ++i)
  {
    ab2 += (b[i] - a[i]) * (b[i] - a[i]);
    t += (x[i] - a[i]) * (b[i] - a[i]);
  }
  t = ab2 > 0 ? std::clamp(t / ab2, Real(0), Real(1)) : Real(0);
  Lifted p;
  for(int i = 0; i < 6; ++i)
    p[i] = a[i] + t * (b[i] - a[i]);
  return distance(x, p);
}

Real triangle_distance(const Lifted& x, const std::array<Lifted, 3>& t)
{
  Real e00 = 0, e01 = 0, e11 = 0, r0 = 0, r1 = 0;
  for(int i = 0; i < 6; ++i)
  {
    const Real u = t[1][i] - t[0][i], v = t[2][i] - t[0][i], r = x[i] - t[0][i];
    e00 += u * u;
    e01 += u * v;
    e11 += v * v;
    r0 += r * u;
    r1 += r * v;
  }
  const Real det = e00 * e11 - e01 * e01;
  if(det > 1e-12L * e00 * e11)
  {
    const Real s = (r0 * e11 - r1 * e01) / det, q = (r1 * e00 - r0 * e01) / det;
    if(s >= 0 && q >= 0 && s + q <= 1)
      return distance(x, combination(t, {double(1 - s - q), double(s), double(q)}));
  }
  return std::min({segment_distance(x, t[0], t[1]), segment_distance(x, t[1], t[2]), segment_distance(x, t[2], t[0])});
}

// The three corners of f in the order of Face_location's barycentric coordinates.
std::array<vertex_descriptor, 3> corners(face_descriptor f, const Mesh& m)
{
  const halfedge_descriptor h = halfedge(f, m);
  return {source(h, m), target(h, m), target(next(h, m), m)};
}

// A source as the checks see it: where it is in R^6 (for chords) and which vertices it reaches
// along a straight segment inside a face, at what length (the start of the explicit paths).
struct Source
{
  enum Kind { VERTEX, POINT, REGION } kind;
  vertex_descriptor vertex;
  Face_location point;
  std::vector<face_descriptor> region;
  std::string describe() const
  {
    std::ostringstream s;
    s.precision(17); // (enough to reproduce the case)
    if(kind == VERTEX)
      s << "vertex " << vertex;
    else if(kind == POINT)
      s << "point " << point.first << " (" << point.second[0] << ", " << point.second[1] << ", " << point.second[2] << ")";
    else
    {
      s << "region of faces";
      for(face_descriptor f : region)
        s << " " << f;
    }
    return s.str();
  }
};

// A count from the environment (the campaign's settings), else `fallback`.
std::size_t environment_count(const char* name, std::size_t fallback)
{
  const char* value = std::getenv(name);
  return value != nullptr ? static_cast<std::size_t>(std::strtoull(value, nullptr, 10)) : fallback;
}

// What one case found wrong, with enough to reproduce it.
struct Verdict
{
  std::vector<std::string> failures;
  std::size_t checked_distances = 0;
  bool compared_with_cgal = false;
  bool cgal_failed = false; // CGAL's reference did not finish on this mesh
  std::size_t below_cgal = 0; // vertices where CGAL's distance is above a path we traced
  std::size_t below_cgals_path = 0; // vertices where CGAL's distance is below the length of its own path
  void fail(const std::string& what)
  {
    if(failures.size() < 5)
      failures.push_back(what);
    else if(failures.size() == 5)
      failures.push_back("...");
  }
};

// The lifted embedding the solver works on: (sqrt(w) p, 0) for the Euclidean metric.
std::vector<Lifted> lifted_points(const Mesh& m, bool euclidean, double w, double w_iso, double L)
{
  std::vector<Lifted> x(num_vertices(m));
  if(euclidean)
  {
    for(vertex_descriptor v : vertices(m))
      x[v] = {Real(m.point(v).x()), Real(m.point(v).y()), Real(m.point(v).z()), 0, 0, 0};
    return x;
  }
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  IM::compute_lifted_embedding(m, lifted,
                               IM::parameters::euclidean_weight(w).isophotic_weight(w_iso).weight_length_scale(L));
  for(vertex_descriptor v : vertices(m))
    for(int i = 0; i < 6; ++i)
      x[v][i] = get(lifted, v)[i];
  return x;
}

// Length of the shortest explicit surface path from the sources to every vertex: straight inside
// the face of a point source to its corners, then along edges (lengths of the lifted edges).
std::vector<Real> explicit_path_lengths(const Mesh& m, const std::vector<Lifted>& x, const std::vector<Source>& sources)
{
  std::vector<Real> d(num_vertices(m), std::numeric_limits<Real>::infinity());
  typedef std::pair<Real, vertex_descriptor> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  auto seed = [&](vertex_descriptor v, Real value) {
    if(value < d[v])
    {
      d[v] = value;
      queue.push({value, v});
    }
  };
  for(const Source& s : sources)
  {
    if(s.kind == Source::VERTEX)
      seed(s.vertex, 0);
    else if(s.kind == Source::REGION)
    {
      for(face_descriptor f : s.region)
        for(vertex_descriptor v : corners(f, m))
          seed(v, 0);
    }
    else
    {
      const std::array<vertex_descriptor, 3> c = corners(s.point.first, m);
      const Lifted p = combination({x[c[0]], x[c[1]], x[c[2]]}, s.point.second);
      for(vertex_descriptor v : c)
        seed(v, distance(p, x[v]));
    }
  }
  while(!queue.empty())
  {
    const auto [value, v] = queue.top();
    queue.pop();
    if(value > d[v] || is_isolated(v, m))
      continue;
    for(vertex_descriptor u : vertices_around_target(halfedge(v, m), m))
      seed(u, value + distance(x[u], x[v]));
  }
  return d;
}

// Lower bound: the straight chord in R^6 from the nearest source.
Real chord(const Mesh& m, const std::vector<Lifted>& x, const std::vector<Source>& sources, const Lifted& target)
{
  Real best = std::numeric_limits<Real>::infinity();
  for(const Source& s : sources)
  {
    if(s.kind == Source::VERTEX)
      best = std::min(best, distance(x[s.vertex], target));
    else if(s.kind == Source::POINT)
    {
      const std::array<vertex_descriptor, 3> c = corners(s.point.first, m);
      best = std::min(best, distance(combination({x[c[0]], x[c[1]], x[c[2]]}, s.point.second), target));
    }
    else
      for(face_descriptor f : s.region)
      {
        const std::array<vertex_descriptor, 3> c = corners(f, m);
        best = std::min(best, triangle_distance(target, {x[c[0]], x[c[1]], x[c[2]]}));
      }
  }
  return best;
}

// CGAL's exact shortest paths on the components of the sources (its package needs connected
// input): distances of the vertices of those components, -1 elsewhere, followed by the lengths of
// CGAL's own paths to the vertices `paths_to` (-1 outside those components). Point sources only.
std::vector<double> cgal_reference_in_process(const Mesh& m, const std::vector<Source>& sources, double scale,
                                              const std::vector<vertex_descriptor>& paths_to)
{
  auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  CGAL::Polygon_mesh_processing::connected_components(m, component);
  std::vector<double> result(num_vertices(m) + paths_to.size(), -1);
  std::vector<std::size_t> done;
  for(const Source& s : sources)
  {
    face_descriptor f0 = s.kind == Source::POINT ? s.point.first : Mesh::null_face();
    if(s.kind == Source::VERTEX && is_isolated(s.vertex, m))
      continue; // reaches nothing but itself
    if(s.kind == Source::VERTEX)
      for(halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(s.vertex, m), m))
        if(!is_border(h, m))
          f0 = face(h, m);
    const std::size_t c = get(component, f0);
    if(std::find(done.begin(), done.end(), c) != done.end())
      continue;
    done.push_back(c);
    // The component, unscaled (the scale is a power of two: exact), copied apart.
    std::vector<face_descriptor> faces_of_c;
    for(face_descriptor f : faces(m))
      if(get(component, f) == c)
        faces_of_c.push_back(f);
    Mesh part;
    std::map<vertex_descriptor, vertex_descriptor> v2v;
    std::map<face_descriptor, face_descriptor> f2f;
    CGAL::copy_face_graph(CGAL::Face_filtered_graph<Mesh>(m, faces_of_c), part,
                          CGAL::parameters::vertex_to_vertex_map(boost::make_assoc_property_map(v2v))
                            .face_to_face_map(boost::make_assoc_property_map(f2f)));
    for(vertex_descriptor v : vertices(part))
      part.point(v) = Point(part.point(v).x() / scale, part.point(v).y() / scale, part.point(v).z() / scale);
    typedef CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<K, Mesh>> Shortest_path;
    Shortest_path reference(part);
    for(const Source& t : sources)
    {
      if(t.kind == Source::VERTEX && v2v.count(t.vertex))
        reference.add_source_point(v2v.at(t.vertex));
      if(t.kind == Source::POINT && f2f.count(t.point.first))
      {
        // barycentric coordinates follow the corners of the copy's face
        const face_descriptor g = f2f.at(t.point.first);
        const std::array<vertex_descriptor, 3> original = corners(t.point.first, m), copy = corners(g, part);
        std::array<double, 3> b{0, 0, 0};
        for(int i = 0; i < 3; ++i)
          for(int j = 0; j < 3; ++j)
            if(v2v.at(original[j]) == copy[i])
              b[i] = t.point.second[j];
        reference.add_source_point(g, Shortest_path::Barycentric_coordinates{{b[0], b[1], b[2]}});
      }
    }
    for(const auto& [v, pv] : v2v)
      result[v] = scale * reference.shortest_distance_to_source_points(pv).first;
    for(std::size_t k = 0; k < paths_to.size(); ++k)
    {
      if(v2v.count(paths_to[k]) == 0)
        continue;
      std::vector<Point> points;
      reference.shortest_path_points_to_source_points(v2v.at(paths_to[k]), std::back_inserter(points));
      Real length = 0;
      for(std::size_t i = 0; i + 1 < points.size(); ++i)
        length += std::sqrt(Real(CGAL::squared_distance(points[i], points[i + 1])));
      result[num_vertices(m) + k] = double(scale * length);
    }
  }
  return result;
}

// CGAL's reference, run in a child process: CGAL 5.5.1's unfolding with inexact constructions can
// make a NaN on a damaged mesh (case 1081 of seed 11 with 80 damages: a NaN coordinate reaches
// Orientation_2 in Cone_tree_node::has_left_side, an assertion with CGAL's checks on, a segmentation
// fault without), which would end the whole campaign. Empty when the reference did not finish; the
// case is then checked by the other bounds only, and the campaign counts it.
std::vector<double> cgal_reference(const Mesh& m, const std::vector<Source>& sources, double scale,
                                   const std::vector<vertex_descriptor>& paths_to = {})
{
  int channel[2];
  if(pipe(channel) != 0)
  {
    ADD_FAILURE() << "no pipe for CGAL's reference";
    return {};
  }
  std::cout.flush();
  const pid_t child = fork();
  if(child < 0)
  {
    ADD_FAILURE() << "no child process for CGAL's reference";
    close(channel[0]);
    close(channel[1]);
    return {};
  }
  if(child == 0)
  {
    close(channel[0]);
    bool finished = false;
    try
    {
      const std::vector<double> d = cgal_reference_in_process(m, sources, scale, paths_to);
      std::cout.flush();
      const char* bytes = reinterpret_cast<const char*>(d.data());
      std::size_t left = d.size() * sizeof(double);
      while(left > 0)
      {
        const ssize_t written = write(channel[1], bytes, left);
        if(written <= 0)
          break;
        bytes += written;
        left -= std::size_t(written);
      }
      finished = left == 0;
    }
    catch(...)
    {
    }
    close(channel[1]);
    _exit(finished ? 0 : 1); // (no destructors of the parent's objects, no gtest report)
  }
  close(channel[1]);
  std::vector<double> d(num_vertices(m) + paths_to.size());
  char* bytes = reinterpret_cast<char*>(d.data());
  std::size_t left = d.size() * sizeof(double);
  while(left > 0)
  {
    const ssize_t got = read(channel[0], bytes, left);
    if(got <= 0)
      break;
    bytes += got;
    left -= std::size_t(got);
  }
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if(left != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return {};
  return d;
}

// Vertices connected to a source (through faces and edges).
std::vector<char> reachable(const Mesh& m, const std::vector<Source>& sources)
{
  std::vector<char> seen(num_vertices(m), 0);
  std::vector<vertex_descriptor> stack;
  auto visit = [&](vertex_descriptor v) {
    if(!seen[v])
    {
      seen[v] = 1;
      stack.push_back(v);
    }
  };
  for(const Source& s : sources)
  {
    if(s.kind == Source::VERTEX)
      visit(s.vertex);
    else
      for(face_descriptor f : s.kind == Source::POINT ? std::vector<face_descriptor>{s.point.first} : s.region)
        for(vertex_descriptor v : corners(f, m))
          visit(v);
  }
  while(!stack.empty())
  {
    const vertex_descriptor v = stack.back();
    stack.pop_back();
    if(!is_isolated(v, m))
      for(vertex_descriptor u : vertices_around_target(halfedge(v, m), m))
        visit(u);
  }
  return seen;
}

// How far the shapes of the mesh's ill-shaped faces are left open by their rounded edge lengths
// (see check_case), summed: eps l^2 / h per face of smallest height h below 1e-4 l, at most
// sqrt(eps) l, four times over.
Real shape_uncertainty(const Mesh& m, const std::vector<Lifted>& x)
{
  const Real eps = std::numeric_limits<double>::epsilon();
  Real sum = 0;
  for(face_descriptor f : faces(m))
  {
    const std::array<vertex_descriptor, 3> c = corners(f, m);
    const Real a = distance(x[c[0]], x[c[1]]), b = distance(x[c[1]], x[c[2]]), e = distance(x[c[2]], x[c[0]]);
    const Real l = std::max({a, b, e}), s = (a + b + e) / 2;
    const Real area = std::sqrt(std::max(Real(0), s * (s - a) * (s - b) * (s - e)));
    const Real h = 2 * area / l;
    if(h < 1e-4L * l)
      sum += 4 * std::min(std::sqrt(eps) * l, h > 0 ? eps * l * l / h : l);
  }
  return sum;
}

// Every check of one solved case. `scale` is the power of two the model was multiplied by.
Verdict check_case(const Mesh& m, const std::vector<Source>& sources, bool euclidean, double w, double w_iso,
                   double L, double scale, std::mt19937_64& random, bool compare_with_cgal)
{
  Verdict verdict;
  const auto np = euclidean ? IM::parameters::euclidean_weight(1.0).isophotic_weight(0.0).weight_length_scale(1.0)
                            : IM::parameters::euclidean_weight(w).isophotic_weight(w_iso).weight_length_scale(L);
  auto solve = [&](Solver& solver) {
    for(const Source& s : sources)
    {
      if(s.kind == Source::VERTEX)
        solver.add_source(s.vertex);
      else if(s.kind == Source::POINT)
        solver.add_source(s.point);
      else
        solver.add_source_region(s.region);
    }
    solver.propagate();
  };
  Solver solver(m, np);
  solve(solver);
  // Without stored windows the engine also cuts the windows of a batch by each other: the same
  // distances, to the rounding checked below.
  Solver distance_only(m, np.store_windows(false));
  solve(distance_only);

  const std::vector<Lifted> x = lifted_points(m, euclidean, w, w_iso, L);
  const std::vector<Real> upper = explicit_path_lengths(m, x, sources);
  const std::vector<char> connected = reachable(m, sources);
  // Rounding: the engine computes each distance to a relative 1e-15 or so, unfolding every face
  // it crosses from edge lengths known to one ulp; 1e-12 leaves room for a million faces. Beyond
  // that, the input itself: the engine sees a face through its three lengths rounded to doubles,
  // which fix its shape only to about eps l^2 / h (l its longest edge, h its smallest height; for
  // a cap at most sqrt(eps) l: a cap of height 1e-9 l has lengths that fit any height below 1e-8 l).
  // Distances through such faces may differ from the 3D surface's by that much: an absolute
  // slack, the sum over the mesh's ill-shaped faces (zero for a mesh without them).
  const Real relative = 1e-12L;
  const Real slack = shape_uncertainty(m, x);
  auto name = [&](vertex_descriptor v) { std::ostringstream s; s << v; return s.str(); };
  for(vertex_descriptor v : vertices(m))
  {
    const double d = solver.distance(v);
    ++verdict.checked_distances;
    const double d_only = distance_only.distance(v);
    if(d_only != d && !(std::abs(Real(d_only) - Real(d)) <= Real(d) * relative + slack))
    {
      std::ostringstream s;
      s.precision(17);
      s << "vertex " << v << ": distance " << d << " with stored windows, " << d_only << " without";
      verdict.fail(s.str());
    }
    if((d < inf) != bool(connected[v]))
    {
      verdict.fail("vertex " + name(v) + ": distance " + std::to_string(d) + " but " +
                   (connected[v] ? "connected to" : "not connected to") + " a source");
      continue;
    }
    if(!(d < inf))
      continue;
    if(d > upper[v] * (1 + relative) + slack)
    {
      std::ostringstream s;
      s.precision(17);
      s << "vertex " << v << ": distance " << d << " above an explicit surface path of length " << double(upper[v]);
      verdict.fail(s.str());
    }
    const Real lower = chord(m, x, sources, x[v]);
    if(d < lower * (1 - relative) - slack)
    {
      std::ostringstream s;
      s.precision(17);
      s << "vertex " << v << ": distance " << d << " below the chord " << double(lower);
      verdict.fail(s.str());
    }
  }
  for(auto e : edges(m))
  {
    const vertex_descriptor u = source(e, m), v = target(e, m);
    const double du = solver.distance(u), dv = solver.distance(v);
    if(!(du < inf) || !(dv < inf))
      continue;
    const Real l = distance(x[u], x[v]);
    // (|du - dv| carries the rounding of the larger distance)
    if(std::abs(Real(du) - Real(dv)) > l * (1 + relative) + 1e-13L * std::max(du, dv) + slack)
    {
      std::ostringstream s;
      s.precision(17);
      s << "edge (" << u << ", " << v << "): |d(u) - d(v)| = " << std::abs(du - dv) << " above its length " << double(l);
      verdict.fail(s.str());
    }
  }

  std::vector<vertex_descriptor> below_cgal;
  // CGAL's package takes no region, and is wrong for a point exactly on an edge (CGAL 5.5.1: on
  // cube-meshed, a source at the middle of an edge gives 0.0707 at a vertex where moving the source
  // 1e-9 into its face gives 0.1061, as we do for both). It is given such a point 1e-9 into its
  // face (the coordinate 0 raised to 1e-9, taken from the largest): no distance moves by more than
  // the length of that displacement, added to the tolerance.
  const bool cgal_applies = std::none_of(sources.begin(), sources.end(), [](const Source& s) { return s.kind == Source::REGION; });
  if(compare_with_cgal && euclidean && cgal_applies)
  {
    std::vector<Source> inside = sources;
    Real moved = 0;
    for(Source& s : inside)
    {
      std::array<double, 3>& b = s.point.second;
      if(s.kind != Source::POINT || std::count(b.begin(), b.end(), 0.0) != 1)
        continue;
      const std::array<double, 3> on_edge = b;
      b[std::find(b.begin(), b.end(), 0.0) - b.begin()] = 1e-9;
      b[std::max_element(b.begin(), b.end()) - b.begin()] -= 1e-9;
      const std::array<vertex_descriptor, 3> t = corners(s.point.first, m);
      Lifted p{}, q{};
      for(int i = 0; i < 3; ++i)
        for(int k = 0; k < 6; ++k)
        {
          p[k] += Real(on_edge[i]) * x[t[i]][k];
          q[k] += Real(b[i]) * x[t[i]][k];
        }
      moved = std::max(moved, distance(p, q));
    }
    // Both compute the exact polyhedral distance; they differ by the rounding of two unfoldings.
    const std::vector<double> reference = cgal_reference(m, inside, scale);
    verdict.compared_with_cgal = !reference.empty();
    verdict.cgal_failed = reference.empty();
    std::vector<vertex_descriptor> above_cgal;
    auto tolerance = [&](double d) { return 1e-9 * d + double(slack + moved); };
    for(vertex_descriptor v : vertices(m))
    {
      if(reference.empty() || reference[v] < 0)
        continue;
      const double d = solver.distance(v);
      if(std::abs(d - reference[v]) <= tolerance(reference[v]))
        continue;
      if(d < reference[v])
      {
        // Below CGAL: right if our path to v is a real one of that length (checked below). CGAL
        // 5.5.1 misses such paths across collapsed corners (cube-meshed: 5e-4 above ours).
        below_cgal.push_back(v);
        continue;
      }
      above_cgal.push_back(v);
    }
    // Above CGAL: wrong unless CGAL's distance is below the length of its own path to v, and that
    // path is as long as our distance. CGAL 5.5.1 reports such distances where its path runs
    // through corners a collapse left 1e-13 apart (case 1408 of seed 11 with 80 damages: 3.7e-7
    // below its path to v0, whose length is ours to 2e-14).
    if(!above_cgal.empty())
    {
      const std::vector<double> with_paths = cgal_reference(m, inside, scale, above_cgal);
      for(std::size_t k = 0; k < above_cgal.size(); ++k)
      {
        const vertex_descriptor v = above_cgal[k];
        const double d = solver.distance(v);
        const double path = with_paths.empty() ? -1 : with_paths[num_vertices(m) + k];
        if(path >= 0 && std::abs(path - d) <= tolerance(d))
        {
          ++verdict.below_cgals_path;
          continue;
        }
        std::ostringstream s;
        s.precision(17);
        s << "vertex " << v << ": distance " << d << ", CGAL's Surface_mesh_shortest_path " << reference[v]
          << ", the length of CGAL's path " << path << " (explicit path " << double(upper[v]) << ", chord "
          << double(chord(m, x, sources, x[v])) << ")";
        verdict.fail(s.str());
      }
    }
  }
  // Traced paths: on the surface (consecutive points in a common face), as long as the distance:
  // the distance is then the length of a real path, never below the geodesic distance.
  std::vector<vertex_descriptor> targets;
  for(vertex_descriptor v : vertices(m))
    if(connected[v] && !is_isolated(v, m))
      targets.push_back(v);
  std::shuffle(targets.begin(), targets.end(), random);
  targets.resize(std::min<std::size_t>(targets.size(), 8));
  verdict.below_cgal = below_cgal.size();
  targets.insert(targets.end(), below_cgal.begin(), below_cgal.begin() + std::min<std::size_t>(below_cgal.size(), 200));
  for(vertex_descriptor v : targets)
  {
    std::vector<Face_location> path;
    solver.trace_path(solver.location(v), std::back_inserter(path));
    Real length = 0;
    for(std::size_t i = 0; i + 1 < path.size(); ++i)
    {
      const std::array<vertex_descriptor, 3> a = corners(path[i].first, m), b = corners(path[i + 1].first, m);
      // a face holding the support (corners of non-zero weight) of both points
      std::vector<vertex_descriptor> support;
      for(int c = 0; c < 3; ++c)
      {
        if(path[i].second[c] > 0)
          support.push_back(a[c]);
        if(path[i + 1].second[c] > 0)
          support.push_back(b[c]);
      }
      bool common_face = false;
      for(halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(support.front(), m), m))
      {
        if(is_border(h, m))
          continue;
        const std::array<vertex_descriptor, 3> f = corners(face(h, m), m);
        common_face = common_face || std::all_of(support.begin(), support.end(), [&](vertex_descriptor u) {
                        return std::find(f.begin(), f.end(), u) != f.end();
                      });
      }
      if(!common_face)
      {
        std::ostringstream s;
        s << "path from vertex " << v << ": points " << i << " and " << i + 1 << " share no face: "
          << path[i].first << " (" << path[i].second[0] << ", " << path[i].second[1] << ", " << path[i].second[2] << "), "
          << path[i + 1].first << " (" << path[i + 1].second[0] << ", " << path[i + 1].second[1] << ", "
          << path[i + 1].second[2] << ")";
        verdict.fail(s.str());
        break;
      }
      length += distance(combination({x[a[0]], x[a[1]], x[a[2]]}, path[i].second),
                         combination({x[b[0]], x[b[1]], x[b[2]]}, path[i + 1].second));
    }
    // it ends at a source: a point source itself, a vertex of a region
    const std::array<vertex_descriptor, 3> last = corners(path.back().first, m);
    const Lifted end = combination({x[last[0]], x[last[1]], x[last[2]]}, path.back().second);
    Real size = 0; // (the rounding of a position is relative to its coordinates)
    for(Real e : end)
      size = std::max(size, std::abs(e));
    if(chord(m, x, sources, end) > 1e-12L * (length + size) + slack)
    {
      std::ostringstream s;
      s << "path from vertex " << v << " ends at " << path.back().first << ", " << double(chord(m, x, sources, end))
        << " away from every source";
      verdict.fail(s.str());
    }
    const double d = solver.distance(v);
    if(std::abs(length - Real(d)) > 1e-9L * d + slack)
    {
      std::ostringstream s;
      s.precision(17);
      s << "path from vertex " << v << ": length " << double(length) << ", distance " << d;
      verdict.fail(s.str());
    }
  }

  // Point queries inside faces: between the chord and the paths through the face's corners.
  for(int k = 0; k < 8 && num_faces(m) > 0; ++k)
  {
    const face_descriptor f(static_cast<Mesh::size_type>(random() % num_faces(m)));
    std::uniform_real_distribution<double> unit(0, 1);
    double b0 = unit(random), b1 = unit(random);
    if(b0 + b1 > 1)
    {
      b0 = 1 - b0;
      b1 = 1 - b1;
    }
    const Face_location p(f, {b0, b1, 1 - b0 - b1});
    const double d = solver.distance(p);
    const std::array<vertex_descriptor, 3> c = corners(f, m);
    const Lifted xp = combination({x[c[0]], x[c[1]], x[c[2]]}, p.second);
    Real through_corners = std::numeric_limits<Real>::infinity();
    for(vertex_descriptor v : c)
      through_corners = std::min(through_corners, upper[v] + distance(xp, x[v]));
    const Real lower = chord(m, x, sources, xp);
    const bool region_face = std::any_of(sources.begin(), sources.end(), [&](const Source& s) {
      return s.kind == Source::REGION && std::find(s.region.begin(), s.region.end(), f) != s.region.end();
    });
    if(region_face ? d != 0
                   : ((d < inf) != (through_corners < std::numeric_limits<Real>::infinity()) ||
                      (d < inf && (d > through_corners * (1 + relative) + slack || d < lower * (1 - relative) - slack))))
    {
      std::ostringstream s;
      s.precision(17);
      s << "point of face " << f << ": distance " << d << ", chord " << double(lower) << ", path through a corner "
        << double(through_corners);
      verdict.fail(s.str());
    }
  }

  // The distance field is 1-Lipschitz: along each edge of a face, seen from just inside the face,
  // two points' distances differ by at most the length between them. A field that jumps is too
  // long on the high side (the low side plus the segment is a path there): the only bound here that
  // catches distances too long without CGAL (a region of faces, the isophotic metric). Each distance
  // carries the rounding of its unfolding, allowed 1e-9 of it as against CGAL (windows of one source
  // unfolded through different faces: 4e-10 apart on a fandisk in R^6 at w' = 0.96). Checked on
  // IM_ROBUSTNESS_FIELD_SAMPLES + 1 points an edge (default 32) of up to 4000 random faces.
  const std::size_t samples = std::max<std::size_t>(1, environment_count("IM_ROBUSTNESS_FIELD_SAMPLES", 32));
  std::vector<face_descriptor> sampled(faces(m).begin(), faces(m).end());
  std::shuffle(sampled.begin(), sampled.end(), random);
  sampled.resize(std::min<std::size_t>(sampled.size(), 4000));
  std::vector<double> along(samples + 1);
  const double inside = 1e-7;
  for(face_descriptor f : sampled)
  {
    const std::array<vertex_descriptor, 3> c = corners(f, m);
    for(int e = 0; e < 3; ++e)
    {
      std::array<double, 3> b{};
      for(std::size_t i = 0; i <= samples; ++i)
      {
        const double t = double(i) / double(samples);
        b[e] = (1 - t) * (1 - inside);
        b[(e + 1) % 3] = t * (1 - inside);
        b[(e + 2) % 3] = inside;
        along[i] = solver.distance(Face_location(f, b));
      }
      // (the points are evenly spaced on the edge's parallel, (1 - inside) times the edge long)
      const Real step = distance(x[c[e]], x[c[(e + 1) % 3]]) * Real(1 - inside) / Real(samples);
      for(std::size_t i = 0; i < samples; ++i)
        for(std::size_t j = i + 1; j <= samples; ++j)
        {
          if(!(along[i] < inf) || !(along[j] < inf))
            continue;
          const Real apart = step * Real(j - i);
          if(std::abs(Real(along[i]) - Real(along[j])) > apart * (1 + 1e-6L) + 1e-9L * std::max(along[i], along[j]) + slack)
          {
            std::ostringstream s;
            s.precision(17);
            s << "face " << f << ", along its edge (" << c[e] << ", " << c[(e + 1) % 3] << "): distances " << along[i]
              << " and " << along[j] << " at points " << double(apart) << " apart";
            verdict.fail(s.str());
            i = j = samples; // (one failure an edge)
          }
        }
    }
  }

  return verdict;
}

// ------------------------------------------------------------------ damage

Real edge_length_3(const Mesh& m, halfedge_descriptor h)
{
  return std::sqrt(Real(CGAL::squared_distance(m.point(source(h, m)), m.point(target(h, m)))));
}

// A corner moved onto (height 0) or next to (height > 0, relative to the edge) the opposite edge
// of its face, at a random place along it: a cap, or a collapsed corner.
void make_cap(Mesh& m, face_descriptor f, double height, std::mt19937_64& random)
{
  const halfedge_descriptor h = halfedge(f, m);
  const Point a = m.point(source(h, m)), b = m.point(target(h, m));
  const vertex_descriptor c = target(next(h, m), m);
  const Vector ab = b - a;
  const double t = std::uniform_real_distribution<double>(0.1, 0.9)(random);
  const Point foot = a + t * ab;
  Vector up = m.point(c) - foot;
  up = up - (up * ab) / (ab * ab) * ab; // perpendicular to ab, in the face's plane, towards c
  const double length = std::sqrt(up * up);
  m.point(c) = length > 0 ? foot + (height * std::sqrt(ab * ab) / length) * up : foot;
}

// An edge shrunk to `width` times its length: needles in its two faces.
void make_needle(Mesh& m, halfedge_descriptor h, double width)
{
  const Point a = m.point(source(h, m));
  m.point(target(h, m)) = a + width * (m.point(target(h, m)) - a);
}

// Removes a face none of whose vertices is on the border (the mesh stays manifold).
void make_hole(Mesh& m, face_descriptor f)
{
  for(vertex_descriptor v : corners(f, m))
    if(CGAL::is_border(v, m))
      return;
  CGAL::Euler::remove_face(halfedge(f, m), m);
}

// A randomized case: a small mesh of CGAL's data set, damaged, scaled, with random sources.
struct Case
{
  Mesh mesh;
  std::vector<Source> sources;
  bool euclidean;
  double w = 1, w_iso = 0, L = 1, scale = 1;
  std::string story;
};

Case random_case(std::mt19937_64& random, const std::vector<Mesh>& pool, const std::vector<std::string>& names,
                 std::size_t damage_draws = 8)
{
  Case c;
  std::uniform_real_distribution<double> unit(0, 1);
  auto chance = [&](double p) { return unit(random) < p; };
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(random() % n); };
  std::ostringstream story;
  const std::size_t k = pick(pool.size());
  c.mesh = pool[k];
  Mesh& m = c.mesh;
  story << names[k];
  if(chance(0.3))
  {
    // a second component: another mesh of the pool, shifted
    const std::size_t j = pick(pool.size());
    const std::size_t before = num_vertices(m);
    CGAL::copy_face_graph(pool[j], m);
    const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(pool[k]);
    for(std::size_t i = before; i < num_vertices(m); ++i)
      m.point(vertex_descriptor(i)) = m.point(vertex_descriptor(i)) + Vector(1.5 * (box.xmax() - box.xmin()), 0, 0);
    story << " + " << names[j];
  }
  // mean edge length, for the noise
  double mean = 0;
  for(auto e : edges(m))
    mean += double(edge_length_3(m, halfedge(e, m)));
  mean /= std::max<std::size_t>(1, num_edges(m));
  if(chance(0.3))
  {
    const double sigma = chance(0.5) ? 1e-3 : 0.1;
    std::normal_distribution<double> noise(0, sigma * mean);
    for(vertex_descriptor v : vertices(m))
      m.point(v) = m.point(v) + Vector(noise(random), noise(random), noise(random));
    story << ", noise " << sigma;
  }
  const int damages = static_cast<int>(pick(damage_draws)); // at most damage_draws - 1
  for(int i = 0; i < damages; ++i)
  {
    const face_descriptor f(static_cast<Mesh::size_type>(pick(num_faces(m))));
    if(m.is_removed(f))
      continue;
    switch(pick(5))
    {
    case 0: make_cap(m, f, 1e-9, random); story << ", cap 1e-9"; break;
    case 1: make_cap(m, f, 0, random); story << ", collapsed corner"; break;
    case 2: make_needle(m, halfedge(f, m), 1e-7); story << ", needle 1e-7"; break;
    case 3: make_needle(m, halfedge(f, m), 1e-12); story << ", needle 1e-12"; break;
    default: make_hole(m, f); story << ", hole"; break;
    }
  }
  m.collect_garbage();
  const int isolated = chance(0.3) ? 1 + static_cast<int>(pick(3)) : 0;
  for(int i = 0; i < isolated; ++i)
  {
    const Point p = m.point(vertex_descriptor(static_cast<Mesh::size_type>(pick(num_vertices(m)))));
    m.add_vertex(p + Vector(mean * (10 + 100 * unit(random)), 0, mean));
  }
  if(isolated > 0)
    story << ", " << isolated << " isolated vertices";
  // a power of two between about 1e-150 and 1e150 (exact: the unscaled mesh is CGAL's reference)
  if(chance(0.5))
  {
    c.scale = std::ldexp(1.0, static_cast<int>(pick(997)) - 498);
    for(vertex_descriptor v : vertices(m))
      m.point(v) = Point(c.scale * m.point(v).x(), c.scale * m.point(v).y(), c.scale * m.point(v).z());
    story << ", scale " << c.scale;
  }
  c.euclidean = chance(0.5);
  if(!c.euclidean)
  {
    c.w = 0.1 + 0.9 * unit(random);
    c.w_iso = unit(random);
    c.L = IM::suggested_weight_length_scale(m) * std::pow(10.0, -1 + 5 * unit(random));
    story << ", isophotic w " << c.w << " w' " << c.w_iso << " L " << c.L;
  }
  else
    story << ", Euclidean";
  const int n_sources = chance(0.2) ? 2 : 1;
  for(int i = 0; i < n_sources; ++i)
  {
    Source s;
    const face_descriptor f(static_cast<Mesh::size_type>(pick(num_faces(m))));
    const double r = unit(random);
    if(r < 0.3 || (r < 0.35 && isolated == 0))
    {
      s.kind = Source::VERTEX;
      s.vertex = vertex_descriptor(static_cast<Mesh::size_type>(pick(num_vertices(m))));
    }
    else if(r < 0.35)
    {
      s.kind = Source::VERTEX; // an isolated vertex
      s.vertex = vertex_descriptor(static_cast<Mesh::size_type>(num_vertices(m) - 1));
    }
    else if(r < 0.85)
    {
      s.kind = Source::POINT;
      std::array<double, 3> b{unit(random), unit(random), 0};
      if(r < 0.45)
        b = {1, 0, 0}; // at a corner
      else if(r < 0.65)
        b[1] = 1 - b[0]; // on an edge
      else
      {
        if(b[0] + b[1] > 1)
          b = {1 - b[0], 1 - b[1], 0};
        b[2] = 1 - b[0] - b[1];
      }
      std::shuffle(b.begin(), b.end(), random);
      s.point = Face_location(f, b);
    }
    else
    {
      s.kind = Source::REGION;
      s.region.push_back(f);
      for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, m), m))
        if(!is_border(opposite(h, m), m) && chance(0.5))
          s.region.push_back(face(opposite(h, m), m));
    }
    c.sources.push_back(s);
    story << (i == 0 ? "; source " : ", ") << s.describe();
  }
  c.story = story.str();
  return c;
}

} // namespace

// ------------------------------------------------------------------ the inputs of the reports

TEST(Robustness, IsolatedSourceVertexReachesNothing)
{
  Mesh m;
  const vertex_descriptor a = m.add_vertex(Point(0, 0, 0)), b = m.add_vertex(Point(1, 0, 0)),
                          c = m.add_vertex(Point(0, 1, 0));
  m.add_face(a, b, c);
  const vertex_descriptor isolated = m.add_vertex(Point(5, 5, 5));
  for(const bool euclidean : {true, false})
  {
    Solver solver(m, euclidean ? IM::parameters::isophotic_weight(0.0).weight_length_scale(1.0)
                               : IM::parameters::isophotic_weight(1.0).weight_length_scale(1.0));
    solver.add_source(isolated);
    solver.propagate();
    EXPECT_EQ(solver.distance(isolated), 0.0);
    for(vertex_descriptor v : {a, b, c})
    {
      EXPECT_EQ(solver.distance(v), inf) << v;
      EXPECT_EQ(solver.nearest_source(v), Solver::no_source) << v;
    }
  }
  // a mesh of isolated vertices only
  Mesh points;
  for(int i = 0; i < 5; ++i)
    points.add_vertex(Point(i, 0, 0));
  Solver solver(points, IM::parameters::isophotic_weight(0.0));
  solver.add_source(vertex_descriptor(2));
  solver.propagate();
  for(vertex_descriptor v : vertices(points))
    EXPECT_EQ(solver.distance(v), v == vertex_descriptor(2) ? 0.0 : inf) << v;
}

TEST(Robustness, LargeWeightLengthScaleLeavesNoReachableVertexAtInfinity)
{
  const Mesh fandisk = load("meshes/fandisk.off");
  const double diagonal = IM::suggested_weight_length_scale(fandisk);
  std::vector<Source> source(1);
  source[0].kind = Source::VERTEX;
  source[0].vertex = vertex_descriptor(0);
  std::mt19937_64 random(7);
  const Verdict v = check_case(fandisk, source, false, 0.5, 0.5, 1e4 * diagonal, 1, random, false);
  EXPECT_TRUE(v.failures.empty()) << v.failures.front();
  // one far isolated vertex enlarges the box, and so the suggested scale
  Mesh with_far_vertex = fandisk;
  with_far_vertex.add_vertex(Point(100, 100, 100));
  const double L = IM::suggested_weight_length_scale(with_far_vertex);
  EXPECT_GT(L, 100 * diagonal);
  const Verdict far = check_case(with_far_vertex, source, false, 0.5, 0.5, L, 1, random, false);
  EXPECT_TRUE(far.failures.empty()) << far.failures.front();
}

TEST(Robustness, ResultsDoNotDependOnTheModelsUnits)
{
  const Mesh fandisk = load("meshes/fandisk.off");
  const auto reference_np = [](const Mesh& m) {
    return IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(IM::suggested_weight_length_scale(m));
  };
  Solver euclidean(fandisk, IM::parameters::isophotic_weight(0.0));
  Solver isophotic(fandisk, reference_np(fandisk));
  for(Solver* s : {&euclidean, &isophotic})
  {
    s->add_source(vertex_descriptor(0));
    s->propagate();
  }
  for(const double scale : {1e-200, 1e-160, 1e-100, 1e-12, 1e12, 1e100, 1e200})
  {
    Mesh m = fandisk;
    for(vertex_descriptor v : vertices(m))
      m.point(v) = Point(scale * m.point(v).x(), scale * m.point(v).y(), scale * m.point(v).z());
    Solver scaled_euclidean(m, IM::parameters::isophotic_weight(0.0));
    Solver scaled_isophotic(m, reference_np(m));
    for(Solver* s : {&scaled_euclidean, &scaled_isophotic})
    {
      s->add_source(vertex_descriptor(0));
      s->propagate();
    }
    double worst = 0;
    for(vertex_descriptor v : vertices(m))
    {
      worst = std::max(worst, std::abs(scaled_euclidean.distance(v) / scale - euclidean.distance(v)) / euclidean.distance(v));
      worst = std::max(worst, std::abs(scaled_isophotic.distance(v) / scale - isophotic.distance(v)) / isophotic.distance(v));
      if(v == vertex_descriptor(0))
        worst = 0;
    }
    // (the scaled coordinates are rounded: a relative 1e-16 change of the model)
    EXPECT_LE(worst, 1e-12) << "scale " << scale;
  }
}

TEST(Robustness, CapsNeedlesAndCollapsedCornersOfRealMeshes)
{
  // The damage of the reports, at fixed places: corners moved onto their opposite edge (exactly,
  // or 1e-9 of its length away), edges shrunk to needles of width 1e-7 and 1e-12.
  struct Damaged
  {
    const char* name;
    vertex_descriptor source;
    bool euclidean;
  };
  for(const Damaged& d : {Damaged{"elephant", vertex_descriptor(925), true}, Damaged{"elephant", vertex_descriptor(925), false},
                          Damaged{"mesh_with_border", vertex_descriptor(0), true}, Damaged{"cube-meshed", vertex_descriptor(216), true}})
  {
    Mesh m = load(std::string("meshes/") + d.name + ".off");
    std::mt19937_64 random(11);
    for(std::size_t i = 0; i < 40; ++i)
    {
      const face_descriptor f(static_cast<Mesh::size_type>((37 * i + 5) % num_faces(m)));
      switch(i % 4)
      {
      case 0: make_cap(m, f, 0, random); break;
      case 1: make_cap(m, f, 1e-9, random); break;
      case 2: make_needle(m, halfedge(f, m), 1e-7); break;
      default: make_needle(m, halfedge(f, m), 1e-12); break;
      }
    }
    std::vector<Source> source(1);
    source[0].kind = Source::VERTEX;
    source[0].vertex = d.source;
    const double L = IM::suggested_weight_length_scale(m);
    const Verdict v = check_case(m, source, d.euclidean, 0.5, 0.5, L, 1, random, true);
    std::ostringstream all;
    for(const std::string& f : v.failures)
      all << "\n  " << f;
    EXPECT_TRUE(v.failures.empty()) << d.name << (d.euclidean ? " Euclidean:" : " isophotic:") << all.str();
  }
}

// ------------------------------------------------------------------ the randomized campaign

namespace {

// The meshes the campaign damages.
struct Campaign_pool
{
  std::vector<std::string> names = {"elephant", "mesh_with_border", "blobby_3cc", "cube-meshed",
                                    "eight", "ellipsoid", "head", "cylinder", "fandisk"};
  std::vector<Mesh> meshes;
  Campaign_pool()
  {
    for(const std::string& name : names)
      meshes.push_back(load("meshes/" + name + ".off"));
  }
};

// What the checks of one case found wrong, as one message naming the case (empty when nothing).
std::string check_campaign_case(const Case& c, std::size_t seed, std::size_t index, std::mt19937_64& check_random,
                                bool compare_with_cgal, Verdict& verdict)
{
  verdict = check_case(c.mesh, c.sources, c.euclidean, c.w, c.w_iso, c.L, c.scale, check_random, compare_with_cgal);
  if(verdict.failures.empty())
    return std::string();
  std::ostringstream all;
  all << "case " << index << " (seed " << seed << "): " << c.story;
  for(const std::string& f : verdict.failures)
    all << "\n  " << f;
  return all.str();
}

// Case `index` of the campaign of `seed` with up to `damages` - 1 damages per mesh, and the
// generator of its checks, as the campaign draws them.
Case replay_case(const Campaign_pool& pool, std::size_t seed, std::size_t index, std::size_t damages,
                 std::mt19937_64& check_random)
{
  std::mt19937_64 random(seed);
  for(std::size_t i = 0; i < index; ++i)
  {
    random_case(random, pool.meshes, pool.names, damages);
    random();
  }
  Case c = random_case(random, pool.meshes, pool.names, damages);
  check_random.seed(random());
  return c;
}

// Case `index` of the campaign of `seed` with up to 79 damages per mesh, checked against every bound,
// CGAL's included; `begins` and `says` are what its story began with and held when it was recorded.
Verdict check_recorded_damaged_case(std::size_t seed, std::size_t index, const std::string& begins, const std::string& says)
{
  const Campaign_pool pool;
  std::mt19937_64 check_random;
  const Case c = replay_case(pool, seed, index, 80, check_random);
  Verdict v;
  if(c.story.compare(0, begins.size(), begins) != 0 || c.story.find(says) == std::string::npos)
  {
    ADD_FAILURE() << "the generator draws another case than when case " << index << " of seed " << seed
                  << " was recorded: " << c.story;
    return v;
  }
  const std::string failures = check_campaign_case(c, seed, index, check_random, true, v);
  EXPECT_TRUE(failures.empty()) << failures;
  return v;
}

} // namespace

TEST(Robustness, RandomizedDamagedMeshesMeetIndependentBounds)
{
  const Campaign_pool pool;
  const std::size_t cases = environment_count("IM_ROBUSTNESS_CASES", 12);
  const std::size_t seed = environment_count("IM_ROBUSTNESS_SEED", 1);
  const std::size_t only_case = environment_count("IM_ROBUSTNESS_ONLY_CASE", cases); // to reproduce one
  const std::size_t damage_draws = std::max<std::size_t>(1, environment_count("IM_ROBUSTNESS_DAMAGES", 8));
  std::mt19937_64 random(seed);
  std::size_t solved = 0, rejected = 0, with_cgal = 0, cgal_failed = 0, wrong = 0, distances = 0, below_cgal = 0,
              below_cgals_path = 0;
  for(std::size_t i = 0; i < cases; ++i)
  {
    Case c = random_case(random, pool.meshes, pool.names, damage_draws);
    std::mt19937_64 check_random(random()); // (the cases do not depend on what the checks draw)
    if(only_case < cases && i != only_case)
      continue;
    if(only_case == i)
    {
      std::cout << "case " << i << " (seed " << seed << "): " << c.story << "\n";
      if(std::getenv("IM_ROBUSTNESS_WRITE") != nullptr) // the damaged mesh, to look at
        CGAL::IO::write_polygon_mesh(std::getenv("IM_ROBUSTNESS_WRITE"), c.mesh, CGAL::parameters::stream_precision(17));
    }
    try
    {
      // (CGAL for every case with a point source on an edge: the seeding of such points is apart)
      const bool on_edge = std::any_of(c.sources.begin(), c.sources.end(), [](const Source& s) {
        return s.kind == Source::POINT && std::count(s.point.second.begin(), s.point.second.end(), 0.0) == 1;
      });
      const bool cgal = num_faces(c.mesh) <= 12000 && (cases <= 50 || i % 4 == 0 || on_edge);
      Verdict v;
      const std::string failures = check_campaign_case(c, seed, i, check_random, cgal, v);
      ++solved;
      with_cgal += v.compared_with_cgal;
      below_cgal += v.below_cgal;
      below_cgals_path += v.below_cgals_path;
      distances += v.checked_distances;
      if(v.cgal_failed)
      {
        ++cgal_failed;
        std::cout << "case " << i << ": CGAL's reference did not finish; checked by the other bounds\n";
      }
      if(!failures.empty())
      {
        ++wrong;
        ADD_FAILURE() << failures;
      }
    }
    catch(const IM::Invalid_mesh_error& e)
    {
      // damage may make a vertex's normal vanish (all its faces flat), or a needle's two ends one
      // point: a package exception, naming the element
      ++rejected;
      std::cout << "case " << i << " rejected: " << e.what() << "\n";
      const std::string what = e.what();
      EXPECT_TRUE(what.find("vertex") != std::string::npos || what.find("edge") != std::string::npos) << what;
    }
    catch(const std::exception& e)
    {
      ++wrong; // any other exception is a failure of the package
      ADD_FAILURE() << "case " << i << " (seed " << seed << "): " << c.story << "\n  exception: " << e.what();
    }
  }
  std::cout << cases << " cases: " << solved << " solved (" << with_cgal << " compared with CGAL's exact shortest paths, "
            << cgal_failed << " where CGAL's reference did not finish, "
            << distances << " vertex distances checked; " << below_cgal
            << " vertices where CGAL's distance is above the length of a path we traced, " << below_cgals_path
            << " where it is below the length of its own path, which is our distance), " << rejected << " rejected with a package exception, "
            << wrong << " with a wrong answer\n";
  EXPECT_EQ(wrong, 0u);
  EXPECT_LE(rejected, cases / 4 + 1);
}

// Every case that gave a wrong answer in the long campaigns (IM_ROBUSTNESS_CASES=5000, seeds 2 and 3,
// before the fixes named with them), drawn again from its seed (the generator runs through the
// cases before it: well under a millisecond each) and checked as in the campaign, always against
// CGAL's exact shortest paths. The story is part of the record: a change of the generator, or of the
// standard library's distributions, that draws other cases fails here instead of checking others.
TEST(Robustness, CasesThatFailedInLongCampaigns)
{
  struct Recorded
  {
    std::size_t seed, index;
    const char* story;
  };
  // Mechanisms (Window_propagation.h, Intrinsic_triangle_mesh.h): [point] a point source barely
  // above an edge sent no window across it; [apex] the children of a window whose source lies on or
  // just below its edge (a collapsed corner's emission) collapsed to one end of their edges;
  // [needle] rays between the two ends of a needle edge are not representable (each end now
  // bends geodesics in every direction); [frame] a needle's short edge had a direction vector of
  // length 1 - 1e-4 in face_frame, shrinking the source images behind it; [query] two windows of one
  // source meeting on one ray, unfolded through different faces, ended 1.3e-10 apart on a needle's
  // short edge, and points between them fell to a corner in the queries (5e-8 too long: found by
  // the field check along the faces' edges). The tag of a case names the one fix without which it
  // fails again (measured with each fix undone alone); the others fail again only with several undone.
  const Recorded recorded[] = {
    {2, 48, "elephant, needle 1e-7, hole, needle 1e-12, 2 isolated vertices, Euclidean; source point f4108 (0.015085374281835207, 0.4964480117067932, 0.48846661401137159), point f5132 (0.02612352186856326, 0.54071840358032097, 0.43315807455111577)"},
    {2, 134, "cylinder + mesh_with_border, cap 1e-9, collapsed corner, needle 1e-7, isophotic w 0.6932 w' 0.272257 L 412684; source point f2912 (0.25090415694312679, 0, 0.74909584305687327), vertex v17"}, // [query]
    {2, 452, "head, noise 0.001, collapsed corner, needle 1e-12, cap 1e-9, collapsed corner, cap 1e-9, hole, Euclidean; source point f475 (1, 0, 0)"}, // [apex]
    {2, 596, "head, noise 0.1, collapsed corner, needle 1e-7, cap 1e-9, needle 1e-12, cap 1e-9, needle 1e-7, Euclidean; source vertex v561"}, // [apex]
    {2, 700, "cube-meshed, cap 1e-9, needle 1e-7, cap 1e-9, needle 1e-7, scale 2.63281e+64, Euclidean; source point f806 (0.30319489064123994, 0.14337894173222909, 0.55342616762653096)"}, // [apex]
    {2, 1036, "head + mesh_with_border, needle 1e-12, hole, collapsed corner, hole, needle 1e-7, hole, cap 1e-9, scale 1.36846e-48, Euclidean; source point f1567 (0, 0, 1)"},
    {2, 1320, "cube-meshed, noise 0.1, needle 1e-12, needle 1e-7, hole, scale 7.38638e-127, Euclidean; source point f734 (0, 0, 1)"},
    {2, 1380, "elephant, hole, cap 1e-9, cap 1e-9, cap 1e-9, cap 1e-9, hole, hole, Euclidean; source vertex v773"}, // [apex]
    {2, 1516, "elephant, hole, collapsed corner, needle 1e-12, cap 1e-9, collapsed corner, collapsed corner, 2 isolated vertices, scale 3.8147e-06, Euclidean; source vertex v2023"},
    {2, 1880, "eight, cap 1e-9, collapsed corner, needle 1e-12, cap 1e-9, hole, needle 1e-7, needle 1e-12, scale 8.84344e-75, Euclidean; source point f523 (0.66508115489950359, 0.17140327050072751, 0.16351557459976887)"},
    {2, 2224, "eight, noise 0.1, needle 1e-7, needle 1e-7, cap 1e-9, needle 1e-12, hole, hole, cap 1e-9, scale 4096, Euclidean; source point f281 (0.25742923734746592, 0.45776566814866193, 0.28480509450387215)"}, // [apex]
    {2, 2572, "eight, noise 0.1, cap 1e-9, needle 1e-12, hole, hole, hole, needle 1e-7, collapsed corner, Euclidean; source point f40 (0.66487432322588946, 0.32998662398041889, 0.0051390527936916452)"}, // [needle]
    {2, 2703, "cube-meshed, cap 1e-9, cap 1e-9, cap 1e-9, needle 1e-7, needle 1e-12, needle 1e-12, needle 1e-12, scale 1.26897e-116, Euclidean; source region of faces f972 f142"}, // [frame]
    {2, 2920, "eight, noise 0.001, needle 1e-7, hole, needle 1e-12, scale 1.23794e+27, Euclidean; source vertex v265"},
    {2, 3304, "eight, needle 1e-12, cap 1e-9, needle 1e-12, Euclidean; source point f318 (0.024578336380663202, 0.16324320178487872, 0.81217846183445808)"},
    {2, 3492, "eight, needle 1e-12, needle 1e-7, hole, 2 isolated vertices, Euclidean; source point f191 (1, 0, 0)"},
    {2, 3588, "eight, collapsed corner, needle 1e-12, needle 1e-12, hole, Euclidean; source point f355 (0.57890477527092998, 0.32564810370630992, 0.095447121022760095)"}, // [point]
    {2, 3648, "mesh_with_border, needle 1e-12, hole, needle 1e-7, scale 2.57378e-85, Euclidean; source point f857 (0.46630323249785471, 0.38674237224162222, 0.14695439526052306), point f545 (0, 0, 1)"}, // [point]
    {2, 3944, "eight, cap 1e-9, needle 1e-7, collapsed corner, scale 4.69709e+108, Euclidean; source point f490 (0.40074584152850717, 0.30986237787128157, 0.2893917806002112), point f88 (0.11254617520472132, 0.027910407731110198, 0.85954341706416848)"}, // [apex]
    {2, 4956, "mesh_with_border, hole, cap 1e-9, cap 1e-9, needle 1e-12, hole, Euclidean; source vertex v178"},
    {3, 592, "elephant, needle 1e-12, needle 1e-12, hole, hole, cap 1e-9, scale 1.29943e-113, Euclidean; source vertex v1459"},
    {3, 640, "blobby_3cc, needle 1e-12, needle 1e-12, collapsed corner, hole, scale 1.33638e-51, Euclidean; source point f1337 (0.21676323282700516, 0.073625786401112295, 0.70961098077188256)"},
    {3, 700, "head, noise 0.1, needle 1e-12, needle 1e-7, hole, Euclidean; source vertex v1352"},
    {3, 820, "elephant, noise 0.1, hole, needle 1e-7, needle 1e-12, hole, hole, needle 1e-12, hole, scale 1.05769e+124, Euclidean; source vertex v1638"},
    {3, 1156, "cube-meshed, noise 0.1, needle 1e-12, needle 1e-12, hole, scale 3.77789e+22, Euclidean; source vertex v690"}, // [needle]
    {3, 1204, "head, noise 0.1, hole, needle 1e-7, needle 1e-12, scale 9.40395e-38, Euclidean; source vertex v1291"},
    {3, 1596, "cylinder, noise 0.1, needle 1e-12, needle 1e-12, cap 1e-9, cap 1e-9, collapsed corner, collapsed corner, cap 1e-9, Euclidean; source point f706 (1, 0, 0)"},
    {3, 1884, "eight, noise 0.1, collapsed corner, needle 1e-7, cap 1e-9, cap 1e-9, needle 1e-12, cap 1e-9, cap 1e-9, Euclidean; source vertex v92"},
    {3, 2096, "head + mesh_with_border, noise 0.1, needle 1e-12, hole, needle 1e-12, collapsed corner, collapsed corner, 1 isolated vertices, Euclidean; source vertex v660"}, // [apex]
    {3, 2372, "blobby_3cc, collapsed corner, needle 1e-12, needle 1e-12, needle 1e-7, needle 1e-12, hole, needle 1e-12, scale 2.20856e+71, Euclidean; source vertex v613"},
    {3, 3128, "elephant + mesh_with_border, cap 1e-9, needle 1e-12, cap 1e-9, 2 isolated vertices, Euclidean; source point f882 (0.042038515089644513, 0.20255970140075874, 0.75540178350959675), point f614 (0.2399271980198992, 0.10097384160613675, 0.65909896037396409)"},
  };
  const Campaign_pool pool;
  for(const std::size_t seed : {2, 3})
  {
    std::size_t last = 0;
    for(const Recorded& r : recorded)
      if(r.seed == seed)
        last = std::max(last, r.index);
    std::mt19937_64 random(seed);
    for(std::size_t i = 0; i <= last; ++i)
    {
      const Case c = random_case(random, pool.meshes, pool.names);
      std::mt19937_64 check_random(random());
      const Recorded* r = std::find_if(std::begin(recorded), std::end(recorded),
                                       [&](const Recorded& x) { return x.seed == seed && x.index == i; });
      if(r == std::end(recorded))
        continue;
      ASSERT_EQ(c.story, r->story) << "the generator draws other cases than when case " << i << " of seed " << seed << " was recorded";
      Verdict v;
      const std::string failures = check_campaign_case(c, seed, i, check_random, num_faces(c.mesh) <= 12000, v);
      EXPECT_TRUE(failures.empty()) << failures;
    }
  }
}

// Case 756 of seed 11 with up to 79 damages per mesh (IM_ROBUSTNESS_DAMAGES=80): a damaged
// "cube-meshed" whose vertex v819, flat before, has corner angles summing to 2 pi + 1e-12 (from the
// damage of its faces). Its shadow, 1e-12 wide, holds vertex v792 exactly, on a grid line through
// v819: with saddles only above 2 pi + 1e-9, v819 did not emit, and v792 and v515 behind it were
// 0.2 % above CGAL's exact distances (and v515 differed with and without stored windows).
TEST(Robustness, SaddleOfTinyAngleExcessEmitsIntoItsShadow)
{
  const char* story =
      "cube-meshed, needle 1e-7, hole, needle 1e-12, cap 1e-9, hole, hole, collapsed corner"
      ", needle 1e-12, needle 1e-12, hole, needle 1e-12, needle 1e-12, cap 1e-9, needle 1e-7"
      ", collapsed corner, needle 1e-7, cap 1e-9, needle 1e-12, hole, needle 1e-12, needle 1e-7"
      ", needle 1e-12, hole, cap 1e-9, collapsed corner, needle 1e-12, needle 1e-12, needle 1e-7, hole"
      ", hole, cap 1e-9, needle 1e-12, hole, cap 1e-9, collapsed corner, cap 1e-9, hole, hole, hole"
      ", cap 1e-9, collapsed corner, cap 1e-9, collapsed corner, cap 1e-9, needle 1e-12"
      ", collapsed corner, cap 1e-9, collapsed corner, needle 1e-12, collapsed corner"
      ", collapsed corner, cap 1e-9, needle 1e-12, cap 1e-9, hole, needle 1e-7, cap 1e-9, cap 1e-9"
      ", needle 1e-7, needle 1e-7, collapsed corner, scale 1.2487e+145, Euclidean; source vertex v411";
  const Verdict v = check_recorded_damaged_case(11, 756, story, "");
  EXPECT_TRUE(v.compared_with_cgal);
}

// Case 1081 of seed 11 with up to 79 damages per mesh: a damaged "cube-meshed" with a point source
// on an edge, on which CGAL's reference makes a NaN and crashed the whole campaign (see
// cgal_reference). The reference now runs apart; the case is still checked, by the other bounds
// (explicit paths above, chords below, the edges' lengths between neighbours).
TEST(Robustness, CaseOnWhichCgalsReferenceFailsIsCheckedByTheOtherBounds)
{
  const Verdict v = check_recorded_damaged_case(11, 1081, "cube-meshed, needle 1e-7, cap 1e-9, coll",
                                                "source point f417 (0.22852635698163104, 0, 0.77147364301836896)");
  EXPECT_GT(v.checked_distances, 0u);
  EXPECT_TRUE(v.compared_with_cgal || v.cgal_failed) << "the case was not sent to CGAL's reference";
  std::cout << (v.cgal_failed ? "CGAL's reference did not finish (CGAL 5.5.1 makes a NaN here)\n"
                              : "CGAL's reference finished and agrees\n");
}

// Case 1576 of seed 14 with up to 79 damages per mesh: a damaged "eight" where two caps lie side by
// side along one line (vertex v129 on the edge v132-v128 of one, v132 on the edge v127-v128 of the
// other). The window v129 emits as a collapsed corner has its source on its edge; crossing the
// second cap, its child's source lay on the child's edge too (height -0) and the child was dropped:
// v201 and v202 were 2.3e-5 and 1.8e-5 above CGAL's distances, which its paths through v129 realise.
TEST(Robustness, CollapsedCornerWindowCrossesACapAlongItsLine)
{
  const Verdict v = check_recorded_damaged_case(14, 1576, "eight, needle 1e-7, collapsed corner, ne",
                                                "source point f325 (0.30889775261259111, 0.66602909998931292, 0.025073147398095963)");
  EXPECT_TRUE(v.compared_with_cgal);
}

// Case 1951 of seed 14 with up to 79 damages per mesh: a damaged "mesh_with_border" where the border
// vertex v328 lies on the long edge of a cap (v544, v116, v328), across which a needle (v544, v116,
// v521) 1e-12 wide leads to the face (v521, v275, v116). The windows through v328 have their source
// on their edge; where they crossed the cap and the needle, only the rays to one side of the source's
// foot were kept, and 70 vertices behind were up to 1 % above CGAL's distances (and differed with and
// without stored windows).
TEST(Robustness, SourceOnItsEdgeLightsTheWholeFaceAcross)
{
  const Verdict v = check_recorded_damaged_case(14, 1951, "mesh_with_border, hole, cap 1e-9, needle 1",
                                                "source point f872 (0, 0.88112223356464026, 0.11887776643535974)");
  EXPECT_TRUE(v.compared_with_cgal);
}

// Case 1794 of seed 14 with up to 79 damages per mesh: a damaged "cube-meshed" whose geodesics run
// along lines of flat vertices; the windows of the two sides of such a vertex meet within 1e-12 of
// each other, and an apex on the ray between them lay 5e-12 outside both (see crossing_slack): v311
// and v401 were 0.5 % and 0.3 % above CGAL's distances with stored windows, v401 1 % without.
TEST(Robustness, ApexOnTheRayThroughAFlatVertexIsReached)
{
  const Verdict v = check_recorded_damaged_case(14, 1794, "cube-meshed, needle 1e-12, needle 1e-7, ",
                                                "source point f1228 (0.36820881925928473, 0.45325007542788709, 0.17854110531282819)");
  EXPECT_TRUE(v.compared_with_cgal);
}

// Case 39 of seed 14 with up to 79 damages per mesh: a damaged "cylinder" (isophotic) where the
// saddle v579 (angle sum 6.87) has a neighbour v620 3e-10 away. v620 emitted first; v579 was reached
// after it, 5e-13 below the key v620 had left the queue at, and its event, raised to that key,
// looked stale: v579 never emitted into its shadow, and the field behind it was up to 1.5e-5 of the
// distance too long (found by the field check only: the vertex distances there were right).
TEST(Robustness, SaddleReachedJustBelowTheQueuesLastKeyEmits)
{
  const Verdict v = check_recorded_damaged_case(14, 39, "cylinder, hole, hole, hole, cap 1e-9, hol",
                                                "source vertex v549");
  EXPECT_GT(v.checked_distances, 0u);
}

// Case 109 of seed 15 with up to 79 damages per mesh: a damaged "cube-meshed" with a needle (v176,
// v177, v660) whose short edge, 1.8e-13, is 1.06e-17 shorter than the difference of its long ones
// (a flat triangle, by rounding). Unfolded on the short edge, its apex lay 6e-5 too far from v177:
// the point distances along the edge (v177, v660) grew 6e-5 faster than the length (the field check).
TEST(Robustness, FlatNeedleUnfoldsWithItsLengths)
{
  typedef IM::internal::Intrinsic_triangle_mesh Intrinsic;
  const double a = 1.7679241084779306e-13, b = 0.14836390416257095, c = 0.14836390416274775;
  ASSERT_GT(c - b, a); // (the lengths of the case: c > a + b by a rounding)
  const auto apex = Intrinsic::unfold_apex(a, b, c);
  EXPECT_NEAR(std::hypot(apex.x, apex.y), b, 1e-16 * b);
  EXPECT_NEAR(std::hypot(apex.x - a, apex.y), c, 1e-15 * c); // (c - a - b = 7e-17 of c)
  const auto right = Intrinsic::unfold_apex(3, 4, 5); // a valid triangle: the corner of its right angle
  EXPECT_DOUBLE_EQ(right.x, 0);
  EXPECT_DOUBLE_EQ(right.y, 4);
  const Verdict v = check_recorded_damaged_case(15, 109, "cube-meshed, needle 1e-7, hole, collapsed",
                                                "source vertex v850, vertex v775");
  EXPECT_GT(v.checked_distances, 0u);
}

// Case 1425 of seed 13 with up to 79 damages per mesh (a damaged "ellipsoid", a point source on an
// edge): a traced path never ended. From a vertex reached through a window the trace-back now goes on
// through the windows of its face first, not through a corner whose value ties with the vertex's and
// may owe it to the vertex (with the wider slack of crossing_slack, more such ties).
TEST(Robustness, TraceBackFromAVertexReachedThroughAWindowEnds)
{
  const Verdict v = check_recorded_damaged_case(13, 1425, "ellipsoid, cap 1e-9, collapsed corner, h",
                                                "source point f57 (0, 0.94622636866699095, 0.053773631333009053)");
  EXPECT_TRUE(v.compared_with_cgal);
}

// Case 1408 of seed 11 with up to 79 damages per mesh: a damaged "ellipsoid", a vertex source and a
// point source on an edge. CGAL's distances of v0, v4, v12, v13, v21 are 3.4e-7 to 3.7e-7 below ours,
// and below the lengths of CGAL's own paths to them, which run through four corners a collapse left
// within 1e-13 of each other and are our distances to 2e-14: the check asks for CGAL's paths where we
// are above its distances, and fails unless each is as long as our distance.
TEST(Robustness, DistanceAboveCgalsIsCheckedAgainstCgalsOwnPath)
{
  const Verdict v = check_recorded_damaged_case(11, 1408, "ellipsoid, collapsed corner, collapsed c",
                                                "source vertex v43, point f176 (0, 0.1763341767595214, 0.82366582324047855)");
  EXPECT_TRUE(v.compared_with_cgal);
  std::cout << v.below_cgals_path << " vertices where CGAL's distance is below the length of its own path\n";
}

// Case 288 of seed 12 with up to 79 damages per mesh: a damaged "blobby_3cc + ellipsoid" at scale
// 2e-13, isophotic, a region of faces as the source. A line wave from the region's boundary reached
// v551, a vertex of the region, at -4.9e-13 (its value rounded through needles): v551 was then no
// longer a source and emitted no windows, so the field jumped by 1.5e-13 across edge (v820, v186)
// behind it, and v506 came out 1.7e-3 too long with stored windows and 2.0e-3 without (the two
// differed). Line-wave values are now never below 0; the field check along the faces' edges fails
// on the case without that.
TEST(Robustness, RegionVertexReachedByALineWaveStaysASource)
{
  check_recorded_damaged_case(12, 288, "blobby_3cc + ellipsoid, collapsed corner, collapsed corner",
                              "2 isolated vertices, scale 2.27374e-13");
}

// Case 1433 of seed 3 (a point source exactly on an edge of a cap of a damaged "eight"): every
// vertex u that bends geodesics (a saddle, or on the boundary) passes its value on, so that every
// vertex w across a face from it is within d(u) + |uw|, the length of the straight path from u to
// w across the edge between them (both faces unfolded into a plane). Found when the seeding of
// such a point lost its windows across the cap's long edge (fixed since: see
// PointSourcesOnAnEdgeOfACapSendWindowsAcrossItsOtherEdges): the repair pass then put about 500
// vertices back into the queue at the edge-path value, the queue raised the keys of those events
// to its last key, the events were taken for stale, and 90 such pairs were above that bound (the
// first at v1, by 2 %). With the seeding fixed the case no longer calls on the repair pass, and
// stays a check of this bound on it; the repair's keys are covered by the queue's own test
// (RadixHeapLowerFloorLetsLowerKeysInUnraised in test_geodesic).
TEST(Robustness, SaddleAndBoundaryVerticesPassTheirValuesOnAcrossTheirFaces)
{
  const Campaign_pool pool;
  std::mt19937_64 random(3);
  for(std::size_t i = 0; i < 1433; ++i)
  {
    random_case(random, pool.meshes, pool.names);
    random();
  }
  const Case c = random_case(random, pool.meshes, pool.names);
  ASSERT_EQ(c.story, "eight, needle 1e-7, collapsed corner, needle 1e-7, needle 1e-7, cap 1e-9, needle 1e-12, needle 1e-12, "
                     "Euclidean; source point f120 (0.061670272672158764, 0.93832972732784126, 0)")
    << "the generator draws other cases than when this one was recorded";
  const Mesh& m = c.mesh;
  const std::vector<Lifted> x = lifted_points(m, true, 0, 0, 1);
  const Real slack = shape_uncertainty(m, x);
  const Real two_pi = 2 * std::acos(Real(-1));
  // the vertices where geodesics may bend: the angle sum clearly above 2 pi, or on the boundary
  std::vector<Real> angle_sum(num_vertices(m), 0);
  for(face_descriptor f : faces(m))
  {
    const std::array<vertex_descriptor, 3> t = corners(f, m);
    for(int k = 0; k < 3; ++k)
    {
      const Real a = distance(x[t[k]], x[t[(k + 1) % 3]]), b = distance(x[t[k]], x[t[(k + 2) % 3]]),
                 o = distance(x[t[(k + 1) % 3]], x[t[(k + 2) % 3]]);
      if(a > 0 && b > 0)
        angle_sum[t[k]] += std::acos(std::clamp((a * a + b * b - o * o) / (2 * a * b), Real(-1), Real(1)));
    }
  }
  auto bends = [&](vertex_descriptor u) { return angle_sum[u] > two_pi + 1e-9L || is_border(u, m); };
  for(const bool store_windows : {true, false})
  {
    Solver solver(m, IM::parameters::euclidean_weight(1.0).isophotic_weight(0.0).weight_length_scale(1.0).store_windows(store_windows));
    solver.add_source(c.sources[0].point);
    solver.propagate();
    std::size_t pairs = 0, above = 0;
    std::ostringstream first;
    for(halfedge_descriptor h : halfedges(m))
    {
      // the apices u of face(h) and w of the face across, with the edge (a, b) at y = 0
      if(is_border(h, m) || is_border(opposite(h, m), m))
        continue;
      const vertex_descriptor a = source(h, m), b = target(h, m), u = target(next(h, m), m),
                              w = target(next(opposite(h, m), m), m);
      const Real ab = distance(x[a], x[b]);
      if(!bends(u) || !(ab > 0))
        continue;
      auto place = [&](vertex_descriptor p, Real side) {
        const Real pa = distance(x[a], x[p]), pb = distance(x[b], x[p]);
        const Real along = (pa * pa - pb * pb + ab * ab) / (2 * ab);
        return std::array<Real, 2>{along, side * std::sqrt(std::max(Real(0), pa * pa - along * along))};
      };
      const std::array<Real, 2> pu = place(u, 1), pw = place(w, -1);
      if(!(pu[1] > 0 && pw[1] < 0))
        continue;
      const Real crossing = pu[0] + (pw[0] - pu[0]) * pu[1] / (pu[1] - pw[1]);
      if(!(crossing > 0 && crossing < ab))
        continue; // the straight segment leaves the two faces
      const Real straight = std::hypot(pu[0] - pw[0], pu[1] - pw[1]);
      const double du = solver.distance(u), dw = solver.distance(w);
      ASSERT_TRUE(du < inf && dw < inf);
      ++pairs;
      if(dw > (du + straight) * (1 + 1e-12L) + slack)
      {
        if(above++ == 0)
        {
          first.precision(17);
          first << "vertex " << w << ": " << dw << " above d(" << u << ") + " << double(straight) << " = " << du + double(straight);
        }
      }
    }
    EXPECT_GT(pairs, 300u);
    EXPECT_EQ(above, 0u) << (store_windows ? "with" : "without") << " stored windows, first: " << first.str();
  }
  // and every check of the campaign (explicit path lengths, chords, edges, traced paths)
  std::mt19937_64 check_random(5);
  Verdict v;
  const std::string failures = check_campaign_case(c, 3, 1433, check_random, false, v);
  EXPECT_TRUE(failures.empty()) << failures;
}

// A point source exactly on a short edge of a cap whose height rounds to 0: its window must cross
// the long edge too (the seeding took the rounded height, 0, for the point lying on the long edge,
// and sent nothing across it: against CGAL, 289 of 315 vertices were above in case 1433 of seed
// 3, by up to 29 %, and 156 of 315 in case 849 of seed 5, by up to 30 %). Every vertex within 1e-9
// of CGAL's distance, with the source 1e-9 into its face (CGAL is wrong exactly on an edge, see
// check_case), plus the length of that displacement.
TEST(Robustness, PointSourcesOnAnEdgeOfACapSendWindowsAcrossItsOtherEdges)
{
  const Campaign_pool pool;
  const struct
  {
    std::size_t seed, index;
    const char* story;
  } recorded[] = {
    {3, 1433, "eight, needle 1e-7, collapsed corner, needle 1e-7, needle 1e-7, cap 1e-9, needle 1e-12, needle 1e-12, "
              "Euclidean; source point f120 (0.061670272672158764, 0.93832972732784126, 0)"},
    {5, 849, "eight, collapsed corner, cap 1e-9, needle 1e-7, cap 1e-9, cap 1e-9, needle 1e-12, needle 1e-7, "
             "Euclidean; source point f406 (0.56457783883985591, 0, 0.43542216116014409)"},
  };
  for(const auto& r : recorded)
  {
    std::mt19937_64 random(r.seed);
    for(std::size_t i = 0; i < r.index; ++i)
    {
      random_case(random, pool.meshes, pool.names);
      random();
    }
    const Case c = random_case(random, pool.meshes, pool.names);
    std::mt19937_64 check_random(random());
    ASSERT_EQ(c.story, r.story) << "the generator draws other cases than when this one was recorded";
    Verdict v;
    const std::string failures = check_campaign_case(c, r.seed, r.index, check_random, true, v);
    EXPECT_TRUE(v.compared_with_cgal) << "case " << r.index << " (seed " << r.seed << ")";
    EXPECT_TRUE(failures.empty()) << failures;
  }
}

// ------------------------------------------------------------------ one-shot bounded calls on their reach

namespace {

// The answers of the four bounded one-shot calls from a bare mesh (which prepare only the region
// their bound reaches) and the same calls on a Metric_mesh of the whole mesh, compared bit for bit.
template <class Metric>
std::string compare_one_shot_with_whole(const Mesh& m, const Metric& metric, face_descriptor f, vertex_descriptor v, double radius)
{
  std::ostringstream failures;
  const IM::Metric_mesh<Mesh> whole(m, metric);
  // dilation of one face
  {
    auto selected = get(CGAL::dynamic_face_property_t<bool>(), m);
    auto dilate = [&](auto&& np) {
      for(face_descriptor g : faces(m))
        put(selected, g, g == f);
      std::vector<face_descriptor> added;
      IM::dilate_face_selection(std::vector<face_descriptor>{f}, m, radius, selected, std::back_inserter(added), np);
      std::sort(added.begin(), added.end()); // (written in breadth-first order, which follows the numbering)
      return added;
    };
    if(dilate(metric) != dilate(IM::parameters::metric_mesh(whole)))
      failures << "dilation of " << f << " by " << radius << " differs; ";
  }
  // neighbourhoods of a face, of a surface point and of a vertex (faces), of a vertex (vertices)
  // (elements written in breadth-first order, which follows the numbering: compared sorted)
  auto compare = [&](auto local, auto full, auto&& key, auto&& values, const std::string& what) {
    for(auto* n : {&local, &full})
      std::sort(n->begin(), n->end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    bool same = local.size() == full.size();
    for(std::size_t i = 0; same && i < local.size(); ++i)
      same = key(local[i]) == key(full[i]) && values(local[i]) == values(full[i]);
    if(!same)
      failures << what << " (" << local.size() << " against " << full.size() << ") differs; ";
  };
  auto same_faces = [&](const auto& center, const char* what) {
    std::vector<IM::Neighborhood_face<face_descriptor>> local, full;
    IM::geodesic_neighborhood(center, m, radius, std::back_inserter(local), metric);
    IM::geodesic_neighborhood(center, m, radius, std::back_inserter(full), IM::parameters::metric_mesh(whole));
    compare(local, full, [](const auto& n) { return n.face; },
            [](const auto& n) { return std::make_pair(n.min_distance, n.covered_fraction); }, std::string(what) + " neighbourhood");
  };
  same_faces(f, "face");
  same_faces(Face_location(f, {{0.2, 0.3, 0.5}}), "surface point");
  same_faces(v, "vertex (faces)");
  std::vector<IM::Neighborhood_vertex<vertex_descriptor>> local, full;
  IM::geodesic_vertex_neighborhood(v, m, radius, std::back_inserter(local), metric);
  IM::geodesic_vertex_neighborhood(v, m, radius, std::back_inserter(full), IM::parameters::metric_mesh(whole));
  compare(local, full, [](const auto& n) { return n.vertex; }, [](const auto& n) { return n.distance; }, "vertex neighbourhood");
  // distances up to the radius from two vertices
  {
    const vertex_descriptor second = target(halfedge(f, m), m);
    std::vector<double> local(num_vertices(m), -1.), full(num_vertices(m), -2.);
    IM::compute_geodesic_distances(std::vector<vertex_descriptor>{v, second}, m, CGAL::make_property_map(local),
                                   metric.max_distance(radius));
    IM::compute_geodesic_distances(std::vector<vertex_descriptor>{v, second}, m, CGAL::make_property_map(full),
                                   IM::parameters::metric_mesh(whole).max_distance(radius));
    std::size_t differ = 0, finite = 0;
    for(std::size_t i = 0; i < local.size(); ++i)
    {
      differ += !(local[i] == full[i]);
      finite += std::isfinite(full[i]);
    }
    if(differ != 0)
      failures << "distances differ at " << differ << " of " << finite << " vertices within " << radius << "; ";
  }
  return failures.str();
}

// The face nearest to a border halfedge, or face 0 on a closed mesh.
face_descriptor face_at_border(const Mesh& m)
{
  for(halfedge_descriptor h : halfedges(m))
    if(is_border(h, m))
      return face(opposite(h, m), m);
  return face_descriptor(0);
}

} // namespace

// Equal, bit for bit, to the whole mesh's answers: closed and open meshes, several components,
// sources at a border, Euclidean and isophotic (given and default length scale), radii from
// nothing to beyond the whole mesh (where the whole mesh is prepared).
TEST(OneShotReach, BoundedCallsGiveTheWholeMeshAnswers)
{
  std::mt19937_64 random(17);
  for(const std::string name : {"meshes/fandisk.off", "meshes/armadillo.off", "meshes/elephant-with-holes.off",
                                "meshes/mech-holes-shark.off", "meshes/blobby_3cc.off", "meshes/nefertiti.off"})
  {
    const Mesh m = load(name);
    const double L = IM::suggested_weight_length_scale(m);
    std::uniform_int_distribution<std::size_t> any_face(0, num_faces(m) - 1);
    const face_descriptor at_border = face_at_border(m);
    for(const face_descriptor f : {at_border, face_descriptor(static_cast<Mesh::size_type>(any_face(random)))})
      for(const double share : {0., 1e-4, 0.003, 0.01, 0.04, 0.15, 3.})
      {
        const vertex_descriptor v = target(next(halfedge(f, m), m), m);
        const double r = share * L;
        const std::string euclidean = compare_one_shot_with_whole(m, IM::parameters::isophotic_weight(0), f, v, r);
        EXPECT_TRUE(euclidean.empty()) << name << ", Euclidean, face " << f << ", radius " << share << " L: " << euclidean;
        const std::string isophotic =
          compare_one_shot_with_whole(m, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L), f, v, r);
        EXPECT_TRUE(isophotic.empty()) << name << ", isophotic, face " << f << ", radius " << share << " L: " << isophotic;
        const std::string default_metric = compare_one_shot_with_whole(m, IM::parameters::euclidean_weight(1.0), f, v, r);
        EXPECT_TRUE(default_metric.empty()) << name << ", default metric, face " << f << ", radius " << share << " L: " << default_metric;
      }
  }
}

namespace {

// The message of the exception `call` throws, of type E ("" when it throws none).
template <class E, class Call>
std::string message_of(Call&& call)
{
  try
  {
    call();
  }
  catch(const E& e)
  {
    return e.what();
  }
  return "";
}

// The four bounded one-shot calls from face f (and its first corner) with radius r, as one string
// of their answers (faces and vertices sorted, values printed to 17 digits).
template <class Metric>
std::string one_shot_answers(const Mesh& m, const Metric& metric, face_descriptor f, double r)
{
  std::ostringstream out;
  out.precision(17);
  const vertex_descriptor v = target(halfedge(f, m), m);
  auto selected = get(CGAL::dynamic_face_property_t<bool>(), m);
  for(face_descriptor g : faces(m))
    put(selected, g, g == f);
  std::vector<face_descriptor> added;
  IM::dilate_face_selection(std::vector<face_descriptor>{f}, m, r, selected, std::back_inserter(added), metric);
  std::sort(added.begin(), added.end());
  for(face_descriptor g : added)
    out << g << " ";
  std::vector<IM::Neighborhood_face<face_descriptor>> around;
  IM::geodesic_neighborhood(f, m, r, std::back_inserter(around), metric);
  std::sort(around.begin(), around.end(), [](const auto& a, const auto& b) { return a.face < b.face; });
  for(const auto& n : around)
    out << n.face << ":" << n.min_distance << " ";
  std::vector<IM::Neighborhood_vertex<vertex_descriptor>> near;
  IM::geodesic_vertex_neighborhood(v, m, r, std::back_inserter(near), metric);
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.vertex < b.vertex; });
  for(const auto& n : near)
    out << n.vertex << ":" << n.distance << " ";
  std::vector<double> d(num_vertices(m));
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{v}, m, CGAL::make_property_map(d), metric.max_distance(r));
  for(std::size_t i = 0; i < d.size(); ++i)
    if(std::isfinite(d[i]))
      out << i << ":" << d[i] << " ";
  return out.str();
}

} // namespace

// Normals smoothed at a scale are filtered over the whole mesh (the filter reads the faces around each
// vertex, out to several edges), so a bounded call with them prepares and validates the whole mesh: a
// quadrangle far away is reported as the validation reports it (the filter assumes triangles), where the
// same call with a smoothing scale of 0, the exact normals, prepares only its reach and is not blocked.
// On fandisk with noise of 0.2 mean edges along the normals, a bounded call with smoothed normals gives
// the whole mesh's answers bit for bit, and the smoothing changes them.
TEST(OneShotReach, SmoothedNormalsPrepareTheWholeMesh)
{
  {
    Mesh m = load("meshes/armadillo.off");
    const double L = IM::suggested_weight_length_scale(m);
    const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
    const face_descriptor f(100);
    const Point p = m.point(target(halfedge(f, m), m));
    vertex_descriptor far = *vertices(m).begin();
    for(vertex_descriptor v : vertices(m))
      if(CGAL::squared_distance(m.point(v), p) > CGAL::squared_distance(m.point(far), p))
        far = v;
    CGAL::Euler::join_face(halfedge(far, m), m);
    m.collect_garbage();
    const std::string expected = message_of<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); });
    ASSERT_NE(expected.find("has 4 vertices"), std::string::npos) << expected;
    const vertex_descriptor v = target(halfedge(f, m), m);
    std::vector<IM::Neighborhood_vertex<vertex_descriptor>> near;
    EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] {
                IM::geodesic_vertex_neighborhood(v, m, 0.01 * L, std::back_inserter(near), metric.normal_smoothing_scale(0.));
              }), std::string());
    EXPECT_FALSE(near.empty());
    EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] {
                IM::geodesic_vertex_neighborhood(v, m, 0.01 * L, std::back_inserter(near),
                                                 metric.normal_smoothing_scale(IM::estimate_mesh_noise(m).mean_edge_length));
              }), expected);
  }

  Mesh m = load("meshes/fandisk.off");
  auto normals = get(CGAL::dynamic_vertex_property_t<K::Vector_3>(), m);
  CGAL::Polygon_mesh_processing::compute_vertex_normals(m, normals);
  const double h = IM::estimate_mesh_noise(m).mean_edge_length;
  std::mt19937_64 random(5);
  std::normal_distribution<double> noise(0., 0.2 * h);
  for(const vertex_descriptor v : vertices(m))
    m.point(v) = m.point(v) + noise(random) * get(normals, v);
  const double s = IM::suggested_normal_smoothing_scale(m);
  ASSERT_GT(s, 0.);
  const double L = IM::suggested_weight_length_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const face_descriptor f(100);
  const vertex_descriptor v = target(next(halfedge(f, m), m), m);
  const std::string smoothed = compare_one_shot_with_whole(m, metric.normal_smoothing_scale(s), f, v, 0.01 * L);
  EXPECT_TRUE(smoothed.empty()) << smoothed;
  std::vector<double> with_smoothing(num_vertices(m)), exact(num_vertices(m));
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{v}, m, CGAL::make_property_map(with_smoothing),
                                 metric.normal_smoothing_scale(s));
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{v}, m, CGAL::make_property_map(exact), metric);
  EXPECT_NE(with_smoothing, exact);
}

// A defect within the reach of a bounded one-shot call is reported as by the whole mesh's
// validation (same type, same message); one far away no longer blocks a small bounded call, whose
// answers are those of the intact mesh; unbounded calls, and bounded ones reaching it, still
// report it.
TEST(OneShotReach, DefectsAreReportedWithinTheReachOnly)
{
  const Mesh intact = load("meshes/armadillo.off");
  const double L = IM::suggested_weight_length_scale(intact);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const face_descriptor f(100);
  const Point centre = CGAL::centroid(intact.point(target(halfedge(f, intact), intact)),
                                      intact.point(target(next(halfedge(f, intact), intact), intact)),
                                      intact.point(source(halfedge(f, intact), intact)));
  vertex_descriptor far = *vertices(intact).begin();
  for(vertex_descriptor v : vertices(intact))
    if(CGAL::squared_distance(intact.point(v), centre) > CGAL::squared_distance(intact.point(far), centre))
      far = v;
  const vertex_descriptor near = target(next(opposite(halfedge(f, intact), intact), intact), intact); // across an edge of f
  const double r = 0.01 * L;
  const std::string intact_answers = one_shot_answers(intact, metric, f, r);
  ASSERT_FALSE(intact_answers.empty());

  // zero-length edge (a vertex moved onto a neighbour), non-finite coordinate
  auto defects = [](vertex_descriptor at) {
    std::vector<std::pair<std::string, Mesh>> made;
    for(const bool zero_length : {true, false})
    {
      Mesh m = load("meshes/armadillo.off");
      const vertex_descriptor neighbour = source(halfedge(at, m), m);
      m.point(at) = zero_length ? m.point(neighbour) : Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
      made.push_back({zero_length ? "zero-length edge" : "non-finite coordinate", std::move(m)});
    }
    return made;
  };
  for(auto& [what, m] : defects(far))
  {
    const std::string expected = message_of<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); });
    ASSERT_FALSE(expected.empty()) << what;
    // a small bounded call: not blocked, the answers of the intact mesh
    std::string answers;
    EXPECT_NO_THROW(answers = one_shot_answers(m, metric, f, r)) << what << " far away";
    EXPECT_EQ(answers, intact_answers) << what << " far away";
    // unbounded, or bounded beyond the defect: reported as the validation reports it
    std::vector<double> d(num_vertices(m));
    EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] {
                IM::compute_geodesic_distances(std::vector<vertex_descriptor>{target(halfedge(f, m), m)}, m, CGAL::make_property_map(d), metric);
              }), expected) << what << ", unbounded";
    EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] { one_shot_answers(m, metric, f, 3 * L); }), expected) << what << ", radius 3 L";
  }
  // a quadrangle (two triangles joined, the removed elements collected): far away, and at the source
  for(const bool at_source : {false, true})
  {
    Mesh m = load("meshes/armadillo.off");
    const vertex_descriptor at = at_source ? near : far;
    CGAL::Euler::join_face(halfedge(at, m), m);
    m.collect_garbage();
    const face_descriptor source_face = at_source ? face(halfedge(at, m), m) : f;
    const std::string expected = message_of<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); });
    ASSERT_NE(expected.find("has 4 vertices"), std::string::npos) << expected;
    std::vector<IM::Neighborhood_face<face_descriptor>> around;
    const std::string got = message_of<IM::Invalid_mesh_error>([&] {
      IM::geodesic_neighborhood(target(halfedge(source_face, m), m), m, r, std::back_inserter(around), metric);
    });
    EXPECT_EQ(got, at_source ? expected : std::string()) << "quadrangle " << (at_source ? "at the source" : "far away");
    if(!at_source)
    {
      EXPECT_FALSE(around.empty());
    }
  }
  for(auto& [what, m] : defects(near))
  {
    const std::string expected = message_of<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); });
    ASSERT_FALSE(expected.empty()) << what;
    EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] { one_shot_answers(m, metric, f, r); }), expected) << what << " within the reach";
    // a face neighbourhood, radius 0, Euclidean (no normals read around the corners of f)
    std::vector<IM::Neighborhood_face<face_descriptor>> around;
    for(const double w_prime : {0.5, 0.})
      EXPECT_EQ(message_of<IM::Invalid_mesh_error>([&] {
                  IM::geodesic_neighborhood(f, m, 0., std::back_inserter(around), IM::parameters::isophotic_weight(w_prime));
                }), expected) << what << " within the reach, radius 0, w' = " << w_prime;
  }
}
