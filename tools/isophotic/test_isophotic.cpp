// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests of the command-line tool `isophotic`: runs it on CGAL's fandisk and checks what it writes
// (counts, values, faces) against the library called directly, its help and its errors.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/selection.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_distances.h>
#include <CGAL/Isophotic_metric/Geodesics/compute_geodesic_path.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>
#include <CGAL/Isophotic_metric/Morphology/radius_for_area_share.h>
#include <CGAL/Isophotic_metric/Segmentation/region_growing.h>

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;
namespace IM = CGAL::Isophotic_metric;

const std::string fandisk = CGAL::data_file_path("meshes/fandisk.off");
// A folder of its own for each test: ctest runs them in parallel.
std::string work_folder()
{
  const std::string folder =
    std::string("isophotic_tool_test/") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "/";
  std::system(("mkdir -p " + folder).c_str());
  return folder;
}

struct Tool_run
{
  int status;
  std::string out, err;
};

std::string read_text(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Tool_run run(const std::string& arguments)
{
  const std::string work = work_folder();
  const int raw = std::system((std::string(ISOPHOTIC_TOOL) + " " + arguments + " > " + work + "out.txt 2> " + work + "err.txt").c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_text(work + "out.txt"), read_text(work + "err.txt")};
}

// The rows of a CSV file, as numbers, after checking its header.
std::vector<std::vector<double>> read_csv(const std::string& file, const std::string& header)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, header) << file;
  std::vector<std::vector<double>> rows;
  while(std::getline(in, line))
  {
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while(std::getline(s, cell, ','))
      row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

Mesh load()
{
  Mesh m;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(fandisk, m));
  return m;
}

auto metric(const Mesh& m)
{
  return IM::parameters::euclidean_weight(0.5).isophotic_weight(0.5).weight_length_scale(IM::suggested_weight_length_scale(m));
}

std::set<std::size_t> selected_faces(const std::vector<std::vector<double>>& rows)
{
  std::set<std::size_t> s;
  for(const auto& row : rows)
    if(row[1] == 1)
      s.insert(std::size_t(row[0]));
  return s;
}

TEST(Isophotic_tool, HelpForEveryCommand)
{
  const Tool_run overview = run("--help");
  EXPECT_EQ(overview.status, 0);
  for(const std::string command : {"distance", "path", "dilate", "erode", "open", "close", "segment", "neighborhood"})
  {
    EXPECT_NE(overview.out.find("  " + command), std::string::npos) << command;
    const Tool_run help = run(command + " --help");
    EXPECT_EQ(help.status, 0) << command;
    EXPECT_NE(help.out.find("usage: isophotic " + command), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("--output"), std::string::npos) << command;
    EXPECT_NE(help.out.find("--repair"), std::string::npos) << command;
    EXPECT_NE(help.out.find("--normal-smoothing-scale"), std::string::npos) << command;
  }
  EXPECT_EQ(run("").status, 2);
}

TEST(Isophotic_tool, DistanceFieldEqualsTheLibrary)
{
  const std::string work = work_folder();
  const Mesh m = load();
  const Tool_run r = run("distance " + fandisk + " --vertex 0,3000 --quiet -o " + work + "d.csv -o " + work + "d.ply");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(work + "d.csv", "vertex,x,y,z,distance");
  ASSERT_EQ(rows.size(), num_vertices(m));

  auto expected = get(CGAL::dynamic_vertex_property_t<double>(), m);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{vertex_descriptor(0), vertex_descriptor(3000)}, m,
                                 expected, metric(m));
  Mesh written;
  std::ifstream ply(work + "d.ply", std::ios::binary); // the stream reader keeps the properties
  ASSERT_TRUE(CGAL::IO::read_PLY(ply, written));
  ASSERT_EQ(num_vertices(written), num_vertices(m));
  ASSERT_EQ(num_faces(written), num_faces(m));
  const auto [ply_distance, found] = written.property_map<vertex_descriptor, double>("v:distance");
  ASSERT_TRUE(found);
  for(vertex_descriptor v : vertices(m))
  {
    EXPECT_EQ(rows[v][0], double(std::size_t(v)));
    EXPECT_EQ(rows[v][1], m.point(v).x());
    EXPECT_NEAR(rows[v][4], get(expected, v), 1e-12) << "vertex " << v;
    EXPECT_EQ(ply_distance[v], rows[v][4]);
  }
  EXPECT_EQ(rows[0][4], 0.);
  EXPECT_EQ(rows[3000][4], 0.);

  // a point source at the position of vertex 0: the same field as from vertex 0 alone
  const Point p0 = m.point(vertex_descriptor(0));
  std::ostringstream point;
  point << std::setprecision(17) << p0.x() << "," << p0.y() << "," << p0.z();
  ASSERT_EQ(run("distance " + fandisk + " --point " + point.str() + " --quiet -o " + work + "p.csv").status, 0);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{vertex_descriptor(0)}, m, expected, metric(m));
  const auto point_rows = read_csv(work + "p.csv", "vertex,x,y,z,distance");
  for(vertex_descriptor v : vertices(m))
    EXPECT_NEAR(point_rows[v][4], get(expected, v), 1e-9) << "vertex " << v;
}

