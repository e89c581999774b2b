// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Output code shared by the examples: coloured triangle soups written as binary PLY files (colours
// per vertex or per face, for `f3d --scalars=RGB`, with `--cells` for face colours), colour maps,
// side-by-side placement of copies of a mesh, vertex and face picking, file naming.
#ifndef ISOPHOTIC_METRIC_EXAMPLES_EXAMPLE_OUTPUT_H
#define ISOPHOTIC_METRIC_EXAMPLES_EXAMPLE_OUTPUT_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace example_output {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
typedef boost::graph_traits<Mesh>::face_descriptor face_descriptor;

// RGB, 0 to 255 per channel: the bytes written to the PLY files.
typedef std::array<unsigned char, 3> Colour;

// ---- Colours --------------------------------------------------------------------------------------

// Blend of two colours, t in [0,1].
inline Colour mix(const Colour& a, const Colour& b, double t)
{
  Colour c;
  for(int i = 0; i < 3; ++i)
    c[i] = static_cast<unsigned char>(std::lround((1 - t) * a[i] + t * b[i]));
  return c;
}

// A sequential colour map from near (yellow) to far (dark blue) for t in [0,1].
inline Colour ramp(double t)
{
  static const Colour stops[5] = {{253, 231, 37}, {94, 201, 98}, {33, 145, 140}, {59, 82, 139}, {68, 1, 84}};
  t = std::clamp(t, 0., 1.) * 4;
  const int i = std::min(3, static_cast<int>(t));
  return mix(stops[i], stops[i + 1], t - i);
}

// Distinct colours for a few labels (Voronoi cells): a fixed palette of 12, repeated.
inline Colour label_colour(std::size_t label)
{
  static const Colour palette[12] = {{228, 26, 28},  {55, 126, 184},  {77, 175, 74},   {152, 78, 163},
                                     {255, 127, 0},  {240, 220, 50},  {166, 86, 40},   {247, 129, 191},
                                     {120, 120, 120}, {102, 194, 165}, {141, 160, 203}, {166, 216, 84}};
  return palette[label % 12];
}

// Distinct colours for any number of patches: hues by the golden angle, alternating lighter and darker,
// so that neighbouring indices never look alike.
inline Colour patch_colour(std::size_t i)
{
  const double h = std::fmod(0.61803398875 * double(i), 1.0) * 6, v = i % 2 ? 0.95 : 0.75, s = 0.6;
  const int sector = static_cast<int>(h);
  const double f = h - sector, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const std::array<std::array<double, 3>, 6> rgb{{{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}}};
  const auto& c = rgb[sector % 6];
  return {static_cast<unsigned char>(255 * c[0]), static_cast<unsigned char>(255 * c[1]),
          static_cast<unsigned char>(255 * c[2])};
}

// ---- PLY writing ----------------------------------------------------------------------------------

enum class Colours_on { vertices, faces };

// Little-endian bytes, written one by one so that the files are the same on any machine.
inline void put_little_endian(std::ostream& out, std::uint32_t bits, int bytes)
{
  for(int i = 0; i < bytes; ++i)
    out.put(static_cast<char>((bits >> (8 * i)) & 0xFF));
}

inline void put_little_endian_float(std::ostream& out, double x)
{
  const float f = static_cast<float>(x);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put_little_endian(out, bits, 4);
}

// The one PLY writer: binary little endian, float coordinates, int vertex indices, uchar red/green/blue
// on the vertices or on the faces. `points` holds anything with x(), y(), z() (CGAL points, Eigen
// vectors), `triangles` three vertex indices each, `colours` one colour per point or per triangle.
template <class PointRange, class TriangleRange>
bool write_coloured_ply(const std::string& filename, const PointRange& points, const TriangleRange& triangles,
                        const std::vector<Colour>& colours, Colours_on colours_on)
{
  const bool per_face = colours_on == Colours_on::faces;
  std::ofstream out(filename, std::ios::binary);
  const char* colour_properties = "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\n" << (per_face ? "" : colour_properties)
      << "element face " << triangles.size() << "\nproperty list uchar int vertex_indices\n"
      << (per_face ? colour_properties : "") << "end_header\n";
  auto put_bytes = [&](std::uint32_t bits, int n) { put_little_endian(out, bits, n); };
  auto put_float = [&](double x) { put_little_endian_float(out, x); };
  std::size_t i = 0;
  for(const auto& p : points)
  {
    put_float(p.x());
    put_float(p.y());
    put_float(p.z());
    if(!per_face)
      for(unsigned char c : colours[i])
        put_bytes(c, 1);
    ++i;
  }
  i = 0;
  for(const auto& triangle : triangles)
  {
    put_bytes(3, 1);
    for(const auto v : triangle)
      put_bytes(static_cast<std::uint32_t>(v), 4);
    if(per_face)
      for(unsigned char c : colours[i])
        put_bytes(c, 1);
    ++i;
  }
  return bool(out);
}

