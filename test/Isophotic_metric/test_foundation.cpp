// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests of the package foundation: lifted embedding, basic measures, input validation, named parameters.
// Every expected value comes from a closed form (plane, sphere, scaling), never from the code under test.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/subdivision_method_3.h>

#include <CGAL/Isophotic_metric.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;
using IM::Lifted_point;

const double pi = 3.14159265358979323846;
const double nan_value = std::numeric_limits<double>::quiet_NaN();
const double inf_value = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Mesh builders, generic over the mesh type.

template <class Mesh>
using vertex_of = typename boost::graph_traits<Mesh>::vertex_descriptor;
template <class Mesh>
using face_of = typename boost::graph_traits<Mesh>::face_descriptor;

// Builds a mesh from a polygon soup with BGL's Euler::add_face; vertices and faces keep the order
// of the soup, so the package's element indices are the soup's indices.
template <class Mesh>
std::vector<vertex_of<Mesh>> build(Mesh& m, const std::vector<Point>& points,
                                   const std::vector<std::vector<int>>& polygons)
{
  std::vector<vertex_of<Mesh>> vs;
  for(const Point& p : points)
  {
    vs.push_back(add_vertex(m));
    put(CGAL::vertex_point, m, vs.back(), p);
  }
  for(const auto& polygon : polygons)
  {
    std::vector<vertex_of<Mesh>> face_vertices;
    for(int i : polygon)
      face_vertices.push_back(vs[i]);
    const auto f = CGAL::Euler::add_face(face_vertices, m);
    EXPECT_NE(f, boost::graph_traits<Mesh>::null_face()) << "the test soup must be a valid polygon mesh";
  }
  return vs;
}

// An n x n grid of squares on [0,a] x [0,b] in the plane spanned by u and v through origin o,
// each square cut into two triangles.
template <class Mesh>
void build_grid(Mesh& m, int n, double a, double b,
                const Vector& u = Vector(1, 0, 0), const Vector& v = Vector(0, 1, 0),
                const Point& o = Point(0, 0, 0))
{
  std::vector<Point> points;
  std::vector<std::vector<int>> triangles;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
      points.push_back(o + (a * i / n) * u + (b * j / n) * v);
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      const int c = j * (n + 1) + i;
      triangles.push_back({c, c + 1, c + n + 2});
      triangles.push_back({c, c + n + 2, c + n + 1});
    }
  build(m, points, triangles);
}

// Icosahedron refined by Loop subdivision, every vertex projected onto the sphere of radius R.
template <class Mesh>
void build_sphere(Mesh& m, int levels, double R)
{
  CGAL::make_icosahedron(m, Point(0, 0, 0), R);
  if(levels > 0)
    CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(levels));
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    const double r = std::sqrt(CGAL::to_double((p - CGAL::ORIGIN).squared_length()));
    put(CGAL::vertex_point, m, v, CGAL::ORIGIN + (R / r) * (p - CGAL::ORIGIN));
  }
}

// The lifted embedding as a vector in the order of vertices(m), in the paper's raw metric (length
// scale 1, which the closed forms below assume) unless `np` gives a length scale.
template <class Mesh, class NP = IM::parameters::Default_named_parameters>
std::vector<Lifted_point> lift(const Mesh& m, const NP& np = IM::parameters::default_values())
{
  auto lifted = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  IM::compute_lifted_embedding(m, lifted, IM::parameters::combine(IM::parameters::weight_length_scale(1.), np));
  std::vector<Lifted_point> result;
  for(auto v : vertices(m))
    result.push_back(get(lifted, v));
  return result;
}

double distance(const Lifted_point& a, const Lifted_point& b)
{
  double s = 0;
  for(int i = 0; i < 6; ++i)
    s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

double length(const Vector& v) { return std::sqrt(CGAL::to_double(v.squared_length())); }

// Radius of the circle through the three corners of a triangle.
double circumradius(const Point& a, const Point& b, const Point& c)
{
  const double la = length(b - c), lb = length(c - a), lc = length(a - b);
  const double area2 = length(CGAL::cross_product(b - a, c - a)); // twice the area
  return la * lb * lc / (2. * area2);
}

// Expects `f` to throw exactly `Exception` with a message containing every part of `expected`.
template <class Exception>
void expect_error(const std::function<void()>& f, const std::vector<std::string>& expected)
{
  try
  {
    f();
    ADD_FAILURE() << "no exception thrown";
  }
  catch(const Exception& e)
  {
    for(const std::string& part : expected)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
        << "message \"" << e.what() << "\" does not contain \"" << part << "\"";
  }
  catch(const std::exception& e)
  {
    ADD_FAILURE() << "wrong exception type, message: " << e.what();
  }
}

template <class Mesh>
class Foundation : public ::testing::Test {};

typedef ::testing::Types<CGAL::Surface_mesh<Point>, CGAL::Polyhedron_3<K>> Mesh_types;
TYPED_TEST_SUITE(Foundation, Mesh_types);

// ---------------------------------------------------------------------------------------------
// Lifted embedding: closed forms.

// Plane z = 0: every normal is (0,0,1), so X = (sqrt(w) p, 0, 0, sqrt(w')).
TYPED_TEST(Foundation, PlaneLiftIsExact)
{
  TypeParam m;
  build_grid(m, 4, 2., 3.);
  const double w = 0.3, wi = 0.7;
  const auto X = lift(m, IM::parameters::euclidean_weight(w).isophotic_weight(wi));
  std::size_t i = 0;
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    const Lifted_point expected = {std::sqrt(w) * p.x(), std::sqrt(w) * p.y(), 0., 0., 0., std::sqrt(wi)};
    for(int k = 0; k < 6; ++k)
      EXPECT_DOUBLE_EQ(X[i][k], expected[k]) << "vertex " << i << " coordinate " << k;
    ++i;
  }
}