TEST(Isophotic_tool, MorphologyEqualsTheLibrary)
{
  const std::string work = work_folder();
  Mesh m = load();
  const std::vector<face_descriptor> seed{face_descriptor(100), face_descriptor(101)};
  const auto rule = metric(m).area_fraction(0.5);
  auto is_selected = get(CGAL::dynamic_face_property_t<bool>(), m);
  auto reset = [&](const std::vector<face_descriptor>& selection) {
    for(face_descriptor f : faces(m))
      put(is_selected, f, false);
    for(face_descriptor f : selection)
      put(is_selected, f, true);
  };
  auto library_selection = [&]() {
    std::set<std::size_t> s;
    for(face_descriptor f : faces(m))
      if(get(is_selected, f))
        s.insert(std::size_t(f));
    return s;
  };

  // dilation to 5 % of the area
  const Tool_run dilated = run("dilate " + fandisk + " --faces 100,101 --area-share 0.05 -o " + work + "s.csv");
  ASSERT_EQ(dilated.status, 0) << dilated.err;
  const double radius = IM::radius_for_area_share(seed, m, 0.05, rule);
  reset(seed);
  IM::dilate_face_selection(seed, m, radius, is_selected, CGAL::Emptyset_iterator(), rule);
  const auto rows = read_csv(work + "s.csv", "face,selected,initial");
  ASSERT_EQ(rows.size(), num_faces(m));
  EXPECT_EQ(selected_faces(rows), library_selection());
  EXPECT_NE(dilated.out.find("2 -> " + std::to_string(library_selection().size()) + " faces"), std::string::npos)
    << dilated.out;
  double area = 0;
  for(std::size_t f : selected_faces(rows))
    area += CGAL::Polygon_mesh_processing::face_area(face_descriptor(Mesh::size_type(f)), m);
  EXPECT_GE(area, 0.05 * CGAL::Polygon_mesh_processing::area(m) * (1 - 1e-12));

  // closing and erosion of a ring selection by a given radius, selection by a seed point
  const Point centre = CGAL::centroid(m.point(vertex_descriptor(10)), m.point(vertex_descriptor(11)),
                                      m.point(vertex_descriptor(12)));
  std::ostringstream where;
  where << std::setprecision(17) << centre.x() << "," << centre.y() << "," << centre.z();
  for(const std::string operation : {"close", "erode"})
  {
    const double r = 0.01 * IM::suggested_weight_length_scale(m);
    const Tool_run out = run(operation + " " + fandisk + " --seed " + where.str() + " --rings 4 --radius " +
                        std::to_string(r) + " --quiet -o " + work + "c.csv");
    ASSERT_EQ(out.status, 0) << out.err;
    const auto c = read_csv(work + "c.csv", "face,selected,initial");
    std::vector<face_descriptor> initial;
    for(const auto& row : c)
      if(row[2] == 1)
        initial.push_back(face_descriptor(Mesh::size_type(row[0])));
    EXPECT_GT(initial.size(), 20u);
    reset(initial);
    if(operation == "close")
      IM::close_face_selection(m, std::stod(std::to_string(r)), is_selected, rule);
    else
      IM::erode_face_selection(initial, m, std::stod(std::to_string(r)), is_selected, CGAL::Emptyset_iterator(), rule);
    EXPECT_EQ(selected_faces(c), library_selection()) << operation;
  }
}

