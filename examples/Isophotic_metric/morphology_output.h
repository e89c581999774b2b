// Helpers shared by the morphology examples: per-face coloured PLY output, seed picking, feature
// patches (faces connected without crossing a sharp edge) and the radius that dilates to a given area.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_OUTPUT_H
#define ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_OUTPUT_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/IO/Color.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Isophotic_metric.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace morphology_output {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;
namespace IM = CGAL::Isophotic_metric;
namespace PMP = CGAL::Polygon_mesh_processing;

// Colours of the pictures: light grey surface, dark red seed, orange growth within the seed's
// feature patch, blue growth beyond a feature.
const CGAL::IO::Color background(215, 217, 222), seed_colour(165, 15, 25), inside_colour(245, 150, 35),
  beyond_colour(40, 110, 220);

// Writes meshes (each moved by its offset) into one binary PLY with per-face uchar red/green/blue.
inline bool write_coloured_ply(const std::string& filename,
                               const std::vector<const Mesh*>& meshes,
                               const std::vector<std::array<double, 3>>& offsets,
                               const std::vector<std::function<CGAL::IO::Color(face_descriptor)>>& colours)
{
  std::size_t nv = 0, nf = 0;
  for(const Mesh* m : meshes)
  {
    nv += num_vertices(*m);
    nf += num_faces(*m);
  }
  std::ofstream out(filename, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << nv
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << nf
      << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  auto put_bytes = [&](std::uint32_t bits, int n) {
    for(int i = 0; i < n; ++i)
      out.put(static_cast<char>((bits >> (8 * i)) & 0xFF));
  };
  auto put_float = [&](double x) {
    const float f = static_cast<float>(x);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    put_bytes(bits, 4);
  };
  for(std::size_t i = 0; i < meshes.size(); ++i)
    for(vertex_descriptor v : vertices(*meshes[i]))
    {
      const auto& p = meshes[i]->point(v);
      put_float(p.x() + offsets[i][0]);
      put_float(p.y() + offsets[i][1]);
      put_float(p.z() + offsets[i][2]);
    }
  std::uint32_t first = 0;
  for(std::size_t i = 0; i < meshes.size(); ++i)
  {
    const Mesh& m = *meshes[i];
    std::vector<std::uint32_t> index(m.number_of_vertices() + m.number_of_removed_vertices());
    std::uint32_t next_index = first;
    for(vertex_descriptor v : vertices(m))
      index[v] = next_index++;
    for(face_descriptor f : faces(m))
    {
      put_bytes(3, 1);
      for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, m), m))
        put_bytes(index[v], 4);
      const CGAL::IO::Color c = colours[i](f);
      put_bytes(c.red(), 1);
      put_bytes(c.green(), 1);
      put_bytes(c.blue(), 1);
    }
    first = next_index;
  }
  return bool(out);
}

// Offset of the next copy in a side-by-side picture: along y, past the bounding box.
inline std::array<double, 3> side_by_side_offset(const Mesh& m)
{
  const CGAL::Bbox_3 box = PMP::bbox(m);
  return {{0, 1.15 * (box.ymax() - box.ymin()), 0}};
}

// Distinct colours for patch indices: hues by the golden angle, alternating lighter and darker.
inline CGAL::IO::Color patch_colour(std::size_t i)
{
  const double h = std::fmod(0.61803398875 * double(i), 1.0) * 6, v = i % 2 ? 0.95 : 0.75, s = 0.6;
  const int sector = static_cast<int>(h);
  const double f = h - sector, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const std::array<std::array<double, 3>, 6> rgb{{{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}}};
  const auto& c = rgb[sector % 6];
  return CGAL::IO::Color(static_cast<unsigned char>(255 * c[0]), static_cast<unsigned char>(255 * c[1]),
                         static_cast<unsigned char>(255 * c[2]));
}

// The face whose centroid is nearest to the point at fractions `where` of the bounding box.
inline face_descriptor face_near(const Mesh& m, const std::array<double, 3>& where)
{
  const CGAL::Bbox_3 box = PMP::bbox(m);
  const K::Point_3 target(box.xmin() + where[0] * (box.xmax() - box.xmin()),
                          box.ymin() + where[1] * (box.ymax() - box.ymin()),
                          box.zmin() + where[2] * (box.zmax() - box.zmin()));
  face_descriptor best;
  double best_distance = std::numeric_limits<double>::infinity();
  for(face_descriptor f : faces(m))
  {
    std::vector<K::Point_3> corners;
    for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, m), m))
      corners.push_back(m.point(v));
    const double d = CGAL::squared_distance(CGAL::centroid(corners[0], corners[1], corners[2]), target);
    if(d < best_distance)
    {
      best_distance = d;
      best = f;
    }
  }
  return best;
}

