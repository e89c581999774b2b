// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fitting of fundamental surfaces (known parameters of exact samples, closed forms) and segmentation
// of generated CAD parts against their B-rep ground truth (data/cad_parts).
#include "cad_part_scores.h"

#include <CGAL/Isophotic_metric/Segmentation/segment_fundamental_surfaces.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace IM = CGAL::Isophotic_metric;
typedef CGAL::Epick::Point_3 Point;
typedef CGAL::Epick::Vector_3 Vector;

namespace {

// Samples of a surface given in an orthonormal frame (e1, e2, axis) at `origin`: the parametrisation
// returns a point and its unit normal in that frame for (u, v) on a grid of [u0,u1] x [v0,v1].
struct Samples
{
  std::vector<Point> points;
  std::vector<Vector> normals;
  std::vector<double> weights;
};

template <class Surface>
Samples sample(const Point& origin, const Vector& axis, double u0, double u1, double v0, double v1, Surface&& surface,
               bool flip = false)
{
  const Vector a = axis / std::sqrt(axis.squared_length());
  Vector e1 = CGAL::cross_product(a, Vector(0.3, -0.5, 0.8));
  e1 = e1 / std::sqrt(e1.squared_length());
  const Vector e2 = CGAL::cross_product(a, e1);
  Samples s;
  const int n = 30;
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j)
    {
      const double u = u0 + (u1 - u0) * (i + 0.5) / n, v = v0 + (v1 - v0) * (j + 0.5) / n;
      std::array<double, 6> pn = surface(u, v); // x y z along e1 e2 a, then the normal
      s.points.push_back(origin + pn[0] * e1 + pn[1] * e2 + pn[2] * a);
      const Vector normal = pn[3] * e1 + pn[4] * e2 + pn[5] * a;
      s.normals.push_back(flip ? -normal : normal);
      s.weights.push_back(1.0 + 0.5 * ((i + j) % 3)); // uneven weights change nothing for exact samples
    }
  return s;
}

double distance(const Point& a, const Point& b) { return std::sqrt(CGAL::squared_distance(a, b)); }

// |a . b| for unit vectors: 1 when parallel
double parallel(const Vector& a, const Vector& b) { return std::abs(a * b) / std::sqrt(a.squared_length() * b.squared_length()); }

IM::Fundamental_surface fit(IM::Surface_type t, const Samples& s)
{
  return IM::fit_fundamental_surface(t, s.points, s.normals, s.weights);
}

// distance from `p` to the line through `c` along `a`
double distance_to_line(const Point& p, const Point& c, const Vector& a)
{
  const Vector d = p - c;
  return std::sqrt(CGAL::cross_product(d, a).squared_length() / a.squared_length());
}

const Point origin(1.5, -2.0, 0.7);
const Vector tilted(0.2, 0.5, 1.0);

} // namespace

