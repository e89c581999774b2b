// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exactness and robustness of the geodesic engine, against independent answers: CGAL's exact
// Surface_mesh_shortest_path, closed forms on planes, spheres and cylinders, edge-graph Dijkstra
// and R^6 chords.
#include <CGAL/Isophotic_metric/Geodesics/Geodesic_solver.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_path.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/Geodesics/for_each_geodesic_distance_field.h>
#include <CGAL/Isophotic_metric/isophotic_length.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Radix_heap.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/Face_filtered_graph.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>

#include <gtest/gtest.h>


#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <queue>
#include <random>
#include <set>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef CGAL::Polyhedron_3<K> Polyhedron;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
typedef boost::graph_traits<Mesh>::halfedge_descriptor halfedge_descriptor;
typedef IM::Geodesic_solver<Mesh>::Face_location Face_location;

const double inf = std::numeric_limits<double>::infinity();
const double pi = 3.14159265358979323846;

template <class PolygonMesh>
PolygonMesh load(const std::string& name)
{
  PolygonMesh m;
  if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path(name), m))
    throw std::runtime_error("cannot read " + name);
  return m;
}

// Relative difference of our Euclidean distances to CGAL's exact shortest paths from one vertex;
// vertices outside the source's component must be +infinity for us.
double max_relative_difference_to_cgal(const Mesh& m, vertex_descriptor source)
{
  auto d = get(CGAL::dynamic_vertex_property_t<double>(), m);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{source}, m, d,
                                 IM::parameters::euclidean_weight(1).isophotic_weight(0));
  // CGAL's package works per connected component: give it just the source's one.
  auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  CGAL::Polygon_mesh_processing::connected_components(m, component);
  face_descriptor source_face;
  for(auto h : CGAL::halfedges_around_target(source, m))
    if(!CGAL::is_border(h, m))
      source_face = face(h, m);
  const std::size_t c = get(component, source_face);
  std::vector<face_descriptor> faces_of_c;
  for(face_descriptor f : faces(m))
    if(get(component, f) == c)
      faces_of_c.push_back(f);
  Mesh part;
  CGAL::copy_face_graph(CGAL::Face_filtered_graph<Mesh>(m, faces_of_c), part);
  // copy_face_graph keeps the order of vertices; match by position
  std::map<Point, vertex_descriptor> by_position;
  for(vertex_descriptor v : vertices(part))
    by_position[part.point(v)] = v;
  typedef CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<K, Mesh>> Shortest_path;
  Shortest_path reference(part);
  reference.add_source_point(by_position.at(m.point(source)));
  double worst = 0;
  for(vertex_descriptor v : vertices(m))
  {
    auto it = by_position.find(m.point(v));
    if(it == by_position.end() || by_position.size() != num_vertices(part))
    {
      EXPECT_EQ(get(d, v), inf) << v;
      continue;
    }
    const double ref = reference.shortest_distance_to_source_points(it->second).first;
    worst = std::max(worst, std::abs(ref - get(d, v)) / std::max(ref, 1e-300));
    if(ref == 0)
    {
      EXPECT_EQ(get(d, v), 0.0);
    }
  }
  return worst;
}

TEST(GeodesicEngine, EuclideanMatchesCgalShortestPathOnRealMeshes)
{
  for(const char* name : {"meshes/fandisk.off", "meshes/elephant.off", "meshes/armadillo.off",
                          "meshes/mech-holes-shark.off", "meshes/blobby_3cc.off"})
  {
    const Mesh m = load<Mesh>(name);
    for(std::size_t s : {std::size_t(0), std::size_t(num_vertices(m) / 2)})
    {
      const double difference = max_relative_difference_to_cgal(m, vertex_descriptor(s));
      EXPECT_LE(difference, 1e-9) << name << " source " << s;
    }
  }
}

TEST(GeodesicEngine, PolyhedronAndSurfaceMeshAgree)
{
  const Mesh m = load<Mesh>("meshes/elephant.off");
  const Polyhedron p = load<Polyhedron>("meshes/elephant.off");
  auto dm = get(CGAL::dynamic_vertex_property_t<double>(), m);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{*vertices(m).begin()}, m, dm);
  std::map<Point, double> by_position;
  for(vertex_descriptor v : vertices(m))
    by_position[m.point(v)] = get(dm, v);
  auto dp = get(CGAL::dynamic_vertex_property_t<double>(), p);
  std::vector<boost::graph_traits<Polyhedron>::vertex_descriptor> source{*vertices(p).begin()};
  IM::compute_geodesic_distances(source, p, dp);
  for(auto v : vertices(p))
    EXPECT_NEAR(get(dp, v), by_position.at(v->point()), 1e-12 * (1 + by_position.at(v->point())));
}

// ------------------------------------------------------------------ closed forms

// A planar grid of n x n squares on [0,1]^2 (z = 0), each split into two triangles.
Mesh planar_grid(int n, double jitter = 0)
{
  Mesh m;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<vertex_descriptor> v;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const double dx = border ? 0 : u(random) / n, dy = border ? 0 : u(random) / n;
      v.push_back(m.add_vertex(Point(double(i) / n + dx, double(j) / n + dy, 0)));
    }
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      const vertex_descriptor a = v[j * (n + 1) + i], b = v[j * (n + 1) + i + 1], c = v[(j + 1) * (n + 1) + i + 1],
                              d = v[(j + 1) * (n + 1) + i];
      m.add_face(a, b, c);
      m.add_face(a, c, d);
    }
  return m;
}

TEST(GeodesicEngine, PlaneGivesSqrtWTimesEuclideanDistanceExactly)
{
  const Mesh m = planar_grid(20, 0.3);
  for(double w : {1.0, 0.25})
    for(double w_prime : {0.0, 1.0, 7.0})
    {
      IM::Geodesic_solver<Mesh> solver(m, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime));
      const vertex_descriptor s(37);
      solver.add_source(s);
      solver.propagate();
      for(vertex_descriptor v : vertices(m))
        EXPECT_NEAR(solver.distance(v), std::sqrt(w) * std::sqrt(CGAL::squared_distance(m.point(s), m.point(v))), 1e-12)
          << "w=" << w << " w'=" << w_prime;
      // and at surface points (face centroids)
      for(face_descriptor f : faces(m))
      {
        const Face_location centroid(f, {{1. / 3, 1. / 3, 1. / 3}});
        Point c = CGAL::centroid(m.point(source(halfedge(f, m), m)), m.point(target(halfedge(f, m), m)),
                                 m.point(target(next(halfedge(f, m), m), m)));
        EXPECT_NEAR(solver.distance(centroid), std::sqrt(w) * std::sqrt(CGAL::squared_distance(m.point(s), c)), 1e-12);
      }
    }
}

TEST(GeodesicEngine, PointSourceInsideAFace)
{
  const Mesh m = planar_grid(10, 0.2);
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::isophotic_weight(0));
  const face_descriptor f(57);
  const Face_location p(f, {{0.2, 0.5, 0.3}});
  const halfedge_descriptor h = halfedge(f, m);
  const Point x = CGAL::barycenter(m.point(source(h, m)), 0.2, m.point(target(h, m)), 0.5, m.point(target(next(h, m), m)), 0.3);
  solver.add_source(p);
  solver.propagate();
  for(vertex_descriptor v : vertices(m))
    EXPECT_NEAR(solver.distance(v), std::sqrt(CGAL::squared_distance(x, m.point(v))), 1e-12);
  // a point on an edge is a source for both faces of that edge
  solver.clear_sources();
  solver.add_source(Face_location(f, {{0.4, 0.6, 0.0}}));
  solver.propagate();
  const Point y = CGAL::barycenter(m.point(source(h, m)), 0.4, m.point(target(h, m)), 0.6);
  for(vertex_descriptor v : vertices(m))
    EXPECT_NEAR(solver.distance(v), std::sqrt(CGAL::squared_distance(y, m.point(v))), 1e-12);
}

// A Face_location of an exact kernel (what PMP::locate() returns on a mesh with exact coordinates)
// is accepted as a source and as a query point: distances from it are the planar closed form.
TEST(GeodesicEngine, ExactKernelLocationsAreAcceptedAsPoints)
{
  typedef CGAL::Exact_predicates_exact_constructions_kernel EK;
  typedef CGAL::Surface_mesh<EK::Point_3> Exact_mesh;
  Exact_mesh m;
  CGAL::copy_face_graph(planar_grid(10, 0.2), m);
  auto to_double = [](const EK::Point_3& p) { return Point(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())); };
  const EK::Point_3 x(0.913, 0.377, 0);
  const auto location = CGAL::Polygon_mesh_processing::locate(x, m);
  static_assert(std::is_same<std::decay_t<decltype(location.second[0])>, EK::FT>::value, "an exact location");
  IM::Geodesic_solver<Exact_mesh> solver(m, IM::parameters::isophotic_weight(0));
  solver.add_source(location);
  solver.propagate();
  for(auto v : vertices(m))
    EXPECT_NEAR(solver.distance(v), std::sqrt(CGAL::squared_distance(to_double(x), to_double(m.point(v)))), 1e-12);
  // a query at another exact location
  const EK::Point_3 y(0.101, 0.713, 0);
  const auto at_y = CGAL::Polygon_mesh_processing::locate(y, m);
  EXPECT_NEAR(solver.distance(at_y), std::sqrt(CGAL::squared_distance(to_double(x), to_double(y))), 1e-12);
  EXPECT_EQ(solver.nearest_source(at_y), 0u);
}

