// Small output helpers shared by the continuous examples: coloured triangle meshes written as
// binary PLY files (per-vertex RGB), ready for `f3d --scalars=RGB`.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H
#define ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace continuous_output {

using Colour = std::array<unsigned char, 3>;

struct Coloured_mesh
{
  std::vector<Eigen::Vector3d> points;
  std::vector<Colour> colours;
  std::vector<std::array<int, 3>> triangles;

  int add_point(const Eigen::Vector3d& p, const Colour& c)
  {
    points.push_back(p);
    colours.push_back(c);
    return int(points.size()) - 1;
  }

  // A tube of radius r around a polyline (for geodesic curves).
  void add_tube(const std::vector<Eigen::Vector3d>& line, double r, const Colour& c, int sides = 8)
  {
    for(std::size_t k = 0; k + 1 < line.size(); ++k)
    {
      const Eigen::Vector3d axis = line[k + 1] - line[k];
      if(axis.norm() < 1e-12) continue;
      const Eigen::Vector3d t = axis.normalized();
      const Eigen::Vector3d a = t.unitOrthogonal(), b = t.cross(a);
      const int base = int(points.size());
      for(int end = 0; end < 2; ++end)
        for(int s = 0; s < sides; ++s)
        {
          const double angle = 2. * M_PI * s / sides;
          add_point(line[k + end] + r * (std::cos(angle) * a + std::sin(angle) * b), c);
        }
      for(int s = 0; s < sides; ++s)
      {
        const int s1 = (s + 1) % sides;
        triangles.push_back({base + s, base + s1, base + sides + s1});
        triangles.push_back({base + s, base + sides + s1, base + sides + s});
      }
    }
  }

  // A small sphere-like marker (octahedron) at p.
  void add_marker(const Eigen::Vector3d& p, double r, const Colour& c)
  {
    const int base = int(points.size());
    for(int a = 0; a < 3; ++a)
      for(int s : {-1, 1}) add_point(p + s * r * Eigen::Vector3d::Unit(a), c);
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for(const auto& f : faces) triangles.push_back({base + f[0], base + f[1], base + f[2]});
  }

  bool write_ply(const std::string& file) const
  {
    std::ofstream out(file, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << points.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face "
        << triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for(std::size_t k = 0; k < points.size(); ++k)
    {
      const float xyz[3] = {float(points[k].x()), float(points[k].y()), float(points[k].z())};
      out.write(reinterpret_cast<const char*>(xyz), sizeof(xyz));
      out.write(reinterpret_cast<const char*>(colours[k].data()), 3);
    }
    for(const auto& t : triangles)
    {
      const unsigned char three = 3;
      const std::int32_t v[3] = {t[0], t[1], t[2]};
      out.write(reinterpret_cast<const char*>(&three), 1);
      out.write(reinterpret_cast<const char*>(v), sizeof(v));
    }
    return bool(out);
  }
};

// Colour of a distance value: a blue-to-yellow ramp with dark bands at multiples of `spacing`
// (the level sets), grey where the value is infinite.
inline Colour distance_colour(double d, double d_max, double spacing)
{
  if(!std::isfinite(d)) return {90, 90, 90};
  const double t = std::clamp(d / d_max, 0., 1.);
  Colour c{static_cast<unsigned char>(40 + 215 * t), static_cast<unsigned char>(80 + 150 * t),
           static_cast<unsigned char>(230 - 200 * t)};
  const double phase = d / spacing - std::floor(d / spacing);
  if(phase < 0.12)
    for(auto& channel : c) channel = static_cast<unsigned char>(channel / 5);
  return c;
}

} // namespace continuous_output

#endif // ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H
