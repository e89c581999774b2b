// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests of feature-sensitive morphology: binary morphology of face selections (lattice properties on
// real meshes, closed-form Euclidean distances on a plane, CGAL's own k-ring and shortest paths as
// independent references), neighbourhoods, labels, grey levels and region growing.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>

#include <CGAL/Isophotic_metric.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
namespace IM = CGAL::Isophotic_metric;

const double nan_value = std::numeric_limits<double>::quiet_NaN();

typedef std::set<face_descriptor> Face_set;

Mesh load(const std::string& name)
{
  Mesh m;
  if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/" + name), m))
    throw std::runtime_error("cannot read " + name);
  return m;
}

// A selection with its property map, as the CGAL selection functions use it.
struct Selection
{
  const Mesh* mesh;
  Mesh::Property_map<face_descriptor, bool> map;
  Selection(Mesh& m, const Face_set& faces, const std::string& name) : mesh(&m)
  {
    map = m.add_property_map<face_descriptor, bool>(name, false).first;
    for(face_descriptor f : m.faces())
      map[f] = faces.count(f) > 0;
  }
  Face_set faces() const
  {
    Face_set s;
    for(face_descriptor f : mesh->faces())
      if(map[f])
        s.insert(f);
    return s;
  }
};

// Applies an operation to a copy of `faces` and returns the resulting selection.
template <class Operation>
Face_set apply(Mesh& m, const Face_set& faces, Operation&& op)
{
  static int counter = 0;
  Selection s(m, faces, "f:test_selection_" + std::to_string(counter++));
  op(s);
  Face_set result = s.faces();
  m.remove_property_map(s.map);
  return result;
}

template <class NP>
Face_set dilation(Mesh& m, const Face_set& s, double r, const NP& np)
{
  return apply(m, s, [&](Selection& sel) {
    std::vector<face_descriptor> added;
    IM::dilate_face_selection(s, m, r, sel.map, std::back_inserter(added), np);
    // every face written is new, and written once
    std::set<face_descriptor> unique(added.begin(), added.end());
    EXPECT_EQ(unique.size(), added.size());
    for(face_descriptor f : added)
      EXPECT_EQ(s.count(f), 0u);
  });
}

template <class NP>
Face_set erosion(Mesh& m, const Face_set& s, double r, const NP& np)
{
  return apply(m, s, [&](Selection& sel) {
    std::vector<face_descriptor> removed;
    IM::erode_face_selection(s, m, r, sel.map, std::back_inserter(removed), np);
    for(face_descriptor f : removed)
      EXPECT_EQ(s.count(f), 1u);
  });
}

template <class NP>
Face_set opening(Mesh& m, const Face_set& s, double r, const NP& np)
{
  return apply(m, s, [&](Selection& sel) { IM::open_face_selection(m, r, sel.map, np); });
}

template <class NP>
Face_set closing(Mesh& m, const Face_set& s, double r, const NP& np)
{
  return apply(m, s, [&](Selection& sel) { IM::close_face_selection(m, r, sel.map, np); });
}

Face_set complement(const Mesh& m, const Face_set& s)
{
  Face_set c;
  for(face_descriptor f : m.faces())
    if(!s.count(f))
      c.insert(f);
  return c;
}

bool includes(const Face_set& big, const Face_set& small)
{
  return std::includes(big.begin(), big.end(), small.begin(), small.end());
}

// A seed selection: the faces within k rings of a face (CGAL's own k-ring).
Face_set k_ring(Mesh& m, face_descriptor seed, unsigned k)
{
  return apply(m, Face_set{seed}, [&](Selection& sel) {
    std::vector<face_descriptor> seed_range{seed};
    CGAL::expand_face_selection(seed_range, m, k, sel.map, CGAL::Emptyset_iterator());
  });
}

// An irregular selection: two k-ring blobs and a thin strip, so that opening and closing change it.
Face_set irregular_selection(Mesh& m)
{
  Face_set s = k_ring(m, face_descriptor(100), 6);
  Face_set t = k_ring(m, face_descriptor(5000), 4);
  s.insert(t.begin(), t.end());
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, int(num_faces(m)) - 1);
  for(int i = 0; i < 40; ++i)
    s.insert(face_descriptor(pick(rng)));
  return s;
}

double metric_scale(const Mesh& m) { return IM::suggested_weight_length_scale(m); }

// ---------------------------------------------------------------------------------------------
// Lattice properties on a real CAD mesh, in the isophotic metric.

class Face_selection_morphology : public ::testing::Test
{
protected:
  void SetUp() override
  {
    mesh = load("fandisk.off");
    scale = metric_scale(mesh);
    selection = irregular_selection(mesh);
  }
  auto metric() const
  {
    return IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(scale);
  }
  Mesh mesh;
  double scale = 0;
  Face_set selection;
};

TEST_F(Face_selection_morphology, DilationIsExtensiveAndMonotoneInRadius)
{
  const double r1 = 0.01 * scale, r2 = 0.02 * scale;
  for(double fraction : {0.0, 0.5})
  {
    const Face_set d1 = dilation(mesh, selection, r1, metric().area_fraction(fraction));
    const Face_set d2 = dilation(mesh, selection, r2, metric().area_fraction(fraction));
    EXPECT_TRUE(includes(d1, selection));
    EXPECT_TRUE(includes(d2, d1));
    EXPECT_GT(d1.size(), selection.size());
    EXPECT_GT(d2.size(), d1.size());
    const Face_set e1 = erosion(mesh, selection, r1, metric().area_fraction(fraction));
    const Face_set e2 = erosion(mesh, selection, r2, metric().area_fraction(fraction));
    EXPECT_TRUE(includes(selection, e1));
    EXPECT_TRUE(includes(e1, e2));
    EXPECT_LT(e2.size(), e1.size());
  }
  // a larger area fraction asks more of a face
  const Face_set loose = dilation(mesh, selection, r2, metric().area_fraction(0.2));
  const Face_set strict = dilation(mesh, selection, r2, metric().area_fraction(0.9));
  EXPECT_TRUE(includes(loose, strict));
  EXPECT_LT(strict.size(), loose.size());
}

TEST_F(Face_selection_morphology, ErosionIsTheComplementOfTheDilationOfTheComplement)
{
  // erosion uses only the unselected faces next to the selection as its source, the dilation of the
  // complement the whole complement: two different computations of the same set
  for(double fraction : {0.0, 0.3})
  {
    const double r = 0.015 * scale;
    const Face_set e = erosion(mesh, selection, r, metric().area_fraction(fraction));
    const Face_set d = dilation(mesh, complement(mesh, selection), r, metric().area_fraction(fraction));
    EXPECT_EQ(e, complement(mesh, d)) << "area fraction " << fraction;
  }
}

TEST_F(Face_selection_morphology, DilationsCompose)
{
  // face-wise dilation rounds up to whole faces: delta_s(delta_r(S)) contains delta_{r+s}(S) and lies
  // within delta_{r+s+l}(S), l the longest metric edge of the faces added by delta_r (a face meeting
  // the disc of radius r lies entirely within r + its diameter, which is its longest edge)
  const double r = 0.01 * scale, s = 0.007 * scale;
  IM::Face_band_solver<Mesh> band(mesh, metric());
  const Face_set first = dilation(mesh, selection, r, IM::parameters::face_band_solver(&band));
  const Face_set both = dilation(mesh, first, s, IM::parameters::face_band_solver(&band));
  const Face_set direct = dilation(mesh, selection, r + s, IM::parameters::face_band_solver(&band));
  double longest = 0;
  for(face_descriptor f : first)
    if(!selection.count(f))
      longest = std::max(longest, band.metric_mesh().max_edge_length(band.metric_mesh().face_index(f)));
  const Face_set upper = dilation(mesh, selection, r + s + longest, IM::parameters::face_band_solver(&band));
  EXPECT_TRUE(includes(both, direct));
  EXPECT_TRUE(includes(upper, both));
  // equality does not hold in general: the rounding of delta_r to whole faces adds reach
  EXPECT_GT(both.size(), direct.size());
}