// A tilted plane with unit normal n = (1,2,2)/3: X = (sqrt(w) p, sqrt(w') n) up to rounding.
TYPED_TEST(Foundation, TiltedPlaneLift)
{
  TypeParam m;
  const Vector n(1. / 3, 2. / 3, 2. / 3);
  const Vector u(0, 1. / std::sqrt(2.), -1. / std::sqrt(2.)); // unit, orthogonal to n
  const Vector v = CGAL::cross_product(n, u);                 // so that u x v = n
  build_grid(m, 3, 1., 1., u, v, Point(5, -2, 1));
  const double w = 2., wi = 0.5;
  const auto X = lift(m, IM::parameters::euclidean_weight(w).isophotic_weight(wi));
  std::size_t i = 0;
  for(auto vd : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, vd);
    const Lifted_point expected = {std::sqrt(w) * p.x(), std::sqrt(w) * p.y(), std::sqrt(w) * p.z(),
                                   std::sqrt(wi) * n.x(), std::sqrt(wi) * n.y(), std::sqrt(wi) * n.z()};
    for(int k = 0; k < 6; ++k)
      EXPECT_NEAR(X[i][k], expected[k], 1e-14) << "vertex " << i << " coordinate " << k;
    ++i;
  }
}

// Sphere of radius R: n = p/R, so X = sqrt(w + w'/R^2) p. The default normal (Max's weights) is exact
// when a vertex and its neighbours lie on a common sphere, so only rounding remains.
TYPED_TEST(Foundation, SphereLiftIsExactWithDefaultNormals)
{
  const double R = 2., w = 0.3, wi = 1.2;
  for(int level = 0; level <= 4; ++level)
  {
    TypeParam m;
    build_sphere(m, level, R);
    const auto X = lift(m, IM::parameters::euclidean_weight(w).isophotic_weight(wi));
    const double factor = std::sqrt(w + wi / (R * R));
    double max_error = 0.;
    std::size_t i = 0;
    for(auto v : vertices(m))
    {
      const Point p = get(CGAL::vertex_point, m, v);
      Lifted_point expected;
      for(int k = 0; k < 3; ++k)
      {
        expected[k] = std::sqrt(w) * p[k];
        expected[k + 3] = std::sqrt(wi) * p[k] / R;
      }
      max_error = (std::max)(max_error, distance(X[i], expected));
      double norm_X = 0.;
      for(int k = 0; k < 6; ++k)
        norm_X += X[i][k] * X[i][k];
      EXPECT_NEAR(std::sqrt(norm_X), factor * R, 1e-12) << "|X| = sqrt(w + w'/R^2) |p|";
      ++i;
    }
    std::cout << "[ sphere   ] level " << level << ": " << num_faces(m)
              << " faces, max |X - sqrt(w+w'/R^2) p| = " << max_error << std::endl;
    EXPECT_LE(max_error, 1e-13);
  }
}

// The same sphere with CGAL's "most visible" normals passed by the user. Each face normal of a triangle
// inscribed in the sphere points to the centre of its circumcircle, at the angle asin(rho/R) from the
// radial direction of each corner (rho = circumradius). That normal lies in the cone spanned by the
// incident face normals, so |n - p/R| <= max over incident faces of asin(rho/R) = O(h/R).
TYPED_TEST(Foundation, SphereLiftWithPMPNormalsIsWithinTheFaceNormalCone)
{
  const double R = 2., w = 0.3, wi = 1.2;
  for(int level = 1; level <= 4; ++level)
  {
    TypeParam m;
    build_sphere(m, level, R);
    auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
    PMP::compute_vertex_normals(m, normals);
    const auto X = lift(m, IM::parameters::vertex_normal_map(normals).euclidean_weight(w).isophotic_weight(wi));
    double max_error = 0., max_bound = 0.;
    std::size_t i = 0;
    for(auto v : vertices(m))
    {
      const Point p = get(CGAL::vertex_point, m, v);
      Lifted_point expected;
      for(int k = 0; k < 3; ++k)
      {
        expected[k] = std::sqrt(w) * p[k];
        expected[k + 3] = std::sqrt(wi) * p[k] / R;
      }
      const double error = distance(X[i], expected);
      double bound = 0.;
      for(auto h : CGAL::halfedges_around_target(halfedge(v, m), m))
      {
        const auto hf = halfedge(face(h, m), m);
        const double rho = circumradius(get(CGAL::vertex_point, m, source(hf, m)),
                                        get(CGAL::vertex_point, m, target(hf, m)),
                                        get(CGAL::vertex_point, m, target(next(hf, m), m)));
        bound = (std::max)(bound, std::sqrt(wi) * std::asin((std::min)(1., rho / R)));
      }
      EXPECT_LE(error, bound + 1e-12) << "level " << level << " vertex " << i;
      max_error = (std::max)(max_error, error);
      max_bound = (std::max)(max_bound, bound);
      ++i;
    }
    std::cout << "[ sphere   ] PMP normals, level " << level << ": " << num_faces(m) << " faces, max error "
              << max_error << " (bound " << max_bound << ")" << std::endl;
  }
}

// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1: n is proportional to (x/a^2, y/b^2, z/c^2). The default normal
// is second-order accurate: halving the edge length (one Loop step) must divide the error by more than 2
// (4 in the limit), and the largest error must stay below (h/rho)^2 / 4, h the longest edge and
// rho = c^2/a = 0.5 the smallest principal radius of curvature of the ellipsoid (a second-order bound
// with constant 1/4; measured constants are about 1/10).
TYPED_TEST(Foundation, EllipsoidLiftConvergesUnderRefinement)
{
  const double a = 2., b = 1.5, c = 1., w = 1., wi = 1.;
  double previous_error = inf_value;
  for(int level = 1; level <= 4; ++level)
  {
    TypeParam m;
    build_sphere(m, level, 1.);
    for(auto v : vertices(m))
    {
      const Point p = get(CGAL::vertex_point, m, v);
      put(CGAL::vertex_point, m, v, Point(a * p.x(), b * p.y(), c * p.z()));
    }
    double h = 0.;
    for(auto e : edges(m))
      h = (std::max)(h, length(get(CGAL::vertex_point, m, source(e, m)) - get(CGAL::vertex_point, m, target(e, m))));
    const auto X = lift(m, IM::parameters::euclidean_weight(w).isophotic_weight(wi));
    double max_error = 0.;
    std::size_t i = 0;
    for(auto v : vertices(m))
    {
      const Point p = get(CGAL::vertex_point, m, v);
      Vector n(p.x() / (a * a), p.y() / (b * b), p.z() / (c * c));
      n = n / length(n);
      const Lifted_point expected = {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()};
      max_error = (std::max)(max_error, distance(X[i], expected));
      ++i;
    }
    std::cout << "[ ellipsoid] level " << level << ": " << num_faces(m) << " faces, h = " << h
              << ", max |X - X_exact| = " << max_error << std::endl;
    const double rho = c * c / a;
    EXPECT_LT(max_error, 0.25 * (h / rho) * (h / rho));
    EXPECT_LT(2. * max_error, previous_error) << "the error must fall faster than the edge length";
    previous_error = max_error;
  }
}

// Exact normals given by the user: the sphere lift is then exact up to rounding.
TYPED_TEST(Foundation, SphereLiftWithGivenNormals)
{
  TypeParam m;
  const double R = 3., w = 0.5, wi = 4.5;
  build_sphere(m, 2, R);
  auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
  for(auto v : vertices(m))
    put(normals, v, (get(CGAL::vertex_point, m, v) - CGAL::ORIGIN) / R);
  const auto X = lift(m, IM::parameters::vertex_normal_map(normals).euclidean_weight(w).isophotic_weight(wi));
  const double factor = std::sqrt(w + wi / (R * R));
  std::size_t i = 0;
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    for(int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(std::sqrt(X[i][k] * X[i][k] + X[i][k + 3] * X[i][k + 3]), factor * std::abs(p[k]), 1e-12);
      EXPECT_NEAR(X[i][k], std::sqrt(w) * p[k], 1e-13);
      EXPECT_NEAR(X[i][k + 3], std::sqrt(wi) * p[k] / R, 1e-13);
    }
    ++i;
  }
}

// Per-vertex weights: X(v) = (sqrt(w(v)) (p - c), sqrt(w'(v)) n) with c the centroid of the vertices.
TYPED_TEST(Foundation, PerVertexWeights)
{
  TypeParam m;
  const double a = 2., b = 1.;
  build_grid(m, 4, a, b);
  auto w = get(CGAL::dynamic_vertex_property_t<double>(), m);
  auto wi = get(CGAL::dynamic_vertex_property_t<double>(), m);
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    put(w, v, 0.5 + p.x());
    put(wi, v, 1. + p.y() * p.y());
  }
  const auto X = lift(m, IM::parameters::euclidean_weight(w).isophotic_weight(wi));
  const Point c(a / 2, b / 2, 0); // centroid of a uniform grid on [0,a] x [0,b]
  std::size_t i = 0;
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    const double sw = std::sqrt(0.5 + p.x()), swi = std::sqrt(1. + p.y() * p.y());
    const Lifted_point expected = {sw * (p.x() - c.x()), sw * (p.y() - c.y()), 0., 0., 0., swi};
    for(int k = 0; k < 6; ++k)
      EXPECT_NEAR(X[i][k], expected[k], 1e-14) << "vertex " << i << " coordinate " << k;
    ++i;
  }
}

