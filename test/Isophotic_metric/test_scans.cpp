// Tests of the package on scans: robust normals (estimate_vertex_normals, normal_smoothing_scale of the
// lift), the noise estimate and the suggested scale, the figure of merit of morphology on noisy CAD
// meshes, and repair_scanned_mesh on damaged copies of real meshes. Expected values come from the
// clean meshes (their normals, their figure of merit), from the noise that was added, and from
// validate_triangle_mesh (whose refusals are tested in test_foundation.cpp).
#include "../../examples/Isophotic_metric/scan_helpers.h"

#include <CGAL/Isophotic_metric/Metric_mesh.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace scan_helpers;

Mesh read_mesh(const std::string& name)
{
  Mesh m;
  if(!CGAL::IO::read_polygon_mesh(CGAL::data_file_path("meshes/" + name), m) || is_empty(m))
    ADD_FAILURE() << "cannot read " << name;
  return m;
}

typedef decltype(get(CGAL::dynamic_vertex_property_t<Vector>(), std::declval<Mesh&>())) Normal_map;

// Mean angle in degrees between the normals and the clean mesh's normals (PMP::compute_vertex_normals),
// over the vertices that do not lie on an edge bending by more than 30 degrees.
double mean_angle_to_clean(const Mesh& clean, const Normal_map& normals)
{
  auto truth = get(CGAL::dynamic_vertex_property_t<Vector>(), clean);
  PMP::compute_vertex_normals(clean, truth);
  std::vector<char> on_sharp_edge(clean.number_of_vertices(), 0);
  for(auto e : edges(clean))
  {
    const auto h = halfedge(e, clean);
    if(!is_border_edge(h, clean) &&
       PMP::compute_face_normal(face(h, clean), clean) * PMP::compute_face_normal(face(opposite(h, clean), clean), clean) <
         std::cos(30 * CGAL_PI / 180))
      on_sharp_edge[source(h, clean)] = on_sharp_edge[target(h, clean)] = 1;
  }
  double sum = 0, count = 0;
  for(vertex_descriptor v : vertices(clean))
    if(!on_sharp_edge[v])
    {
      sum += std::acos(std::clamp(get(truth, v) * get(normals, v), -1., 1.)) * 180 / CGAL_PI;
      count += 1;
    }
  return sum / count;
}

// Raw normals (scale 0) or robust normals at `scale` with the Gaussian guidance for all faces and the
// range 0.3 (the filter these bounds were set for; the default, the guidance chosen per face, errs by
// 4.5 degrees on fandisk at noise 0.35 by this measure, and is tested by the figure of merit below).
Normal_map normals_of(const Mesh& m, double scale)
{
  Normal_map normals = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
  if(scale > 0)
    IM::estimate_vertex_normals(m, scale, normals, IM::parameters::normal_range(0.3).use_patch_guidance(false));
  else
    PMP::compute_vertex_normals(m, normals);
  return normals;
}

// ---- Robust normals -------------------------------------------------------------------------------

// Without smoothing asked for, the lift is today's, bit for bit.
TEST(Scan_normals, ScaleZeroKeepsTheExactLift)
{
  const Mesh m = read_mesh("fandisk.off");
  const double L = IM::suggested_weight_length_scale(m);
  auto plain = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  auto zero = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  IM::compute_lifted_embedding(m, plain, IM::parameters::weight_length_scale(L));
  IM::compute_lifted_embedding(m, zero, IM::parameters::weight_length_scale(L).normal_smoothing_scale(0));
  for(vertex_descriptor v : vertices(m))
    ASSERT_EQ(get(plain, v), get(zero, v));
}

// On fandisk (sharp edges: normal_range 0.3) with noise along the normal, the robust normals are close
// to the clean mesh's normals,
// far closer than the raw normals of the noisy mesh; on the clean mesh they stay close too (planes
// keep their exact normal, sharp edges stay sharp).
TEST(Scan_normals, RobustNormalsRecoverTheCleanNormals)
{
  const Mesh clean = read_mesh("fandisk.off");
  const double h = mean_edge_length(clean);
  EXPECT_LT(mean_angle_to_clean(clean, normals_of(clean, 2 * h)), 2.);
  for(double level : {0.2, 0.35})
  {
    const Mesh noisy = noisy_copy(clean, level, 1);
    const double raw = mean_angle_to_clean(clean, normals_of(noisy, 0));
    const double robust = mean_angle_to_clean(clean, normals_of(noisy, 2 * h));
    EXPECT_GT(raw, 8.) << "noise " << level;
    EXPECT_LT(robust, 4.) << "noise " << level;
    EXPECT_LT(robust, raw / 4) << "noise " << level;
  }
}

// The noise estimate finds the noise that was added (within 20 %), on a clean CAD mesh (fandisk) and
// on a real scan (bunny00, which has a noise of its own: the two add in quadrature); the suggested
// scale is 0 on the clean CAD mesh and twice the mean edge length on the noisy copies.
TEST(Scan_normals, NoiseEstimateAndSuggestedScale)
{
  const Mesh fandisk = read_mesh("fandisk.off");
  const double h = mean_edge_length(fandisk);
  EXPECT_LT(IM::estimate_mesh_noise(fandisk).noise, 0.02 * h);
  EXPECT_EQ(IM::suggested_normal_smoothing_scale(fandisk), 0.);
  for(double level : {0.1, 0.2, 0.35})
  {
    const Mesh noisy = noisy_copy(fandisk, level, 7);
    const IM::Mesh_noise_estimate estimate = IM::estimate_mesh_noise(noisy);
    EXPECT_NEAR(estimate.noise / h, level, 0.2 * level);
    EXPECT_DOUBLE_EQ(IM::suggested_normal_smoothing_scale(noisy), 2 * estimate.mean_edge_length);
  }
  const Mesh bunny = read_mesh("bunny00.off");
  const double hb = mean_edge_length(bunny), own = IM::estimate_mesh_noise(bunny).noise;
  const double added = 0.35 * hb;
  const double found = IM::estimate_mesh_noise(noisy_copy(bunny, 0.35, 3)).noise;
  EXPECT_NEAR(found, std::sqrt(own * own + added * added), 0.2 * added);
}