TEST(GeodesicEngine, RegionSourceGivesPerpendicularDistanceToAStrip)
{
  // Strip x in [0.3, 0.5] of a 10x10 grid: the distance is the distance to the strip, also at points
  // between vertices (vertex sources on the strip's border would be off there).
  const int n = 10;
  const Mesh m = planar_grid(n);
  std::vector<face_descriptor> strip;
  for(face_descriptor f : faces(m))
  {
    const Point c = CGAL::centroid(m.point(source(halfedge(f, m), m)), m.point(target(halfedge(f, m), m)),
                                   m.point(target(next(halfedge(f, m), m), m)));
    if(c.x() > 0.3 && c.x() < 0.5)
      strip.push_back(f);
  }
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::euclidean_weight(1).isophotic_weight(0));
  solver.add_source_region(strip);
  solver.propagate();
  auto expected = [](const Point& p) { return p.x() < 0.3 ? 0.3 - p.x() : (p.x() > 0.5 ? p.x() - 0.5 : 0.0); };
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0, 1);
  for(face_descriptor f : faces(m))
  {
    double a = u(random), b = u(random) * (1 - a);
    const Face_location p(f, {{a, b, 1 - a - b}});
    const halfedge_descriptor h = halfedge(f, m);
    const Point x = CGAL::barycenter(m.point(source(h, m)), a, m.point(target(h, m)), b, m.point(target(next(h, m), m)), 1 - a - b);
    EXPECT_NEAR(solver.distance(p), expected(x), 1e-9);
    EXPECT_EQ(solver.nearest_source(p), 0u);
  }
  for(vertex_descriptor v : vertices(m))
    EXPECT_NEAR(solver.distance(v), expected(m.point(v)), 1e-9);
}

// Icosphere of radius R with `levels` Loop subdivisions, projected onto the sphere.
Mesh icosphere(int levels, double R)
{
  Mesh m;
  CGAL::make_icosahedron(m, Point(0, 0, 0), 1.0);
  CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(levels));
  for(vertex_descriptor v : vertices(m))
  {
    const Vector p = m.point(v) - CGAL::ORIGIN;
    m.point(v) = CGAL::ORIGIN + R * p / std::sqrt(p.squared_length());
  }
  return m;
}

TEST(GeodesicEngine, LiftedSphereConvergesToClosedForm)
{
  const double R = 2.0, w = 0.5, w_prime = 3.0;
  std::vector<double> errors;
  for(int level = 2; level <= 5; ++level)
  {
    Mesh m = icosphere(level, R);
    auto normal = m.add_property_map<vertex_descriptor, Vector>("v:exact_normal").first;
    for(vertex_descriptor v : vertices(m))
      normal[v] = (m.point(v) - CGAL::ORIGIN) / R;
    IM::Geodesic_solver<Mesh> solver(
      m, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(1).vertex_normal_map(normal));
    const vertex_descriptor s(0);
    solver.add_source(s);
    solver.propagate();
    double worst = 0;
    EXPECT_EQ(solver.distance(s), 0.0);
    for(vertex_descriptor v : vertices(m))
    {
      if(v == s)
        continue; // acos of a rounded cosine is not 0 there
      const double cosine = (m.point(s) - CGAL::ORIGIN) * (m.point(v) - CGAL::ORIGIN) / (R * R);
      const double theta = std::acos(std::clamp(cosine, -1.0, 1.0));
      const double exact = std::sqrt(w + w_prime / (R * R)) * R * theta;
      if(exact > 0)
        worst = std::max(worst, std::abs(solver.distance(v) - exact) / exact);
    }
    errors.push_back(worst);
  }
  for(std::size_t i = 0; i + 1 < errors.size(); ++i)
  {
    const double order = std::log2(errors[i] / errors[i + 1]);
    std::cout << "sphere level " << i + 2 << " -> " << i + 3 << ": max rel. error " << errors[i] << " -> "
              << errors[i + 1] << ", observed order " << order << "\n";
    EXPECT_GT(order, 1.5); // second order in the edge length
  }
  EXPECT_LT(errors.back(), 2e-3);
}

// Open cylinder of radius R and height H: n_around x n_along quads split into triangles.
Mesh cylinder(int n_around, int n_along, double R, double H)
{
  Mesh m;
  std::vector<vertex_descriptor> v;
  for(int j = 0; j <= n_along; ++j)
    for(int i = 0; i < n_around; ++i)
    {
      const double a = 2 * pi * i / n_around;
      v.push_back(m.add_vertex(Point(R * std::cos(a), R * std::sin(a), H * j / n_along)));
    }
  for(int j = 0; j < n_along; ++j)
    for(int i = 0; i < n_around; ++i)
    {
      const int i1 = (i + 1) % n_around;
      const vertex_descriptor a = v[j * n_around + i], b = v[j * n_around + i1], c = v[(j + 1) * n_around + i1],
                              d = v[(j + 1) * n_around + i];
      m.add_face(a, b, c);
      m.add_face(a, c, d);
    }
  return m;
}

TEST(GeodesicEngine, LiftedCylinderConvergesToClosedForm)
{
  const double R = 1.5, H = 3.0, w = 1.0, w_prime = 2.0;
  std::vector<double> errors;
  for(int k = 1; k <= 4; ++k)
  {
    const int n_around = 12 << k, n_along = 6 << k;
    Mesh m = cylinder(n_around, n_along, R, H);
    auto normal = m.add_property_map<vertex_descriptor, Vector>("v:exact_normal").first;
    for(vertex_descriptor v : vertices(m))
      normal[v] = Vector(m.point(v).x() / R, m.point(v).y() / R, 0);
    IM::Geodesic_solver<Mesh> solver(
      m, IM::parameters::euclidean_weight(w).isophotic_weight(w_prime).weight_length_scale(1).vertex_normal_map(normal));
    const vertex_descriptor s((n_along / 2) * n_around);
    solver.add_source(s);
    solver.propagate();
    double worst = 0;
    for(vertex_descriptor v : vertices(m))
    {
      double angle = std::abs(std::atan2(m.point(v).y(), m.point(v).x()) - std::atan2(m.point(s).y(), m.point(s).x()));
      angle = std::min(angle, 2 * pi - angle);
      const double arc = R * angle, along = m.point(v).z() - m.point(s).z();
      const double exact = std::sqrt((w + w_prime / (R * R)) * arc * arc + w * along * along);
      if(exact > 0)
        worst = std::max(worst, std::abs(solver.distance(v) - exact) / exact);
    }
    errors.push_back(worst);
  }
  for(std::size_t i = 0; i + 1 < errors.size(); ++i)
  {
    const double order = std::log2(errors[i] / errors[i + 1]);
    std::cout << "cylinder refinement " << i + 1 << " -> " << i + 2 << ": max rel. error " << errors[i] << " -> "
              << errors[i + 1] << ", observed order " << order << "\n";
    EXPECT_GT(order, 1.5);
  }
  EXPECT_LT(errors.back(), 1e-3);
}

// ------------------------------------------------------------------ paths

TEST(GeodesicEngine, EuclideanPathLengthEqualsCgalDistance)
{
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  typedef CGAL::Surface_mesh_shortest_path<CGAL::Surface_mesh_shortest_path_traits<K, Mesh>> Shortest_path;
  Shortest_path reference(m);
  const vertex_descriptor s(0);
  reference.add_source_point(s);
  for(vertex_descriptor t : {vertex_descriptor(1000), vertex_descriptor(3000), vertex_descriptor(6000)})
  {
    std::vector<Point> path;
    const double length = IM::compute_geodesic_path(s, t, m, std::back_inserter(path),
                                                     IM::parameters::euclidean_weight(1).isophotic_weight(0));
    const double expected = reference.shortest_distance_to_source_points(t).first;
    EXPECT_NEAR(length, expected, 1e-9 * expected);
    ASSERT_GE(path.size(), 2u);
    EXPECT_EQ(path.front(), m.point(s));
    EXPECT_EQ(path.back(), m.point(t));
    double polyline = 0;
    for(std::size_t i = 1; i < path.size(); ++i)
      polyline += std::sqrt(CGAL::squared_distance(path[i - 1], path[i]));
    EXPECT_NEAR(polyline, expected, 1e-9 * expected);
  }
}

