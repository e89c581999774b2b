// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Output helpers shared by the continuous examples (parametric and implicit surfaces, given by Eigen
// points rather than by a CGAL mesh): coloured triangle meshes with per-vertex colours, distance colour
// maps with level-set bands, and the zero level set of a function sampled on a grid.
// The PLY writing and the colour type are those of example_output.h.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H
#define ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H

#include "example_output.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace continuous_output {

using example_output::Colour;

// Triangles with one colour per vertex, on Eigen points.
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
    return example_output::write_coloured_ply(file, points, triangles, colours, example_output::Colours_on::vertices);
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

// A saturated ramp (red near, through yellow and green, to blue far) with dark bands of width
// 15 % at multiples of `spacing`: for level sets on curved, shaded surfaces.
inline Colour banded_colour(double d, double d_max, double spacing)
{
  if(!std::isfinite(d)) return {90, 90, 90};
  const double t = std::clamp(d / d_max, 0., 1.);
  const double stops[4][3] = {{220, 40, 30}, {240, 210, 40}, {60, 180, 80}, {40, 80, 220}};
  const double x = 3. * t;
  const int a = std::min(2, int(x));
  const double f = x - a;
  Colour c;
  for(int k = 0; k < 3; ++k) c[k] = static_cast<unsigned char>((1 - f) * stops[a][k] + f * stops[a + 1][k]);
  const double phase = d / spacing - std::floor(d / spacing);
  if(phase < 0.15)
    for(auto& channel : c) channel = static_cast<unsigned char>(channel / 6);
  return c;
}

// Zero level set of a function sampled at the nodes of an (nx, ny, nz) grid with spacing h from
// `origin` (node (i,j,k) has index i + nx (j + ny k)), by marching tetrahedra: every cube is cut
// into the 6 tetrahedra around its main diagonal, and every tetrahedron the level set crosses
// gives one or two triangles, oriented so that their normals point towards positive values.
// Vertices on a grid edge are shared.  Colours are filled by `colour(point)`.
template <typename ColourOf>
void add_zero_level_set(Coloured_mesh& mesh, const std::vector<double>& values, const Eigen::Vector3d& origin,
                        double h, int nx, int ny, int nz, const ColourOf& colour)
{
  auto index = [&](int i, int j, int k) { return std::size_t(i) + std::size_t(nx) * (std::size_t(j) + std::size_t(ny) * k); };
  std::unordered_map<std::uint64_t, int> edge_vertex;
  auto vertex_on_edge = [&](std::size_t a, std::size_t b, const Eigen::Vector3d& pa, const Eigen::Vector3d& pb) {
    const std::uint64_t key = std::uint64_t(std::min(a, b)) * std::uint64_t(values.size()) + std::max(a, b);
    auto it = edge_vertex.find(key);
    if(it != edge_vertex.end()) return it->second;
    const double t = values[a] / (values[a] - values[b]);
    const Eigen::Vector3d p = pa + t * (pb - pa);
    return edge_vertex[key] = mesh.add_point(p, colour(p));
  };
  // The 6 tetrahedra 0 - e_a - e_a+e_b - 7 of the cube (corner c has offset bits x=1, y=2, z=4).
  const int tetrahedra[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for(int k = 0; k + 1 < nz; ++k)
    for(int j = 0; j + 1 < ny; ++j)
      for(int i = 0; i + 1 < nx; ++i)
      {
        std::size_t node[8];
        Eigen::Vector3d position[8];
        bool negative = false, positive = false;
        for(int c = 0; c < 8; ++c)
        {
          const int a = i + (c & 1), b = j + ((c >> 1) & 1), e = k + ((c >> 2) & 1);
          node[c] = index(a, b, e);
          position[c] = origin + h * Eigen::Vector3d(a, b, e);
          (values[node[c]] < 0. ? negative : positive) = true;
        }
        if(!negative || !positive) continue;
        for(const auto& tet : tetrahedra)
        {
          std::vector<int> in, out;
          for(int c : tet) (values[node[c]] < 0. ? in : out).push_back(c);
          if(in.empty() || out.empty()) continue;
          std::vector<int> polygon; // crossing points, in cyclic order
          if(in.size() == 1 || out.size() == 1)
          {
            const std::vector<int>& lone = in.size() == 1 ? in : out;
            const std::vector<int>& rest = in.size() == 1 ? out : in;
            for(int c : rest) polygon.push_back(vertex_on_edge(node[lone[0]], node[c], position[lone[0]], position[c]));
          }
          else // two and two: a quadrilateral
          {
            polygon.push_back(vertex_on_edge(node[in[0]], node[out[0]], position[in[0]], position[out[0]]));
            polygon.push_back(vertex_on_edge(node[in[0]], node[out[1]], position[in[0]], position[out[1]]));
            polygon.push_back(vertex_on_edge(node[in[1]], node[out[1]], position[in[1]], position[out[1]]));
            polygon.push_back(vertex_on_edge(node[in[1]], node[out[0]], position[in[1]], position[out[0]]));
          }
          Eigen::Vector3d inside = Eigen::Vector3d::Zero(), outside = Eigen::Vector3d::Zero();
          for(int c : in) inside += position[c] / double(in.size());
          for(int c : out) outside += position[c] / double(out.size());
          for(std::size_t q = 1; q + 1 < polygon.size(); ++q)
          {
            std::array<int, 3> t{polygon[0], polygon[q], polygon[q + 1]};
            const Eigen::Vector3d normal = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]);
            if(normal.dot(outside - inside) < 0.) std::swap(t[1], t[2]);
            mesh.triangles.push_back(t);
          }
        }
      }
}

} // namespace continuous_output

#endif // ISOPHOTIC_METRIC_EXAMPLES_CONTINUOUS_OUTPUT_H