TEST(Isophotic_tool, SegmentationPathAndNeighbourhoodEqualTheLibrary)
{
  const std::string work = work_folder();
  const Mesh m = load();
  const double L = IM::suggested_weight_length_scale(m);

  const Tool_run segmented = run("segment " + fandisk + " --quiet -o " + work + "g.csv");
  ASSERT_EQ(segmented.status, 0) << segmented.err;
  auto patch = get(CGAL::dynamic_face_property_t<std::size_t>(), m);
  const std::size_t patches = IM::segment_by_region_growing(m, 0.1 * L, patch, metric(m).area_fraction(0));
  const auto rows = read_csv(work + "g.csv", "face,patch");
  ASSERT_EQ(rows.size(), num_faces(m));
  std::set<double> labels;
  for(face_descriptor f : faces(m))
  {
    EXPECT_EQ(rows[f][1], double(get(patch, f)));
    labels.insert(rows[f][1]);
  }
  EXPECT_EQ(labels.size(), patches);

  const Tool_run path = run("path " + fandisk + " --from 0 --to 3000 -o " + work + "path.csv");
  ASSERT_EQ(path.status, 0) << path.err;
  std::vector<Point> expected;
  const double length = IM::compute_geodesic_path(vertex_descriptor(0), vertex_descriptor(3000), m,
                                                  std::back_inserter(expected), metric(m));
  const auto points = read_csv(work + "path.csv", "point,x,y,z");
  ASSERT_EQ(points.size(), expected.size());
  for(std::size_t i = 0; i < points.size(); ++i)
    EXPECT_NEAR(CGAL::squared_distance(Point(points[i][1], points[i][2], points[i][3]), expected[i]), 0., 1e-20) << i;
  const std::size_t at = path.out.find("path length ");
  ASSERT_NE(at, std::string::npos) << path.out;
  EXPECT_NEAR(std::stod(path.out.substr(at + 12)), length, 1e-5 * length);

  const double radius = 0.05 * L;
  const Tool_run disc = run("neighborhood " + fandisk + " --vertex 0 --radius " + std::to_string(radius) + " --quiet -o " +
                       work + "n.csv");
  ASSERT_EQ(disc.status, 0) << disc.err;
  std::vector<IM::Neighborhood_face<face_descriptor>> faces_within;
  IM::geodesic_neighborhood(vertex_descriptor(0), m, std::stod(std::to_string(radius)), std::back_inserter(faces_within),
                            metric(m));
  std::set<std::size_t> expected_faces, written_faces;
  for(const auto& n : faces_within)
    expected_faces.insert(std::size_t(n.face));
  for(const auto& row : read_csv(work + "n.csv", "face,min_distance,covered_fraction"))
    written_faces.insert(std::size_t(row[0]));
  EXPECT_GT(expected_faces.size(), 5u);
  EXPECT_EQ(written_faces, expected_faces);
}

// Runs the tool and expects it to fail with `status` and a message containing `fragment`.
void expect_error(const std::string& arguments, int status, const std::string& fragment)
{
  const Tool_run r = run(arguments);
  EXPECT_EQ(r.status, status) << arguments << "\n" << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << arguments << "\n" << r.err;
}