TEST(GeodesicEngine, IsophoticPathsLieOnTheSurfaceAndHaveTheDistanceAsLength)
{
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  const auto np = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5);
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  IM::compute_lifted_embedding(m, lifted, np);
  IM::Geodesic_solver<Mesh> solver(m, np);
  solver.add_source(vertex_descriptor(0));
  solver.add_source(Face_location(face_descriptor(5000), {{0.1, 0.3, 0.6}}));
  face_descriptor region[2] = {face_descriptor(9000), face_descriptor(9001)};
  solver.add_source_region(region);
  solver.propagate();
  std::mt19937 random(11);
  std::uniform_int_distribution<std::size_t> pick(0, num_faces(m) - 1);
  for(int k = 0; k < 200; ++k)
  {
    const Face_location p(face_descriptor(pick(random)), {{0.25, 0.25, 0.5}});
    std::vector<Face_location> path;
    solver.trace_path(p, std::back_inserter(path));
    ASSERT_GE(path.size(), 1u);
    // throws if two consecutive points do not share a face, i.e. the path leaves the surface
    const double length = IM::polyline_isophotic_length(path, m, lifted);
    const double d = solver.distance(p);
    EXPECT_NEAR(length, d, 1e-9 * d) << "query " << k;
  }
  // vertex paths through compute_geodesic_path agree with the solver's distances
  IM::Geodesic_solver<Mesh> single(m, np);
  single.add_source(vertex_descriptor(0));
  single.propagate();
  std::vector<Point> points;
  const double length = IM::compute_geodesic_path(vertex_descriptor(0), vertex_descriptor(4321), m, std::back_inserter(points), np);
  EXPECT_NEAR(length, single.distance(vertex_descriptor(4321)), 1e-12 * length);
}

// Propagates from the solver's sources and returns the distance within which `fraction` of the
// vertices lie (a bound for a bounded run).
double distance_reaching(IM::Geodesic_solver<Mesh>& solver, const Mesh& m, double fraction)
{
  solver.propagate();
  std::vector<double> d;
  for(vertex_descriptor v : vertices(m))
    d.push_back(solver.distance(v));
  std::sort(d.begin(), d.end());
  return d[static_cast<std::size_t>(d.size() * fraction)];
}

TEST(GeodesicEngine, EveryPointOfATracedPathIsAsFarAsWhatRemainsOfThePath)
{
  // Archived windows carry no link to the window they were propagated from: behind a window, a path
  // goes on through what realises its crossing point in the face across. A step that took anything
  // but a shortest way would leave some point of the path farther from the source along the rest
  // of the path than its distance. On scans (irregular triangles, many saddles), Euclidean and
  // isophotic, bounded and unbounded, from a vertex, a point and a region at once: at every point
  // of every path, the distance equals the length of the rest of the path.
  std::mt19937 random(23);
  for(const char* name : {"meshes/bunny00.off", "meshes/elephant.off"})
  {
    const Mesh m = load<Mesh>(name);
    const std::size_t nf = num_faces(m);
    for(const double w_prime : {0.0, 0.5})
    {
      const auto np = IM::parameters::euclidean_weight(1.0 - w_prime).isophotic_weight(w_prime);
      auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
      IM::compute_lifted_embedding(m, lifted, np);
      IM::Geodesic_solver<Mesh> solver(m, np);
      auto add_sources = [&] {
        solver.clear_sources();
        solver.add_source(vertex_descriptor(0));
        solver.add_source(Face_location(face_descriptor(Mesh::size_type(nf / 3)), {{0.2, 0.5, 0.3}}));
        solver.add_source_region(std::vector<face_descriptor>{face_descriptor(Mesh::size_type(2 * nf / 3)),
                                                              face_descriptor(Mesh::size_type(2 * nf / 3 + 1))});
      };
      for(const bool bounded : {false, true})
      {
        add_sources();
        double bound = inf;
        if(bounded)
        {
          bound = distance_reaching(solver, m, 0.4);
          add_sources();
        }
        solver.propagate(bound);
        std::uniform_int_distribution<std::size_t> pick(0, nf - 1);
        std::uniform_real_distribution<double> unit(0, 1);
        int traced = 0;
        for(int k = 0; k < 100; ++k)
        {
          const double x = unit(random), y = unit(random) * (1 - x);
          const Face_location p(face_descriptor(Mesh::size_type(pick(random))), {{x, y, 1 - x - y}});
          const double d = solver.distance(p);
          std::vector<Face_location> path;
          const std::size_t n = solver.trace_path(p, std::back_inserter(path));
          const std::string where = std::string(name) + " w'=" + std::to_string(w_prime) + (bounded ? " bounded" : "") +
                                    " query " + std::to_string(k);
          if(!std::isfinite(d))
          {
            EXPECT_EQ(n, 0u) << where;
            continue;
          }
          ASSERT_GE(n, 1u) << where;
          ++traced;
          EXPECT_NEAR(IM::polyline_isophotic_length(path, m, lifted), d, 1e-9 * d) << where; // (on the surface)
          double remaining = 0;
          for(std::size_t i = n; i-- > 0;)
          {
            if(i + 1 < n)
              remaining += std::sqrt(IM::internal::squared_distance(IM::construct_lifted_point(path[i], m, lifted),
                                                                    IM::construct_lifted_point(path[i + 1], m, lifted)));
            EXPECT_NEAR(solver.distance(path[i]), remaining, 1e-9 * d + 1e-12) << where << " point " << i;
          }
        }
        EXPECT_GT(traced, 20) << name;
      }
    }
  }
}

// ------------------------------------------------------------------ invariants on CGAL's data set

// Edge-graph Dijkstra on lifted edge lengths.
template <class LiftedMap>
std::vector<double> dijkstra(const Mesh& m, vertex_descriptor s, const LiftedMap& lifted)
{
  std::vector<double> d(num_vertices(m), inf);
  typedef std::pair<double, std::size_t> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  d[s] = 0;
  queue.push({0, s});
  while(!queue.empty())
  {
    const auto [du, u] = queue.top();
    queue.pop();
    if(du > d[u])
      continue;
    for(auto h : CGAL::halfedges_around_source(vertex_descriptor(u), m))
    {
      const vertex_descriptor v = target(h, m);
      const double len = std::sqrt(IM::internal::squared_distance(get(lifted, vertex_descriptor(u)), get(lifted, v)));
      if(du + len < d[v])
      {
        d[v] = du + len;
        queue.push({d[v], std::size_t(v)});
      }
    }
  }
  return d;
}

TEST(GeodesicEngine, InvariantsOnEveryTriangleMeshOfCgalDataSet)
{
  namespace fs = std::filesystem;
  const fs::path dir(CGAL::data_file_path("meshes"));
  std::vector<fs::path> files;
  for(const fs::directory_entry& entry : fs::directory_iterator(dir))
    if(entry.path().extension() == ".off")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  int tested = 0, rejected = 0;
  for(const fs::path& file : files)
  {
    Mesh m;
    if(!CGAL::IO::read_polygon_mesh(file.string(), m) || num_faces(m) == 0 || !CGAL::is_triangle_mesh(m))
      continue;
    const auto np = IM::parameters::euclidean_weight(1).isophotic_weight(1).weight_length_scale(
      IM::suggested_weight_length_scale(m));
    std::unique_ptr<IM::Geodesic_solver<Mesh>> solver;
    try
    {
      solver = std::make_unique<IM::Geodesic_solver<Mesh>>(m, np);
    }
    catch(const IM::Invalid_mesh_error& e)
    {
      // must be the same verdict as the package's validation
      EXPECT_THROW(IM::validate_triangle_mesh(m), IM::Invalid_mesh_error) << file << ": " << e.what();
      ++rejected;
      continue;
    }
    auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
    IM::compute_lifted_embedding(m, lifted, np);
    vertex_descriptor s = *vertices(m).begin();
    for(vertex_descriptor v : vertices(m))
      if(!(halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()))
      {
        s = v;
        break;
      }
    // Large meshes: a bounded run keeps the test short; the invariants hold inside the bound.
    const bool large = num_faces(m) > 30000;
    solver->add_source(s);
    const std::vector<double> graph = dijkstra(m, s, lifted);
    double bound = inf;
    if(large)
    {
      std::vector<double> finite;
      for(double x : graph)
        if(x < inf)
          finite.push_back(x);
      std::nth_element(finite.begin(), finite.begin() + finite.size() / 10, finite.end());
      bound = finite[finite.size() / 10];
    }
    solver->propagate(bound);
    ++tested;
    const double scale = 1e-9 * (1 + *std::max_element(graph.begin(), graph.end(), [](double a, double b) {
                                   return (a < inf ? a : 0) < (b < inf ? b : 0);
                                 }));
    EXPECT_EQ(solver->distance(s), 0.0) << file;
    for(vertex_descriptor v : vertices(m))
    {
      const double d = solver->distance(v);
      if(large && !(d < inf))
        continue;
      EXPECT_EQ(d < inf, graph[v] < inf) << file << " " << v; // finite iff reachable
      if(!(d < inf))
        continue;
      EXPECT_LE(d, graph[v] + scale) << file << " " << v;
      const double chord = std::sqrt(IM::internal::squared_distance(get(lifted, s), get(lifted, v)));
      EXPECT_GE(d, chord - scale) << file << " " << v;
    }
    for(auto e : edges(m))
    {
      const vertex_descriptor u = source(e, m), v = target(e, m);
      const double du = solver->distance(u), dv = solver->distance(v);
      if(!(du < inf) || !(dv < inf))
        continue;
      const double len = std::sqrt(IM::internal::squared_distance(get(lifted, u), get(lifted, v)));
      EXPECT_LE(std::abs(du - dv), len + scale) << file << " edge " << e;
    }
  }
  std::cout << "invariants checked on " << tested << " triangle meshes (" << rejected << " rejected as invalid)\n";
  EXPECT_GT(tested, 40);
}