// Patch id of every face: faces connected across edges whose dihedral angle is below `angle_degrees`.
inline std::vector<std::size_t> feature_patches(const Mesh& m, double angle_degrees, std::size_t& number_of_patches)
{
  Mesh& mutable_mesh = const_cast<Mesh&>(m);
  auto is_sharp = mutable_mesh.add_property_map<Mesh::Edge_index, bool>("e:morphology_sharp", false).first;
  PMP::detect_sharp_edges(m, angle_degrees, is_sharp);
  auto patch = mutable_mesh.add_property_map<face_descriptor, std::size_t>("f:morphology_patch", 0).first;
  number_of_patches = PMP::connected_components(m, patch, CGAL::parameters::edge_is_constrained_map(is_sharp));
  std::vector<std::size_t> result(m.number_of_faces() + m.number_of_removed_faces(), 0);
  for(face_descriptor f : faces(m))
    result[f] = patch[f];
  mutable_mesh.remove_property_map(is_sharp);
  mutable_mesh.remove_property_map(patch);
  return result;
}

inline double face_area(const Mesh& m, face_descriptor f) { return PMP::face_area(f, m); }

inline double area_of(const Mesh& m, const std::set<face_descriptor>& fs)
{
  double a = 0;
  for(face_descriptor f : fs)
    a += face_area(m, f);
  return a;
}

// Dilation of `seed` by `radius` with a prepared band solver: a face joins when half of its area
// (by default) lies within the radius.
inline std::set<face_descriptor> dilate(const Mesh& m, const std::set<face_descriptor>& seed, double radius,
                                        IM::Face_band_solver<Mesh>& band, double area_fraction = 0.5)
{
  Mesh& mutable_mesh = const_cast<Mesh&>(m);
  auto selected = mutable_mesh.add_property_map<face_descriptor, bool>("f:morphology_selected", false).first;
  for(face_descriptor f : seed)
    selected[f] = true;
  std::set<face_descriptor> result(seed);
  std::vector<face_descriptor> added;
  IM::dilate_face_selection(seed, m, radius, selected, std::back_inserter(added), IM::parameters::face_band_solver(&band).area_fraction(area_fraction));
  result.insert(added.begin(), added.end());
  mutable_mesh.remove_property_map(selected);
  return result;
}

// The radius whose dilation of `seed` covers `target_area` (bisection on the radius, to 0.2 % of area).
inline double radius_for_area(const Mesh& m, const std::set<face_descriptor>& seed, double target_area,
                              IM::Face_band_solver<Mesh>& band, double first_guess)
{
  double low = 0, high = first_guess;
  while(area_of(m, dilate(m, seed, high, band)) < target_area && high < 1e12)
  {
    low = high;
    high *= 2;
  }
  for(int i = 0; i < 40; ++i)
  {
    const double mid = 0.5 * (low + high);
    const double a = area_of(m, dilate(m, seed, mid, band));
    if(a < target_area) low = mid; else high = mid;
    if(std::abs(a - target_area) < 0.002 * target_area)
      return mid;
  }
  return high;
}

// Share of the area of `grown` (minus the seed) lying outside the feature patches touched by the seed.
inline double share_beyond_features(const Mesh& m, const std::set<face_descriptor>& seed,
                                    const std::set<face_descriptor>& grown, const std::vector<std::size_t>& patch)
{
  std::set<std::size_t> seed_patches;
  for(face_descriptor f : seed)
    seed_patches.insert(patch[f]);
  double beyond = 0, total = 0;
  for(face_descriptor f : grown)
  {
    if(seed.count(f))
      continue;
    total += face_area(m, f);
    if(!seed_patches.count(patch[f]))
      beyond += face_area(m, f);
  }
  return total > 0 ? beyond / total : 0;
}

} // namespace morphology_output

#endif // ISOPHOTIC_METRIC_EXAMPLES_MORPHOLOGY_OUTPUT_H