TEST(Isophotic_tool, BadInputGivesAClearErrorAndAnExitCode)
{
  const std::string work = work_folder();
  expect_error("distance no_such_mesh.off --vertex 0", 1, "cannot open 'no_such_mesh.off'");
  expect_error("distance " + fandisk + " --vertex 99999999", 2, "vertex 99999999 does not exist");
  expect_error("distance " + fandisk, 2, "--vertex or --point");
  expect_error("distance " + fandisk + " --vertex 0 --bogus 1", 2, "has no option --bogus");
  expect_error("dilate " + fandisk + " --faces 1 --radius -1", 1, "radius");
  expect_error("dilate " + fandisk + " --faces 1 --radius 0.1 --area-share 0.2", 2, "one of --radius");
  expect_error("dilate " + fandisk + " --faces 1 --area-share 1.5", 1, "area share is 1.5");
  expect_error("distance " + fandisk + " --vertex 0 --w -2", 1, "euclidean_weight is -2");
  expect_error("distance " + fandisk + " --vertex zero", 2, "'zero' is not a number");
  expect_error("distance " + fandisk + " --vertex 0 -o out.xyz", 2, "must end in .ply, .csv or .png");
  expect_error("frobnicate " + fandisk, 2, "unknown command 'frobnicate'");
  // a mesh the package refuses: vertices 1 and 3 at the same point, the edge between them named
  std::ofstream(work + "zero_edge.off") << "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n3 0 1 2\n3 1 3 2\n";
  expect_error("distance " + work + "zero_edge.off --vertex 0", 1, "edge (1, 3) has zero length");
  expect_error("distance " + work + "zero_edge.off --vertex 0", 1, "isophotic --repair");
  std::ofstream(work + "not_a_mesh.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  expect_error("distance " + work + "not_a_mesh.off --vertex 0", 1, "cannot read a polygon mesh");
}

// --repair on a scan-like mesh: a planar 6 x 6 grid whose vertex (3, 3) lies on its neighbour (3, 4),
// a zero-length edge (and two zero-area faces) that the package refuses. The repair removes them, the
// report says so, and the distance runs on the repaired grid: still the square in the plane z = 0, so
// the distance is sqrt(w) = sqrt(0.5) times the straight distance from vertex 0.
// A clean mesh is reported as such and gives the same field as without the option.
TEST(Isophotic_tool, RepairPreparesAScan)
{
  const std::string work = work_folder();
  {
    const int n = 6;
    std::ofstream off(work + "scan.off");
    off << "OFF\n" << (n + 1) * (n + 1) << " " << 2 * n * n << " 0\n";
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
        off << i << " " << (i == 3 && j == 3 ? 4 : j) << " 0\n";
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i)
      {
        const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        off << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
      }
  }
  expect_error("distance " + work + "scan.off --vertex 0", 1, "has zero length");
  const Tool_run r = run("distance " + work + "scan.off --vertex 0 --repair -o " + work + "d.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("repair: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("degenerate faces removed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the mesh is valid"), std::string::npos) << r.out;
  const auto rows = read_csv(work + "d.csv", "vertex,x,y,z,distance");
  ASSERT_EQ(rows.size(), 48u); // the two coincident vertices merged
  ASSERT_EQ(rows[0][4], 0.);
  for(const auto& row : rows)
    EXPECT_NEAR(row[4], std::sqrt(0.5) * std::hypot(row[1] - rows[0][1], row[2] - rows[0][2]), 1e-12);

  const Tool_run clean = run("distance " + fandisk + " --vertex 0 --repair -o " + work + "c.csv");
  ASSERT_EQ(clean.status, 0) << clean.err;
  EXPECT_NE(clean.out.find("repair: nothing to repair; the mesh is valid"), std::string::npos) << clean.out;
  ASSERT_EQ(run("distance " + fandisk + " --vertex 0 --quiet -o " + work + "p.csv").status, 0);
  EXPECT_EQ(read_text(work + "c.csv"), read_text(work + "p.csv"));
}