// ------------------------------------------------------------------ degenerate and bad input

TEST(GeodesicEngine, NeedleObtuseAndFlatTrianglesDoNotBreakIt)
{
  // A fan around a centre with needle and very obtuse triangles, plus an isolated vertex.
  Mesh m;
  const vertex_descriptor c = m.add_vertex(Point(0, 0, 0));
  std::vector<vertex_descriptor> ring;
  const std::vector<double> angles = {0, 1e-7, 2e-7, 1.0, 3.1415, 3.1416, 4.0, 6.0};
  for(double a : angles)
    ring.push_back(m.add_vertex(Point(std::cos(a), std::sin(a), a > 3.5 ? 0.3 : 0.0)));
  for(std::size_t i = 0; i < ring.size(); ++i)
    m.add_face(c, ring[i], ring[(i + 1) % ring.size()]);
  m.add_vertex(Point(5, 5, 5)); // isolated
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::isophotic_weight(0));
  solver.add_source(ring[1]);
  solver.propagate();
  for(vertex_descriptor v : vertices(m))
  {
    if((halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()))
    {
      EXPECT_EQ(solver.distance(v), inf);
      EXPECT_EQ(solver.nearest_source(v), IM::Geodesic_solver<Mesh>::no_source);
      continue;
    }
    const double d = solver.distance(v);
    EXPECT_TRUE(std::isfinite(d));
    EXPECT_GE(d, std::sqrt(CGAL::squared_distance(m.point(ring[1]), m.point(v))) - 1e-12);
    EXPECT_LE(d, std::sqrt(CGAL::squared_distance(m.point(ring[1]), m.point(c))) +
                   std::sqrt(CGAL::squared_distance(m.point(c), m.point(v))) + 1e-12);
  }
  // a zero-area (collinear) triangle with positive edge lengths is still processed
  Mesh flat;
  const auto a = flat.add_vertex(Point(0, 0, 0)), b = flat.add_vertex(Point(2, 0, 0)), d = flat.add_vertex(Point(1, 0, 0)),
             e = flat.add_vertex(Point(1, 1, 0));
  flat.add_face(a, b, e);
  flat.add_face(a, d, b);
  IM::Geodesic_solver<Mesh> flat_solver(flat, IM::parameters::isophotic_weight(0));
  flat_solver.add_source(e);
  flat_solver.propagate();
  // d lies on the edge ab of the unfolded surface: straight below e
  EXPECT_NEAR(flat_solver.distance(d), 1.0, 1e-12);
  EXPECT_NEAR(flat_solver.distance(a), std::sqrt(2.0), 1e-12);
}

TEST(GeodesicEngine, BadInputGetsPackageExceptionsNamingTheElement)
{
  Mesh m = planar_grid(3);
  // out-of-range source
  IM::Geodesic_solver<Mesh> solver(m);
  try
  {
    solver.add_source(vertex_descriptor(1000));
    ADD_FAILURE() << "no exception";
  }
  catch(const IM::Invalid_source_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("v1000"), std::string::npos) << e.what();
  }
  EXPECT_THROW(solver.add_source(Face_location(face_descriptor(0), {{0.5, 0.6, -0.1}})), IM::Invalid_source_error);
  EXPECT_THROW(solver.add_source(Face_location(face_descriptor(0), {{0.5, 0.6, 0.1}})), IM::Invalid_source_error);
  EXPECT_THROW(solver.add_source(Face_location(face_descriptor(99), {{1, 0, 0}})), IM::Invalid_source_error);
  EXPECT_THROW(solver.propagate(), IM::Invalid_source_error); // no source
  solver.add_source(vertex_descriptor(0));
  EXPECT_THROW(solver.propagate(-1.0), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::full_window_every(0)), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::full_window_every(256)), IM::Invalid_parameter_error);
  std::vector<face_descriptor> none;
  EXPECT_THROW(solver.add_source_region(none), IM::Invalid_source_error);
  // negative weight
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::euclidean_weight(-1.0)), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::euclidean_weight(-1.0).isophotic_weight(0)),
               IM::Invalid_parameter_error);
  // NaN coordinate
  Mesh nan_mesh = planar_grid(3);
  nan_mesh.point(vertex_descriptor(5)) = Point(std::nan(""), 0, 0);
  try
  {
    IM::Geodesic_solver<Mesh> s(nan_mesh);
    ADD_FAILURE() << "no exception";
  }
  catch(const IM::Invalid_mesh_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("vertex 5"), std::string::npos) << e.what();
  }
  // zero-length edge
  Mesh zero = planar_grid(3);
  zero.point(vertex_descriptor(5)) = zero.point(vertex_descriptor(6));
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(zero, IM::parameters::isophotic_weight(0)), IM::Invalid_mesh_error);
  // non-triangle face
  Mesh quad;
  quad.add_face(quad.add_vertex(Point(0, 0, 0)), quad.add_vertex(Point(1, 0, 0)), quad.add_vertex(Point(1, 1, 0)),
                quad.add_vertex(Point(0, 1, 0)));
  EXPECT_THROW(IM::Geodesic_solver<Mesh>{quad}, IM::Invalid_mesh_error);
  // queries needing windows in distance-only mode
  IM::Geodesic_solver<Mesh> light(m, IM::parameters::store_windows(false));
  light.add_source(vertex_descriptor(0));
  light.propagate();
  EXPECT_THROW(light.distance(Face_location(face_descriptor(0), {{1, 0, 0}})), IM::Error);
}

// ------------------------------------------------------------------ solver features

