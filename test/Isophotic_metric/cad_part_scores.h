// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The generated CAD part suite (data/cad_parts) and the scores of a segmentation against its B-rep
// ground truth. Shared by test_segmentation.cpp and bench_segmentation.cpp.
#ifndef CGAL_ISOPHOTIC_METRIC_TEST_CAD_PART_SCORES_H
#define CGAL_ISOPHOTIC_METRIC_TEST_CAD_PART_SCORES_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cad_parts {

typedef CGAL::Epick K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Face_index face_descriptor;

struct Part
{
  std::string name;
  Mesh mesh;
  std::vector<int> brep_face;          // ground truth per face
  std::vector<unsigned char> surface_type; // 0 plane ... 5 free-form, per face
  std::vector<double> area;
  int number_of_brep_faces = 0;
};

inline std::string directory() { return CGAL_ISOPHOTIC_METRIC_CAD_PARTS_DIR; }

// names listed in parts.csv, in its order
inline std::vector<std::string> part_names()
{
  std::ifstream in(directory() + "/parts.csv");
  if(!in)
    throw std::runtime_error("no " + directory() + "/parts.csv: reconfigure with python3-gmsh installed");
  std::vector<std::string> names;
  std::string line;
  std::getline(in, line);
  while(std::getline(in, line))
    if(!line.empty())
      names.push_back(line.substr(0, line.find(',')));
  return names;
}

inline Part load(const std::string& name)
{
  Part part;
  part.name = name;
  std::ifstream in(directory() + "/" + name + ".ply", std::ios::binary);
  if(!in || !CGAL::IO::read_PLY(in, part.mesh))
    throw std::runtime_error("cannot read " + directory() + "/" + name + ".ply");
  auto brep = part.mesh.property_map<face_descriptor, std::int32_t>("f:brep_face");
  auto type = part.mesh.property_map<face_descriptor, std::uint8_t>("f:surface_type");
  if(!brep.second || !type.second)
    throw std::runtime_error(name + ".ply has no brep_face / surface_type face property");
  for(face_descriptor f : part.mesh.faces())
  {
    part.brep_face.push_back(brep.first[f]);
    part.surface_type.push_back(type.first[f]);
    part.area.push_back(CGAL::Polygon_mesh_processing::face_area(f, part.mesh));
    part.number_of_brep_faces = std::max(part.number_of_brep_faces, brep.first[f] + 1);
  }
  return part;
}

inline double mean_edge_length(const Mesh& m)
{
  double sum = 0;
  for(auto e : m.edges())
    sum += std::sqrt(CGAL::squared_distance(m.point(m.vertex(e, 0)), m.point(m.vertex(e, 1))));
  return sum / double(m.number_of_edges());
}

// Gaussian noise along the vertex normals, standard deviation `sigma` times the mean edge length
inline void add_normal_noise(Mesh& m, double sigma, unsigned seed)
{
  std::map<Mesh::Vertex_index, K::Vector_3> normal;
  for(face_descriptor f : m.faces())
  {
    const auto h = m.halfedge(f);
    const K::Vector_3 n = CGAL::cross_product(m.point(m.target(m.next(h))) - m.point(m.target(h)),
                                              m.point(m.source(h)) - m.point(m.target(h)));
    for(auto v : CGAL::vertices_around_face(h, m))
      normal[v] = (normal.count(v) ? normal[v] : K::Vector_3(0, 0, 0)) + n;
  }
  const double s = sigma * mean_edge_length(m);
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0, s);
  for(auto v : m.vertices())
  {
    const K::Vector_3 n = normal[v] / std::sqrt(normal[v].squared_length());
    m.point(v) = m.point(v) + gauss(random) * n;
  }
}

struct Scores
{
  double ari = 0, miou = 0, fillet_iou = 0, segment_ratio = 0, correct_type = 0;
  std::size_t segments = 0;
};

// Area-weighted scores of a segmentation (`label` per face, any integers) with a surface type per face
// (`type`, the ground truth's numbering):
// - ARI: adjusted Rand index with the pairs of points of the surface (areas in place of counts);
// - mIoU: for each true face the best intersection over union of a segment, weighted by area;
// - fillet IoU: the same over the fillets (non-planar true faces of less than 10 % of the part's area);
// - segments / true faces; correct type: fraction of the area whose type is the true one.
inline Scores score(const Part& part, const std::vector<long>& label, const std::vector<int>& type)
{
  Scores s;
  std::map<std::pair<int, long>, double> joint;
  std::map<int, double> truth_area;
  std::map<long, double> segment_area;
  double total = 0, typed = 0;
  for(std::size_t f = 0; f < label.size(); ++f)
  {
    const double a = part.area[f];
    joint[{part.brep_face[f], label[f]}] += a;
    truth_area[part.brep_face[f]] += a;
    segment_area[label[f]] += a;
    total += a;
    if(type[f] == part.surface_type[f])
      typed += a;
  }
  double sum_joint = 0, sum_truth = 0, sum_segment = 0;
  for(const auto& j : joint)
    sum_joint += j.second * j.second;
  for(const auto& t : truth_area)
    sum_truth += t.second * t.second;
  for(const auto& g : segment_area)
    sum_segment += g.second * g.second;
  const double expected = sum_truth * sum_segment / (total * total);
  const double maximum = 0.5 * (sum_truth + sum_segment);
  s.ari = maximum - expected > 0 ? (sum_joint - expected) / (maximum - expected) : 1.0;
  std::map<int, double> best_iou;
  for(const auto& j : joint)
  {
    const double iou = j.second / (truth_area[j.first.first] + segment_area[j.first.second] - j.second);
    best_iou[j.first.first] = std::max(best_iou[j.first.first], iou);
  }
  std::map<int, bool> fillet;
  for(std::size_t f = 0; f < label.size(); ++f)
    fillet[part.brep_face[f]] = part.surface_type[f] != 0 && truth_area[part.brep_face[f]] < 0.1 * total;
  double fillet_area = 0;
  for(const auto& t : truth_area)
  {
    s.miou += t.second * best_iou[t.first];
    if(fillet[t.first])
    {
      s.fillet_iou += t.second * best_iou[t.first];
      fillet_area += t.second;
    }
  }
  s.miou /= total;
  s.fillet_iou = fillet_area > 0 ? s.fillet_iou / fillet_area : 1.0;
  s.segments = segment_area.size();
  s.segment_ratio = double(s.segments) / double(truth_area.size());
  s.correct_type = typed / total;
  return s;
}

} // namespace cad_parts

#endif // CGAL_ISOPHOTIC_METRIC_TEST_CAD_PART_SCORES_H