// ---- Coloured triangle soup -----------------------------------------------------------------------

// Which corner of a face of a mesh comes first in its triangle: the source or the target of
// halfedge(f). The same triangle either way; the geodesic and the morphology pictures were written
// with different first corners, and each keeps its own so that their files stay the same.
enum class First_corner { source_of_halfedge, target_of_halfedge };

// Triangles with one colour per vertex and one per face; either set is written.
struct Coloured_soup
{
  std::vector<Point> points;
  std::vector<Colour> vertex_colours;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Colour> face_colours;

  std::uint32_t add_point(const Point& p, const Colour& c = {0, 0, 0})
  {
    points.push_back(p);
    vertex_colours.push_back(c);
    return static_cast<std::uint32_t>(points.size() - 1);
  }

  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Colour& colour = {0, 0, 0})
  {
    triangles.push_back({a, b, c});
    face_colours.push_back(colour);
  }

  // A copy of the triangle mesh `m` moved by `offset`, coloured per vertex and per face by the two functions.
  void add_mesh(const Mesh& m, const Vector& offset,
                const std::function<Colour(vertex_descriptor)>& vertex_colour,
                const std::function<Colour(face_descriptor)>& face_colour,
                First_corner first_corner = First_corner::source_of_halfedge)
  {
    std::vector<std::uint32_t> index(m.number_of_vertices() + m.number_of_removed_vertices());
    for(vertex_descriptor v : vertices(m))
      index[v] = add_point(m.point(v) + offset, vertex_colour(v));
    for(face_descriptor f : faces(m))
    {
      auto h = halfedge(f, m);
      if(first_corner == First_corner::target_of_halfedge)
        h = next(h, m);
      add_triangle(index[source(h, m)], index[target(h, m)], index[target(next(h, m), m)], face_colour(f));
    }
  }

  // A tube of radius `r` around a polyline, so that a path shows from any viewpoint.
  void add_tube(const std::vector<Point>& line, double r, const Colour& c, int sides = 8)
  {
    for(std::size_t k = 0; k + 1 < line.size(); ++k)
    {
      const Vector axis = line[k + 1] - line[k];
      const double length = std::sqrt(axis.squared_length());
      if(length < 1e-12 * r)
        continue;
      const Vector t = axis / length;
      // any unit vector orthogonal to t
      Vector a = std::abs(t.x()) < 0.9 ? CGAL::cross_product(t, Vector(1, 0, 0)) : CGAL::cross_product(t, Vector(0, 1, 0));
      a = a / std::sqrt(a.squared_length());
      const Vector b = CGAL::cross_product(t, a);
      // spheres at the joints would be nicer; slightly longer segments close the gaps well enough
      const Point ends[2] = {line[k] - 0.5 * r * t, line[k + 1] + 0.5 * r * t};
      const std::uint32_t base = static_cast<std::uint32_t>(points.size());
      for(const Point& e : ends)
        for(int s = 0; s < sides; ++s)
        {
          const double angle = 2. * M_PI * s / sides;
          add_point(e + r * (std::cos(angle) * a + std::sin(angle) * b), c);
        }
      for(int s = 0; s < sides; ++s)
      {
        const std::uint32_t s0 = base + s, s1 = base + (s + 1) % sides;
        add_triangle(s0, s1, s1 + sides, c);
        add_triangle(s0, s1 + sides, s0 + sides, c);
      }
    }
  }

  // Level sets {value = k * period} of a field that is linear on each face of `m` (moved by
  // `offset`), drawn as narrow ribbons of width `width` lying just above the faces.
  template <class ValueMap>
  void add_level_sets(const Mesh& m, const Vector& offset, const ValueMap& value, double period, double width,
                      const Colour& c)
  {
    for(face_descriptor f : faces(m))
    {
      const auto h = halfedge(f, m);
      const vertex_descriptor v[3] = {source(h, m), target(h, m), target(next(h, m), m)};
      const Point p[3] = {m.point(v[0]) + offset, m.point(v[1]) + offset, m.point(v[2]) + offset};
      const double d[3] = {get(value, v[0]), get(value, v[1]), get(value, v[2])};
      if(!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2]))
        continue;
      Vector n = CGAL::cross_product(p[1] - p[0], p[2] - p[0]);
      n = n / std::sqrt(n.squared_length());
      const double lo = std::min({d[0], d[1], d[2]}), hi = std::max({d[0], d[1], d[2]});
      for(double level = std::ceil(lo / period) * period; level < hi; level += period)
      {
        // the two points where the level crosses the edges of the face
        std::vector<Point> ends;
        for(int i = 0; i < 3; ++i)
        {
          const int j = (i + 1) % 3;
          if((d[i] < level) != (d[j] < level))
          {
            const double t = (level - d[i]) / (d[j] - d[i]);
            ends.push_back(p[i] + t * (p[j] - p[i]));
          }
        }
        if(ends.size() != 2)
          continue;
        Vector side = CGAL::cross_product(n, ends[1] - ends[0]);
        const double length = std::sqrt(side.squared_length());
        if(length == 0)
          continue;
        side = (0.5 * width / length) * side;
        const Vector lift = 0.2 * width * n; // above the surface, so the ribbon is not hidden
        const std::uint32_t a = add_point(ends[0] - side + lift, c), b = add_point(ends[0] + side + lift, c),
                            e = add_point(ends[1] + side + lift, c), g = add_point(ends[1] - side + lift, c);
        add_triangle(a, b, e, c);
        add_triangle(a, e, g, c);
      }
    }
  }

  // A small octahedron at p (source and target markers).
  void add_marker(const Point& p, double r, const Colour& c)
  {
    const std::uint32_t base = static_cast<std::uint32_t>(points.size());
    const Vector axes[3] = {Vector(r, 0, 0), Vector(0, r, 0), Vector(0, 0, r)};
    for(const Vector& a : axes)
    {
      add_point(p + a, c);
      add_point(p - a, c);
    }
    for(int i = 0; i < 2; ++i)
      for(int j = 2; j < 4; ++j)
        for(int k = 4; k < 6; ++k)
          add_triangle(base + i, base + j, base + k, c);
  }

  bool write_ply(const std::string& filename, Colours_on colours_on) const
  {
    return write_coloured_ply(filename, points, triangles,
                              colours_on == Colours_on::faces ? face_colours : vertex_colours, colours_on);
  }
};

