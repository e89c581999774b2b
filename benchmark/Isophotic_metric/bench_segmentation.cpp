// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Segmentation into fundamental surfaces against CGAL's alternatives, on the generated CAD part suite
// (B-rep ground truth) and on noisy copies of it (Gaussian noise along the normals, 0.1, 0.2 and 0.35
// mean edge lengths, seeded). Scores are printed first (area-weighted ARI, mIoU, fillet IoU, segments / true faces,
// correct type), then Google Benchmark times one segmentation per method.
// Then CGAL's CAD meshes (fandisk, anchor_dense, rotor, couplingdown, turbine): segment counts and typed
// areas, with pictures (ours left, RANSAC right) when --pictures is given.
//   bench_segmentation [--parts=a,b,...] [--noise=0.1,0.2,0.35] [--conditions=1|2|4 (sum)] [--methods=N]
//                      [--pictures=DIR] [--verbose] [google benchmark flags]
#include "../../examples/Isophotic_metric/example_output.h"
#include "../../test/Isophotic_metric/cad_part_scores.h"

#include <CGAL/Isophotic_metric/Segmentation/segment_fundamental_surfaces.h>

#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Shape_detection/Efficient_RANSAC.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing.h>
#include <CGAL/Shape_detection/Region_growing/Region_growing_on_polygon_mesh.h>
#include <CGAL/property_map.h>

#include <benchmark/benchmark.h>

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <cstring>
#include <iostream>

namespace IM = CGAL::Isophotic_metric;
using cad_parts::Mesh;
using cad_parts::Part;
using cad_parts::face_descriptor;
typedef cad_parts::K K;

// A segmentation: a label and a surface type (ground-truth numbering) per face.
struct Labelling
{
  std::vector<long> label;
  std::vector<int> type;
};

double region_radius = 0; // --radius=R: seed_spacing of R times the bounding-box diagonal (0: default)
double angle = 0;         // --angle=A: angle_tolerance A degrees (0: default)

template <class ConcurrencyTag = CGAL::Parallel_if_available_tag>
Labelling run_isophotic(const Mesh& m)
{
  Labelling r;
  std::vector<std::size_t> id(m.number_of_faces());
  std::vector<IM::Fundamental_surface_segment> segments;
  auto map = CGAL::make_property_map(id);
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(m);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  if(region_radius > 0 || angle > 0)
    IM::segment_fundamental_surfaces<ConcurrencyTag>(m, map, std::back_inserter(segments),
                                     IM::parameters::seed_spacing(region_radius > 0 ? region_radius * diagonal : 0.05 * diagonal)
                                       .angle_tolerance(angle > 0 ? angle : 10.0));
  else
    IM::segment_fundamental_surfaces<ConcurrencyTag>(m, map, std::back_inserter(segments));
  for(face_descriptor f : m.faces())
  {
    r.label.push_back(long(id[f]));
    r.type.push_back(int(segments[id[f]].surface.type));
  }
  return r;
}

// Efficient_RANSAC on the face centroids with the face normals; unassigned faces form one label.
// Each point carries its face's index: detection reorders the input range.
Labelling run_ransac(const Mesh& m)
{
  typedef std::tuple<K::Point_3, K::Vector_3, std::size_t> Sample;
  typedef std::vector<Sample> Sample_vector;
  typedef CGAL::Shape_detection::Efficient_RANSAC_traits<K, Sample_vector, CGAL::Nth_of_tuple_property_map<0, Sample>,
                                                         CGAL::Nth_of_tuple_property_map<1, Sample>> Traits;
  typedef CGAL::Shape_detection::Efficient_RANSAC<Traits> Ransac;
  Sample_vector points;
  for(face_descriptor f : m.faces())
  {
    std::vector<K::Point_3> p;
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      p.push_back(m.point(v));
    points.emplace_back(CGAL::centroid(p[0], p[1], p[2]), CGAL::Polygon_mesh_processing::compute_face_normal(f, m),
                        std::size_t(f));
  }
  Ransac ransac;
  ransac.set_input(points);
  ransac.add_shape_factory<CGAL::Shape_detection::Plane<Traits>>();
  ransac.add_shape_factory<CGAL::Shape_detection::Cylinder<Traits>>();
  ransac.add_shape_factory<CGAL::Shape_detection::Sphere<Traits>>();
  ransac.add_shape_factory<CGAL::Shape_detection::Cone<Traits>>();
  ransac.add_shape_factory<CGAL::Shape_detection::Torus<Traits>>();
  Ransac::Parameters parameters;
  const double h = cad_parts::mean_edge_length(m);
  // tolerances as ours (0.3 mean edge, 20 degrees); clusters connected within two edges; shapes of at
  // least 0.2 % of the faces
  parameters.epsilon = 0.3 * h;
  parameters.cluster_epsilon = 2 * h;
  parameters.normal_threshold = std::cos(20 * CGAL_PI / 180);
  parameters.min_points = std::max<std::size_t>(10, points.size() / 500);
  parameters.probability = 0.05;
  ransac.detect(parameters);
  Labelling r;
  r.label.assign(points.size(), -1);
  r.type.assign(points.size(), 5);
  long id = 0;
  for(const auto& shape : ransac.shapes())
  {
    int type = 5;
    if(dynamic_cast<CGAL::Shape_detection::Plane<Traits>*>(shape.get())) type = 0;
    else if(dynamic_cast<CGAL::Shape_detection::Cylinder<Traits>*>(shape.get())) type = 1;
    else if(dynamic_cast<CGAL::Shape_detection::Cone<Traits>*>(shape.get())) type = 2;
    else if(dynamic_cast<CGAL::Shape_detection::Sphere<Traits>*>(shape.get())) type = 3;
    else if(dynamic_cast<CGAL::Shape_detection::Torus<Traits>*>(shape.get())) type = 4;
    for(std::size_t i : shape->indices_of_assigned_points())
    {
      r.label[std::get<2>(points[i])] = id;
      r.type[std::get<2>(points[i])] = type;
    }
    ++id;
  }
  return r;
}