TEST(GeodesicEngine, BoundedPropagationMatchesUnboundedInsideTheBound)
{
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  IM::Geodesic_solver<Mesh> full(m), bounded(m);
  full.add_source(vertex_descriptor(10));
  bounded.add_source(vertex_descriptor(10));
  full.propagate();
  const double radius = 0.3;
  bounded.propagate(radius);
  int inside = 0;
  for(vertex_descriptor v : vertices(m))
  {
    if(full.distance(v) <= radius)
    {
      EXPECT_EQ(bounded.distance(v), full.distance(v));
      ++inside;
    }
    else
    {
      EXPECT_EQ(bounded.distance(v), inf);
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_LT(bounded.number_of_windows_created(), full.number_of_windows_created() / 2);
  // a second propagate() with a larger bound continues exactly
  bounded.propagate(2 * radius);
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(bounded.distance(v), full.distance(v) <= 2 * radius ? full.distance(v) : inf);
  bounded.propagate();
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(bounded.distance(v), full.distance(v));
}

TEST(GeodesicEngine, VoronoiLabelsReuseAndCancellation)
{
  const Mesh m = planar_grid(16, 0.2);
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::isophotic_weight(0));
  const vertex_descriptor a(20), b(250);
  EXPECT_EQ(solver.add_source(a), 0u);
  EXPECT_EQ(solver.add_source(b), 1u);
  solver.propagate();
  for(vertex_descriptor v : vertices(m))
  {
    const double da = std::sqrt(CGAL::squared_distance(m.point(a), m.point(v)));
    const double db = std::sqrt(CGAL::squared_distance(m.point(b), m.point(v)));
    EXPECT_NEAR(solver.distance(v), std::min(da, db), 1e-12);
    if(std::abs(da - db) > 1e-9)
    {
      EXPECT_EQ(solver.nearest_source(v), da < db ? 0u : 1u);
    }
  }
  // reuse for a new source set: same as a fresh solver
  solver.clear_sources();
  solver.add_source(vertex_descriptor(100));
  solver.propagate();
  IM::Geodesic_solver<Mesh> fresh(m, IM::parameters::isophotic_weight(0));
  fresh.add_source(vertex_descriptor(100));
  fresh.propagate();
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(solver.distance(v), fresh.distance(v));
  // cancellation through the visitor
  const Mesh big = load<Mesh>("meshes/fandisk.off");
  IM::Geodesic_solver<Mesh> cancelled(big);
  cancelled.add_source(vertex_descriptor(0));
  EXPECT_THROW(cancelled.propagate(inf, [](double) { return false; }), IM::Cancelled_error);
}

TEST(GeodesicEngine, ParallelBatchEqualsSerial)
{
  const Mesh m = load<Mesh>("meshes/elephant.off");
  std::vector<face_descriptor> sources;
  for(std::size_t i = 0; i < num_faces(m); i += 97)
    sources.push_back(face_descriptor(i));
  const auto np = IM::parameters::max_distance(0.05);
  std::vector<std::vector<double>> serial(sources.size()), parallel(sources.size());
  auto collect = [&](std::vector<std::vector<double>>& out) {
    return [&](std::size_t i, const IM::Geodesic_solver<Mesh>& solver) {
      for(vertex_descriptor v : vertices(m))
        out[i].push_back(solver.distance(v));
    };
  };
  IM::for_each_geodesic_distance_field<CGAL::Sequential_tag>(sources, m, collect(serial), np);
  IM::for_each_geodesic_distance_field<CGAL::Parallel_if_available_tag>(sources, m, collect(parallel), np);
  EXPECT_EQ(serial, parallel);
  // each field is the field of a single solver
  IM::Geodesic_solver<Mesh> one(m);
  const face_descriptor f[1] = {sources[3]};
  one.add_source_region(f);
  one.propagate(0.05);
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(serial[3][std::size_t(v)], one.distance(v));
}

// The propagation in bands of the front: distances and labels the same as the serial run's, bit for
// bit, on 1 to 65 threads, and window counts the same for thread counts that share their partitions
// (8 a thread, 16 to 64: 1 and 2 threads, 3 and 4, 8 and 65); on scans and CAD, open
// meshes, several components, bounded runs, the isophotic metric; cancellation; bad options.
TEST(GeodesicEngine, PropagationOnThreadsEqualsSerial)
{
  struct Case
  {
    const char* file;
    double w, w_prime;
    std::vector<std::size_t> sources;
    double bound_fraction; // of the largest finite distance; 1: unbounded
  };
  const std::vector<Case> cases = {
    {"meshes/bunny00.off", 0.5, 0.5, {0, 9000, 20000}, 1},       // a scan, open, isophotic, three labels
    {"meshes/fandisk.off", 1, 0, {0}, 1},                         // CAD
    {"meshes/fandisk.off", 0.5, 0.5, {100, 5000}, 0.4},           // bounded, isophotic
    {"meshes/elephant-with-holes.off", 1, 0, {0, 1000}, 1},        // holes
    {"meshes/blobby_3cc.off", 1, 0, {0, 3000}, 1},                // three components
    {"meshes/mesh_with_border.off", 0.5, 0.5, {0}, 0.5}};         // open, bounded
  for(const Case& c : cases)
  {
    const Mesh m = load<Mesh>(c.file);
    const IM::Metric_mesh<Mesh> metric(m, IM::parameters::euclidean_weight(c.w).isophotic_weight(c.w_prime).weight_length_scale(
                                            IM::suggested_weight_length_scale(m)));
    auto run = [&](int threads, double bound) {
      IM::Geodesic_solver<Mesh> solver(metric, IM::parameters::store_windows(false).propagation_threads(threads));
      for(std::size_t s : c.sources)
        solver.add_source(vertex_descriptor(static_cast<std::uint32_t>(s % num_vertices(m))));
      solver.propagate(bound);
      return solver;
    };
    double bound = inf;
    if(c.bound_fraction < 1)
    {
      const IM::Geodesic_solver<Mesh> full = run(0, inf);
      double largest = 0;
      for(vertex_descriptor v : vertices(m))
        if(full.distance(v) < inf)
          largest = std::max(largest, full.distance(v));
      bound = c.bound_fraction * largest;
    }
    const IM::Geodesic_solver<Mesh> serial = run(0, bound);
    std::size_t created = 0, propagated = 0, reached = 0;
    // (65: more threads than partitions, some of them with nothing to do in any band)
    for(int threads : {1, 2, 3, 4, 8, 65})
    {
      const IM::Geodesic_solver<Mesh> banded = run(threads, bound);
      std::size_t differences = 0;
      for(vertex_descriptor v : vertices(m))
      {
        if(banded.distance(v) != serial.distance(v) || banded.nearest_source(v) != serial.nearest_source(v))
          ++differences;
        reached += threads == 1 && serial.distance(v) < inf;
      }
      EXPECT_EQ(differences, 0u) << c.file << " on " << threads << " threads";
      if(threads == 1 || threads == 3 || threads == 8) // the first of each pair sharing partitions
      {
        created = banded.number_of_windows_created();
        propagated = banded.number_of_windows_propagated();
      }
      EXPECT_EQ(banded.number_of_windows_created(), created) << c.file << " on " << threads << " threads";
      EXPECT_EQ(banded.number_of_windows_propagated(), propagated) << c.file << " on " << threads << " threads";
    }
    EXPECT_GT(reached, num_vertices(m) / 10) << c.file;
  }

  // One-shot distances on threads; cancellation, then the solver cleared and reused.
  const Mesh m = load<Mesh>("meshes/bunny00.off");
  std::vector<double> serial(num_vertices(m)), banded(num_vertices(m));
  const vertex_descriptor sources[2] = {vertex_descriptor(0), vertex_descriptor(5000)};
  IM::compute_geodesic_distances(sources, m, CGAL::make_property_map(serial));
  IM::compute_geodesic_distances(sources, m, CGAL::make_property_map(banded), IM::parameters::propagation_threads(2));
  EXPECT_EQ(serial, banded);
  IM::Geodesic_solver<Mesh> solver(m, IM::parameters::store_windows(false).propagation_threads(2));
  solver.add_source(sources[0]);
  int calls = 0;
  EXPECT_THROW(solver.propagate(inf, [&](double) { return ++calls < 3; }), IM::Cancelled_error);
  EXPECT_EQ(calls, 3);
  solver.clear_sources();
  solver.add_source(sources[0]);
  solver.add_source(sources[1]);
  solver.propagate();
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(solver.distance(v), serial[std::size_t(v)]);
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::propagation_threads(2)), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::Geodesic_solver<Mesh>(m, IM::parameters::store_windows(false).propagation_threads(-1)),
               IM::Invalid_parameter_error);
}

TEST(GeodesicEngine, DistanceOnlyModeForgetsWindowsAndChangesNoDistance)
{
  // Distance-only mode forgets each window once it has crossed its face; with stored windows every
  // propagated window is archived. Both must give the same distances. Distance-only mode also
  // cuts the windows of a batch where another one is shorter (stored windows are not cut so): it
  // propagates fewer, on a scan (armadillo) as on CAD meshes.
  for(const char* name : {"meshes/fandisk.off", "meshes/elephant.off", "meshes/mech-holes-shark.off", "meshes/armadillo.off"})
  {
    const Mesh m = load<Mesh>(name);
    IM::internal::Intrinsic_triangle_mesh intrinsic;
    std::vector<vertex_descriptor> vs;
    std::vector<face_descriptor> fs;
    IM::internal::build_intrinsic_triangle_mesh(
      intrinsic, m,
      [&](vertex_descriptor u, vertex_descriptor v) { return std::sqrt(CGAL::squared_distance(m.point(u), m.point(v))); },
      vs, fs, get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), m), get(CGAL::dynamic_face_property_t<std::uint32_t>(), m));
    IM::internal::Window_propagation distance_only(intrinsic), kept(intrinsic);
    distance_only.set_keep_windows(false);
    kept.set_keep_windows(true);
    distance_only.add_vertex_source(3);
    kept.add_vertex_source(3);
    distance_only.propagate(inf);
    kept.propagate(inf);
    for(std::uint32_t v = 0; v < intrinsic.number_of_vertices(); ++v)
      EXPECT_EQ(distance_only.vertex_distance(v), kept.vertex_distance(v)) << name << " " << v;
    EXPECT_EQ(distance_only.stored_windows(), 0u) << name;
    EXPECT_EQ(kept.stored_windows(), kept.windows_propagated()) << name;
    EXPECT_GT(kept.windows_propagated(), intrinsic.number_of_vertices()) << name;
    EXPECT_LT(distance_only.windows_propagated(), kept.windows_propagated()) << name;
  }
}