// Varying weights: lifted edge lengths do not depend on where the model sits in space, and a weight
// map holding one value gives the lengths of that constant weight.
TYPED_TEST(Foundation, PerVertexWeightsTranslationInvariantAndConsistent)
{
  TypeParam m, moved;
  build_sphere(m, 1, 1.);
  build_sphere(moved, 1, 1.);
  for(auto v : vertices(moved))
    put(CGAL::vertex_point, moved, v, get(CGAL::vertex_point, moved, v) + Vector(100., -50., 7.));
  auto weight_of = [](const TypeParam& mesh) {
    auto w = get(CGAL::dynamic_vertex_property_t<double>(), mesh);
    int i = 0;
    for(auto v : vertices(mesh))
      put(w, v, 0.2 + 0.1 * (i++ % 5));
    return w;
  };
  auto w = weight_of(m), w_moved = weight_of(moved);
  auto X = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  auto X_moved = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), moved);
  IM::compute_lifted_embedding(m, X, IM::parameters::euclidean_weight(w).isophotic_weight(0.5).weight_length_scale(1));
  IM::compute_lifted_embedding(moved, X_moved, IM::parameters::euclidean_weight(w_moved).isophotic_weight(0.5).weight_length_scale(1));
  std::vector<double> lengths, lengths_moved;
  for(auto e : edges(m))
    lengths.push_back(IM::edge_isophotic_length(e, m, X));
  for(auto e : edges(moved))
    lengths_moved.push_back(IM::edge_isophotic_length(e, moved, X_moved));
  ASSERT_EQ(lengths.size(), lengths_moved.size());
  for(std::size_t i = 0; i < lengths.size(); ++i)
    EXPECT_NEAR(lengths[i], lengths_moved[i], 1e-12 * lengths[i]);

  auto same = get(CGAL::dynamic_vertex_property_t<float>(), m);
  for(auto v : vertices(m))
    put(same, v, 0.25f);
  auto Y = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  IM::compute_lifted_embedding(m, Y, IM::parameters::euclidean_weight(same).isophotic_weight(0.5).weight_length_scale(1));
  for(auto e : edges(m))
  {
    const Point p = get(CGAL::vertex_point, m, source(e, m)), q = get(CGAL::vertex_point, m, target(e, m));
    const Lifted_point yp = get(Y, source(e, m)), yq = get(Y, target(e, m));
    double dn2 = 0.;
    for(int k = 3; k < 6; ++k)
      dn2 += (yp[k] - yq[k]) * (yp[k] - yq[k]);
    // positional part: sqrt(0.25) |p - q| exactly as with a constant weight
    EXPECT_NEAR(IM::edge_isophotic_length(e, m, Y), std::sqrt(0.25 * CGAL::to_double(CGAL::squared_distance(p, q)) + dn2),
                1e-14);
  }
}

// weight_length_scale: scaling a model by s and L by s scales the lift by s; so does the default L
// (the bounding-box diagonal); with L = 1 (the paper's raw weights) it does not.
TYPED_TEST(Foundation, WeightLengthScaleMakesWeightsScaleFree)
{
  TypeParam m, scaled;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/fandisk.off"), m));
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/fandisk.off"), scaled));
  const double s = 7.5;
  for(auto v : vertices(scaled))
    put(CGAL::vertex_point, scaled, v, CGAL::ORIGIN + s * (get(CGAL::vertex_point, scaled, v) - CGAL::ORIGIN));

  const double L = IM::suggested_weight_length_scale(m);
  const double L_scaled = IM::suggested_weight_length_scale(scaled);
  EXPECT_NEAR(L_scaled, s * L, 1e-12 * L_scaled);

  const auto X = lift(m, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8).weight_length_scale(L));
  const auto Xs = lift(scaled, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8).weight_length_scale(L_scaled));
  ASSERT_EQ(X.size(), Xs.size());
  for(std::size_t i = 0; i < X.size(); ++i)
    for(int k = 0; k < 6; ++k)
      EXPECT_NEAR(Xs[i][k], s * X[i][k], 1e-9 * s * L);

  // The default is L = the bounding-box diagonal: the same lifts.
  auto default_lift = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), scaled);
  IM::compute_lifted_embedding(scaled, default_lift, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8));
  std::size_t i = 0;
  for(auto v : vertices(scaled))
  {
    for(int k = 0; k < 6; ++k)
      EXPECT_EQ(get(default_lift, v)[k], Xs[i][k]);
    ++i;
  }

  // With L = 1 the normal part does not scale: the two lifts are not similar.
  const auto Y = lift(m, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8).weight_length_scale(1));
  const auto Ys = lift(scaled, IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8).weight_length_scale(1));
  double worst = 0.;
  for(std::size_t i = 0; i < Y.size(); ++i)
    for(int k = 3; k < 6; ++k)
      worst = (std::max)(worst, std::abs(Ys[i][k] - s * Y[i][k]));
  EXPECT_GT(worst, 1.);
}

TYPED_TEST(Foundation, SuggestedWeightLengthScaleIsBoxDiagonal)
{
  TypeParam m;
  build_grid(m, 3, 3., 4.);
  EXPECT_NEAR(IM::suggested_weight_length_scale(m), 5., 1e-14);
  TypeParam empty;
  EXPECT_EQ(IM::suggested_weight_length_scale(empty), 0.);
}

// ---------------------------------------------------------------------------------------------
// Basic measures.