TEST_F(Face_selection_morphology, OpeningAndClosingAreOrderedAndIdempotent)
{
  const double r = 0.012 * scale;
  const Face_set o = opening(mesh, selection, r, metric());
  const Face_set c = closing(mesh, selection, r, metric());
  EXPECT_TRUE(includes(selection, o));
  EXPECT_TRUE(includes(c, selection));
  EXPECT_LT(o.size(), selection.size()); // the isolated faces go
  EXPECT_GT(c.size(), selection.size());
  EXPECT_EQ(opening(mesh, o, r, metric()), o);
  EXPECT_EQ(closing(mesh, c, r, metric()), c);
  // (opening by a larger radius is not always inside the opening by a smaller one here: that needs
  // delta_{2r} = delta_r o delta_r, which the rounding to whole faces breaks)
}

TEST_F(Face_selection_morphology, RadiusZeroIsTheOneRingOfCGAL)
{
  // a closed face meets the selection at distance 0 exactly when it shares a vertex with it:
  // CGAL's expand_face_selection with k = 1 is an independent combinatorial reference
  const Face_set d0 = dilation(mesh, selection, 0.0, metric());
  const Face_set ring = apply(mesh, selection, [&](Selection& sel) {
    IM::dilate_face_selection_k_ring(selection, mesh, 1, sel.map, CGAL::Emptyset_iterator());
  });
  EXPECT_EQ(d0, ring);
  // with a positive area fraction, radius 0 adds nothing
  EXPECT_EQ(dilation(mesh, selection, 0.0, metric().area_fraction(0.1)), selection);
}

TEST_F(Face_selection_morphology, IsophoticDilationStaysOnItsSideOfFeatures)
{
  // the same radius reaches less area across features in the isophotic metric than in the
  // Euclidean one measured with sqrt(w) (on flat parts both agree)
  const double r = 0.05 * scale;
  const Face_set euclidean = dilation(mesh, k_ring(mesh, face_descriptor(100), 2), r,
                                      IM::parameters::euclidean_weight(0.5).isophotic_weight(0));
  const Face_set isophotic = dilation(mesh, k_ring(mesh, face_descriptor(100), 2), r, metric());
  EXPECT_TRUE(includes(euclidean, isophotic)); // the isophotic metric is never shorter
  EXPECT_LT(isophotic.size(), euclidean.size());
}

// ---------------------------------------------------------------------------------------------
// Euclidean growth against independent references.

// Distance from point p to segment ab in the plane.
double point_segment(const std::array<double, 2>& p, const std::array<double, 2>& a, const std::array<double, 2>& b)
{
  const double ux = b[0] - a[0], uy = b[1] - a[1];
  double t = ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / (ux * ux + uy * uy);
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * ux, p[1] - a[1] - t * uy);
}

typedef std::array<std::array<double, 2>, 3> Triangle_2;

bool inside(const std::array<double, 2>& p, const Triangle_2& t)
{
  auto side = [&](int i) {
    const auto& a = t[i];
    const auto& b = t[(i + 1) % 3];
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  };
  const double s0 = side(0), s1 = side(1), s2 = side(2);
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

double point_triangle(const std::array<double, 2>& p, const Triangle_2& t)
{
  if(inside(p, t))
    return 0;
  return std::min({point_segment(p, t[0], t[1]), point_segment(p, t[1], t[2]), point_segment(p, t[2], t[0])});
}

// Distance between two closed triangles of the plane.
double triangle_triangle(const Triangle_2& s, const Triangle_2& t)
{
  double d = std::numeric_limits<double>::infinity();
  for(int i = 0; i < 3; ++i)
    d = std::min({d, point_triangle(s[i], t), point_triangle(t[i], s)});
  return d;
}

// A perturbed planar grid on [0,1]^2 (boundary kept straight, so the domain is convex and geodesic
// distances are Euclidean distances).
Mesh perturbed_grid(int n, unsigned seed)
{
  Mesh m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<vertex_descriptor> v;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      double x = double(i) / n, y = double(j) / n;
      if(i > 0 && i < n) x += jitter(rng) / n;
      if(j > 0 && j < n) y += jitter(rng) / n;
      v.push_back(m.add_vertex(Point(x, y, 0)));
    }
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      const auto a = v[j * (n + 1) + i], b = v[j * (n + 1) + i + 1], c = v[(j + 1) * (n + 1) + i + 1],
                 d = v[(j + 1) * (n + 1) + i];
      if((i + j) % 2) { m.add_face(a, b, c); m.add_face(a, c, d); }
      else            { m.add_face(a, b, d); m.add_face(b, c, d); }
    }
  return m;
}

Triangle_2 triangle_of(const Mesh& m, face_descriptor f)
{
  Triangle_2 t;
  int k = 0;
  for(vertex_descriptor v : CGAL::vertices_around_face(m.halfedge(f), m))
    t[k++] = {m.point(v).x(), m.point(v).y()};
  return t;
}

// A disc and a bar of faces on the plane, and the closed-form distance of every face to them.
Face_set disc_and_bar(const Mesh& m)
{
  Face_set s;
  for(face_descriptor f : m.faces())
  {
    const Triangle_2 t = triangle_of(m, f);
    const double cx = (t[0][0] + t[1][0] + t[2][0]) / 3, cy = (t[0][1] + t[1][1] + t[2][1]) / 3;
    if(std::hypot(cx - 0.45, cy - 0.5) < 0.12 || (std::abs(cx - 0.75) < 0.03 && std::abs(cy - 0.5) < 0.2))
      s.insert(f);
  }
  return s;
}

std::vector<double> exact_distances_to(const Mesh& m, const Face_set& s)
{
  std::vector<double> exact(num_faces(m));
  for(face_descriptor f : m.faces())
  {
    double d = std::numeric_limits<double>::infinity();
    for(face_descriptor g : s)
      d = std::min(d, triangle_triangle(triangle_of(m, f), triangle_of(m, g)));
    exact[f] = d;
  }
  return exact;
}

TEST(Face_selection_morphology_plane, DilationMatchesClosedFormDistances)
{
  Mesh m = perturbed_grid(24, 3);
  const Face_set s = disc_and_bar(m);
  ASSERT_GT(s.size(), 20u);
  // distance of every face to the selection, closed form
  const std::vector<double> exact = exact_distances_to(m, s);
  int checked_near_threshold = 0;
  for(double r : {0.031, 0.0737, 0.152})
    for(int metric = 0; metric < 3; ++metric)
    {
      // Euclidean (w'=0), isophotic on a plane (normals constant: same distances), and w = 4 (twice as long)
      const double w = metric == 2 ? 4.0 : 1.0;
      const Face_set d = metric == 0 ? dilation(m, s, r, IM::parameters::isophotic_weight(0))
                                     : dilation(m, s, r * std::sqrt(w), IM::parameters::euclidean_weight(w).isophotic_weight(1));
      for(face_descriptor f : m.faces())
      {
        if(std::abs(exact[f] - r) < 1e-9)
          continue; // too close to call
        if(std::abs(exact[f] - r) < 0.01) // the minimum is often inside an edge here
          ++checked_near_threshold;
        EXPECT_EQ(d.count(f) > 0, exact[f] <= r) << "face " << f << " at distance " << exact[f] << ", radius " << r;
      }
    }
  EXPECT_GT(checked_near_threshold, 20);
}