TEST(GeodesicEngine, RebuiltWindowsGiveTheAnswersOfWindowsKeptInFull)
{
  // Most stored windows are kept as a link to their parent and rebuilt for a query, trimmed with
  // the final vertex distances. A rebuild that went wrong (wrong parent, wrong child, a trim
  // cutting what defines the distance) changes answers: point values, segment minima, labels and
  // paths must be those of the same propagation with every window kept in full, bit for bit, with
  // the default share of full records and a larger one, on a scan and a CAD mesh, Euclidean and
  // isophotic, bounded and unbounded, from two vertices, a point and a region.
  typedef IM::Geodesic_solver<Mesh> Solver;
  std::mt19937 random(5);
  for(const char* name : {"meshes/bunny00.off", "meshes/fandisk.off"})
  {
    const Mesh m = load<Mesh>(name);
    const std::size_t nv = num_vertices(m), nf = num_faces(m);
    auto add_sources = [&](Solver& solver) {
      solver.clear_sources();
      solver.add_source(vertex_descriptor(0));
      solver.add_source(vertex_descriptor(static_cast<std::uint32_t>(nv / 2)));
      solver.add_source(Face_location(face_descriptor(static_cast<std::uint32_t>(nf / 3)), {{0.2, 0.5, 0.3}}));
      solver.add_source_region(std::vector<face_descriptor>{face_descriptor(static_cast<std::uint32_t>(2 * nf / 3)),
                                                            face_descriptor(static_cast<std::uint32_t>(2 * nf / 3 + 1))});
    };
    for(const double w_prime : {0.0, 0.5})
    {
      const IM::Metric_mesh<Mesh> metric(m, IM::parameters::euclidean_weight(1.0 - w_prime).isophotic_weight(w_prime));
      Solver full(metric, IM::parameters::full_window_every(1));
      std::vector<Solver> rebuilt;
      rebuilt.emplace_back(metric); // the default share
      rebuilt.emplace_back(metric, IM::parameters::full_window_every(5));
      add_sources(full);
      full.propagate();
      std::vector<double> d;
      for(vertex_descriptor v : vertices(m))
        d.push_back(full.distance(v));
      std::sort(d.begin(), d.end());
      for(const double fraction : {1.0, 0.3})
      {
        const double bound = fraction < 1 ? d[static_cast<std::size_t>(d.size() * fraction)] : inf;
        add_sources(full);
        full.propagate(bound);
        for(Solver& solver : rebuilt)
        {
          add_sources(solver);
          solver.propagate(bound);
          EXPECT_EQ(solver.number_of_windows_stored(), full.number_of_windows_stored()) << name;
        }
        std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(nf - 1));
        std::uniform_real_distribution<double> unit(0, 1);
        int finite = 0;
        for(int k = 0; k < 2000; ++k)
        {
          const double x = unit(random), y = unit(random) * (1 - x);
          const Face_location p(face_descriptor(pick(random)), {{x, y, 1 - x - y}});
          const Face_location q(p.first, {{y, 1 - x - y, x}});
          const double value = full.distance(p);
          finite += std::isfinite(value);
          double t_full;
          const double minimum = full.minimum_distance_on_segment(p, q, &t_full);
          std::vector<Face_location> path_full;
          if(k % 10 == 0)
            full.trace_path(p, std::back_inserter(path_full));
          for(std::size_t r = 0; r < rebuilt.size(); ++r)
          {
            const std::string where = std::string(name) + " w'=" + std::to_string(w_prime) + " fraction " +
                                      std::to_string(fraction) + " solver " + std::to_string(r) + " query " + std::to_string(k);
            EXPECT_EQ(rebuilt[r].distance(p), value) << where;
            EXPECT_EQ(rebuilt[r].nearest_source(p), full.nearest_source(p)) << where;
            double t;
            EXPECT_EQ(rebuilt[r].minimum_distance_on_segment(p, q, &t), minimum) << where;
            EXPECT_EQ(t, t_full) << where;
            if(k % 10 != 0)
              continue;
            std::vector<Face_location> path;
            rebuilt[r].trace_path(p, std::back_inserter(path));
            ASSERT_EQ(path.size(), path_full.size()) << where;
            for(std::size_t i = 0; i < path.size(); ++i)
            {
              EXPECT_EQ(path[i].first, path_full[i].first) << where << " point " << i;
              EXPECT_EQ(path[i].second, path_full[i].second) << where << " point " << i;
            }
          }
        }
        EXPECT_GT(finite, 500) << name;
      }
    }
  }
}

TEST(GeodesicEngine, HugePageMemoryIsAlignedAndKeepsItsContents)
{
  // The engine's large arrays are mapped in 2 MB pages (internal/Huge_page_chunk.h): a chunk must
  // be aligned to 2 MB and hold what is written to it; a vector that grows past 2 MB (and so moves
  // from ordinary memory to mapped memory and between mappings) and shrinks back must keep its
  // contents, and giving the memory back must not disturb other allocations.
  using IM::internal::huge_page_bytes;
  const std::size_t count = 3 * huge_page_bytes / sizeof(std::uint64_t) + 5; // not a whole page
  auto chunk = IM::internal::allocate_huge_page_chunk<std::uint64_t>(count);
  ASSERT_NE(chunk.get(), nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(chunk.get()) % huge_page_bytes, 0u);
  for(std::size_t i = 0; i < count; ++i)
    chunk.get()[i] = i * 2654435761u;
  std::uint64_t mismatches = 0;
  for(std::size_t i = 0; i < count; ++i)
    mismatches += chunk.get()[i] != i * 2654435761u;
  EXPECT_EQ(mismatches, 0u);

  IM::internal::Huge_page_vector<std::uint64_t> grown;
  std::vector<std::uint64_t> reference;
  for(std::uint64_t i = 0; i < 4 * huge_page_bytes / sizeof(std::uint64_t); ++i)
  {
    grown.push_back(i ^ 0x9e3779b97f4a7c15u);
    reference.push_back(i ^ 0x9e3779b97f4a7c15u);
  }
  EXPECT_TRUE(std::equal(grown.begin(), grown.end(), reference.begin(), reference.end()));
  grown.resize(100);
  grown.shrink_to_fit(); // from mapped memory back to the ordinary heap
  EXPECT_TRUE(std::equal(grown.begin(), grown.end(), reference.begin()));
  chunk.reset();
  std::vector<std::uint64_t> after(count, 7); // the heap still works after the memory went back
  EXPECT_EQ(std::count(after.begin(), after.end(), 7u), static_cast<std::ptrdiff_t>(count));
}

namespace {
// An entry of the queue's tests: its key, and which push it was.
struct Keyed_entry
{
  double key;
  int id;
};
} // namespace

TEST(GeodesicEngine, RadixHeapPeekDoesNotRaiseLaterKeys)
{
  // A bounded propagation peeks at the smallest key and stops when it is beyond the bound; the
  // repair pass then pushes vertex events below that key, which must come out first and with
  // their own keys (a peek by top() raised them to the peeked key, so the next propagation took
  // them for stale events). Against a sorted reference: every key pushed at or above the last
  // one removed, peeks between pushes, keys equal to the peeked one and to the last removed.
  IM::internal::Radix_heap<Keyed_entry> heap;
  heap.push({1.0, 0});
  heap.pop();
  heap.push({5.0, 1});
  EXPECT_EQ(heap.min_key(), 5.0);
  heap.push({3.0, 2}); // below the peeked key, above the last removed one
  EXPECT_EQ(heap.min_key(), 3.0);
  EXPECT_EQ(heap.top().id, 2);
  EXPECT_EQ(heap.top().key, 3.0);
  heap.pop();
  EXPECT_EQ(heap.top().key, 5.0);
  heap.pop();
  EXPECT_TRUE(heap.empty());
  EXPECT_EQ(heap.min_key(), inf);

  std::mt19937 random(17);
  std::uniform_real_distribution<double> step(0.0, 4.0);
  std::multiset<double> reference;
  double last_removed = 0;
  heap.clear();
  for(int round = 0; round < 20000; ++round)
  {
    const int kind = int(random() % 8);
    if(kind < 4 || reference.empty())
    {
      // mostly just above the last removed key, sometimes exactly on it or on the current minimum
      double key = last_removed + step(random) * step(random);
      if(kind == 1)
        key = last_removed;
      else if(kind == 2 && !reference.empty())
        key = *reference.begin();
      heap.push({key, round});
      reference.insert(key);
    }
    else if(kind < 6)
    {
      EXPECT_EQ(heap.min_key(), *reference.begin()) << "round " << round;
    }
    else
    {
      ASSERT_EQ(heap.top().key, *reference.begin()) << "round " << round;
      last_removed = heap.top().key;
      heap.pop();
      reference.erase(reference.begin());
    }
    ASSERT_EQ(heap.size(), reference.size());
  }
}