// --normal-smoothing-scale on a scan-like mesh: a planar 30 x 30 grid of unit squares with noise of 0.2
// edges along its normal. In the plane the normals are constant and the isophotic distance is
// sqrt(w) = sqrt(0.5) times the straight one (the noise lengthens the surface by a few per cent): with
// the raw normals the distance across the grid is over twice that, with the robust ones close to it.
// `auto` says what it estimated and chose, and the field equals the library's with that scale; on the
// clean fandisk it keeps the exact normals (the field without the option, byte for byte), as does 0.
TEST(Isophotic_tool, RobustNormalsOfAScan)
{
  const std::string work = work_folder();
  const int n = 30;
  Mesh grid;
  {
    std::mt19937_64 random(3);
    std::normal_distribution<double> noise(0., 0.2);
    std::ofstream off(work + "scan.off");
    off << "OFF\n" << (n + 1) * (n + 1) << " " << 2 * n * n << " 0\n" << std::setprecision(17);
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
        off << i << " " << j << " " << noise(random) << "\n";
    for(int j = 0; j < n; ++j)
      for(int i = 0; i < n; ++i)
      {
        const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        off << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
      }
  }
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(work + "scan.off", grid));
  const std::size_t far_corner = std::size_t(n) * (n + 2);
  const double plane = std::sqrt(0.5) * std::hypot(double(n), double(n));

  const Tool_run raw = run("distance " + work + "scan.off --vertex 0 --quiet -o " + work + "raw.csv");
  ASSERT_EQ(raw.status, 0) << raw.err;
  const Tool_run robust = run("distance " + work + "scan.off --vertex 0 --normal-smoothing-scale auto -o " + work + "robust.csv");
  ASSERT_EQ(robust.status, 0) << robust.err;
  const std::size_t said = robust.out.find("normals: estimated noise ");
  ASSERT_NE(said, std::string::npos) << robust.out;
  double edge_sum = 0;
  for(const auto e : edges(grid))
    edge_sum += CGAL::Polygon_mesh_processing::edge_length(e, grid);
  const double mean_edge = edge_sum / double(num_edges(grid)); // (about 1.15: sides and diagonals)
  EXPECT_NEAR(std::stod(robust.out.substr(said + 25)), 0.2 / mean_edge, 0.025) << robust.out;
  EXPECT_NE(robust.out.find("smoothed at the scale"), std::string::npos) << robust.out;
  const auto raw_rows = read_csv(work + "raw.csv", "vertex,x,y,z,distance");
  const auto robust_rows = read_csv(work + "robust.csv", "vertex,x,y,z,distance");
  ASSERT_EQ(robust_rows.size(), num_vertices(grid));
  EXPECT_GT(raw_rows[far_corner][4], 2. * plane);
  EXPECT_LT(robust_rows[far_corner][4], 1.25 * plane);
  EXPECT_GT(robust_rows[far_corner][4], plane);

  const double scale = IM::suggested_normal_smoothing_scale(grid);
  ASSERT_GT(scale, 0.);
  auto expected = get(CGAL::dynamic_vertex_property_t<double>(), grid);
  IM::compute_geodesic_distances(std::vector<vertex_descriptor>{vertex_descriptor(0)}, grid, expected,
                                 metric(grid).normal_smoothing_scale(scale));
  for(vertex_descriptor v : vertices(grid))
    EXPECT_NEAR(robust_rows[v][4], get(expected, v), 1e-12) << "vertex " << v;

  ASSERT_EQ(run("distance " + fandisk + " --vertex 0 --quiet -o " + work + "plain.csv").status, 0);
  const Tool_run clean = run("distance " + fandisk + " --vertex 0 --normal-smoothing-scale auto -o " + work + "auto.csv");
  ASSERT_EQ(clean.status, 0) << clean.err;
  EXPECT_NE(clean.out.find("the exact normals"), std::string::npos) << clean.out;
  EXPECT_EQ(read_text(work + "auto.csv"), read_text(work + "plain.csv"));
  ASSERT_EQ(run("distance " + fandisk + " --vertex 0 --normal-smoothing-scale 0 --quiet -o " + work + "zero.csv").status, 0);
  EXPECT_EQ(read_text(work + "zero.csv"), read_text(work + "plain.csv"));

  expect_error("distance " + fandisk + " --vertex 0 --normal-smoothing-scale -1", 1, "normal_smoothing_scale is -1");
  expect_error("distance " + fandisk + " --vertex 0 --normal-smoothing-scale rough", 2, "'rough' is not a number");
}

TEST(Isophotic_tool, PictureOfADilation)
{
  const std::string work = work_folder();
  if(std::system("command -v f3d > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "f3d is not installed";
  std::remove((work + "s.png").c_str());
  const Tool_run r = run("dilate " + fandisk + " --seed 0.1,0.2,0.3 --area-share 0.05 --quiet -o " + work + "s.png");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream png(work + "s.png", std::ios::binary | std::ios::ate);
  ASSERT_TRUE(png.good());
  EXPECT_GT(png.tellg(), 10000); // a picture, not an empty frame
}

} // namespace