// On a sphere with exact normals the lift is k p with k = sqrt(w + w' L^2 / R^2): any segment of a face
// has isophotic length k times its Euclidean length.
TYPED_TEST(Foundation, EdgeAndPolylineLengthsOnSphere)
{
  TypeParam m;
  const double R = 2., w = 0.4, wi = 0.9, L = 3.;
  const double k = std::sqrt(w + wi * L * L / (R * R));
  build_sphere(m, 1, R);
  auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
  for(auto v : vertices(m))
    put(normals, v, 2. * (get(CGAL::vertex_point, m, v) - CGAL::ORIGIN)); // not unit: normalized by the lift
  auto X = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  IM::compute_lifted_embedding(m, X, IM::parameters::vertex_normal_map(normals).euclidean_weight(w)
                                       .isophotic_weight(wi).weight_length_scale(L));
  for(auto e : edges(m))
  {
    const double euclidean = length(get(CGAL::vertex_point, m, source(e, m)) - get(CGAL::vertex_point, m, target(e, m)));
    EXPECT_NEAR(IM::edge_isophotic_length(e, m, X), k * euclidean, 1e-12);
  }

  // A polyline through two faces sharing an edge: interior point, point on the edge, interior point.
  const auto h = halfedge(*faces(m).begin(), m);
  const auto f = face(h, m), g = face(opposite(h, m), m);
  const auto hg = halfedge(g, m);
  auto corner = [&](const typename boost::graph_traits<TypeParam>::halfedge_descriptor& hh, int i) {
    const auto vi = i == 0 ? source(hh, m) : (i == 1 ? target(hh, m) : target(next(hh, m), m));
    return get(CGAL::vertex_point, m, vi);
  };
  auto position = [&](const PMP::Face_location<TypeParam, double>& loc) {
    const auto hh = halfedge(loc.first, m);
    Vector s = CGAL::NULL_VECTOR;
    for(int i = 0; i < 3; ++i)
      s = s + loc.second[i] * (corner(hh, i) - CGAL::ORIGIN);
    return CGAL::ORIGIN + s;
  };
  // h runs from corner 0 to corner 1 of f; its midpoint has coordinates (1/2, 1/2, 0) in f.
  std::vector<PMP::Face_location<TypeParam, double>> polyline = {
    {f, {{0.2, 0.3, 0.5}}}, {f, {{0.5, 0.5, 0.}}}, {g, {{0.6, 0.1, 0.3}}}, {g, {{0., 0., 1.}}}};
  (void)hg;
  double euclidean = 0.;
  for(std::size_t i = 1; i < polyline.size(); ++i)
    euclidean += length(position(polyline[i]) - position(polyline[i - 1]));
  EXPECT_NEAR(IM::polyline_isophotic_length(polyline, m, X), k * euclidean, 1e-12);

  // The same surface point written in two faces: a zero-length step.
  const auto midpoint_in_g = [&]() -> PMP::Face_location<TypeParam, double> {
    // the edge of h, seen from g, is opposite(h); find its corners in g's order
    const auto og = opposite(h, m);
    std::array<double, 3> bc = {0., 0., 0.};
    const auto hh = halfedge(g, m);
    const std::array<typename boost::graph_traits<TypeParam>::vertex_descriptor, 3> c = {
      source(hh, m), target(hh, m), target(next(hh, m), m)};
    for(int i = 0; i < 3; ++i)
      if(c[i] == source(og, m) || c[i] == target(og, m))
        bc[i] = 0.5;
    return {g, bc};
  }();
  std::vector<PMP::Face_location<TypeParam, double>> step = {{f, {{0.5, 0.5, 0.}}}, midpoint_in_g};
  EXPECT_NEAR(IM::polyline_isophotic_length(step, m, X), 0., 1e-14);

  const Lifted_point at_corner = IM::construct_lifted_point(PMP::Face_location<TypeParam, double>{f, {{0., 1., 0.}}}, m, X);
  const Point p1 = corner(h, 1);
  for(int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(at_corner[i], std::sqrt(w) * p1[i], 1e-14);
    EXPECT_NEAR(at_corner[i + 3], std::sqrt(wi) * L * p1[i] / R, 1e-14);
  }
}

// On a plane the normal part is constant: the isophotic length is sqrt(w) times the Euclidean length.
TYPED_TEST(Foundation, PolylineLengthOnPlaneThroughAVertex)
{
  TypeParam m;
  build_grid(m, 2, 2., 2.);
  const double w = 0.36;
  auto X = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  IM::compute_lifted_embedding(m, X, IM::parameters::euclidean_weight(w).isophotic_weight(5.).weight_length_scale(1));
  // Walk: centre of face 0 -> its corner 2 -> centre of every face around that vertex, crossing at it.
  const auto f0 = *faces(m).begin();
  const auto h0 = halfedge(f0, m);
  const auto apex = target(next(h0, m), m);
  std::vector<PMP::Face_location<TypeParam, double>> polyline = {{f0, {{1. / 3, 1. / 3, 1. / 3}}}, {f0, {{0., 0., 1.}}}};
  double euclidean = 0.;
  Point last = CGAL::centroid(get(CGAL::vertex_point, m, source(h0, m)), get(CGAL::vertex_point, m, target(h0, m)),
                              get(CGAL::vertex_point, m, apex));
  euclidean += length(get(CGAL::vertex_point, m, apex) - last);
  last = get(CGAL::vertex_point, m, apex);
  for(auto f : CGAL::faces_around_target(halfedge(apex, m), m))
  {
    if(f == boost::graph_traits<TypeParam>::null_face())
      continue;
    const auto h = halfedge(f, m);
    std::array<double, 3> at_apex = {source(h, m) == apex ? 1. : 0., target(h, m) == apex ? 1. : 0.,
                                     target(next(h, m), m) == apex ? 1. : 0.};
    polyline.push_back({f, at_apex});                           // the apex again, seen from f
    polyline.push_back({f, {{0.25, 0.25, 0.5}}});               // a point inside f
    polyline.push_back({f, at_apex});                           // back to the apex
    const Point inside = CGAL::ORIGIN + 0.25 * (get(CGAL::vertex_point, m, source(h, m)) - CGAL::ORIGIN) +
                         0.25 * (get(CGAL::vertex_point, m, target(h, m)) - CGAL::ORIGIN) +
                         0.5 * (get(CGAL::vertex_point, m, target(next(h, m), m)) - CGAL::ORIGIN);
    euclidean += 2. * length(inside - last);
  }
  EXPECT_NEAR(IM::polyline_isophotic_length(polyline, m, X), std::sqrt(w) * euclidean, 1e-13);
}