TEST(GeodesicEngine, SegmentMinimumEqualsDenseSamplingOfPointQueries)
{
  // minimum_distance_on_segment minimises every candidate in closed form; dense sampling of the
  // (separately tested) point queries gives an independent answer. The minimum can be no larger
  // than any sample, and no smaller than the smallest sample minus half a sampling step (the
  // distance is 1-Lipschitz along the segment: in the Euclidean metric the step's 3D length).
  std::mt19937 random(7);
  const int samples = 2000;
  for(const char* name : {"meshes/fandisk.off", "meshes/mech-holes-shark.off"})
    for(const double w_prime : {0.0, 0.5})
      for(const bool bounded : {false, true})
      {
        const Mesh m = load<Mesh>(name);
        // (every window in full: 640k point queries; the rebuilt ones give the same answers, bit
        // for bit, RebuiltWindowsGiveTheAnswersOfWindowsKeptInFull)
        IM::Geodesic_solver<Mesh> solver(
          m, IM::parameters::euclidean_weight(1.0 - w_prime).isophotic_weight(w_prime).full_window_every(1));
        solver.add_source_region(std::vector<face_descriptor>{face_descriptor(17)});
        solver.add_source(Face_location(face_descriptor(400), {{0.2, 0.3, 0.5}}));
        double bound = inf;
        if(bounded)
        {
          bound = distance_reaching(solver, m, 0.6);
          solver.clear_sources();
          solver.add_source_region(std::vector<face_descriptor>{face_descriptor(17)});
          solver.add_source(Face_location(face_descriptor(400), {{0.2, 0.3, 0.5}}));
        }
        solver.propagate(bound);
        std::uniform_int_distribution<std::size_t> pick(0, num_faces(m) - 1);
        std::uniform_real_distribution<double> unit(0, 1);
        int finite = 0;
        for(int trial = 0; trial < 40; ++trial)
        {
          const face_descriptor f(static_cast<Mesh::size_type>(pick(random)));
          std::array<double, 3> ba{0, 0, 0}, bb{0, 0, 0};
          if(trial % 2 == 0) // an edge of the face
          {
            ba[trial / 2 % 3] = 1;
            bb[(trial / 2 + 1) % 3] = 1;
          }
          else // a segment across the face
            for(std::array<double, 3>* b : {&ba, &bb})
            {
              const double x = unit(random), y = unit(random) * (1 - x);
              *b = {x, y, 1 - x - y};
            }
          double t = -1;
          const double minimum = solver.minimum_distance_on_segment(Face_location(f, ba), Face_location(f, bb), &t);
          double sampled = inf, largest_step_change = 0, previous = inf;
          for(int i = 0; i <= samples; ++i)
          {
            const double s = double(i) / samples;
            const double d = solver.distance(Face_location(f, {{(1 - s) * ba[0] + s * bb[0], (1 - s) * ba[1] + s * bb[1], (1 - s) * ba[2] + s * bb[2]}}));
            sampled = std::min(sampled, d);
            if(std::isfinite(d) && std::isfinite(previous))
              largest_step_change = std::max(largest_step_change, std::abs(d - previous));
            previous = d;
          }
          const std::string where = std::string(name) + " w'=" + std::to_string(w_prime) + (bounded ? " bounded" : "") +
                                    " face " + std::to_string(std::size_t(f)) + " trial " + std::to_string(trial);
          if(!std::isfinite(sampled))
          {
            EXPECT_EQ(minimum, inf) << where;
            continue;
          }
          ++finite;
          ASSERT_TRUE(t >= 0 && t <= 1) << where;
          EXPECT_LE(minimum, sampled * (1 + 1e-12) + 1e-15) << where;
          double step = largest_step_change / 2;
          if(w_prime == 0)
          {
            const Point pa = CGAL::barycenter(m.point(source(halfedge(f, m), m)), ba[0], m.point(target(halfedge(f, m), m)), ba[1],
                                              m.point(target(next(halfedge(f, m), m), m)), ba[2]);
            const Point pb = CGAL::barycenter(m.point(source(halfedge(f, m), m)), bb[0], m.point(target(halfedge(f, m), m)), bb[1],
                                              m.point(target(next(halfedge(f, m), m), m)), bb[2]);
            step = std::sqrt(CGAL::squared_distance(pa, pb)) / samples / 2;
          }
          EXPECT_GE(minimum, sampled - step * (1 + 1e-9) - 1e-12) << where;
          // the reported place realises the minimum
          const double at = solver.distance(Face_location(f, {{(1 - t) * ba[0] + t * bb[0], (1 - t) * ba[1] + t * bb[1], (1 - t) * ba[2] + t * bb[2]}}));
          EXPECT_NEAR(at, minimum, 1e-12 * std::max(1.0, minimum)) << where;
        }
        EXPECT_GT(finite, 10) << name;
      }
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  IM::Geodesic_solver<Mesh> solver(m);
  solver.add_source(vertex_descriptor(0));
  solver.propagate();
  EXPECT_THROW(solver.minimum_distance_on_segment(Face_location(face_descriptor(0), {{1, 0, 0}}),
                                                   Face_location(face_descriptor(1), {{1, 0, 0}})),
               IM::Invalid_parameter_error);
}

// ---------------------------------------------------------------------------------------------
// The prepared mesh: edge lengths given by the user, sharing between solvers.

namespace {

// A cylinder of `n` columns and `rows` rows given by its edge lengths only: the flat strip of width
// n * ds (glued along its long sides) and height rows * dt, cut in right triangles. Every vertex is
// put at the origin, so nothing but the lengths can give the distances.
struct Flat_cylinder
{
  Mesh mesh;
  std::vector<std::array<int, 2>> grid; // (column, row) of every vertex
  int n, rows;
  double ds, dt;

  Flat_cylinder(int columns, int r, double s, double t) : n(columns), rows(r), ds(s), dt(t)
  {
    std::vector<vertex_descriptor> v;
    for(int j = 0; j <= rows; ++j)
      for(int i = 0; i < n; ++i)
      {
        v.push_back(mesh.add_vertex(Point(0, 0, 0)));
        grid.push_back({i, j});
      }
    auto at = [&](int i, int j) { return v[j * n + (i % n)]; };
    for(int j = 0; j < rows; ++j)
      for(int i = 0; i < n; ++i)
      {
        mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }
  // Length of the edge between two vertices, in the unrolled strip (columns wrap around).
  double length(vertex_descriptor a, vertex_descriptor b) const
  {
    int di = std::abs(grid[a][0] - grid[b][0]);
    di = std::min(di, n - di);
    const int dj = grid[a][1] - grid[b][1];
    return std::hypot(di * ds, dj * dt);
  }
  // Closed form: the straight segment in the unrolled strip to the nearest copy of the target.
  double distance(vertex_descriptor a, vertex_descriptor b) const { return length(a, b); }
};

} // namespace

TEST(MetricMesh, EdgeLengthsOfAFlatCylinderGiveItsClosedForm)
{
  const Flat_cylinder c(24, 9, 0.13, 0.21);
  auto lengths = get(CGAL::dynamic_edge_property_t<double>(), c.mesh);
  for(auto e : edges(c.mesh))
    put(lengths, e, c.length(source(e, c.mesh), target(e, c.mesh)));
  IM::Geodesic_solver<Mesh> solver(c.mesh, IM::parameters::edge_length_map(lengths));
  const vertex_descriptor s(3 * 24 + 5);
  solver.add_source(s);
  solver.propagate();
  for(vertex_descriptor v : vertices(c.mesh))
    EXPECT_NEAR(solver.distance(v), c.distance(s, v), 1e-12) << "vertex " << v;
  // the one-shot function takes the same parameter; halfedge-keyed lengths work as edge-keyed ones
  auto halfedge_lengths = get(CGAL::dynamic_halfedge_property_t<double>(), c.mesh);
  for(auto h : halfedges(c.mesh))
    put(halfedge_lengths, h, c.length(source(h, c.mesh), target(h, c.mesh)));
  auto d = get(CGAL::dynamic_vertex_property_t<double>(), c.mesh);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{s}, c.mesh, d, IM::parameters::edge_length_map(halfedge_lengths));
  for(vertex_descriptor v : vertices(c.mesh))
    EXPECT_EQ(get(d, v), solver.distance(v));
}

TEST(MetricMesh, LiftedEdgeLengthsGiveTheDistancesOfTheLiftedRoute)
{
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(IM::suggested_weight_length_scale(m));
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  IM::compute_lifted_embedding(m, lifted, metric);
  auto lengths = get(CGAL::dynamic_halfedge_property_t<double>(), m);
  for(auto h : halfedges(m))
  {
    const IM::Lifted_point a = get(lifted, source(h, m)), b = get(lifted, target(h, m));
    double s = 0;
    for(int k = 0; k < 6; ++k)
      s += (a[k] - b[k]) * (a[k] - b[k]);
    put(lengths, h, std::sqrt(s));
  }
  IM::Geodesic_solver<Mesh> from_lift(m, metric), from_lengths(m, IM::parameters::edge_length_map(lengths));
  for(IM::Geodesic_solver<Mesh>* solver : {&from_lift, &from_lengths})
  {
    solver->add_source(vertex_descriptor(17));
    solver->propagate();
  }
  std::size_t finite = 0;
  for(vertex_descriptor v : vertices(m))
  {
    EXPECT_NEAR(from_lengths.distance(v), from_lift.distance(v), 1e-12 * (1 + from_lift.distance(v))) << "vertex " << v;
    finite += std::isfinite(from_lift.distance(v));
  }
  EXPECT_EQ(finite, num_vertices(m));
}

TEST(MetricMesh, SolversShareOnePreparedMesh)
{
  const Mesh m = load<Mesh>("meshes/fandisk.off");
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(IM::suggested_weight_length_scale(m));
  const IM::Metric_mesh<Mesh> prepared(m, metric);
  IM::Geodesic_solver<Mesh> shared(prepared), own(m, metric);
  const IM::Geodesic_solver<Mesh> sibling = shared.sibling();
  EXPECT_EQ(&shared.metric_mesh().intrinsic(), &prepared.intrinsic());
  EXPECT_EQ(&sibling.metric_mesh().intrinsic(), &prepared.intrinsic());
  for(IM::Geodesic_solver<Mesh>* solver : {&shared, &own})
  {
    solver->add_source(vertex_descriptor(5));
    solver->propagate();
  }
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(shared.distance(v), own.distance(v));
  // the numbering: every descriptor maps to its index and back
  for(vertex_descriptor v : vertices(m))
    EXPECT_EQ(prepared.vertex(prepared.vertex_index(v)), v);
  for(face_descriptor f : faces(m))
    EXPECT_EQ(prepared.face(prepared.face_index(f)), f);
}