// Shape_detection region growing of planes on the mesh faces; unassigned faces form one label.
Labelling run_plane_region_growing(const Mesh& m)
{
  namespace SD = CGAL::Shape_detection;
  typedef SD::Polygon_mesh::One_ring_neighbor_query<Mesh> Neighbor_query;
  typedef SD::Polygon_mesh::Least_squares_plane_fit_region<K, Mesh> Region_type;
  typedef SD::Polygon_mesh::Least_squares_plane_fit_sorting<K, Mesh, Neighbor_query> Sorting;
  typedef SD::Region_growing<Mesh::Face_range, Neighbor_query, Region_type, typename Sorting::Seed_map> Region_growing;
  const double h = cad_parts::mean_edge_length(m);
  Neighbor_query neighbor_query(m);
  // the point maps are passed: their default-constructed values are empty
  Region_type region_type(m, 0.3 * h, 20, 1, get(CGAL::vertex_point, m));
  Sorting sorting(m, neighbor_query, get(CGAL::vertex_point, m));
  sorting.sort();
  const Mesh::Face_range face_range = m.faces(); // kept by reference
  Region_growing region_growing(face_range, neighbor_query, region_type, sorting.seed_map());
  std::vector<std::vector<std::size_t>> regions;
  region_growing.detect(std::back_inserter(regions));
  Labelling r;
  r.label.assign(m.number_of_faces(), -1);
  r.type.assign(m.number_of_faces(), 5);
  for(std::size_t i = 0; i < regions.size(); ++i)
    for(std::size_t f : regions[i])
    {
      r.label[f] = long(i);
      r.type[f] = 0;
    }
  return r;
}

// PMP::sharp_edges_segmentation at 20 degrees: the patches between sharp edges, untyped.
Labelling run_sharp_edges(const Mesh& m)
{
  Mesh copy = m;
  auto is_sharp = copy.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  auto patch = copy.add_property_map<face_descriptor, std::size_t>("f:patch", 0).first;
  CGAL::Polygon_mesh_processing::sharp_edges_segmentation(copy, 20, is_sharp, patch);
  Labelling r;
  for(face_descriptor f : copy.faces())
  {
    r.label.push_back(long(patch[f]));
    r.type.push_back(5);
  }
  return r;
}

struct Method
{
  const char* name;
  Labelling (*run)(const Mesh&);
};
const Method methods[] = {{"isophotic fundamental surfaces", run_isophotic<>},
                          {"CGAL Efficient_RANSAC", run_ransac},
                          {"CGAL plane region growing", run_plane_region_growing},
                          {"PMP sharp_edges_segmentation 20deg", run_sharp_edges}};

// Face colours by type as in the example segment_fundamental_surfaces: plane blue-grey, cylinder
// orange, cone green, sphere red, torus purple, free-form or unassigned yellow; a shade per segment.
example_output::Colour type_colour(int type, long segment)
{
  using example_output::Colour;
  static const Colour base[6] = {{150, 170, 200}, {240, 140, 40}, {80, 180, 90}, {220, 50, 50}, {150, 80, 190}, {240, 220, 60}};
  const double shade[4] = {0, 0.25, -0.2, 0.4};
  const double s = shade[std::size_t(segment + 1) % 4];
  return s >= 0 ? example_output::mix(base[type], {255, 255, 255}, s) : example_output::mix(base[type], {0, 0, 0}, -s);
}

