// Tests of feature-sensitive morphology: binary morphology of face selections (lattice properties on
// real meshes, closed-form Euclidean distances on a plane, CGAL's own k-ring and shortest paths as
// independent references), neighbourhoods, labels, grey levels and region growing.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>

#include <CGAL/Isophotic_metric.h>
#include <CGAL/Isophotic_metric/face_selection_morphology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <string>
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
      longest = std::max(longest, band.max_edge(band.face_index(f)));
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

TEST(Face_selection_morphology_plane, DilationMatchesClosedFormDistances)
{
  Mesh m = perturbed_grid(24, 3);
  Face_set s;
  for(face_descriptor f : m.faces())
  {
    const Triangle_2 t = triangle_of(m, f);
    const double cx = (t[0][0] + t[1][0] + t[2][0]) / 3, cy = (t[0][1] + t[1][1] + t[2][1]) / 3;
    if(std::hypot(cx - 0.45, cy - 0.5) < 0.12 || (std::abs(cx - 0.75) < 0.03 && std::abs(cy - 0.5) < 0.2))
      s.insert(f);
  }
  ASSERT_GT(s.size(), 20u);
  // distance of every face to the selection, closed form
  std::vector<double> exact(num_faces(m));
  for(face_descriptor f : m.faces())
  {
    double d = std::numeric_limits<double>::infinity();
    for(face_descriptor g : s)
      d = std::min(d, triangle_triangle(triangle_of(m, f), triangle_of(m, g)));
    exact[f] = d;
  }
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
// Bad input.

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
}

} // namespace