TEST(PurelyIsophoticDistance, GreatCircleAngle)
{
  EXPECT_NEAR(IM::purely_isophotic_distance(Vector(1, 0, 0), Vector(0, 1, 0)), pi / 2, 1e-15);
  EXPECT_NEAR(IM::purely_isophotic_distance(Vector(1, 0, 0), Vector(-2, 0, 0)), pi, 1e-15);
  EXPECT_NEAR(IM::purely_isophotic_distance(Vector(0, 0, 3), Vector(0, 0, 1)), 0., 1e-15);
  EXPECT_NEAR(IM::purely_isophotic_distance(Vector(1, 0, 0), Vector(1, 1, 0)), pi / 4, 1e-15);
  EXPECT_NEAR(IM::purely_isophotic_distance(Vector(1, 0, 0), Vector(1, 1e-9, 0)), 1e-9, 1e-22);
  // The chord used by the lift, |n1 - n2| = 2 sin(theta/2), is shorter than the arc.
  const double theta = IM::purely_isophotic_distance(Vector(1, 0, 0), Vector(0.6, 0.8, 0));
  EXPECT_NEAR(2 * std::sin(theta / 2), std::sqrt(0.4 * 0.4 + 0.8 * 0.8), 1e-15);
  expect_error<IM::Invalid_parameter_error>([] { IM::purely_isophotic_distance(Vector(0, 0, 0), Vector(0, 1, 0)); },
                                            {"first normal"});
  expect_error<IM::Invalid_parameter_error>([] { IM::purely_isophotic_distance(Vector(0, 1, 0), Vector(nan_value, 1, 0)); },
                                            {"second normal"});
}

// ---------------------------------------------------------------------------------------------
// Input validation: every error triggered by a crafted input, of the right type, naming the element.

TYPED_TEST(Foundation, OpenTwoComponentMeshWithIsolatedVertexIsAccepted)
{
  TypeParam m;
  // two separate open patches (a square and a triangle) plus an isolated vertex
  const auto vs = build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                            Point(5, 0, 1), Point(6, 0, 1), Point(5, 1, 2), Point(9, 9, 9)},
                        {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}});
  EXPECT_NO_THROW(IM::validate_triangle_mesh(m));
  const auto X = lift(m, IM::parameters::euclidean_weight(4.).isophotic_weight(1.));
  ASSERT_EQ(X.size(), 8u);
  // the isolated vertex: positional part sqrt(w) p, no normal part
  const Lifted_point expected = {18., 18., 18., 0., 0., 0.};
  for(int k = 0; k < 6; ++k)
    EXPECT_DOUBLE_EQ(X[7][k], expected[k]);
  // the triangle (5,0,1) (6,0,1) (5,1,2): normal (0,-1,1)/sqrt(2)
  for(int i = 4; i < 7; ++i)
  {
    EXPECT_NEAR(X[i][3], 0., 1e-15);
    EXPECT_NEAR(X[i][4], -1. / std::sqrt(2.), 1e-15);
    EXPECT_NEAR(X[i][5], 1. / std::sqrt(2.), 1e-15);
  }
  (void)vs;
}

TYPED_TEST(Foundation, RealOpenMeshIsAccepted)
{
  TypeParam m;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/mech-holes-shark.off"), m));
  EXPECT_NO_THROW(IM::validate_triangle_mesh(m));
  EXPECT_NO_THROW(lift(m));
}

TYPED_TEST(Foundation, NonTriangleFaceIsRejected)
{
  TypeParam m;
  build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0), Point(2, 0, 0), Point(2, 1, 0)},
        {{0, 1, 2}, {1, 4, 5, 2}});
  expect_error<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); }, {"face 1 has 4 vertices", "triangle mesh"});
  expect_error<IM::Invalid_mesh_error>([&] { lift(m); }, {"face 1 has 4 vertices"});
}

TYPED_TEST(Foundation, CorruptedHalfedgeStructureIsRejected)
{
  TypeParam m;
  build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}, {{0, 1, 2}});
  const auto h = halfedge(*faces(m).begin(), m);
  set_next(h, h, m); // next(h) = h: the face cycle is broken
  expect_error<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); }, {"halfedge "});
  expect_error<IM::Invalid_mesh_error>([&] { lift(m); }, {"halfedge "});
}

