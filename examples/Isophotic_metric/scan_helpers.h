// Helpers of the scan examples and tests: seeded noise along the normal (a scan-like copy of a clean
// mesh), the planar face that seeds the figure of merit, and the figure of merit itself: the seed
// dilated in the Euclidean and in the isophotic metric until the same area lies inside its planar
// face; the area of each dilation beyond the face's border, their ratio, and the radii.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_SCAN_HELPERS_H
#define ISOPHOTIC_METRIC_EXAMPLES_SCAN_HELPERS_H

#include "morphology_helpers.h"

#include <algorithm>
#include <cstdint>
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

// The planar faces of a clean mesh: faces connected across edges that bend by less than 1 degree.
inline std::vector<std::size_t> planar_faces(const Mesh& clean)
{
  std::size_t number_of_patches = 0;
  return feature_patches(clean, 1., number_of_patches);
}

// The `n` largest patches, by area, largest first.
inline std::vector<std::size_t> largest_patches(const Mesh& m, const std::vector<std::size_t>& patch, std::size_t n)
{
  std::map<std::size_t, double> area;
  for(face_descriptor f : faces(m))
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
  Leakage result;
  result.radius = radius_for_area(m, seeds, inside_area, band, first_guess, area_inside);
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
Figure_of_merit figure_of_merit(const Mesh& m, const std::vector<std::size_t>& patch,
                                const IsophoticParameters& isophotic_parameters, double inside_fraction = 0.5)
{
  const double h = mean_edge_length(m);
  IM::Face_band_solver<Mesh> euclidean(m, IM::parameters::isophotic_weight(0));
  IM::Face_band_solver<Mesh> isophotic(m, isophotic_parameters);
  Figure_of_merit result;
  const std::vector<std::size_t> ids = largest_patches(m, patch, 3);
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