// <dir>/<part>[_noise<level>].ply: the ground truth, ours and RANSAC's side by side, coloured by type
void write_picture(const std::string& dir, const Part& part, double noise, const Labelling& ours, const Labelling& ransac)
{
  const example_output::Vector shift = example_output::side_by_side_shift(part.mesh, example_output::oblique_view_horizontal, 1.15);
  std::vector<long> truth(part.brep_face.begin(), part.brep_face.end());
  std::vector<int> truth_type(part.surface_type.begin(), part.surface_type.end());
  const std::vector<const std::vector<long>*> labels{&truth, &ours.label, &ransac.label};
  const std::vector<const std::vector<int>*> types{&truth_type, &ours.type, &ransac.type};
  std::vector<std::function<example_output::Colour(face_descriptor)>> colours;
  for(std::size_t k = 0; k < 3; ++k)
    colours.push_back([&, k](face_descriptor f) { return type_colour((*types[k])[f], (*labels[k])[f]); });
  example_output::write_face_coloured_meshes(dir + "/" + part.name + (noise > 0 ? "_noise" + std::to_string(noise).substr(0, 4) : "") + ".ply",
                                             {&part.mesh, &part.mesh, &part.mesh}, {example_output::Vector(0, 0, 0), shift, 2 * shift}, colours);
}

std::string picture_dir;      // --pictures=DIR
std::vector<std::string> chosen_parts;
std::vector<double> noise_levels{0.1, 0.2, 0.35}; // --noise=a,b,...
bool verbose = false;
std::size_t method_count = 4;   // --methods=N: the first N methods only
int conditions = 7;             // --conditions= bits: 1 clean parts, 2 noisy parts, 4 CGAL's meshes

void print_scores()
{
  std::vector<double> levels; // 0: clean
  if(conditions & 1)
    levels.push_back(0);
  if(conditions & 2)
    levels.insert(levels.end(), noise_levels.begin(), noise_levels.end());
  for(double noise : levels)
  {
    const bool noisy = noise > 0;
    if(noisy)
      std::printf("\nnoisy parts (%zu) (noise %.2f mean edge along the normals)\n", chosen_parts.size(), noise);
    else
      std::printf("\nclean parts (%zu)\n", chosen_parts.size());
    // besides the mean of segments / true faces, which over- and under-segmented parts can bring to 1:
    // the mean of |log(segments / true faces)| and the parts whose count is within 0.9-1.2 of the truth
    std::printf("%-36s %6s %6s %7s %9s %7s %9s %8s %7s\n", "method", "ARI", "mIoU", "filletIoU", "seg/true", "type", "time(s)",
                "|logseg|", "in0.9-1.2");
    for(std::size_t k = 0; k < method_count && k < std::size(methods); ++k)
    {
      const Method& method = methods[k];
      cad_parts::Scores mean;
      double seconds = 0, log_ratio = 0;
      int within = 0;
      for(const std::string& name : chosen_parts)
      {
        Part part = cad_parts::load(name);
        if(noisy)
          cad_parts::add_normal_noise(part.mesh, noise, 1);
        const auto start = std::chrono::steady_clock::now();
        const Labelling l = method.run(part.mesh);
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        seconds += t;
        const cad_parts::Scores s = cad_parts::score(part, l.label, l.type);
        if(!picture_dir.empty() && k == 0)
          write_picture(picture_dir, part, noise, l, run_ransac(part.mesh));
        if(verbose)
          std::printf("  %-28s ARI %.3f mIoU %.3f fillet %.3f seg %3zu/%3d type %.3f %.2fs\n", name.c_str(), s.ari, s.miou,
                      s.fillet_iou, s.segments, part.number_of_brep_faces, s.correct_type, t);
        mean.ari += s.ari;
        mean.miou += s.miou;
        mean.fillet_iou += s.fillet_iou;
        mean.segment_ratio += s.segment_ratio;
        mean.correct_type += s.correct_type;
        log_ratio += std::abs(std::log(s.segment_ratio));
        within += s.segment_ratio >= 0.9 && s.segment_ratio <= 1.2;
      }
      const double n = double(chosen_parts.size());
      std::printf("%-36s %6.3f %6.3f %7.3f %8.2fx %7.3f %9.2f %8.3f %4d/%zu\n", method.name, mean.ari / n, mean.miou / n,
                  mean.fillet_iou / n, mean.segment_ratio / n, mean.correct_type / n, seconds, log_ratio / n, within,
                  chosen_parts.size());
      std::fflush(stdout);
    }
  }
}