// The radius helpers against the closed-form distances: with area_fraction 0 a face joins at its
// distance to the selection, so the radius for n faces is the distance of the n-th nearest face and
// the radius for a share of the area that of the face where the areas, by distance, reach the share.
TEST(Face_selection_morphology_plane, RadiusHelpersMatchClosedFormDistances)
{
  Mesh m = perturbed_grid(24, 3);
  const Face_set s = disc_and_bar(m);
  const std::vector<double> exact = exact_distances_to(m, s);
  std::vector<std::pair<double, face_descriptor>> by_distance;
  double total = 0;
  for(face_descriptor f : m.faces())
  {
    by_distance.emplace_back(exact[f], f);
    total += CGAL::Polygon_mesh_processing::face_area(f, m);
  }
  std::sort(by_distance.begin(), by_distance.end());
  const auto euclidean = IM::parameters::isophotic_weight(0);

  const std::size_t nf = num_faces(m);
  for(std::size_t n : {s.size(), s.size() + 1, s.size() + 90, nf - 7, nf})
    EXPECT_NEAR(IM::radius_for_face_count(s, m, n, euclidean), by_distance[n - 1].first, 1e-9) << n << " faces";

  for(double share : {0.05, 0.3, 0.77, 1.0})
  {
    double area = 0, expected = 0;
    for(const auto& [d, f] : by_distance)
    {
      area += CGAL::Polygon_mesh_processing::face_area(f, m);
      expected = d;
      if(area >= share * total * (1 - 1e-12))
        break;
    }
    const double r = IM::radius_for_area_share(s, m, share, euclidean);
    EXPECT_NEAR(r, expected, 1e-9) << "share " << share;
    // the dilation at that radius covers the share, a little below it does not
    auto area_of = [&](const Face_set& faces) {
      double a = 0;
      for(face_descriptor f : faces)
        a += CGAL::Polygon_mesh_processing::face_area(f, m);
      return a;
    };
    EXPECT_GE(area_of(dilation(m, s, r, euclidean)), share * total * (1 - 1e-12));
    if(r > 1e-6)
    {
      EXPECT_LT(area_of(dilation(m, s, r - 1e-6, euclidean)), share * total);
    }
  }
}

// The default length scale makes the weights mean the same in any units: fandisk in kilometres and
// in micrometres, dilated to the same share of its area in the same isophotic metric, selects the
// same faces. With the paper's raw weights (length scale 1) it does not.
TEST(Face_selection_morphology_real, DilationToAnAreaShareDoesNotDependOnTheUnits)
{
  Mesh m = load("fandisk.off");
  const Face_set seed = k_ring(m, face_descriptor(100), 1);
  auto scaled_copy = [&](double s) {
    Mesh c = m;
    for(vertex_descriptor v : c.vertices())
      c.point(v) = CGAL::ORIGIN + s * (c.point(v) - CGAL::ORIGIN);
    return c;
  };
  Mesh small = scaled_copy(1e-3), large = scaled_copy(1e3);
  auto dilated = [&](Mesh& mesh, const auto& metric) {
    const auto rule = metric.area_fraction(0.5);
    return dilation(mesh, seed, IM::radius_for_area_share(seed, mesh, 0.05, rule), rule);
  };
  const auto scale_free = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5);
  const Face_set d_small = dilated(small, scale_free), d_large = dilated(large, scale_free);
  EXPECT_GT(d_small.size(), 10 * seed.size());
  EXPECT_EQ(d_small, d_large);
  EXPECT_EQ(d_small, dilated(m, scale_free));
  EXPECT_NEAR(IM::radius_for_area_share(seed, large, 0.05, scale_free) / IM::radius_for_area_share(seed, small, 0.05, scale_free),
              1e6, 1e-6 * 1e6);

  const auto raw = scale_free.weight_length_scale(1);
  EXPECT_NE(dilated(small, raw), dilated(large, raw));
}

TEST(Face_selection_morphology_plane, AreaFractionMatchesFineSampling)
{
  Mesh m = perturbed_grid(16, 5);
  Face_set s;
  for(face_descriptor f : m.faces())
  {
    const Triangle_2 t = triangle_of(m, f);
    const double cx = (t[0][0] + t[1][0] + t[2][0]) / 3, cy = (t[0][1] + t[1][1] + t[2][1]) / 3;
    if(std::hypot(cx - 0.5, cy - 0.5) < 0.15)
      s.insert(f);
  }
  const double r = 0.093;
  // covered fraction of every face by fine sampling of the closed-form distance
  auto distance_to_selection = [&](const std::array<double, 2>& p) {
    double d = std::numeric_limits<double>::infinity();
    for(face_descriptor g : s)
      d = std::min(d, point_triangle(p, triangle_of(m, g)));
    return d;
  };
  const int n = 40;
  std::vector<double> fraction(num_faces(m), 0);
  for(face_descriptor f : m.faces())
  {
    if(s.count(f))
      continue;
    const Triangle_2 t = triangle_of(m, f);
    if(std::min({distance_to_selection(t[0]), distance_to_selection(t[1]), distance_to_selection(t[2])}) > r + 0.2)
      continue;
    int in = 0, total = 0;
    for(int j = 0; j < n; ++j)
      for(int i = 0; i + j < n; ++i)
      {
        // centroids of the n^2 congruent sub-triangles
        for(int up = 0; up < (i + j + 1 < n ? 2 : 1); ++up)
        {
          const double a = up ? (i + 2.0 / 3) / n : (i + 1.0 / 3) / n, b = up ? (j + 2.0 / 3) / n : (j + 1.0 / 3) / n;
          const std::array<double, 2> p{(1 - a - b) * t[0][0] + a * t[1][0] + b * t[2][0],
                                        (1 - a - b) * t[0][1] + a * t[1][1] + b * t[2][1]};
          in += distance_to_selection(p) <= r;
          ++total;
        }
      }
    fraction[f] = double(in) / total;
  }
  // Two independent estimates of the same fraction: 1600-point sampling (error ~1/40 of a face
  // width) and the package's resolution-8 linear interpolation. A face must be classified like the
  // reference unless the reference lies within 0.06 of the threshold.
  int decided = 0;
  for(double a : {0.25, 0.5, 0.75})
  {
    const Face_set d = dilation(m, s, r, IM::parameters::isophotic_weight(0).area_fraction(a).area_resolution(8));
    for(face_descriptor f : m.faces())
      if(!s.count(f) && std::abs(fraction[f] - a) > 0.06)
      {
        EXPECT_EQ(d.count(f) > 0, fraction[f] >= a) << "face " << f << " fraction " << fraction[f] << " threshold " << a;
        ++decided;
      }
  }
  EXPECT_GT(decided, 100);
}