TEST(Fit_fundamental_surface, PlaneCylinderSphereConeTorusFromExactSamples)
{
  // plane through origin with normal `tilted`
  {
    const Samples s = sample(origin, tilted, -3, 3, -2, 2, [](double u, double v) {
      return std::array<double, 6>{{u, v, 0, 0, 0, 1}};
    });
    const IM::Fundamental_surface f = fit(IM::Surface_type::plane, s);
    EXPECT_EQ(f.type, IM::Surface_type::plane);
    EXPECT_NEAR(parallel(f.axis, tilted), 1, 1e-12);
    EXPECT_GT(f.axis * tilted, 0); // oriented like the normals
    EXPECT_NEAR(std::abs((origin - f.center) * f.axis), 0, 1e-12);
    EXPECT_LT(f.residual, 1e-12);
  }
  // cylinder of radius 2.5 around the tilted axis, half of it, outward and inward normals
  for(bool inward : {false, true})
  {
    const double R = 2.5;
    const Samples s = sample(origin, tilted, 0, CGAL_PI, -4, 4, [&](double u, double v) {
      return std::array<double, 6>{{R * std::cos(u), R * std::sin(u), v, std::cos(u), std::sin(u), 0}};
    }, inward);
    const IM::Fundamental_surface f = fit(IM::Surface_type::cylinder, s);
    EXPECT_NEAR(f.radius, R, 1e-9);
    EXPECT_NEAR(parallel(f.axis, tilted), 1, 1e-12);
    EXPECT_NEAR(distance_to_line(origin, f.center, f.axis), 0, 1e-9);
    EXPECT_EQ(f.outward, !inward);
    EXPECT_LT(f.residual, 1e-9);
  }
  // sphere of radius 3, a cap of it
  {
    const double R = 3;
    const Samples s = sample(origin, tilted, 0, 2 * CGAL_PI, 0.2, 1.2, [&](double u, double v) {
      const Vector n(std::sin(v) * std::cos(u), std::sin(v) * std::sin(u), std::cos(v));
      return std::array<double, 6>{{R * n.x(), R * n.y(), R * n.z(), n.x(), n.y(), n.z()}};
    });
    const IM::Fundamental_surface f = fit(IM::Surface_type::sphere, s);
    EXPECT_NEAR(f.radius, R, 1e-9);
    EXPECT_NEAR(distance(f.center, origin), 0, 1e-9);
    EXPECT_TRUE(f.outward);
    EXPECT_LT(f.residual, 1e-9);
  }
  // cone with apex at origin, half angle 0.4, from 1 to 5 along the axis
  {
    const double beta = 0.4;
    const Samples s = sample(origin, tilted, 0, 2 * CGAL_PI, 1, 5, [&](double u, double t) {
      const double rho = t * std::tan(beta);
      return std::array<double, 6>{{rho * std::cos(u), rho * std::sin(u), t, std::cos(beta) * std::cos(u),
                                    std::cos(beta) * std::sin(u), -std::sin(beta)}};
    });
    const IM::Fundamental_surface f = fit(IM::Surface_type::cone, s);
    EXPECT_EQ(f.type, IM::Surface_type::cone);
    EXPECT_NEAR(f.half_angle, beta, 1e-9);
    EXPECT_NEAR(distance(f.center, origin), 0, 1e-8);
    EXPECT_NEAR(f.axis * tilted / std::sqrt(tilted.squared_length()), 1, 1e-12); // from the apex into the cone
    EXPECT_LT(f.residual, 1e-9);
    // a cylinder has no apex: no cone
    const Samples c = sample(origin, tilted, 0, CGAL_PI, -4, 4, [](double u, double v) {
      return std::array<double, 6>{{std::cos(u), std::sin(u), v, std::cos(u), std::sin(u), 0}};
    });
    EXPECT_EQ(fit(IM::Surface_type::cone, c).type, IM::Surface_type::free_form);
  }
  // torus R = 5, r = 1.5: a pipe bend (outer side, normals out of the tube) and a concave blend
  // (normals into the tube)
  for(bool inward : {false, true})
  {
    const double R = 5, r = 1.5;
    const Samples s = sample(origin, tilted, 0, CGAL_PI / 2, -2.5, 2.5, [&](double u, double v) {
      const Vector n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      return std::array<double, 6>{{(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                                    r * std::sin(v), n.x(), n.y(), n.z()}};
    }, inward);
    const IM::Fundamental_surface f = fit(IM::Surface_type::torus, s);
    EXPECT_NEAR(f.radius, R, 1e-9 * R);
    EXPECT_NEAR(f.minor_radius, r, 1e-9 * r);
    EXPECT_NEAR(parallel(f.axis, tilted), 1, 1e-9);
    EXPECT_NEAR(distance(f.center, origin), 0, 1e-9);
    EXPECT_EQ(f.outward, !inward);
    EXPECT_LT(f.residual, 1e-9);
    // distance query: a point 0.3 off the tube, on the spine circle's plane
    const Vector a = tilted / std::sqrt(tilted.squared_length());
    Vector e1 = CGAL::cross_product(a, Vector(0.3, -0.5, 0.8));
    e1 = e1 / std::sqrt(e1.squared_length());
    EXPECT_NEAR(IM::distance_to_surface(f, origin + (R + r + 0.3) * e1), 0.3, 1e-9);
  }
}

TEST(Fit_fundamental_surface, BadInputNamesTheProblem)
{
  const std::vector<Point> p{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  const std::vector<Vector> n{Vector(0, 0, 1), Vector(0, 0, 1)};
  const std::vector<double> w{1, 1, 1};
  EXPECT_THROW(IM::fit_fundamental_surface(IM::Surface_type::plane, p, n, w), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::fit_fundamental_surface(IM::Surface_type::free_form, p, std::vector<Vector>(3, Vector(0, 0, 1)), w),
               IM::Invalid_parameter_error);
  // too few samples: no surface, infinite residual
  const IM::Fundamental_surface f =
    IM::fit_fundamental_surface(IM::Surface_type::sphere, std::vector<Point>(2, Point(0, 0, 0)),
                                std::vector<Vector>(2, Vector(0, 0, 1)), std::vector<double>(2, 1.0));
  EXPECT_EQ(f.type, IM::Surface_type::free_form);
  EXPECT_FALSE(std::isfinite(f.residual));
}

namespace {

struct Segmented
{
  std::vector<long> label;
  std::vector<int> type;
  std::vector<IM::Fundamental_surface_segment> segments;
};

Segmented segment(const cad_parts::Mesh& m)
{
  Segmented r;
  std::vector<std::size_t> id(m.number_of_faces());
  IM::segment_fundamental_surfaces(m, CGAL::make_property_map(id), std::back_inserter(r.segments));
  for(cad_parts::face_descriptor f : m.faces())
  {
    r.label.push_back(long(id[f]));
    r.type.push_back(int(r.segments[id[f]].surface.type));
  }
  return r;
}

// every segment of `type` has radius `radius` within `relative`
void expect_radius(const Segmented& s, IM::Surface_type type, double radius, double relative, std::size_t at_least)
{
  std::size_t n = 0;
  for(const auto& g : s.segments)
    if(g.surface.type == type)
    {
      EXPECT_NEAR(g.surface.radius, radius, relative * radius) << IM::surface_type_name(type) << " of " << g.number_of_faces << " faces, residual " << g.surface.residual;
      ++n;
    }
  EXPECT_GE(n, at_least) << IM::surface_type_name(type);
}

} // namespace

// A box with all edges filleted at r = 4: 6 planes, 12 cylinders, 8 spherical corners, all tangent.
// The metric alone cannot tell the equal-radius cylinders from the spheres; the fit must.
TEST(Segment_fundamental_surfaces, FilletedBoxAgainstItsBrep)
{
  const cad_parts::Part part = cad_parts::load("box_fillet_r4");
  const Segmented s = segment(part.mesh);
  const cad_parts::Scores score = cad_parts::score(part, s.label, s.type);
  EXPECT_GE(score.ari, 0.95);
  EXPECT_GE(score.miou, 0.93);
  EXPECT_GE(score.fillet_iou, 0.85);
  EXPECT_GE(score.correct_type, 0.95);
  EXPECT_GE(score.segment_ratio, 0.85);
  EXPECT_LE(score.segment_ratio, 1.2);
  expect_radius(s, IM::Surface_type::cylinder, 4, 0.05, 10);
  // the corner blends hold about 25 faces each: their radius is less well determined
  expect_radius(s, IM::Surface_type::sphere, 4, 0.08, 6);
  double total = 0;
  for(const auto& g : s.segments)
    total += g.area;
  double mesh_area = 0;
  for(double a : part.area)
    mesh_area += a;
  EXPECT_NEAR(total, mesh_area, 1e-9 * mesh_area);
}

// A pipe elbow: cylinder, torus (bend radius 30, tube 8), cylinder, tangent, and two end discs.
TEST(Segment_fundamental_surfaces, PipeElbowSplitsTheBendFromTheStraightParts)
{
  const cad_parts::Part part = cad_parts::load("pipe_elbow");
  const Segmented s = segment(part.mesh);
  const cad_parts::Scores score = cad_parts::score(part, s.label, s.type);
  EXPECT_GE(score.ari, 0.9);
  EXPECT_GE(score.correct_type, 0.95);
  EXPECT_EQ(s.segments.size(), 5u);
  expect_radius(s, IM::Surface_type::cylinder, 8, 0.03, 2);
  bool torus = false;
  for(const auto& g : s.segments)
    if(g.surface.type == IM::Surface_type::torus)
    {
      EXPECT_NEAR(g.surface.radius, 30, 0.03 * 30);
      EXPECT_NEAR(g.surface.minor_radius, 8, 0.03 * 8);
      EXPECT_TRUE(g.surface.outward);
      torus = true;
    }
  EXPECT_TRUE(torus);
}

// A knob (shaft, head, torus blends) and a chamfered block: planes, cylinders, tori; and noisy copies
// of the knob and of an L-bracket (noise of 0.2 mean edge lengths along the normals), scored against
// the B-rep of the clean part: the target ARI >= 0.85 with noise.
TEST(Segment_fundamental_surfaces, KnobChamferedBlockAndNoisyCopies)
{
  for(const char* name : {"knob", "chamfered_block"})
  {
    const cad_parts::Part part = cad_parts::load(name);
    const Segmented s = segment(part.mesh);
    const cad_parts::Scores score = cad_parts::score(part, s.label, s.type);
    EXPECT_GE(score.ari, 0.95) << name;
    EXPECT_GE(score.miou, 0.95) << name;
    EXPECT_GE(score.correct_type, 0.95) << name;
    EXPECT_EQ(int(s.segments.size()), part.number_of_brep_faces) << name;
  }
  for(const char* name : {"knob", "l_bracket"})
  {
    cad_parts::Part noisy = cad_parts::load(name);
    cad_parts::add_normal_noise(noisy.mesh, 0.2, 1);
    const Segmented s = segment(noisy.mesh);
    const cad_parts::Scores score = cad_parts::score(noisy, s.label, s.type);
    EXPECT_GE(score.ari, 0.85) << name;
    EXPECT_GE(score.miou, 0.85) << name;
    EXPECT_GE(score.correct_type, 0.9) << name;
    EXPECT_LE(score.segment_ratio, 1.4) << name;
  }
}

// A vase: a spline profile revolved (one free-form B-rep face) between two flat ends. Tori, spheres and
// cones each fit a band of it within the tolerances; the bands' fitted curvatures jump at their borders
// where the faces' do not, so they are one free-form segment. (The knob and the pipe elbow above, whose
// tangent surfaces do change curvature at their borders, keep one segment per B-rep face.)
TEST(Segment_fundamental_surfaces, FreeFormVaseIsOneSegment)
{
  const cad_parts::Part part = cad_parts::load("vase");
  const Segmented s = segment(part.mesh);
  const cad_parts::Scores score = cad_parts::score(part, s.label, s.type);
  EXPECT_GE(score.ari, 0.9);
  EXPECT_GE(score.miou, 0.95);
  EXPECT_GE(score.correct_type, 0.95);
}

// The merge step fits its candidate pairs on TBB's threads by default: the same segmentation as on one
// thread.
TEST(Segment_fundamental_surfaces, ParallelAndSequentialAgree)
{
  const cad_parts::Part part = cad_parts::load("box_fillet_r4");
  std::vector<std::size_t> parallel(part.mesh.number_of_faces()), sequential(part.mesh.number_of_faces());
  std::vector<IM::Fundamental_surface_segment> a, b;
  IM::segment_fundamental_surfaces<CGAL::Parallel_if_available_tag>(part.mesh, CGAL::make_property_map(parallel), std::back_inserter(a));
  IM::segment_fundamental_surfaces<CGAL::Sequential_tag>(part.mesh, CGAL::make_property_map(sequential), std::back_inserter(b));
  EXPECT_EQ(parallel, sequential);
  ASSERT_EQ(a.size(), b.size());
  for(std::size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(a[i].surface.type, b[i].surface.type);
}

TEST(Segment_fundamental_surfaces, BadParametersThrow)
{
  const cad_parts::Part part = cad_parts::load("chamfered_block");
  std::vector<std::size_t> id(part.mesh.number_of_faces());
  std::vector<IM::Fundamental_surface_segment> out;
  EXPECT_THROW(IM::segment_fundamental_surfaces(part.mesh, CGAL::make_property_map(id), std::back_inserter(out),
                                                IM::parameters::distance_tolerance(-1.0)),
               IM::Invalid_parameter_error);
  EXPECT_THROW(IM::segment_fundamental_surfaces(part.mesh, CGAL::make_property_map(id), std::back_inserter(out),
                                                IM::parameters::angle_tolerance(std::nan(""))),
               IM::Invalid_parameter_error);
  cad_parts::Mesh empty;
  EXPECT_EQ(IM::segment_fundamental_surfaces(empty, CGAL::make_property_map(id), std::back_inserter(out)), 0u);
}