TYPED_TEST(Foundation, NonManifoldVertexIsRejected)
{
  TypeParam m;
  // a bow tie: two triangles sharing only vertex 0
  build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(-1, 0, 0), Point(-1, -1, 0)},
        {{0, 1, 2}, {0, 3, 4}});
  expect_error<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); }, {"vertex 0 is non-manifold"});
}

TYPED_TEST(Foundation, NonFiniteCoordinateIsRejected)
{
  for(double bad : {nan_value, inf_value, -inf_value})
  {
    TypeParam m;
    build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 1, bad)}, {{0, 1, 2}, {1, 3, 2}});
    expect_error<IM::Invalid_mesh_error>([&] { IM::validate_triangle_mesh(m); }, {"vertex 3 has a non-finite coordinate"});
    expect_error<IM::Invalid_mesh_error>([&] { lift(m); }, {"vertex 3"});
  }
}

TYPED_TEST(Foundation, ZeroLengthEdgeIsRejected)
{
  TypeParam m;
  build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 1, 0)}, {{0, 1, 2}, {1, 3, 2}});
  try
  {
    IM::validate_triangle_mesh(m);
    ADD_FAILURE() << "no exception thrown";
  }
  catch(const IM::Invalid_mesh_error& e)
  {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("edge (2, 3) has zero length") != std::string::npos ||
                what.find("edge (3, 2) has zero length") != std::string::npos) << what;
  }
}

TYPED_TEST(Foundation, BadUserNormalsAreRejected)
{
  const std::vector<std::pair<Vector, std::string>> cases = {
    {Vector(nan_value, 0, 1), "vertex 2 has a non-finite normal"},
    {Vector(0, inf_value, 1), "vertex 2 has a non-finite normal"},
    {Vector(0, 0, 0), "vertex 2 has a zero normal"}};
  for(const auto& [bad, expected] : cases)
  {
    TypeParam m;
    build_grid(m, 1, 1., 1.);
    auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
    int i = 0;
    for(auto v : vertices(m))
      put(normals, v, i++ == 2 ? bad : Vector(0, 0, 1));
    expect_error<IM::Invalid_mesh_error>([&] { lift(m, IM::parameters::vertex_normal_map(normals)); }, {expected});
  }
}

TYPED_TEST(Foundation, DegenerateFacesGiveAZeroNormal)
{
  TypeParam m;
  // a single triangle with collinear corners: edges of non-zero length, no normal anywhere
  build(m, {Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0)}, {{0, 1, 2}});
  EXPECT_NO_THROW(IM::validate_triangle_mesh(m));
  expect_error<IM::Invalid_mesh_error>([&] { lift(m); }, {"vertex 0 has a", "normal"});
}

TYPED_TEST(Foundation, BadWeightsAreRejected)
{
  TypeParam m;
  build_grid(m, 2, 1., 1.);
  using IM::parameters::euclidean_weight;
  using IM::parameters::isophotic_weight;
  using IM::parameters::weight_length_scale;
  using E = IM::Invalid_parameter_error;
  expect_error<E>([&] { lift(m, euclidean_weight(-1.)); }, {"euclidean_weight is -1", "non-negative"});
  expect_error<E>([&] { lift(m, isophotic_weight(nan_value)); }, {"isophotic_weight is nan"});
  expect_error<E>([&] { lift(m, isophotic_weight(inf_value)); }, {"isophotic_weight is inf"});
  expect_error<E>([&] { lift(m, euclidean_weight(0).isophotic_weight(0.f)); }, {"both zero"});
  expect_error<E>([&] { lift(m, weight_length_scale(0.)); }, {"weight_length_scale is 0"});
  expect_error<E>([&] { lift(m, weight_length_scale(-2)); }, {"weight_length_scale is -2"});
  expect_error<E>([&] { lift(m, weight_length_scale(nan_value)); }, {"weight_length_scale is nan"});

  auto w = get(CGAL::dynamic_vertex_property_t<double>(), m);
  auto wi = get(CGAL::dynamic_vertex_property_t<double>(), m);
  auto fill = [&](int bad_vertex, double bad_w, double bad_wi) {
    int i = 0;
    for(auto v : vertices(m))
    {
      put(w, v, i == bad_vertex ? bad_w : 1.);
      put(wi, v, i == bad_vertex ? bad_wi : 1.);
      ++i;
    }
  };
  fill(4, -0.5, 1.);
  expect_error<E>([&] { lift(m, euclidean_weight(w).isophotic_weight(wi)); }, {"euclidean_weight at vertex 4 is -0.5"});
  fill(5, 1., inf_value);
  expect_error<E>([&] { lift(m, euclidean_weight(w).isophotic_weight(wi)); }, {"isophotic_weight at vertex 5 is inf"});
  fill(2, 0., 0.);
  expect_error<E>([&] { lift(m, euclidean_weight(w).isophotic_weight(wi)); }, {"both zero at vertex 2"});
  fill(3, 0., 0.);
  expect_error<E>([&] { lift(m, euclidean_weight(0.).isophotic_weight(wi)); }, {"both zero at vertex 3"});
}