TEST(Face_selection_morphology_real, EuclideanDilationAgreesWithCGALShortestPaths)
{
  // CGAL's exact Surface_mesh_shortest_path from the selection's vertices gives, at every vertex,
  // an upper bound d_V of the distance to the selection's faces and d_V - l a lower bound, l the longest
  // edge of the selection (every point of a selected face is within l of one of its vertices).
  Mesh m = load("couplingdown.off");
  const face_descriptor seed(1234);
  const Face_set s = k_ring(m, seed, 2);
  std::set<vertex_descriptor> source_vertices;
  double longest = 0;
  for(face_descriptor f : s)
    for(auto h : CGAL::halfedges_around_face(m.halfedge(f), m))
    {
      source_vertices.insert(m.target(h));
      longest = std::max(longest, std::sqrt(CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)))));
    }
  typedef CGAL::Surface_mesh_shortest_path_traits<K, Mesh> Traits;
  CGAL::Surface_mesh_shortest_path<Traits> shortest_paths(m);
  for(vertex_descriptor v : source_vertices)
    shortest_paths.add_source_point(v);
  const double r = 0.04 * metric_scale(m);
  const Face_set d = dilation(m, s, r, IM::parameters::isophotic_weight(0));
  int inside = 0, outside = 0;
  for(face_descriptor f : m.faces())
  {
    double lowest = std::numeric_limits<double>::infinity();
    double face_longest = 0;
    for(auto h : CGAL::halfedges_around_face(m.halfedge(f), m))
    {
      lowest = std::min(lowest, shortest_paths.shortest_distance_to_source_points(m.target(h)).first);
      face_longest = std::max(face_longest, std::sqrt(CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)))));
    }
    if(lowest <= r) { EXPECT_TRUE(d.count(f)) << "face " << f; ++inside; }
    // a point of f within r would put a vertex of f within r + face_longest of the selection
    if(lowest - longest > r + face_longest) { EXPECT_FALSE(d.count(f)) << "face " << f; ++outside; }
  }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 1000);
}

// ---------------------------------------------------------------------------------------------
// Neighbourhoods, grey levels, labels, region growing.

std::array<double, 2> xy(const Mesh& m, vertex_descriptor v) { return {m.point(v).x(), m.point(v).y()}; }

TEST(Geodesic_neighborhoods, VertexNeighborhoodsOnAPlaneAreEuclideanDiscs)
{
  Mesh m = perturbed_grid(14, 11);
  const double r = 0.17;
  auto all = get(CGAL::dynamic_vertex_property_t<std::vector<IM::Neighborhood_vertex<vertex_descriptor>>>(), m);
  IM::all_vertex_neighborhoods(m, r, all, IM::parameters::isophotic_weight(0));
  std::vector<vertex_descriptor> vs(m.vertices().begin(), m.vertices().end());
  for(std::size_t i = 0; i < vs.size(); ++i)
  {
    std::set<vertex_descriptor> got;
    for(const auto& n : get(all, vs[i]))
    {
      got.insert(n.vertex);
      const auto p = xy(m, vs[i]), q = xy(m, n.vertex);
      EXPECT_NEAR(n.distance, std::hypot(p[0] - q[0], p[1] - q[1]), 1e-12);
    }
    for(std::size_t j = 0; j < vs.size(); ++j)
    {
      const auto p = xy(m, vs[i]), q = xy(m, vs[j]);
      const double d = std::hypot(p[0] - q[0], p[1] - q[1]);
      if(std::abs(d - r) > 1e-9)
      {
        EXPECT_EQ(got.count(vs[j]) > 0, d <= r) << "vertices " << i << " " << j << " at " << d;
      }
    }
  }
  // the single-vertex query agrees with the batch
  std::vector<IM::Neighborhood_vertex<vertex_descriptor>> one;
  IM::geodesic_vertex_neighborhood(vs[20], m, r, std::back_inserter(one), IM::parameters::isophotic_weight(0));
  EXPECT_EQ(one.size(), get(all, vs[20]).size());
}

TEST(Geodesic_neighborhoods, FaceNeighborhoodsAreSymmetricAndSameInParallel)
{
  Mesh m = load("couplingdown.off");
  const double L = metric_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const double r = 0.02 * L;
  typedef std::vector<IM::Neighborhood_face<face_descriptor>> Neighborhood;
  auto serial = get(CGAL::dynamic_face_property_t<Neighborhood>(), m);
  auto parallel = get(CGAL::dynamic_face_property_t<Neighborhood>(), m);
  IM::all_face_neighborhoods<CGAL::Sequential_tag>(m, r, serial, metric.neighborhood_center(IM::Neighborhood_center::FACE));
  IM::all_face_neighborhoods<CGAL::Parallel_if_available_tag>(m, r, parallel, metric);
  auto sorted = [](const Neighborhood& n) {
    std::vector<std::pair<face_descriptor, double>> s;
    for(const auto& g : n)
      s.push_back({g.face, g.min_distance});
    std::sort(s.begin(), s.end());
    return s;
  };
  std::size_t total = 0;
  for(face_descriptor f : faces(m))
  {
    ASSERT_EQ(sorted(get(serial, f)), sorted(get(parallel, f))) << "face " << f;
    total += get(serial, f).size();
  }
  EXPECT_GT(total, 10 * num_faces(m));
  // g in N(f) iff f in N(g): the distance between two closed faces, computed from either side
  std::size_t asymmetric = 0;
  for(face_descriptor f : faces(m))
    for(const auto& g : get(serial, f))
    {
      bool found = false;
      for(const auto& h : get(serial, g.face))
        found = found || h.face == f;
      if(!found)
        ++asymmetric;
    }
  EXPECT_EQ(asymmetric, 0u);
  // a neighbourhood is the dilation of the single face
  const face_descriptor f(777);
  const Face_set d = dilation(m, Face_set{f}, r, metric);
  Face_set n;
  for(const auto& g : get(serial, f))
    n.insert(g.face);
  EXPECT_EQ(n, d);
  std::vector<IM::Neighborhood_face<face_descriptor>> one;
  IM::geodesic_neighborhood(f, m, r, std::back_inserter(one), metric);
  EXPECT_EQ(one.size(), n.size());
}

TEST(Grey_level_morphology, FlatAndNonFlatOnAPlaneMatchBruteForce)
{
  Mesh m = perturbed_grid(12, 17);
  std::vector<vertex_descriptor> vs(m.vertices().begin(), m.vertices().end());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(0, 1);
  auto u_map = m.add_property_map<vertex_descriptor, double>("v:u", 0).first;
  std::vector<double> u;
  for(vertex_descriptor v : vs)
  {
    u_map[v] = std::sin(4 * m.point(v).x()) + 0.3 * noise(rng);
    u.push_back(u_map[v]);
  }
  const double r = 0.21;
  auto b = [](double d) { return -3.0 * d * d; };
  auto result = m.add_property_map<vertex_descriptor, double>("v:result", 0).first;
  IM::dilate_values(m, r, u_map, result, IM::parameters::isophotic_weight(0).structuring_function(b));
  const IM::Grey_level_morphology<Mesh> flat(m, r, IM::Field_location::VERTICES, IM::parameters::isophotic_weight(0));
  const std::vector<double> flat_eroded = flat.erode(u);
  for(std::size_t i = 0; i < vs.size(); ++i)
  {
    double expected_dilation = -1e300, expected_erosion = 1e300;
    bool tie = false;
    for(std::size_t j = 0; j < vs.size(); ++j)
    {
      const auto p = xy(m, vs[i]), q = xy(m, vs[j]);
      const double d = std::hypot(p[0] - q[0], p[1] - q[1]);
      tie = tie || std::abs(d - r) < 1e-9;
      if(d <= r)
      {
        expected_dilation = std::max(expected_dilation, u[j] + b(d));
        expected_erosion = std::min(expected_erosion, u[j]);
      }
    }
    if(tie)
      continue;
    EXPECT_NEAR(result[vs[i]], expected_dilation, 1e-12) << "vertex " << i;
    EXPECT_EQ(flat_eroded[i], expected_erosion) << "vertex " << i;
  }
}