// Copies of meshes, each moved by its offset and coloured per face by its function, in one PLY file.
inline bool write_face_coloured_meshes(const std::string& filename, const std::vector<const Mesh*>& meshes,
                                       const std::vector<Vector>& offsets,
                                       const std::vector<std::function<Colour(face_descriptor)>>& colours)
{
  Coloured_soup soup;
  for(std::size_t i = 0; i < meshes.size(); ++i)
    soup.add_mesh(*meshes[i], offsets[i], [](vertex_descriptor) { return Colour{0, 0, 0}; }, colours[i],
                  First_corner::target_of_halfedge);
  return soup.write_ply(filename, Colours_on::faces);
}

// ---- Placement and picking ------------------------------------------------------------------------

// Unit horizontal of a view from direction (1, -1.2, 0.8) with +Z up (the geodesic pictures).
inline const Vector oblique_view_horizontal(1.2 / std::sqrt(2.44), 1 / std::sqrt(2.44), 0);

// Offset of the next copy of `m` in a side-by-side picture: along `horizontal` (a unit vector of the
// xy plane with non-negative coordinates, the horizontal of the picture's view), `gap` times the extent
// of the bounding box in that direction; a gap above 1 keeps the copies apart.
inline Vector side_by_side_shift(const Mesh& m, const Vector& horizontal, double gap)
{
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(m);
  const double extent = horizontal.x() * (box.xmax() - box.xmin()) + horizontal.y() * (box.ymax() - box.ymin());
  return gap * extent * horizontal;
}

// The point at fractions `where` of the bounding box of `m`: a place to pick that does not depend on
// the mesh's size or position.
inline Point point_at_fractions(const Mesh& m, const std::array<double, 3>& where)
{
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(m);
  return Point(box.xmin() + where[0] * (box.xmax() - box.xmin()),
               box.ymin() + where[1] * (box.ymax() - box.ymin()),
               box.zmin() + where[2] * (box.zmax() - box.zmin()));
}

// The vertex nearest to the point at fractions `where` of the bounding box.
inline vertex_descriptor vertex_near(const Mesh& m, const std::array<double, 3>& where)
{
  const Point target = point_at_fractions(m, where);
  vertex_descriptor best;
  double best_distance = std::numeric_limits<double>::infinity();
  for(vertex_descriptor v : vertices(m))
  {
    const double d = CGAL::squared_distance(m.point(v), target);
    if(d < best_distance)
    {
      best_distance = d;
      best = v;
    }
  }
  return best;
}

// The triangle whose centroid is nearest to the point at fractions `where` of the bounding box.
inline face_descriptor face_near(const Mesh& m, const std::array<double, 3>& where)
{
  const Point target = point_at_fractions(m, where);
  face_descriptor best;
  double best_distance = std::numeric_limits<double>::infinity();
  for(face_descriptor f : faces(m))
  {
    std::vector<Point> corners;
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

// The file name without directory and extension, to name outputs after the input.
inline std::string stem(const std::string& filename)
{
  std::string s = filename.substr(filename.find_last_of("/\\") + 1);
  return s.substr(0, s.find_last_of('.'));
}

} // namespace example_output

#endif // ISOPHOTIC_METRIC_EXAMPLES_EXAMPLE_OUTPUT_H