// w = 0 on a plane: every lifted vertex has the same normal part and no positional part.
TYPED_TEST(Foundation, ZeroLengthLiftedEdgeIsRejected)
{
  TypeParam m;
  build_grid(m, 2, 1., 1.);
  expect_error<IM::Invalid_mesh_error>(
    [&] { lift(m, IM::parameters::euclidean_weight(0.).isophotic_weight(1.)); },
    {"edge (", "zero length in the lifted embedding"});
  // w = 0 is fine where the normals vary: a sphere
  TypeParam sphere;
  build_sphere(sphere, 1, 1.);
  EXPECT_NO_THROW(lift(sphere, IM::parameters::euclidean_weight(0.).isophotic_weight(1.)));
}

TYPED_TEST(Foundation, MalformedPolylinesAreRejected)
{
  TypeParam m;
  build_grid(m, 3, 1., 1.);
  auto X = get(CGAL::dynamic_vertex_property_t<Lifted_point>(), m);
  IM::compute_lifted_embedding(m, X);
  const auto first = *faces(m).begin();
  face_of<TypeParam> far_face = first;
  for(auto f : faces(m))
    far_face = f; // the last face of the grid, opposite corner from the first
  typedef PMP::Face_location<TypeParam, double> Loc;
  using E = IM::Invalid_source_error;
  const Loc inside = {first, {{0.2, 0.3, 0.5}}};
  expect_error<E>([&] { IM::polyline_isophotic_length(std::vector<Loc>{inside, {first, {{0.5, 0.6, 0.}}}}, m, X); },
                  {"polyline point 1 has barycentric coordinates"});
  expect_error<E>([&] { IM::polyline_isophotic_length(std::vector<Loc>{inside, {first, {{-0.1, 0.6, 0.5}}}}, m, X); },
                  {"polyline point 1"});
  expect_error<E>([&] { IM::polyline_isophotic_length(std::vector<Loc>{{first, {{nan_value, 0.5, 0.5}}}}, m, X); },
                  {"polyline point 0"});
  expect_error<E>(
    [&] { IM::polyline_isophotic_length(std::vector<Loc>{inside, {boost::graph_traits<TypeParam>::null_face(), {{1., 0., 0.}}}}, m, X); },
    {"polyline point 1 has the null face"});
  expect_error<E>([&] { IM::polyline_isophotic_length(std::vector<Loc>{inside, inside, {far_face, {{0.2, 0.3, 0.5}}}}, m, X); },
                  {"polyline points 1 and 2 do not lie in a common face"});
}

// ---------------------------------------------------------------------------------------------
// Named parameters: ours and CGAL's chain in one expression and reach CGAL's functions unchanged.

TYPED_TEST(Foundation, NamedParametersChainAndForwardToCGAL)
{
  TypeParam m;
  const double a = 3., b = 2.;
  build_grid(m, 3, a, b);
  // A vertex point map that moves the grid z = 0 to the plane y = 0, scaled by 2: (x, y, 0) -> (2x, 0, 2y).
  // Its triangles have normal (1,0,0) x (0,0,1) = (0,-1,0) and total area 4ab.
  auto vpm = get(CGAL::dynamic_vertex_property_t<Point>(), m);
  for(auto v : vertices(m))
  {
    const Point p = get(CGAL::vertex_point, m, v);
    put(vpm, v, Point(2 * p.x(), 0, 2 * p.y()));
  }
  const auto np = IM::parameters::vertex_point_map(vpm).isophotic_weight(0.8).euclidean_weight(0.2);

  EXPECT_NEAR(PMP::area(m, IM::parameters::cgal_np(np)), 4 * a * b, 1e-12);
  EXPECT_NEAR(PMP::area(faces(m), m, np), 4 * a * b, 1e-12);
  auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
  PMP::compute_vertex_normals(m, normals, np);
  for(auto v : vertices(m))
  {
    EXPECT_NEAR(get(normals, v).x(), 0., 1e-15);
    EXPECT_NEAR(get(normals, v).y(), -1., 1e-15);
    EXPECT_NEAR(get(normals, v).z(), 0., 1e-15);
  }
  EXPECT_NEAR(IM::suggested_weight_length_scale(m, np), 2 * std::sqrt(a * a + b * b), 1e-12);

  auto check_lift = [&](const std::vector<Lifted_point>& X) {
    std::size_t i = 0;
    for(auto v : vertices(m))
    {
      const Point p = get(CGAL::vertex_point, m, v);
      const Lifted_point expected = {std::sqrt(0.2) * 2 * p.x(), 0., std::sqrt(0.2) * 2 * p.y(),
                                     0., -std::sqrt(0.8), 0.};
      for(int k = 0; k < 6; ++k)
        EXPECT_NEAR(X[i][k], expected[k], 1e-14) << "vertex " << i << " coordinate " << k;
      ++i;
    }
  };
  check_lift(lift(m, np));
  // The other order: ours first, then CGAL's, plus a CGAL parameter the package does not read.
  check_lift(lift(m, IM::parameters::euclidean_weight(0.2).vertex_point_map(vpm).isophotic_weight(0.8).geom_traits(K())));
  // A plain CGAL pack combined with ours.
  check_lift(lift(m, IM::parameters::combine(CGAL::parameters::vertex_point_map(vpm),
                                             IM::parameters::euclidean_weight(0.2).isophotic_weight(0.8))));
}

} // namespace