TEST(Grey_level_morphology, OpeningAndClosingOnFacesOfACADPart)
{
  Mesh m = load("couplingdown.off");
  const double L = metric_scale(m);
  const IM::Grey_level_morphology<Mesh> g(m, 0.05 * L, IM::Field_location::FACES,
                                          IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(0, 1);
  std::vector<double> u(num_faces(m));
  for(double& x : u)
    x = noise(rng);
  const auto o = g.open(u), c = g.close(u), d = g.dilate(u), e = g.erode(u);
  std::size_t changed = 0;
  for(std::size_t i = 0; i < u.size(); ++i)
  {
    EXPECT_LE(o[i], u[i]);
    EXPECT_GE(c[i], u[i]);
    EXPECT_GE(d[i], u[i]);
    EXPECT_LE(e[i], u[i]);
    changed += o[i] < u[i];
  }
  EXPECT_GT(changed, u.size() / 10); // not vacuous: many faces see a lower neighbour
  EXPECT_EQ(g.open(o), o);
  EXPECT_EQ(g.close(c), c);
  std::vector<double> bad(u);
  bad[12] = nan_value;
  try
  {
    g.dilate(bad);
    ADD_FAILURE() << "NaN accepted";
  }
  catch(const IM::Invalid_parameter_error& err)
  {
    EXPECT_NE(std::string(err.what()).find("f12"), std::string::npos) << err.what();
  }
}

TEST(Label_morphology, DilationIsTheNearestLabelOnAPlane)
{
  Mesh m = perturbed_grid(20, 23);
  auto labels = m.add_property_map<face_descriptor, int>("f:label", -1).first;
  std::vector<Face_set> classes(3);
  for(face_descriptor f : m.faces())
  {
    const Triangle_2 t = triangle_of(m, f);
    const double cx = (t[0][0] + t[1][0] + t[2][0]) / 3, cy = (t[0][1] + t[1][1] + t[2][1]) / 3;
    int l = -1;
    if(std::hypot(cx - 0.3, cy - 0.3) < 0.1) l = 0;
    if(std::hypot(cx - 0.65, cy - 0.4) < 0.08) l = 1;
    if(cy > 0.8 && cx > 0.2) l = 2;
    labels[f] = l;
    if(l >= 0)
      classes[l].insert(f);
  }
  const double r = 0.2;
  std::map<face_descriptor, int> before;
  for(face_descriptor f : m.faces())
    before[f] = labels[f];
  IM::dilate_face_labels(m, r, labels, -1, IM::parameters::isophotic_weight(0));
  int checked = 0;
  for(face_descriptor f : m.faces())
  {
    if(before[f] >= 0)
    {
      EXPECT_EQ(labels[f], before[f]);
      continue;
    }
    std::array<double, 3> d;
    for(int l = 0; l < 3; ++l)
    {
      d[l] = std::numeric_limits<double>::infinity();
      for(face_descriptor g : classes[l])
        d[l] = std::min(d[l], triangle_triangle(triangle_of(m, f), triangle_of(m, g)));
    }
    const int nearest = int(std::min_element(d.begin(), d.end()) - d.begin());
    std::array<double, 3> sorted = d;
    std::sort(sorted.begin(), sorted.end());
    if(std::abs(sorted[0] - r) < 1e-9 || sorted[1] - sorted[0] < 1e-6)
      continue; // a tie
    EXPECT_EQ(labels[f], sorted[0] <= r ? nearest : -1) << "face " << f;
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

TEST(Label_morphology, OpeningClosingAndErosionKeepAPartition)
{
  Mesh m = load("couplingdown.off");
  const double L = metric_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  auto labels = m.add_property_map<face_descriptor, int>("f:label", -1).first;
  // labels: sharp-edge patches of the part, with noise (random faces unlabelled or relabelled)
  std::vector<std::size_t> patch(num_faces(m));
  {
    auto sharp = m.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
    CGAL::Polygon_mesh_processing::detect_sharp_edges(m, 30, sharp);
    auto p = m.add_property_map<face_descriptor, std::size_t>("f:p", 0).first;
    CGAL::Polygon_mesh_processing::connected_components(m, p, CGAL::parameters::edge_is_constrained_map(sharp));
    for(face_descriptor f : m.faces())
      patch[f] = p[f];
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> coin(0, 1);
  for(face_descriptor f : m.faces())
    labels[f] = coin(rng) < 0.1 ? -1 : coin(rng) < 0.05 ? int(patch[f] + 1) % 5 : int(patch[f]);
  std::vector<int> original;
  for(face_descriptor f : m.faces())
    original.push_back(labels[f]);
  auto restore = [&] { for(face_descriptor f : m.faces()) labels[f] = original[f]; };

  const double r = 0.01 * L;
  EXPECT_GT(IM::erode_face_labels(m, r, labels, -1, metric), 0u);
  for(face_descriptor f : m.faces())
    EXPECT_TRUE(labels[f] == original[f] || labels[f] == -1);
  restore();
  EXPECT_GT(IM::open_face_labels(m, r, labels, -1, metric), 0u);
  for(face_descriptor f : m.faces())
    EXPECT_TRUE(labels[f] == original[f] || labels[f] == -1);
  restore();
  const std::size_t filled = IM::close_face_labels(m, r, labels, -1, metric);
  std::size_t unlabelled_after = 0, unlabelled_before = 0;
  for(face_descriptor f : m.faces())
  {
    if(original[f] != -1)
    {
      EXPECT_EQ(labels[f], original[f]);
    }
    unlabelled_before += original[f] == -1;
    unlabelled_after += labels[f] == -1;
  }
  EXPECT_EQ(unlabelled_before - unlabelled_after, filled);
  EXPECT_GT(filled, unlabelled_before / 2); // isolated holes in a class are closed
  // most filled holes get the label of their sharp-edge patch
  std::size_t right = 0, filled_count = 0;
  for(face_descriptor f : m.faces())
    if(original[f] == -1 && labels[f] != -1)
    {
      ++filled_count;
      right += labels[f] == int(patch[f]);
    }
  EXPECT_GT(right, 0.9 * filled_count);
  restore();
  const std::vector<double> radii{0.02 * L, 0.005 * L};
  EXPECT_GE(IM::series_close_face_labels(m, radii, labels, -1, metric), filled);
}

TEST(Region_growing, GrowthStopsAtSharpEdgesAndVoronoiPartition)
{
  Mesh m = load("fandisk.off");
  const double L = metric_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  std::size_t number_of_patches = 0;
  std::vector<std::size_t> patch(num_faces(m));
  {
    auto sharp = m.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
    CGAL::Polygon_mesh_processing::detect_sharp_edges(m, 30, sharp);
    auto p = m.add_property_map<face_descriptor, std::size_t>("f:p", 0).first;
    number_of_patches = CGAL::Polygon_mesh_processing::connected_components(m, p, CGAL::parameters::edge_is_constrained_map(sharp));
    for(face_descriptor f : m.faces())
      patch[f] = p[f];
  }
  // a region grown in the isophotic metric stays on its sharp-edge patch far more than a Euclidean
  // region of the same area
  const face_descriptor seed(100);
  auto grow = [&](double radius, const auto& np, double& area) {
    std::vector<face_descriptor> region;
    IM::grow_region(std::vector<face_descriptor>{seed}, m, radius, std::back_inserter(region), np);
    double inside = 0;
    area = 0;
    for(face_descriptor f : region)
    {
      const double a = CGAL::Polygon_mesh_processing::face_area(f, m);
      area += a;
      inside += patch[f] == patch[seed] ? a : 0;
    }
    return inside / area;
  };
  double isophotic_area = 0, euclidean_area = 0;
  const double isophotic_share = grow(0.3 * L, metric.area_fraction(0.5), isophotic_area);
  IM::Face_band_solver<Mesh> euclidean(m, IM::parameters::isophotic_weight(0));
  double low = 0, high = L, euclidean_share = 0;
  for(int i = 0; i < 30 && std::abs(euclidean_area - isophotic_area) > 0.02 * isophotic_area; ++i)
  {
    const double mid = 0.5 * (low + high);
    euclidean_share = grow(mid, IM::parameters::face_band_solver(&euclidean).area_fraction(0.5), euclidean_area);
    (euclidean_area < isophotic_area ? low : high) = mid;
  }
  EXPECT_NEAR(euclidean_area, isophotic_area, 0.02 * isophotic_area);
  EXPECT_GT(isophotic_area, 0.02 * CGAL::Polygon_mesh_processing::area(m));
  EXPECT_GT(isophotic_share, 0.8);
  EXPECT_LT(euclidean_share, isophotic_share - 0.2);
  // a predicate stops growth: faces on other patches are refused
  std::vector<face_descriptor> confined;
  const std::function<bool(face_descriptor)> same_patch = [&](face_descriptor f) { return patch[f] == patch[seed]; };
  IM::grow_region(std::vector<face_descriptor>{seed}, m, 0.5 * L, std::back_inserter(confined), metric.face_predicate(same_patch));
  for(face_descriptor f : confined)
    EXPECT_EQ(patch[f], patch[seed]);
  // Voronoi partition: every seed face takes its own index; labels are the nearest seed
  auto label = m.add_property_map<face_descriptor, std::size_t>("f:voronoi", 99).first;
  const std::vector<std::vector<face_descriptor>> seeds{{face_descriptor(100)}, {face_descriptor(5000)}, {face_descriptor(9000)}};
  EXPECT_EQ(IM::partition_by_nearest_seed(seeds, m, label, metric), num_faces(m));
  for(std::size_t i = 0; i < seeds.size(); ++i)
    EXPECT_EQ(label[seeds[i][0]], i);
  auto segment = m.add_property_map<face_descriptor, std::size_t>("f:segment", 0).first;
  const std::size_t patches = IM::segment_by_region_growing(m, 0.3 * L, segment, metric.area_fraction(0.0));
  EXPECT_GE(patches, number_of_patches / 2);
  std::set<std::size_t> used;
  for(face_descriptor f : m.faces())
    used.insert(segment[f]);
  EXPECT_EQ(used.size(), patches);
}

// A plane, a quarter-cylinder fillet of radius 0.3 in `round` segments and a second plane at right
// angles, extruded along y: the known answer of a segmentation is these three pieces. `piece`
// receives 0, 1, 2 by face; `tangent_plane` the plane (0 or 2) whose line with the fillet holds a
// vertex of the face, -1 for a face with no vertex on these two tangent lines.
Mesh plane_fillet_plane(int round, std::vector<int>& piece, std::vector<int>& tangent_plane)
{
  const int flat = 10, along = 20;
  const double rho = 0.3;
  std::vector<std::array<double, 2>> profile; // (x, z)
  for(int i = 0; i <= flat; ++i)
    profile.push_back({-1 + double(i) / flat, 0});
  for(int i = 1; i <= round; ++i)
  {
    const double t = 0.5 * CGAL_PI * i / round;
    profile.push_back({rho * std::sin(t), rho - rho * std::cos(t)});
  }
  for(int i = 1; i <= flat; ++i)
    profile.push_back({rho, rho + double(i) / flat});
  Mesh m;
  std::vector<std::vector<vertex_descriptor>> v(profile.size());
  for(std::size_t i = 0; i < profile.size(); ++i)
    for(int j = 0; j <= along; ++j)
      v[i].push_back(m.add_vertex(Point(profile[i][0], 2.0 * j / along, profile[i][1])));
  piece.clear();
  tangent_plane.clear();
  for(int i = 0; i + 1 < int(profile.size()); ++i)
    for(int j = 0; j < along; ++j)
    {
      const int p = i < flat ? 0 : i < flat + round ? 1 : 2;
      const int line = i + 1 == flat || i == flat ? 0 : i + 1 == flat + round || i == flat + round ? 2 : -1;
      m.add_face(v[i][j], v[i + 1][j], v[i + 1][j + 1]);
      m.add_face(v[i][j], v[i + 1][j + 1], v[i][j + 1]);
      piece.insert(piece.end(), 2, p);
      tangent_plane.insert(tangent_plane.end(), 2, line);
    }
  return m;
}

// The vertex normals on a tangent line average the plane and the fillet, so the lift bends the faces
// with a vertex on the line (one row on either side) by an amount in between: which side they join is
// not determined by the geometry, and they may join either. Every other face must be in the patch of
// its own piece, with one patch per piece: the fillet whole up to its first and last row, and no
// plane face with it beyond the row at the line. On a fine and on a coarse fillet.
TEST(Region_growing, SegmentationFindsPlaneFilletPlane)
{
  for(int round : {12, 4})
  {
    SCOPED_TRACE("fillet in " + std::to_string(round) + " segments");
    std::vector<int> piece;
    std::vector<int> tangent_plane;
    Mesh m = plane_fillet_plane(round, piece, tangent_plane);
    const double L = metric_scale(m);
    const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L).area_fraction(0.0);
    auto segment = m.add_property_map<face_descriptor, std::size_t>("f:segment", 0).first;
    // the greedy cover alone cuts the pieces (its radius bounds every patch)
    EXPECT_GT(IM::segment_by_region_growing(m, 0.1 * L, segment, metric.merge_tolerance(-1)), 6u);
    // with the merge: one patch per piece
    EXPECT_EQ(IM::segment_by_region_growing(m, 0.1 * L, segment, metric), 3u);
    std::map<int, std::set<std::size_t>> patches_of_piece; // faces off the tangent lines only
    std::map<std::size_t, std::set<int>> pieces_of_patch;
    for(face_descriptor f : m.faces())
      if(tangent_plane[f] < 0)
      {
        patches_of_piece[piece[f]].insert(segment[f]);
        pieces_of_patch[segment[f]].insert(piece[f]);
      }
    for(const auto& p : patches_of_piece)
      EXPECT_EQ(p.second.size(), 1u) << "piece " << p.first << " is split";
    ASSERT_EQ(pieces_of_patch.size(), 3u) << "a patch holds two pieces, or only faces at a tangent line";
    // a face at a tangent line joins one of the two pieces that meet there
    for(face_descriptor f : m.faces())
      if(tangent_plane[f] >= 0)
      {
        const std::set<int>& joined = pieces_of_patch[segment[f]];
        EXPECT_TRUE(joined == std::set<int>{1} || joined == std::set<int>{tangent_plane[f]})
          << "face " << f << " at a tangent line joined a piece that does not meet there";
      }
    EXPECT_THROW(IM::segment_by_region_growing(m, 0.1 * L, segment, metric.merge_tolerance(std::nan(""))),
                 IM::Invalid_parameter_error);
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input.

// The `callback` named parameter: told of advancements in [0, 1], the result unchanged while it says
// go on, a Cancelled_error as soon as it says stop (single propagations, parallel and sequential
// loops over faces and vertices, a solver passed in keeping its own callback afterwards).
TEST(Morphology_callback, ReportsAdvancementAndCancels)
{
  Mesh m = load("fandisk.off");
  const double L = metric_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const double r = 0.03 * L;
  std::vector<double> heard;
  const std::function<bool(double)> listen = [&](double a) { heard.push_back(a); return true; };
  const std::function<bool(double)> stop = [](double) { return false; };
  auto check_heard = [&](const char* what) {
    EXPECT_FALSE(heard.empty()) << what;
    for(double a : heard)
      EXPECT_TRUE(a >= 0 && a <= 1) << what << ": " << a;
    heard.clear();
  };

  // one propagation: a dilation of one face to a large radius
  const Face_set seed{face_descriptor(10)};
  const Face_set plain = dilation(m, seed, 0.5 * L, metric);
  const Face_set heard_dilation = dilation(m, seed, 0.5 * L, metric.callback(listen));
  EXPECT_EQ(plain, heard_dilation);
  check_heard("dilation");
  EXPECT_THROW(dilation(m, seed, 0.5 * L, metric.callback(stop)), IM::Cancelled_error);

  // loops over faces (parallel and sequential) and vertices
  typedef std::vector<IM::Neighborhood_face<face_descriptor>> Neighborhood;
  auto n1 = get(CGAL::dynamic_face_property_t<Neighborhood>(), m);
  auto n2 = get(CGAL::dynamic_face_property_t<Neighborhood>(), m);
  IM::all_face_neighborhoods<CGAL::Sequential_tag>(m, r, n1, metric);
  IM::all_face_neighborhoods<CGAL::Parallel_if_available_tag>(m, r, n2, metric.callback(listen));
  for(face_descriptor f : faces(m))
    ASSERT_EQ(get(n1, f).size(), get(n2, f).size()) << "face " << f;
  check_heard("all_face_neighborhoods");
  std::size_t calls = 0;
  const std::function<bool(double)> stop_at_half = [&](double a) { ++calls; return a < 0.5; };
  EXPECT_THROW(IM::all_face_neighborhoods<CGAL::Parallel_if_available_tag>(m, r, n2, metric.callback(stop_at_half)),
               IM::Cancelled_error);
  EXPECT_GT(calls, 100u); // about a thousand reports over the loop, stopped at about half of it
  EXPECT_LT(calls, 1000u);
  auto v = get(CGAL::dynamic_vertex_property_t<std::vector<IM::Neighborhood_vertex<vertex_descriptor>>>(), m);
  EXPECT_THROW(IM::all_vertex_neighborhoods<CGAL::Sequential_tag>(m, r, v, metric.callback(stop)), IM::Cancelled_error);
  EXPECT_THROW(IM::Grey_level_morphology<Mesh>(m, r, IM::Field_location::FACES, metric.callback(stop)), IM::Cancelled_error);
  try
  {
    IM::Grey_level_morphology<Mesh>(m, r, IM::Field_location::VERTICES, metric.callback(stop));
    ADD_FAILURE() << "not cancelled";
  }
  catch(const IM::Cancelled_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("cancelled by its callback"), std::string::npos) << e.what();
  }

  // a solver passed in hears the call's callback during the call only
  IM::Face_band_solver<Mesh> band(m, metric);
  auto selected = m.add_property_map<face_descriptor, bool>("f:callback", false).first;
  put(selected, face_descriptor(10), true);
  std::vector<face_descriptor> added;
  EXPECT_THROW(IM::dilate_face_selection(seed, m, 0.5 * L, selected, std::back_inserter(added),
                                         IM::parameters::face_band_solver(&band).callback(stop)),
               IM::Cancelled_error);
  EXPECT_FALSE(band.progress_callback());
  band.clear_sources();
  added.clear();
  IM::dilate_face_selection(seed, m, 0.5 * L, selected, std::back_inserter(added), IM::parameters::face_band_solver(&band));
  EXPECT_EQ(added.size() + 1, plain.size());
}

TEST(Face_selection_morphology_errors, BadInputNamesTheOffendingItem)
{
  Mesh m = perturbed_grid(4, 1);
  Face_set s{face_descriptor(0)};
  auto expect_message = [](auto&& call, const std::string& type_hint, const std::string& fragment) {
    try
    {
      call();
      ADD_FAILURE() << "no exception, expected one mentioning " << fragment;
    }
    catch(const IM::Error& e)
    {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << type_hint << ": " << e.what();
    }
  };
  auto map = m.add_property_map<face_descriptor, bool>("f:sel", false).first;
  std::vector<face_descriptor> out;
  expect_message([&] { IM::dilate_face_selection(s, m, -1.0, map, std::back_inserter(out)); }, "negative", "radius");
  expect_message([&] { IM::erode_face_selection(s, m, nan_value, map, std::back_inserter(out)); }, "NaN", "radius");
  expect_message([&] { IM::dilate_face_selection(s, m, 0.1, map, std::back_inserter(out), IM::parameters::area_fraction(1.5)); },
                 "fraction", "area_fraction");
  expect_message([&] { IM::open_face_selection(m, 0.1, map, IM::parameters::area_fraction(nan_value)); }, "fraction", "area_fraction");
  expect_message([&] { IM::dilate_face_selection(Face_set{face_descriptor(999)}, m, 0.1, map, std::back_inserter(out)); },
                 "face", "f999");
  EXPECT_THROW(IM::close_face_selection(m, -0.5, map), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::dilate_face_selection(Face_set{face_descriptor(999)}, m, 0.1, map, std::back_inserter(out)),
               IM::Invalid_source_error);

  // radius helpers: a share outside (0, 1], an empty selection, a target beyond the selection's component
  expect_message([&] { IM::radius_for_area_share(s, m, 0., IM::parameters::isophotic_weight(0)); }, "share", "area share is 0");
  expect_message([&] { IM::radius_for_area_share(s, m, 1.5, IM::parameters::isophotic_weight(0)); }, "share", "area share is 1.5");
  expect_message([&] { IM::radius_for_face_count(Face_set{}, m, 3, IM::parameters::isophotic_weight(0)); }, "empty", "empty");
  const std::size_t grid_faces = num_faces(m);
  m.add_face(m.add_vertex(Point(5, 5, 0)), m.add_vertex(Point(6, 5, 0)), m.add_vertex(Point(5, 6, 0)));
  expect_message([&] { IM::radius_for_face_count(s, m, grid_faces + 1, IM::parameters::isophotic_weight(0)); },
                 "unreachable", "no radius dilates the selection to");
  expect_message([&] { IM::radius_for_area_share(s, m, 1., IM::parameters::isophotic_weight(0)); },
                 "unreachable", "100 % of the area");
  EXPECT_GT(IM::radius_for_face_count(s, m, grid_faces, IM::parameters::isophotic_weight(0)), 0.);
}

TEST(Reused_memory, KeptMappingsAreReusedWithinTheirBounds)
{
  // The set-up's and the engine's large arrays come from mappings kept for reuse when freed
  // (internal/Huge_page_chunk.h). A request of a size given back gets that mapping again; what is
  // kept stays within the capacity and within half the most ever in use beyond it (counted here,
  // not by the cache); mappings in use are never handed out twice (each keeps its own contents).
  typedef IM::internal::Page_cache Cache;
  Cache cache;
  const std::size_t page = IM::internal::small_page_bytes, huge = IM::internal::huge_page_bytes;
  void* a = cache.take(16 * page, false, false);
  cache.give_back(a, 16 * page, false, false);
  EXPECT_EQ(cache.kept_bytes(), 16 * page);
  EXPECT_EQ(cache.take(16 * page, false, false), a);
  EXPECT_EQ(cache.kept_bytes(), 0u);
  cache.give_back(a, 16 * page, false, false);
  // beyond the most ever in use, what is kept goes back first (a single run's peak is unchanged);
  // below it, a repeated call keeps up to half that most more
  void* b = cache.take(32 * page, false, false);
  EXPECT_EQ(cache.kept_bytes(), 0u);
  cache.give_back(b, 32 * page, false, false);
  a = cache.take(16 * page, false, false); // most 32 pages: 16 in use + 32 kept within 48
  EXPECT_EQ(cache.kept_bytes(), 32 * page);
  cache.give_back(a, 16 * page, false, false);

  std::mt19937 random(7);
  const std::size_t sizes[] = {16 * page, 64 * page, 250 * page, huge, 3 * huge};
  struct Taken { std::size_t* p; std::size_t size; bool huge; std::size_t tag; };
  std::vector<Taken> taken;
  std::size_t in_use = 0, most = 32 * page, tag = 0, corrupted = 0; // (the most so far: b)
  for(int step = 0; step < 2000; ++step)
  {
    if(taken.empty() || random() % 5 < 3)
    {
      const std::size_t size = sizes[random() % 5];
      const bool is_huge = size >= huge;
      std::size_t* p = static_cast<std::size_t*>(cache.take(size, is_huge, false));
      if(is_huge)
      {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % huge, 0u);
      }
      in_use += size;
      most = (std::max)(most, in_use);
      ++tag;
      std::fill(p, p + size / sizeof(std::size_t), tag);
      taken.push_back({p, size, is_huge, tag});
      ASSERT_LE(in_use + cache.kept_bytes(), most + (std::min)(Cache::capacity, most / 2)) << "step " << step;
    }
    else
    {
      const std::size_t i = random() % taken.size();
      const Taken t = taken[i];
      corrupted += std::count_if(t.p, t.p + t.size / sizeof(std::size_t), [&](std::size_t x) { return x != t.tag; });
      cache.give_back(t.p, t.size, t.huge, false);
      in_use -= t.size;
      taken.erase(taken.begin() + std::ptrdiff_t(i));
    }
    ASSERT_LE(cache.kept_bytes(), Cache::capacity);
  }
  EXPECT_EQ(corrupted, 0u);
  for(const Taken& t : taken)
    cache.give_back(t.p, t.size, t.huge, false);
  // more than the capacity given back: the oldest go
  std::vector<void*> large;
  for(std::size_t k = 0; k < 2 * Cache::capacity / (3 * huge) + 2; ++k)
    large.push_back(cache.take(3 * huge, true, false));
  for(void* p : large)
    cache.give_back(p, 3 * huge, true, false);
  EXPECT_LE(cache.kept_bytes(), Cache::capacity);
  EXPECT_GT(cache.kept_bytes(), Cache::capacity - 3 * huge);
}

TEST(Reused_memory, RepeatedAndConcurrentOneShotCallsGiveTheSameResults)
{
  // One-shot calls reuse the mappings of the previous calls; two threads make one-shot calls and
  // calls on one shared Metric_mesh at the same time. Every result must be bit-identical to the
  // first, serial one (distances from a vertex, bounded; a dilation; a face neighbourhood).
  const Mesh m = load("fandisk.off");
  const double L = metric_scale(m);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const double r = 0.05 * L;
  const vertex_descriptor source[1] = {vertex_descriptor(0)};
  const face_descriptor seed[1] = {face_descriptor(100)};
  struct Results
  {
    std::vector<double> distances;
    std::vector<bool> dilated;
    std::vector<std::pair<face_descriptor, double>> neighborhood;
    bool operator==(const Results& o) const
    {
      return distances == o.distances && dilated == o.dilated && neighborhood == o.neighborhood;
    }
  };
  auto run = [&](const IM::Metric_mesh<Mesh>* prepared) {
    Results out;
    out.distances.assign(num_vertices(m), 0.);
    std::unique_ptr<bool[]> selected(new bool[num_faces(m)]());
    selected[100] = true;
    std::vector<IM::Neighborhood_face<face_descriptor>> n;
    if(prepared != nullptr)
    {
      const auto np = IM::parameters::metric_mesh(*prepared);
      IM::compute_geodesic_distances(source, m, CGAL::make_property_map(out.distances), np.max_distance(2 * r));
      IM::dilate_face_selection(seed, m, r, CGAL::make_property_map(selected.get()), CGAL::Emptyset_iterator(), np);
      IM::geodesic_neighborhood(seed[0], m, r, std::back_inserter(n), np);
    }
    else
    {
      IM::compute_geodesic_distances(source, m, CGAL::make_property_map(out.distances), metric.max_distance(2 * r));
      IM::dilate_face_selection(seed, m, r, CGAL::make_property_map(selected.get()), CGAL::Emptyset_iterator(), metric);
      IM::geodesic_neighborhood(seed[0], m, r, std::back_inserter(n), metric);
    }
    out.dilated.assign(selected.get(), selected.get() + num_faces(m));
    for(const auto& g : n)
      out.neighborhood.push_back({g.face, g.min_distance});
    std::sort(out.neighborhood.begin(), out.neighborhood.end());
    return out;
  };
  const Results first = run(nullptr);
  ASSERT_GT(std::count(first.dilated.begin(), first.dilated.end(), true), 20);
  ASSERT_GT(std::count_if(first.distances.begin(), first.distances.end(), [](double d) { return std::isfinite(d) && d > 0; }), 20);
  ASSERT_EQ(first.neighborhood.size(), std::size_t(std::count(first.dilated.begin(), first.dilated.end(), true)));
  for(int repeat = 0; repeat < 3; ++repeat)
    EXPECT_TRUE(run(nullptr) == first) << "repeat " << repeat;

  const IM::Metric_mesh<Mesh> shared(m, metric);
  EXPECT_TRUE(run(&shared) == first); // (metric_mesh was ignored by compute_geodesic_distances once)
  const Mesh copy = m; // another mesh: its prepared mesh is not this one's
  std::vector<double> d(num_vertices(copy));
  EXPECT_THROW(IM::compute_geodesic_distances(source, copy, CGAL::make_property_map(d), IM::parameters::metric_mesh(shared)),
               IM::Invalid_parameter_error);
  int different[2] = {0, 0};
  auto work = [&](int thread) {
    for(int k = 0; k < 6; ++k)
      different[thread] += !(run((k + thread) % 2 == 0 ? &shared : nullptr) == first);
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  EXPECT_EQ(different[0] + different[1], 0);
}

} // namespace
