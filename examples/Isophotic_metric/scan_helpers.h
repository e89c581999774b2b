// Helpers of the scan examples and tests: seeded noise along the normal (a scan-like copy of a clean
// mesh), the planar face that seeds the figure of merit, and the figure of merit itself: the seed
// dilated in the Euclidean and in the isophotic metric until the same area lies inside its planar
// face; the area of each dilation beyond the face's border, their ratio, and the radii.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_SCAN_HELPERS_H
#define ISOPHOTIC_METRIC_EXAMPLES_SCAN_HELPERS_H

#include "morphology_helpers.h"

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh/IO/PLY.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <random>
#include <utility>

namespace scan_helpers {

using namespace morphology_helpers;

inline double mean_edge_length(const Mesh& m)
{
  double sum = 0;
  for(auto e : edges(m))
    sum += PMP::edge_length(e, m);
  return num_edges(m) > 0 ? sum / double(num_edges(m)) : 0.;
}

// Standard normal numbers from the bits of std::mt19937 (Box-Muller): std::normal_distribution is not
// the same in every standard library, these numbers are.
class Seeded_gaussian
{
public:
  explicit Seeded_gaussian(std::uint32_t seed) : bits_(seed) {}
  double operator()()
  {
    const double u1 = (double(bits_()) + 1.) / 4294967297., u2 = double(bits_()) / 4294967296.;
    return std::sqrt(-2. * std::log(u1)) * std::cos(2. * CGAL_PI * u2);
  }

private:
  std::mt19937 bits_;
};

// A copy of `clean` whose vertices moved along their clean normals by Gaussian noise of standard
// deviation `level` mean edge lengths (a laser scan measures depth along the line of sight).
inline Mesh noisy_copy(const Mesh& clean, double level, std::uint32_t seed)
{
  Mesh noisy = clean;
  if(level == 0.)
    return noisy;
  const double sigma = level * mean_edge_length(clean);
  auto normal = get(CGAL::dynamic_vertex_property_t<Vector>(), clean);
  PMP::compute_vertex_normals(clean, normal);
  Seeded_gaussian gaussian(seed);
  for(vertex_descriptor v : vertices(clean))
    noisy.point(v) = clean.point(v) + sigma * gaussian() * get(normal, v);
  return noisy;
}

// A clean CAD mesh and its faces in the sense of CAD: the patch of every triangle, and which patches
// are planar. Generated parts (PLY with the face property brep_face and surface_type, 0 for planes)
// carry their B-rep faces; for other meshes a patch is a set of triangles connected across edges that
// bend by less than 1 degree, and the patches of more than one triangle count as planar.
struct Part
{
  std::string name;
  Mesh mesh;
  std::vector<std::size_t> patch;
  std::set<std::size_t> planar;
};

inline bool read_part(const std::string& filename, Part& part)
{
  part = Part();
  part.name = stem(filename);
  if(filename.size() > 4 && filename.substr(filename.size() - 4) == ".ply")
  {
    std::ifstream in(filename, std::ios::binary);
    if(!in || !CGAL::IO::read_PLY(in, part.mesh))
      return false;
    auto brep_face = part.mesh.property_map<face_descriptor, int>("f:brep_face");
    auto surface_type = part.mesh.property_map<face_descriptor, unsigned char>("f:surface_type");
    if(!brep_face.second || !surface_type.second)
      return false;
    part.patch.assign(num_faces(part.mesh), 0);
    for(face_descriptor f : faces(part.mesh))
    {
      part.patch[f] = static_cast<std::size_t>(brep_face.first[f]);
      if(surface_type.first[f] == 0)
        part.planar.insert(part.patch[f]);
    }
    return true;
  }
  if(!CGAL::IO::read_polygon_mesh(filename, part.mesh) || is_empty(part.mesh))
    return false;
  std::size_t number_of_patches = 0;
  part.patch = feature_patches(part.mesh, 1., number_of_patches);
  std::map<std::size_t, std::size_t> size;
  for(face_descriptor f : faces(part.mesh))
    ++size[part.patch[f]];
  for(const auto& s : size)
    if(s.second > 1)
      part.planar.insert(s.first);
  return true;
}

// The `n` largest patches among `candidates`, by area, largest first.
inline std::vector<std::size_t> largest_patches(const Mesh& m, const std::vector<std::size_t>& patch,
                                                const std::set<std::size_t>& candidates, std::size_t n)
{
  std::map<std::size_t, double> area;
  for(face_descriptor f : faces(m))
    if(candidates.count(patch[f]))
      area[patch[f]] += face_area(m, f);
  std::vector<std::pair<double, std::size_t>> by_area;
  for(const auto& a : area)
    by_area.emplace_back(-a.second, a.first);
  std::sort(by_area.begin(), by_area.end());
  std::vector<std::size_t> result;
  for(std::size_t i = 0; i < std::min(n, by_area.size()); ++i)
    result.push_back(by_area[i].second);
  return result;
}

// The face of patch `id` farthest from the patch's border, in rings of faces.
inline face_descriptor central_face(const Mesh& m, const std::vector<std::size_t>& patch, std::size_t id)
{
  // Rings from the border of the patch inwards; the last face reached is the most central.
  std::vector<face_descriptor> ring;
  std::vector<char> reached(patch.size(), 0);
  for(face_descriptor f : faces(m))
  {
    if(patch[f] != id)
      continue;
    for(auto h : CGAL::halfedges_around_face(halfedge(f, m), m))
      if(is_border(opposite(h, m), m) || patch[face(opposite(h, m), m)] != id)
      {
        ring.push_back(f);
        reached[f] = 1;
        break;
      }
  }
  face_descriptor last = ring.empty() ? *faces(m).begin() : ring.back();
  for(std::size_t i = 0; i < ring.size(); ++i)
  {
    last = ring[i];
    for(auto h : CGAL::halfedges_around_face(halfedge(ring[i], m), m))
    {
      if(is_border(opposite(h, m), m))
        continue;
      const face_descriptor g = face(opposite(h, m), m);
      if(patch[g] == id && !reached[g])
      {
        reached[g] = 1;
        ring.push_back(g);
      }
    }
  }
  return last;
}

struct Leakage
{
  double radius = 0;      // radius of the dilation
  double inside = 0;      // area of the dilation inside the seed's planar face
  double beyond = 0;      // area of the dilation beyond its border
};

// Dilates `seed` until `inside_area` of the dilation lies inside the seed's patch; the radius and
// the areas inside and beyond.
inline Leakage leakage_at_inside_area(const Mesh& m, face_descriptor seed, const std::vector<std::size_t>& patch,
                                      double inside_area, IM::Face_band_solver<Mesh>& band, double first_guess)
{
  const std::set<face_descriptor> seeds{seed};
  auto area_inside = [&](const std::set<face_descriptor>& grown) {
    double a = 0;
    for(face_descriptor f : grown)
      if(patch[f] == patch[seed])
        a += face_area(m, f);
    return a;
  };
  // bisection on the radius until the area inside is within 0.2 % of the target
  double low = 0, high = first_guess;
  while(area_inside(dilate(m, seeds, high, band)) < inside_area && high < 1e12)
  {
    low = high;
    high *= 2;
  }
  Leakage result;
  result.radius = high;
  for(int i = 0; i < 40; ++i)
  {
    const double mid = 0.5 * (low + high), a = area_inside(dilate(m, seeds, mid, band));
    (a < inside_area ? low : high) = mid;
    result.radius = high;
    if(std::abs(a - inside_area) < 0.002 * inside_area)
    {
      result.radius = mid;
      break;
    }
  }
  const std::set<face_descriptor> grown = dilate(m, seeds, result.radius, band);
  result.inside = area_inside(grown);
  result.beyond = area_of(m, grown) - result.inside;
  return result;
}

// The figure of merit of one mesh and one choice of normals: for each of the three largest planar faces,
// Euclidean and isophotic dilations of its central face until `inside_fraction` of it is covered; the
// areas beyond their borders are summed, the radii averaged.
struct Figure_of_merit
{
  Leakage euclidean, isophotic;
  double ratio() const { return euclidean.beyond > 0 ? isophotic.beyond / euclidean.beyond : 0.; }
};

template <typename IsophoticParameters>
Figure_of_merit figure_of_merit(const Mesh& m, const Part& part, const IsophoticParameters& isophotic_parameters,
                                double inside_fraction = 0.8)
{
  const std::vector<std::size_t>& patch = part.patch;
  const double h = mean_edge_length(m);
  IM::Face_band_solver<Mesh> euclidean(m, IM::parameters::isophotic_weight(0));
  IM::Face_band_solver<Mesh> isophotic(m, isophotic_parameters);
  Figure_of_merit result;
  const std::vector<std::size_t> ids = largest_patches(m, patch, part.planar, 3);
  for(std::size_t id : ids)
  {
    double patch_area = 0;
    for(face_descriptor f : faces(m))
      if(patch[f] == id)
        patch_area += face_area(m, f);
    const face_descriptor seed = central_face(m, patch, id);
    for(auto [band, total] : {std::make_pair(&euclidean, &result.euclidean), std::make_pair(&isophotic, &result.isophotic)})
    {
      const Leakage l = leakage_at_inside_area(m, seed, patch, inside_fraction * patch_area, *band, 4 * h);
      total->radius += l.radius / double(ids.size());
      total->inside += l.inside;
      total->beyond += l.beyond;
    }
  }
  return result;
}

} // namespace scan_helpers

#endif // ISOPHOTIC_METRIC_EXAMPLES_SCAN_HELPERS_H