// CGAL's CAD meshes (no ground truth): segments and type areas of ours and RANSAC's, pictures side by side
void cgal_meshes()
{
  std::printf("\nCGAL's CAD meshes: segments (ours / RANSAC), area typed plane-cylinder-cone-sphere-torus-free %% (ours), time\n");
  for(const char* name : {"fandisk", "anchor_dense", "rotor", "couplingdown", "turbine"})
  {
    Part part;
    part.name = name;
    if(!CGAL::IO::read_polygon_mesh(std::string(CGAL_DATA_DIR) + "/meshes/" + name + ".off", part.mesh))
      continue;
    const auto start = std::chrono::steady_clock::now();
    const Labelling ours = run_isophotic<>(part.mesh);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Labelling ransac = run_ransac(part.mesh);
    double area[6] = {0, 0, 0, 0, 0, 0}, total = 0;
    std::size_t f = 0;
    for(face_descriptor fd : part.mesh.faces())
    {
      const double a = CGAL::Polygon_mesh_processing::face_area(fd, part.mesh);
      area[ours.type[f++]] += a;
      total += a;
    }
    const auto count = [](const std::vector<long>& l) { return std::set<long>(l.begin(), l.end()).size(); };
    std::printf("%-14s %7zu faces  %4zu / %4zu segments  %4.1f %4.1f %4.1f %4.1f %4.1f %4.1f  %.2f s\n", name,
                std::size_t(part.mesh.number_of_faces()), count(ours.label), count(ransac.label), 100 * area[0] / total, 100 * area[1] / total,
                100 * area[2] / total, 100 * area[3] / total, 100 * area[4] / total, 100 * area[5] / total, t);
    if(!picture_dir.empty())
    {
      const example_output::Vector shift =
        example_output::side_by_side_shift(part.mesh, example_output::oblique_view_horizontal, 1.15);
      example_output::write_face_coloured_meshes(
        picture_dir + "/" + name + ".ply", {&part.mesh, &part.mesh}, {example_output::Vector(0, 0, 0), shift},
        {[&](face_descriptor fd) { return type_colour(ours.type[fd], ours.label[fd]); },
         [&](face_descriptor fd) { return type_colour(ransac.type[fd], ransac.label[fd]); }});
    }
  }
}

// Google Benchmark: one segmentation of the 99k-face flange, ours (on TBB's threads, and on the calling
// thread alone: there its CPU time is all the CPU it takes) and RANSAC's
void register_timings()
{
  static Part flange = cad_parts::load("flange_fine");
  benchmark::RegisterBenchmark("isophotic_fundamental_surfaces/flange_fine_99k", [](benchmark::State& state) {
    for(auto _ : state)
      benchmark::DoNotOptimize(run_isophotic(flange.mesh).label.size());
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("isophotic_fundamental_surfaces_sequential/flange_fine_99k", [](benchmark::State& state) {
    for(auto _ : state)
      benchmark::DoNotOptimize(run_isophotic<CGAL::Sequential_tag>(flange.mesh).label.size());
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Efficient_RANSAC/flange_fine_99k", [](benchmark::State& state) {
    for(auto _ : state)
      benchmark::DoNotOptimize(run_ransac(flange.mesh).label.size());
  })->Unit(benchmark::kMillisecond);
}

int main(int argc, char** argv)
{
  std::vector<char*> rest{argv[0]};
  std::string only_method;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a.rfind("--parts=", 0) == 0)
    {
      std::stringstream list(a.substr(8));
      for(std::string n; std::getline(list, n, ',');)
        chosen_parts.push_back(n);
    }
    else if(a.rfind("--noise=", 0) == 0)
    {
      noise_levels.clear();
      std::stringstream list(a.substr(8));
      for(std::string n; std::getline(list, n, ',');)
        noise_levels.push_back(std::stod(n));
    }
    else if(a.rfind("--methods=", 0) == 0)
      method_count = std::stoul(a.substr(10));
    else if(a.rfind("--conditions=", 0) == 0)
      conditions = std::stoi(a.substr(13));
    else if(a.rfind("--radius=", 0) == 0)
      region_radius = std::stod(a.substr(9));
    else if(a.rfind("--angle=", 0) == 0)
      angle = std::stod(a.substr(8));
    else if(a.rfind("--pictures=", 0) == 0)
      picture_dir = a.substr(11);
    else if(a == "--verbose")
      verbose = true;
    else
      rest.push_back(argv[i]);
  }
  if(chosen_parts.empty())
    chosen_parts = cad_parts::part_names();
  if(conditions & 1 || conditions & 2)
    print_scores();
  if(conditions & 4)
    cgal_meshes();
  register_timings();
  int n = int(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