// On a real scan with extra noise (bunny00, a smooth shape), the robust normals are closer to the
// normals of the scan without the extra noise than the raw normals are.
TEST(Scan_normals, RealScanNormals)
{
  const Mesh bunny = read_mesh("bunny00.off");
  const Mesh noisy = noisy_copy(bunny, 0.35, 3);
  const double scale = IM::suggested_normal_smoothing_scale(noisy);
  ASSERT_GT(scale, 0.);
  const double raw = mean_angle_to_clean(bunny, normals_of(noisy, 0));
  const double robust = mean_angle_to_clean(bunny, normals_of(noisy, scale));
  EXPECT_LT(robust, raw / 2);
}

// The robust normals on all threads (CGAL::Parallel_tag) are the serial ones bit for bit, for the four
// estimators (the guidance chosen per face, the Gaussian guidance, the patch guidance, the guidance chosen
// per face with two rounds of vertex updates, which move every vertex from its faces in the previous
// positions), on a noisy CAD part
// (l_bracket) and a real CGAL mesh with noise (fandisk): every pass computes each face from the previous
// pass only, and each thread walks the discs with its own buffers. Both the face normals of the filter and
// the vertex normals are compared, every coordinate with ==.
TEST(Scan_normals, ParallelNormalsAreTheSerialOnesBitForBit)
{
#ifndef CGAL_LINKED_WITH_TBB
  GTEST_SKIP() << "no TBB: CGAL::Parallel_tag is not available";
#else
  Part part;
  ASSERT_TRUE(read_part(std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/l_bracket.ply", part));
  const std::vector<std::pair<std::string, Mesh>> meshes = {{"l_bracket", noisy_copy(part.mesh, 0.35, 1)},
                                                            {"fandisk", noisy_copy(read_mesh("fandisk.off"), 0.35, 1)}};
  for(const auto& [name, m] : meshes)
  {
    SCOPED_TRACE(name);
    const double scale = IM::suggested_normal_smoothing_scale(m);
    ASSERT_GT(scale, 0.);
    for(int estimator = 0; estimator < 4; ++estimator) // default, Gaussian, patch, default with vertex updates
    {
      SCOPED_TRACE(estimator);
      std::vector<std::array<double, 3>> faces_serial, faces_parallel;
      Normal_map serial = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
      Normal_map parallel = get(CGAL::dynamic_vertex_property_t<Vector>(), const_cast<Mesh&>(m));
      const auto run = [&](const auto& np) {
        faces_serial = IM::internal::filtered_face_normals<CGAL::Sequential_tag>(m, scale, np, true);
        faces_parallel = IM::internal::filtered_face_normals<CGAL::Parallel_tag>(m, scale, np, true);
        IM::estimate_vertex_normals<CGAL::Sequential_tag>(m, scale, serial, np);
        IM::estimate_vertex_normals<CGAL::Parallel_tag>(m, scale, parallel, np);
      };
      if(estimator == 0)
        run(IM::parameters::default_values());
      else if(estimator == 3)
        run(IM::parameters::number_of_vertex_updates(2));
      else
        run(IM::parameters::use_patch_guidance(estimator == 2));
      ASSERT_EQ(faces_serial.size(), num_faces(m));
      ASSERT_EQ(faces_parallel.size(), num_faces(m));
      std::size_t faces_differing = 0, unit = 0;
      for(std::size_t i = 0; i < faces_serial.size(); ++i)
      {
        faces_differing += faces_serial[i] == faces_parallel[i] ? 0 : 1;
        const auto& n = faces_serial[i];
        unit += std::abs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1) < 1e-12 ? 1 : 0;
      }
      EXPECT_EQ(faces_differing, 0u) << "of " << faces_serial.size() << " faces";
      EXPECT_EQ(unit, faces_serial.size()); // the normals are filtered ones, not left unset
      std::size_t vertices_differing = 0;
      for(vertex_descriptor v : vertices(m))
      {
        const Vector a = get(serial, v), b = get(parallel, v);
        vertices_differing += a.x() == b.x() && a.y() == b.y() && a.z() == b.z() ? 0 : 1;
      }
      EXPECT_EQ(vertices_differing, 0u) << "of " << num_vertices(m) << " vertices";
    }
  }
#endif
}

TEST(Scan_normals, ParametersAreChecked)
{
  const Mesh m = read_mesh("fandisk.off");
  auto normals = get(CGAL::dynamic_vertex_property_t<Vector>(), m);
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), m);
  for(double bad : {0., -1., std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(IM::estimate_vertex_normals(m, bad, normals), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::estimate_vertex_normals(m, 1., normals, IM::parameters::normal_range(0)), IM::Invalid_parameter_error);
  EXPECT_THROW(IM::compute_lifted_embedding(m, lifted, IM::parameters::normal_smoothing_scale(-1.)),
               IM::Invalid_parameter_error);
  // number_of_vertex_updates: an integer from 0 to 10 (each round filters the whole mesh again)
  for(int bad : {-1, 11, 1000})
  {
    EXPECT_THROW(IM::estimate_vertex_normals(m, 1., normals, IM::parameters::number_of_vertex_updates(bad)),
                 IM::Invalid_parameter_error);
    EXPECT_THROW(IM::compute_lifted_embedding(
                   m, lifted, IM::parameters::normal_smoothing_scale(1.).number_of_vertex_updates(bad)),
                 IM::Invalid_parameter_error);
  }
  EXPECT_THROW(IM::estimate_vertex_normals(m, 1., normals, IM::parameters::number_of_vertex_updates(1.5)),
               IM::Invalid_parameter_error);
}

// The discs that every pass of the filter reads (walked at every read, or once and kept):
// around every face, the faces connected to it across edges through faces whose centroids lie within
// the radius, the face itself first and each face once, with the spatial weights area exp(-d^2 / 2 s^2).
// Checked against a flood fill over the mesh's own
// adjacency and CGAL's areas, on a noisy fandisk with a hole (faces at its border have a null neighbour).
TEST(Scan_normals, FaceDiscsAreTheConnectedFacesWithinTheRadius)
{
  Mesh m = noisy_copy(read_mesh("fandisk.off"), 0.35, 1);
  for(int k = 0; k < 5; ++k)
    CGAL::Euler::remove_face(halfedge(face_descriptor(100 + k), m), m);
  m.collect_garbage();
  const double rho = 2 * mean_edge_length(m);
  std::vector<face_descriptor> face_list;
  std::vector<std::array<double, 3>> centroid;
  std::vector<double> area;
  for(face_descriptor f : faces(m))
  {
    const auto h = halfedge(f, m);
    const Point c = CGAL::centroid(m.point(source(h, m)), m.point(target(h, m)), m.point(target(next(h, m), m)));
    face_list.push_back(f);
    centroid.push_back({c.x(), c.y(), c.z()});
    area.push_back(PMP::face_area(f, m));
  }
  const IM::internal::Face_disc_graph graph(m, face_list, centroid, area);
  IM::internal::Face_disc_walker walker(graph);
  const auto squared_distance = [&](std::size_t i, std::size_t j) {
    return CGAL::squared_distance(Point(centroid[i][0], centroid[i][1], centroid[i][2]),
                                  Point(centroid[j][0], centroid[j][1], centroid[j][2]));
  };
  for(const auto& [radius, kept] : {std::make_pair(0.5 * rho, false), std::make_pair(2 * rho, true),
                                    std::make_pair(2 * rho, false), std::make_pair(4 * rho, false)})
  {
    SCOPED_TRACE(radius / rho);
    SCOPED_TRACE(kept);
    const double spatial_scale = radius / 2;
    IM::internal::Face_discs discs(graph, radius, spatial_scale);
    if(kept) // walked on all threads when TBB is linked
      discs.keep<CGAL::Parallel_if_available_tag>();
    std::size_t mismatches = 0, bad_weights = 0, faces_at_border = 0;
    for(std::size_t i = 0; i < face_list.size(); ++i)
    {
      // flood fill from face i through faces within the radius
      std::set<std::size_t> expected{i};
      std::vector<std::size_t> front{i};
      while(!front.empty())
      {
        const face_descriptor f = face_list[front.back()];
        front.pop_back();
        for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
        {
          if(is_border(opposite(h, m), m))
            continue;
          const std::size_t j = std::size_t(face(opposite(h, m), m));
          if(squared_distance(i, j) <= radius * radius && expected.insert(j).second)
            front.push_back(j);
        }
      }
      const std::vector<std::uint32_t> found = discs.faces(walker, i);
      if(found.empty() || found.front() != i || std::set<std::size_t>(found.begin(), found.end()) != expected ||
         found.size() != expected.size())
        ++mismatches;
      const std::vector<double>& weights = discs.spatial_weights(walker);
      for(std::size_t k = 0; k < found.size(); ++k)
      {
        const double truth = area[found[k]] * std::exp(-squared_distance(i, found[k]) / (2 * spatial_scale * spatial_scale));
        if(!(weights.size() == found.size() && std::abs(weights[k] - truth) <= 1e-12 * truth))
          ++bad_weights;
      }
      for(auto h : CGAL::halfedges_around_face(halfedge(face_list[i], m), m))
        faces_at_border += is_border(opposite(h, m), m) ? 1 : 0;
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(bad_weights, 0u);
    EXPECT_GT(faces_at_border, 5u);
  }
}

// The faces of `clean` beside an edge bending by more than 30 degrees, and how many of them have a
// filtered normal (internal::filtered_face_normals on the noisy copy at `level`, suggested scale) more
// than 15 degrees off their clean normal.
template <typename NamedParameters>
std::pair<std::size_t, std::size_t> faces_beside_sharp_edges_off(const Mesh& clean, double level, const NamedParameters& np)
{
  std::vector<char> beside(num_faces(clean), 0);
  for(auto e : edges(clean))
  {
    const auto h = halfedge(e, clean);
    if(is_border_edge(h, clean))
      continue;
    const face_descriptor f = face(h, clean), g = face(opposite(h, clean), clean);
    if(PMP::compute_face_normal(f, clean) * PMP::compute_face_normal(g, clean) < std::cos(30 * CGAL_PI / 180))
      beside[f] = beside[g] = 1;
  }
  const Mesh noisy = noisy_copy(clean, level, 1);
  const std::vector<std::array<double, 3>> filtered =
    IM::internal::filtered_face_normals(noisy, IM::suggested_normal_smoothing_scale(noisy), np, true);
  EXPECT_EQ(filtered.size(), num_faces(clean));
  std::size_t faces_beside = 0, off = 0, i = 0;
  for(face_descriptor f : faces(clean))
  {
    const std::array<double, 3>& n = filtered[i++];
    if(!beside[f])
      continue;
    ++faces_beside;
    const Vector truth = PMP::compute_face_normal(f, clean);
    if(truth * Vector(n[0], n[1], n[2]) < std::cos(15 * CGAL_PI / 180))
      ++off;
  }
  return {faces_beside, off};
}

// With the patch guidance, a face right beside a sharp edge takes the side of the edge its own raw
// normal is clearly closer to, when discs of both sides are nearly as consistent (by the spread alone
// the side was left to the noise). Measured against the clean mesh: at noise 0.2 mean edge, the share
// of the faces beside an edge bending by more than 30 degrees whose filtered normal is more than 15
// degrees off their clean normal (by the spread alone: anchor_dense 446 of 1743, fandisk 133 of 1426,
// l_bracket 106 of 736; with the side taken: 279, 69, 53).
TEST(Scan_normals, PatchGuidanceTakesTheSideOfFacesBesideSharpEdges)
{
  for(const auto& [file, share_bound] :
      {std::make_pair(CGAL::data_file_path("meshes/anchor_dense.off"), 0.2),
       std::make_pair(CGAL::data_file_path("meshes/fandisk.off"), 0.07),
       std::make_pair(std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/l_bracket.ply", 0.1)})
  {
    SCOPED_TRACE(file);
    Part part;
    ASSERT_TRUE(read_part(file, part));
    const auto [faces_beside, off] =
      faces_beside_sharp_edges_off(part.mesh, 0.2, IM::parameters::normal_range(0.3).use_patch_guidance(true));
    ASSERT_GT(faces_beside, 100u);
    EXPECT_LE(double(off), share_bound * double(faces_beside)) << off << " of " << faces_beside;
  }
}

// The default filter (the guidance chosen per face) keeps the faces beside sharp edges on their side as
// the patch guidance does, where the Gaussian guidance for all faces (the default before) rounds the
// edges: on anchor_dense at noise 0.2 and 0.35, the share of the 1743 faces beside an edge bending by
// more than 30 degrees whose filtered normal is more than 15 degrees off their clean normal (default,
// with its round of vertex updates: 242 and 410; without it, number_of_vertex_updates(0): 279 and 548;
// Gaussian guidance: 1453 and 1438; patch guidance with the range 0.3: 279 and 547).
TEST(Scan_normals, DefaultFilterKeepsTheFacesBesideSharpEdges)
{
  Part part;
  ASSERT_TRUE(read_part(CGAL::data_file_path("meshes/anchor_dense.off"), part));
  for(const auto& [level, share_bound] : {std::make_pair(0.2, 0.15), std::make_pair(0.35, 0.25)})
  {
    SCOPED_TRACE(level);
    const auto [faces_beside, off] = faces_beside_sharp_edges_off(part.mesh, level, IM::parameters::default_values());
    ASSERT_GT(faces_beside, 100u);
    EXPECT_LE(double(off), share_bound * double(faces_beside)) << off << " of " << faces_beside;
  }
}

// One step of the vertex update (internal::update_vertices) on a fan of six triangles around a vertex
// raised by h above the plane z = 0 of its ring, every filtered normal (0, 0, 1): each face's centroid
// lies at h / 3, so the centre moves by the mean of h / 3 - h, down to h / 3, and each ring vertex (two
// faces) up to h / 3; nothing moves within the plane. Then a vertex of the edge of two planes, off both:
// it moves towards their line by the mean of its offsets along each plane's normal (each offset to its face's
// centroid), so each of its two offsets shrinks by a third.
TEST(Scan_normals, VertexUpdateMovesVerticesTowardsThePlanesOfTheirFaces)
{
  // the centroids of the faces, which the update is given
  auto centroids = [](const std::vector<std::array<double, 3>>& p, const std::vector<std::array<std::uint32_t, 3>>& faces) {
    std::vector<std::array<double, 3>> c;
    for(const auto& f : faces)
      c.push_back({(p[f[0]][0] + p[f[1]][0] + p[f[2]][0]) / 3, (p[f[0]][1] + p[f[1]][1] + p[f[2]][1]) / 3,
                   (p[f[0]][2] + p[f[1]][2] + p[f[2]][2]) / 3});
    return c;
  };
  const double h = 0.3;
  std::vector<std::array<double, 3>> positions{{0., 0., h}};
  std::vector<std::array<std::uint32_t, 3>> corners;
  for(int i = 0; i < 6; ++i)
  {
    positions.push_back({std::cos(i * CGAL_PI / 3), std::sin(i * CGAL_PI / 3), 0.});
    corners.push_back({0u, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % 6)});
  }
  // the faces of each vertex: the centre all six, ring vertex 1 + i the faces i - 1 and i
  std::vector<std::uint32_t> faces_of{0, 1, 2, 3, 4, 5};
  std::vector<std::size_t> first_face{0, 6};
  for(std::uint32_t i = 0; i < 6; ++i)
  {
    faces_of.push_back((i + 5) % 6);
    faces_of.push_back(i);
    first_face.push_back(faces_of.size());
  }
  const std::vector<std::array<double, 3>> up(6, {0., 0., 1.});
  const std::vector<std::array<double, 3>> before = positions;
  IM::internal::update_vertices<CGAL::Sequential_tag>(positions, centroids(positions, corners), faces_of, first_face, up);
  for(std::size_t v = 0; v < positions.size(); ++v)
  {
    SCOPED_TRACE(v);
    EXPECT_NEAR(positions[v][2], h / 3, 1e-15);
    EXPECT_EQ(positions[v][0], before[v][0]);
    EXPECT_EQ(positions[v][1], before[v][1]);
  }

  // Two faces on the planes x = 0 (normal (1, 0, 0)) and y = 0 (normal (0, 1, 0)), sharing the edge from
  // vertex 0 to vertex 1; vertex 0 lies off both planes by 0.2 and 0.4 (it and vertex 1 count only the
  // faces given here). The first face's centroid has x = (0.2 + 0 + 0) / 3, the second's y = 0.4 / 3.
  std::vector<std::array<double, 3>> edge{{0.2, 0.4, 0.}, {0., 0., 1.}, {0., -1., 0.5}, {-1., 0., 0.5}};
  const std::vector<std::array<std::uint32_t, 3>> two_faces{{0u, 1u, 2u}, {0u, 3u, 1u}};
  const std::vector<std::array<double, 3>> normals{{1., 0., 0.}, {0., 1., 0.}};
  const std::vector<std::uint32_t> of{0, 1, 0, 1, 0, 1};
  const std::vector<std::size_t> first{0, 2, 4, 5, 6};
  IM::internal::update_vertices<CGAL::Sequential_tag>(edge, centroids(edge, two_faces), of, first, normals);
  // x: 0.2 + (0.2 / 3 - 0.2) / 2, y: 0.4 + (0.4 / 3 - 0.4) / 2; z unchanged
  EXPECT_NEAR(edge[0][0], 0.2 * 2 / 3, 1e-15);
  EXPECT_NEAR(edge[0][1], 0.4 * 2 / 3, 1e-15);
  EXPECT_EQ(edge[0][2], 0.);
}

// ---- Figure of merit on noisy CAD parts -----------------------------------------------------------

// The targets of the manual's figure of merit on a generated CAD part with fillets (B-rep faces as the
// ground truth of the planar faces): at noise 0.2 and 0.35 mean edge length, with robust normals, the
// isophotic / Euclidean leakage ratio is within 1.3x of the clean part's and the isophotic radius within
// 1.5x; with the raw normals of the noisy part neither holds.
TEST(Scan_figure_of_merit, RobustNormalsKeepTheCleanFigureOfMerit)
{
  Part part;
  ASSERT_TRUE(read_part(std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/box_fillet_r4.ply", part));
  const double L = IM::suggested_weight_length_scale(part.mesh);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const Figure_of_merit clean = figure_of_merit(part.mesh, part, metric);
  ASSERT_GT(clean.euclidean.beyond, 0.);
  ASSERT_GT(clean.isophotic.beyond, 0.);
  ASSERT_LT(clean.ratio(), 0.5); // the clean part is feature-sensitive to begin with
  for(double level : {0.2, 0.35})
  {
    SCOPED_TRACE(level);
    const Mesh noisy = noisy_copy(part.mesh, level, 1);
    const double scale = IM::suggested_normal_smoothing_scale(noisy);
    const Figure_of_merit raw = figure_of_merit(noisy, part, metric);
    const Figure_of_merit robust =
      figure_of_merit(noisy, part, IM::parameters::combine(metric, IM::parameters::normal_smoothing_scale(scale)));
    EXPECT_LE(robust.ratio(), 1.3 * clean.ratio());
    EXPECT_LE(robust.isophotic.radius, 1.5 * clean.isophotic.radius);
    EXPECT_GT(raw.ratio(), 1.3 * clean.ratio());
    EXPECT_GT(raw.isophotic.radius, 1.5 * clean.isophotic.radius);
  }
}

// A part with the leakage-ratio bounds of a test at noise 0.2 and 0.35 (over the clean part's ratio).
struct Ratio_bounds
{
  std::string file;
  double at_02, at_035;
};

// Calls check(part, noisy copy, metric, clean figure of merit, ratio bound) at noise 0.2 and 0.35, with
// the metric of the manual's figure of merit.
template <typename Check>
void for_each_noisy_copy(const Ratio_bounds& bounds, const Check& check)
{
  SCOPED_TRACE(bounds.file);
  Part part;
  ASSERT_TRUE(read_part(bounds.file, part));
  const double L = IM::suggested_weight_length_scale(part.mesh);
  const auto metric = IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(L);
  const Figure_of_merit clean = figure_of_merit(part.mesh, part, metric);
  ASSERT_GT(clean.euclidean.beyond, 0.);
  for(double level : {0.2, 0.35})
  {
    SCOPED_TRACE(level);
    check(part, noisy_copy(part.mesh, level, 1), metric, clean, level == 0.2 ? bounds.at_02 : bounds.at_035);
  }
}

// On parts with sharp edges (l_bracket, generated with its B-rep faces; CGAL's anchor_dense, whose planar
// faces are bounded by sharp edges only) and on top_fillet, at noise 0.2 and 0.35: robust normals with the
// patch guidance (normal_range 0.3) keep the isophotic radius within 1.5x of the clean part's, and leak
// less than the Gaussian guidance, which rounds the sharp edges (anchor_dense: 2-6x the clean ratio against
// 40-70x; raw normals: 150-270x and a radius 3.7-5.4x). The refinement passes of the patch guidance bring
// top_fillet within the leakage-ratio target (1.3x; 1.8-2.1x without them); the side taken by the faces
// beside a sharp edge brings l_bracket within 1.45x (1.55x at noise 0.35 by the spread alone, 2.2-2.6x
// without the refinement passes) and anchor_dense at noise 0.2 within 2.5x (3.4x by the spread alone);
// anchor_dense at 0.35 stays above the target (see the manual, section "Figure of Merit on Noisy Input").
TEST(Scan_figure_of_merit, PatchGuidanceKeepsSharpEdges)
{
  const double no_bound = std::numeric_limits<double>::infinity();
  for(const Ratio_bounds& bounds : {Ratio_bounds{std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/l_bracket.ply", 1.45, 1.45},
                                    Ratio_bounds{CGAL::data_file_path("meshes/anchor_dense.off"), 2.5, no_bound},
                                    Ratio_bounds{std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/top_fillet.ply", 1.3, 1.3}})
    for_each_noisy_copy(bounds, [](const Part& part, const Mesh& noisy, const auto& metric, const Figure_of_merit& clean,
                                   double ratio_bound) {
      const auto robust = IM::parameters::normal_smoothing_scale(IM::suggested_normal_smoothing_scale(noisy)).normal_range(0.3);
      const Figure_of_merit gaussian =
        figure_of_merit(noisy, part, IM::parameters::combine(metric, robust.use_patch_guidance(false)));
      const Figure_of_merit patch =
        figure_of_merit(noisy, part, IM::parameters::combine(metric, robust.use_patch_guidance(true)));
      EXPECT_LE(patch.isophotic.radius, 1.5 * clean.isophotic.radius);
      EXPECT_LT(patch.ratio(), gaussian.ratio());
      EXPECT_LE(patch.ratio(), ratio_bound * clean.ratio());
    });
}

// One default for fillets and sharp edges: the robust normals with the defaults of
// estimate_vertex_normals() (the guidance chosen per face, one round of vertex updates) keep the isophotic
// radius within 1.5x of the clean part's at noise 0.2 and 0.35, and the leakage ratio within the bounds
// below (the target is 1.3x): on box_fillet_r8, whose fillets the patch guidance flattens (2.0x / 2.8x)
// and the Gaussian guidance keeps but for 1.7x at 0.35; on l_bracket and anchor_dense, whose sharp edges
// the Gaussian guidance for all faces (the default before) rounds (l_bracket 2.3x / 3.7x, anchor_dense 82x
// at 0.2). The round of vertex updates brings l_bracket within the target (1.17x / 1.15x; 1.35x / 1.36x
// without it) and anchor_dense at 0.35 within 4x (3.8x; 6.4x without it, still above the target, see the
// manual, section "Figure of Merit on Noisy Input"; at 0.2 1.9x, 1.8x without it).
TEST(Scan_figure_of_merit, DefaultNormalsKeepFilletsAndSharpEdges)
{
  for(const Ratio_bounds& bounds : {Ratio_bounds{std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/box_fillet_r8.ply", 1.3, 1.3},
                                    Ratio_bounds{std::string(CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR) + "/l_bracket.ply", 1.3, 1.3},
                                    Ratio_bounds{CGAL::data_file_path("meshes/anchor_dense.off"), 2.5, 4.0}})
    for_each_noisy_copy(bounds, [](const Part& part, const Mesh& noisy, const auto& metric, const Figure_of_merit& clean,
                                   double ratio_bound) {
      const Figure_of_merit robust = figure_of_merit(
        noisy, part,
        IM::parameters::combine(metric, IM::parameters::normal_smoothing_scale(IM::suggested_normal_smoothing_scale(noisy))));
      EXPECT_LE(robust.isophotic.radius, 1.5 * clean.isophotic.radius);
      EXPECT_LE(robust.ratio(), ratio_bound * clean.ratio());
    });
}

// ---- Scan defects ---------------------------------------------------------------------------------

// Expects `refuse` to throw Invalid_mesh_error whose message mentions `what` and says what to do: run
// the repair, in C++ or from the command line.
template <typename Refuse>
void expect_refusal_with_repair_hint(const Refuse& refuse, const std::string& what)
{
  try
  {
    refuse();
    ADD_FAILURE() << "no refusal, expected: " << what;
  }
  catch(const IM::Invalid_mesh_error& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_NE(message.find("run CGAL::Isophotic_metric::repair_scanned_mesh() on the mesh first"), std::string::npos) << message;
    EXPECT_NE(message.find("isophotic --repair"), std::string::npos) << message;
  }
}

// The same for the first refusal of validate_triangle_mesh.
void expect_refusal(const Mesh& m, const std::string& what)
{
  expect_refusal_with_repair_hint([&] { IM::validate_triangle_mesh(m); }, what);
}

// The first vertex from the fraction `where` of the vertex indices on whose one-ring no vertex is on
// the border (each defect of the test at its own place).
vertex_descriptor interior_vertex(const Mesh& m, double where)
{
  const std::size_t end = m.number_of_vertices() + m.number_of_removed_vertices();
  for(std::size_t i = static_cast<std::size_t>(where * double(end)); i < end; ++i)
  {
    const vertex_descriptor v(static_cast<Mesh::size_type>(i));
    if(m.is_removed(v) || halfedge(v, m) == Mesh::null_halfedge())
      continue;
    bool deep = !is_border(v, m);
    for(vertex_descriptor w : CGAL::vertices_around_target(halfedge(v, m), m))
      deep = deep && !is_border(w, m);
    if(deep)
      return v;
  }
  return Mesh::null_vertex();
}

// A copy of a real mesh with the defects of a scan, each at its own place; the repair must make it
// valid, and leave the rest of the mesh alone.
TEST(Scan_repair, DamagedCopiesOfRealMeshesAreRepaired)
{
  for(const std::string name : {"bunny00.off", "elephant.off"})
  {
    SCOPED_TRACE(name);
    Mesh m = read_mesh(name);
    Mesh reference = m; // the undamaged mesh, repaired: a scan's own holes are filled too
    IM::repair_scanned_mesh(reference);
    const std::size_t original_faces = num_faces(reference);
    const double h = mean_edge_length(m);

    // zero-length edge: a vertex moved onto a neighbour
    Mesh zero_edge = m;
    const vertex_descriptor a = interior_vertex(zero_edge, 0.1);
    ASSERT_NE(a, Mesh::null_vertex());
    zero_edge.point(a) = zero_edge.point(source(halfedge(a, zero_edge), zero_edge));
    expect_refusal(zero_edge, "zero length");

    // hole: the faces around a vertex removed; non-manifold vertex: two faces of the fan of another
    // vertex removed, which leaves it the only link between two fans
    Mesh pinched = m;
    const vertex_descriptor c = interior_vertex(pinched, 0.3);
    ASSERT_NE(c, Mesh::null_vertex());
    CGAL::Euler::make_hole(CGAL::Euler::remove_center_vertex(halfedge(c, pinched), pinched), pinched);
    const vertex_descriptor p = interior_vertex(pinched, 0.5);
    ASSERT_NE(p, Mesh::null_vertex());
    const auto hp = halfedge(p, pinched);
    const face_descriptor second = face(opposite(next(opposite(next(hp, pinched), pinched), pinched), pinched), pinched);
    CGAL::Euler::remove_face(hp, pinched);
    CGAL::Euler::remove_face(halfedge(second, pinched), pinched);
    std::vector<Mesh::Halfedge_index> pinches;
    PMP::non_manifold_vertices(pinched, std::back_inserter(pinches));
    EXPECT_EQ(pinches.size(), 1u);
    expect_refusal(pinched, "non-manifold");

    // all defects in one mesh: those two, a zero-area face, a triangle cut loose with duplicated
    // vertices (coincident border edges), debris (small components) and isolated vertices
    Mesh scan = pinched;
    const vertex_descriptor a2 = interior_vertex(scan, 0.1);
    ASSERT_NE(a2, Mesh::null_vertex());
    scan.point(a2) = scan.point(source(halfedge(a2, scan), scan));
    const vertex_descriptor d = interior_vertex(scan, 0.7);
    ASSERT_NE(d, Mesh::null_vertex());
    const auto hd = halfedge(d, scan);
    scan.point(d) = CGAL::midpoint(scan.point(source(hd, scan)), scan.point(target(next(opposite(hd, scan), scan), scan)));
    const vertex_descriptor e = interior_vertex(scan, 0.9);
    ASSERT_NE(e, Mesh::null_vertex());
    const face_descriptor loose = face(halfedge(e, scan), scan);
    std::vector<Point> corners;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(loose, scan), scan))
      corners.push_back(scan.point(v));
    CGAL::Euler::remove_face(halfedge(loose, scan), scan);
    scan.add_face(scan.add_vertex(corners[0]), scan.add_vertex(corners[1]), scan.add_vertex(corners[2]));
    for(int i = 0; i < 5; ++i)
    {
      const Point far(1e3 * h + 3 * i * h, 0, 0);
      scan.add_face(scan.add_vertex(far), scan.add_vertex(far + Vector(h, 0, 0)), scan.add_vertex(far + Vector(0, h, 0)));
      scan.add_vertex(far + Vector(0, 0, h));
    }
    EXPECT_THROW(IM::validate_triangle_mesh(scan), IM::Invalid_mesh_error);

    const IM::Scan_repair_report report = IM::repair_scanned_mesh(scan);
    EXPECT_TRUE(report.valid) << report;
    EXPECT_NO_THROW(IM::validate_triangle_mesh(scan));
    pinches.clear();
    PMP::non_manifold_vertices(scan, std::back_inserter(pinches));
    EXPECT_TRUE(pinches.empty());
    EXPECT_EQ(report.border_edges_stitched, 3u) << report;
    EXPECT_GE(report.degenerate_faces_removed, 2u) << report; // the faces of the zero-length edge
    EXPECT_GE(report.needles_and_caps_removed, 1u) << report; // the flattened face, a cap
    EXPECT_GE(report.non_manifold_vertices_split, 1u) << report;
    EXPECT_GE(report.components_removed, 5u) << report; // the five debris
    EXPECT_GE(report.holes_filled, 1u) << report;
    EXPECT_GE(report.isolated_vertices_removed, 5u) << report;
    // the rest is the original mesh: the same number of faces up to the few that were repaired
    EXPECT_NEAR(double(num_faces(scan)), double(original_faces), 20.) << report;
    // and the package runs on it: a Euclidean geodesic distance field, finite on the main component
    auto distance = get(CGAL::dynamic_vertex_property_t<double>(), scan);
    IM::compute_geodesic_distances(std::vector<vertex_descriptor>{*vertices(scan).begin()}, scan, distance,
                                   IM::parameters::isophotic_weight(0));
    std::size_t finite = 0;
    for(vertex_descriptor v : vertices(scan))
      finite += std::isfinite(get(distance, v)) ? 1 : 0;
    EXPECT_GT(double(finite), 0.95 * double(num_vertices(scan)));
  }
}

// The other refusals a scan triggers say what to do too: a polygon (validation and the intrinsic mesh of
// the solvers), a vertex whose faces all have zero area (the lift: its normal is zero), and a zero-length
// edge given to the solvers' intrinsic mesh (e.g. lengths measured on a scan).
TEST(Scan_repair, EveryRefusalOfAScanDefectNamesTheRepair)
{
  Mesh quad;
  quad.add_face(quad.add_vertex(Point(0, 0, 0)), quad.add_vertex(Point(1, 0, 0)), quad.add_vertex(Point(1, 1, 0)),
                quad.add_vertex(Point(0, 1, 0)));
  expect_refusal(quad, "has 4 vertices; a triangle mesh is required");
  const Mesh quad_copy = quad;
  auto quad_lengths = get(CGAL::dynamic_halfedge_property_t<double>(), quad_copy);
  for(auto h : halfedges(quad_copy))
    put(quad_lengths, h, 1.);
  expect_refusal_with_repair_hint([&] { IM::Metric_mesh<Mesh>(quad_copy, IM::parameters::edge_length_map(quad_lengths)); },
                                  "a triangle mesh is required");

  // a 6 x 6 grid with a flat triangle (three distinct points on a line) on a border edge: validation
  // accepts it, the lift finds no normal at the triangle's own vertex
  Mesh flat;
  std::vector<vertex_descriptor> grid;
  for(int j = 0; j <= 6; ++j)
    for(int i = 0; i <= 6; ++i)
      grid.push_back(flat.add_vertex(Point(i, j, 0)));
  for(int j = 0; j < 6; ++j)
    for(int i = 0; i < 6; ++i)
    {
      const int a = 7 * j + i;
      flat.add_face(grid[a], grid[a + 1], grid[a + 8]);
      flat.add_face(grid[a], grid[a + 8], grid[a + 7]);
    }
  ASSERT_NE(flat.add_face(grid[6], grid[5], flat.add_vertex(Point(7, 0, 0))), Mesh::null_face());
  EXPECT_NO_THROW(IM::validate_triangle_mesh(flat));
  auto lifted = get(CGAL::dynamic_vertex_property_t<IM::Lifted_point>(), flat);
  expect_refusal_with_repair_hint([&] { IM::compute_lifted_embedding(flat, lifted); }, "has a zero normal");
  EXPECT_TRUE(IM::repair_scanned_mesh(flat).valid);
  EXPECT_NO_THROW(IM::compute_lifted_embedding(flat, lifted));

  const Mesh fandisk = read_mesh("fandisk.off");
  auto lengths = get(CGAL::dynamic_halfedge_property_t<double>(), fandisk);
  for(auto h : halfedges(fandisk))
    put(lengths, h, PMP::edge_length(h, fandisk));
  const auto h0 = *halfedges(fandisk).begin();
  put(lengths, h0, 0.);
  put(lengths, opposite(h0, fandisk), 0.);
  expect_refusal_with_repair_hint([&] { IM::Metric_mesh<Mesh>(fandisk, IM::parameters::edge_length_map(lengths)); },
                                  "has zero length");
}

// A clean mesh is left as it is.
// A hole is filled, a small piece of surface inside a short border is not closed onto itself: a loose
// triangle kept (min_component_fraction 0) stays one face, and the lift, which needs a normal at every
// vertex, runs on the result.
TEST(Scan_repair, SmallPiecesAreNotClosedOntoThemselves)
{
  Mesh m = read_mesh("fandisk.off");
  const std::size_t faces_before = num_faces(m);
  const vertex_descriptor c = interior_vertex(m, 0.3);
  ASSERT_NE(c, Mesh::null_vertex());
  CGAL::Euler::make_hole(CGAL::Euler::remove_center_vertex(halfedge(c, m), m), m);
  const double h = mean_edge_length(m);
  const Point far(1e3 * h, 0, 0);
  m.add_face(m.add_vertex(far), m.add_vertex(far + Vector(h, 0, 0)), m.add_vertex(far + Vector(0, h, 0)));
  const IM::Scan_repair_report report = IM::repair_scanned_mesh(m, IM::parameters::min_component_fraction(0));
  EXPECT_TRUE(report.valid) << report;
  EXPECT_EQ(report.holes_filled, 1u) << report;
  EXPECT_EQ(report.components_removed, 0u) << report;
  EXPECT_GE(num_faces(m), faces_before - 1); // the hole's fan, refilled, and the loose triangle
  auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  EXPECT_EQ(PMP::connected_components(m, component), 2u);
  std::size_t loose_faces = 0;
  for(face_descriptor f : faces(m))
    loose_faces += get(component, f) != get(component, *faces(m).begin()) ? 1 : 0;
  EXPECT_EQ(std::min(loose_faces, num_faces(m) - loose_faces), 1u);
  EXPECT_NO_THROW(IM::Metric_mesh<Mesh>(m, IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5)));
}

TEST(Scan_repair, CleanMeshIsUntouched)
{
  Mesh m = read_mesh("fandisk.off");
  const Mesh copy = m;
  const IM::Scan_repair_report report = IM::repair_scanned_mesh(m);
  EXPECT_TRUE(report.valid);
  EXPECT_EQ(num_faces(m), num_faces(copy));
  EXPECT_EQ(num_vertices(m), num_vertices(copy));
  for(vertex_descriptor v : vertices(m))
    ASSERT_EQ(m.point(v), copy.point(v));
}

} // namespace