TEST(MetricMesh, PseudoSourceCandidatesAreBorderVerticesAndAngleSumsAbove2Pi)
{
  // The prepared mesh decides most vertices from a bound on approximate corner angles; every
  // decision must be that of the plain sum of corner_angle() (std::atan2) over the vertex's corners
  // in increasing order, compared with 2 pi + 1e-13 + 2 pi n^2 2^-53 (n corners: above its
  // rounding), or the vertex is on the border or at an end of a needle edge.
  std::size_t inner = 0, near_threshold = 0, saddles = 0;
  auto check = [&](const Mesh& m, const auto& np, const std::string& what) {
    const IM::Metric_mesh<Mesh> prepared(m, np);
    const IM::internal::Intrinsic_triangle_mesh& in = prepared.intrinsic();
    std::vector<double> sum(in.number_of_vertices(), 0.0);
    std::vector<char> bends_anyway(in.number_of_vertices(), 0);
    std::vector<double> corners(in.number_of_vertices(), 0.0);
    for(std::uint32_t h = 0; h < in.number_of_corners(); ++h)
    {
      sum[in.source(h)] += in.corner_angle(h);
      ++corners[in.source(h)];
      if(in.opposite(h) == IM::internal::Intrinsic_triangle_mesh::no_halfedge ||
         in.length(h) <= 1e-6 * std::max(in.length(in.next(h)), in.length(in.prev(h))))
        bends_anyway[in.source(h)] = bends_anyway[in.target(h)] = 1;
    }
    for(std::uint32_t v = 0; v < in.number_of_vertices(); ++v)
    {
      const double threshold = 2 * pi + 1e-13 + 2 * pi * corners[v] * corners[v] * 0x1p-53;
      const bool bends = bends_anyway[v] || sum[v] > threshold;
      EXPECT_EQ(in.is_pseudo_source_candidate(v), bends) << what << " vertex " << v << " angle sum - 2 pi = " << sum[v] - 2 * pi;
      if(!bends_anyway[v])
      {
        ++inner;
        near_threshold += std::abs(sum[v] - threshold) < 1e-10;
        saddles += bends;
      }
    }
  };
  // Fans around a centre (one inner vertex each): flat, saddles (rims alternating up and down)
  // and cones, with heights swept so that the centre's angle sum passes the threshold, some with
  // needle corners.
  Mesh fans;
  for(int n : {5, 6, 8, 12})
    for(int shape = 0; shape < 3; ++shape)
      for(int i = 0; i < 300; ++i)
      {
        const double height = shape == 0 ? 0. : 1e-7 * std::pow(1e5, i / 299.);
        const bool needles = i % 3 == 0;
        const double x0 = 3. * i, y0 = 3. * (3 * n + shape);
        const vertex_descriptor c = fans.add_vertex(Point(x0, y0, 0));
        std::vector<vertex_descriptor> rim;
        for(int k = 0; k < n; ++k)
        {
          const double angle = 2 * pi * k / n + (needles && k == 1 ? -2 * pi / n + 1e-7 : 0.);
          const double z = shape == 1 ? (k % 2 == 0 ? height : -height) : height;
          rim.push_back(fans.add_vertex(Point(x0 + std::cos(angle), y0 + std::sin(angle), z)));
        }
        for(int k = 0; k < n; ++k)
          fans.add_face(c, rim[k], rim[(k + 1) % n]);
      }
  check(fans, IM::parameters::isophotic_weight(0), "fans");
  EXPECT_GT(near_threshold, 0u); // sums within 1e-10 of the threshold: the bound cannot decide them
  for(const char* name : {"meshes/fandisk.off", "meshes/elephant.off", "meshes/mech-holes-shark.off"})
  {
    const Mesh m = load<Mesh>(name);
    check(m, IM::parameters::isophotic_weight(0), name);
    check(m, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5), std::string(name) + " (isophotic)");
  }
  EXPECT_GT(saddles, 1000u);
  EXPECT_GT(inner - saddles, 1000u);
}

TEST(MetricMesh, BadEdgeLengthsGetPackageExceptions)
{
  const Flat_cylinder c(8, 2, 1.0, 1.0);
  auto lengths = get(CGAL::dynamic_halfedge_property_t<double>(), c.mesh);
  for(auto h : halfedges(c.mesh))
    put(lengths, h, c.length(source(h, c.mesh), target(h, c.mesh)));
  halfedge_descriptor h; // a halfedge of an edge between two faces
  for(halfedge_descriptor g : halfedges(c.mesh))
    if(!is_border_edge(g, c.mesh))
    {
      h = g;
      break;
    }
  put(lengths, h, 1.5 * get(lengths, h)); // its opposite keeps the old length
  EXPECT_THROW(IM::Metric_mesh<Mesh>(c.mesh, IM::parameters::edge_length_map(lengths)), IM::Invalid_parameter_error);
  put(lengths, opposite(h, c.mesh), get(lengths, h));
  put(lengths, h, 10.0); // violates the triangle inequality
  put(lengths, opposite(h, c.mesh), 10.0);
  EXPECT_THROW(IM::Metric_mesh<Mesh>(c.mesh, IM::parameters::edge_length_map(lengths)), IM::Invalid_mesh_error);
  put(lengths, h, 0.0);
  put(lengths, opposite(h, c.mesh), 0.0);
  EXPECT_THROW(IM::Metric_mesh<Mesh>(c.mesh, IM::parameters::edge_length_map(lengths)), IM::Invalid_mesh_error);
}

TEST(GeodesicEngine, RadixHeapLowerFloorLetsLowerKeysInUnraised)
{
  // After a propagation the repair pass pushes vertex events below the last key removed (edge-path
  // values of vertices the front passed long ago); a push raises such keys to that key, and the
  // event was then taken for stale. lower_floor() lets them in with their own keys, the entries
  // waiting keeping theirs: against a sorted reference, over keys spread across many buckets.
  IM::internal::Radix_heap<Keyed_entry> heap;
  heap.push({2.0, 0});
  heap.pop();
  heap.push({1.0, 1}); // raised: the behaviour lower_floor() is there to avoid
  EXPECT_EQ(heap.top().key, 2.0);
  heap.pop();
  std::mt19937 random(29);
  std::uniform_real_distribution<double> exponent(-20.0, 20.0);
  for(int round = 0; round < 50; ++round)
  {
    heap.lower_floor(); // (empty: the last round's keys bound nothing any more)
    std::multiset<double> reference;
    for(int i = 0; i < 30; ++i)
    {
      const double key = std::exp2(exponent(random));
      heap.push({key, i});
      reference.insert(key);
    }
    // remove some (the last removed key grows), then lower the floor and push below it
    double last_removed = 0;
    for(int i = 0; i < 10; ++i)
    {
      last_removed = heap.top().key;
      ASSERT_EQ(last_removed, *reference.begin());
      reference.erase(reference.begin());
      heap.pop();
    }
    heap.lower_floor();
    for(int i = 0; i < 10; ++i)
    {
      const double key = last_removed * std::exp2(-1 - exponent(random) / 4 - 5); // below it
      heap.push({key, 100 + i});
      reference.insert(key);
    }
    heap.push({last_removed, 200}); // and at it
    reference.insert(last_removed);
    ASSERT_EQ(heap.size(), reference.size());
    for(double expected : reference)
    {
      EXPECT_EQ(heap.min_key(), expected) << "round " << round;
      ASSERT_EQ(heap.top().key, expected) << "round " << round;
      heap.pop();
    }
    EXPECT_TRUE(heap.empty());
  }
}

TEST(GeodesicEngine, RadixHeapClearForgetsTheBucketsInUse)
{
  // The queue finds its lowest bucket in use from a mask; clear() must empty the mask with the
  // buckets, or a heap reused for the next propagation (Geodesic_solver::clear_sources) takes an
  // emptied bucket for the one holding the minimum. Keys spread over many buckets, cleared half
  // way, then checked against a sorted reference.
  IM::internal::Radix_heap<Keyed_entry> heap;
  for(int round = 0; round < 2; ++round)
  {
    std::vector<double> keys;
    for(int i = 0; i < 40; ++i)
      keys.push_back(std::ldexp(1.0 + i / 64.0, (i * 7) % 40 - 10)); // 2^-10 .. 2^29
    for(std::size_t i = 0; i < keys.size(); ++i)
      heap.push({keys[i], static_cast<int>(i)});
    heap.pop();
    heap.pop();
    heap.clear();
    EXPECT_TRUE(heap.empty());
    EXPECT_EQ(heap.min_key(), inf);
    std::vector<double> second = {0.75, 3.0, 1e6, 0.5, 40.0};
    for(std::size_t i = 0; i < second.size(); ++i)
      heap.push({second[i], static_cast<int>(i)});
    std::sort(second.begin(), second.end());
    for(double expected : second)
    {
      EXPECT_EQ(heap.min_key(), expected) << "round " << round;
      ASSERT_EQ(heap.top().key, expected) << "round " << round;
      heap.pop();
    }
    EXPECT_TRUE(heap.empty());
    heap.clear();
  }
}
