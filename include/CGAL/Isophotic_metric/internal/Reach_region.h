// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The part of a mesh that the paths of bounded metric length from a few sources can touch, found
// and checked without visiting the rest: what a one-shot bounded call prepares instead of the whole
// mesh.
//
// With ds_i^2 = w ds^2 + w' ds*^2 and a constant w > 0, a path of metric length at most B is at
// least sqrt(w) times as long in space, so it stays in the Euclidean ball of radius B / sqrt(w)
// around the sources (its length is at least the chord). Every face such a path crosses meets that
// ball, and the faces meeting it that a path can cross are connected to a source face across edges
// (a path through a vertex in the ball passes between faces of its umbrella, which all meet the
// ball and are joined by edges around it). So a breadth-first walk across edges from the source
// faces, entering only faces that meet the ball, finds every face the propagation bounded by B can
// reach. The region's border is then at distance above B, where the bounded propagation never goes.
#ifndef CGAL_ISOPHOTIC_METRIC_INTERNAL_REACH_REGION_H
#define CGAL_ISOPHOTIC_METRIC_INTERNAL_REACH_REGION_H

#include <CGAL/Isophotic_metric/Geodesics/internal/Intrinsic_triangle_mesh.h>
#include <CGAL/Isophotic_metric/internal/sphere_exact_vertex_normals.h>

#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// The sources of a one-shot call: closed faces, vertices, and faces holding a surface point (the
// point is taken as its whole face: a larger ball, never a smaller one).
template <class TriangleMesh>
struct Reach_sources
{
  typedef boost::graph_traits<TriangleMesh> GT;
  std::vector<typename GT::face_descriptor> faces;
  std::vector<typename GT::vertex_descriptor> vertices;
};

// The faces a bounded propagation from the sources can reach and their corners, each in the order
// of the mesh's own indices (the order of faces(tm) and vertices(tm)).
template <class TriangleMesh>
struct Reach_region
{
  typedef boost::graph_traits<TriangleMesh> GT;
  std::vector<typename GT::face_descriptor> faces;
  std::vector<typename GT::vertex_descriptor> vertices;
};

// Only a Surface_mesh without removed elements is walked this way: its indices bound every check
// below (any other mesh is prepared whole).
template <class TriangleMesh>
struct Has_reach_region : std::false_type {};
template <class Point>
struct Has_reach_region<CGAL::Surface_mesh<Point>> : std::true_type {};

// Finds the region of a Surface_mesh and checks, on the region alone, the conditions of
// validate_triangle_mesh_connectivity(): the halfedges of the faces it holds and of the umbrellas
// of their corners, the faces of those umbrellas (triangles), and that each corner's umbrella is one
// fan holding every face of the region at it. Any condition that fails makes the walk give up
// (false): the whole mesh is then prepared and its validation names the offending element as it
// always did.
template <class Point, class VertexPointMap>
class Reach_region_walk
{
  typedef CGAL::Surface_mesh<Point> Mesh;
  typedef typename Mesh::Vertex_index Vertex_index;
  typedef typename Mesh::Halfedge_index Halfedge_index;
  typedef typename Mesh::Face_index Face_index;

public:
  Reach_region_walk(const Mesh& tm, const VertexPointMap& vpm)
    : tm_(tm), vpm_(vpm), nv_(tm.num_vertices()), nh_(tm.num_halfedges()), nf_(tm.num_faces())
  {}

  // The longest edge of the source faces (around a source vertex: its umbrella's faces), in space;
  // 0 when a source is not a usable element of the mesh.
  double longest_source_edge(const Reach_sources<Mesh>& sources)
  {
    if(tm_.has_garbage() || nh_ >= Intrinsic_triangle_mesh::no_halfedge)
      return 0;
    double longest = 0;
    auto of_face = [&](Face_index f) {
      std::array<Halfedge_index, 3> h;
      if(!face_holds(f, h))
        return false;
      for(int k = 0; k < 3; ++k)
        longest = (std::max)(longest, std::sqrt(squared_distance(point(tm_.target(h[k])), point(tm_.target(h[(k + 1) % 3])))));
      return true;
    };
    for(Face_index f : sources.faces)
      if(!of_face(f))
        return 0;
    for(Vertex_index v : sources.vertices)
    {
      std::vector<Face_index> around;
      if(static_cast<std::size_t>(v) >= nv_ || !umbrella_holds(v, &around) || around.empty())
        return 0; // (an isolated source vertex reaches nothing: the whole-mesh call says so)
      for(Face_index f : around)
        if(!of_face(f))
          return 0;
    }
    return longest;
  }

  // The region of the faces meeting the ball of radius `radius` around the sources, or false when
  // it would hold more than `max_faces` faces or a check fails. Requires longest_source_edge() > 0.
  bool gather(const Reach_sources<Mesh>& sources, double radius, std::size_t max_faces, Reach_region<Mesh>& region)
  {
    // The balls around the sources: a vertex's point, a face's centroid with the distance to its
    // farthest corner. Beyond a few sources, one ball holding them all (a larger ball, never a
    // smaller one).
    std::vector<std::array<double, 4>> balls;
    std::vector<Face_index> start;
    for(Face_index f : sources.faces)
    {
      balls.push_back(bounding_ball(f));
      start.push_back(f);
    }
    for(Vertex_index v : sources.vertices)
    {
      const std::array<double, 3> p = point(v);
      balls.push_back({p[0], p[1], p[2], 0.});
      umbrella_holds(v, &start);
    }
    if(balls.size() > 16)
      balls = {ball_around(balls)};

    // Breadth-first across edges, entering the faces that meet a ball.
    std::vector<unsigned char> seen(nf_, 0); // 1: in the region, 2: tested, outside
    std::vector<Face_index>& faces = region.faces;
    faces.clear();
    for(Face_index f : start)
      if(!seen[f])
      {
        seen[f] = 1;
        faces.push_back(f);
      }
    std::vector<std::uint32_t> corners_in_region(nv_, 0);
    std::vector<Vertex_index>& vertices = region.vertices;
    vertices.clear();
    for(std::size_t next_face = 0; next_face < faces.size(); ++next_face)
    {
      if(faces.size() > max_faces)
        return false;
      std::array<Halfedge_index, 3> h;
      if(!face_holds(faces[next_face], h))
        return false;
      for(int k = 0; k < 3; ++k)
      {
        if(!halfedge_holds(h[k]))
          return false;
        const Vertex_index v = tm_.target(h[k]);
        if(corners_in_region[v]++ == 0)
          vertices.push_back(v);
        const Face_index g = tm_.face(tm_.opposite(h[k]));
        if(g == Mesh::null_face() || seen[g])
          continue;
        std::array<Halfedge_index, 3> hg;
        if(!face_holds(g, hg))
          return false;
        seen[g] = meets_a_ball(bounding_ball(g), balls, radius) ? 1 : 2;
        if(seen[g] == 1)
          faces.push_back(g);
      }
    }
    // The umbrellas of the corners: their normals and the checks of the region's vertices read them.
    for(Vertex_index v : vertices)
    {
      std::vector<Face_index> around;
      if(!umbrella_holds(v, &around))
        return false;
      std::uint32_t in_region = 0;
      for(Face_index f : around)
      {
        std::array<Halfedge_index, 3> h;
        if(!face_holds(f, h))
          return false;
        in_region += seen[f] == 1;
      }
      if(in_region != corners_in_region[v]) // a face of the region at v that the walk around v misses
        return false;
    }
    std::sort(faces.begin(), faces.end());
    std::sort(vertices.begin(), vertices.end());
    return true;
  }

private:
  std::array<double, 3> point(Vertex_index v) const { return to_array(get(vpm_, v)); }

  static double squared_distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
  {
    const std::array<double, 3> d = difference(a, b);
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  }

  // Centroid and distance to the farthest corner of a face that passed face_holds().
  std::array<double, 4> bounding_ball(Face_index f) const
  {
    const Halfedge_index h0 = tm_.halfedge(f), h1 = tm_.next(h0), h2 = tm_.next(h1);
    const std::array<double, 3> p[3] = {point(tm_.target(h0)), point(tm_.target(h1)), point(tm_.target(h2))};
    std::array<double, 4> ball{};
    for(int i = 0; i < 3; ++i)
      ball[i] = (p[0][i] + p[1][i] + p[2][i]) / 3;
    const std::array<double, 3> c{ball[0], ball[1], ball[2]};
    for(int k = 0; k < 3; ++k)
      ball[3] = (std::max)(ball[3], std::sqrt(squared_distance(c, p[k])));
    return ball;
  }

  // A ball holding the given balls: centred at the middle of their bounding box.
  static std::array<double, 4> ball_around(const std::vector<std::array<double, 4>>& balls)
  {
    std::array<double, 3> low = {balls[0][0], balls[0][1], balls[0][2]}, high = low;
    for(const auto& b : balls)
      for(int i = 0; i < 3; ++i)
      {
        low[i] = (std::min)(low[i], b[i]);
        high[i] = (std::max)(high[i], b[i]);
      }
    std::array<double, 4> around{};
    for(int i = 0; i < 3; ++i)
      around[i] = 0.5 * (low[i] + high[i]);
    const std::array<double, 3> c{around[0], around[1], around[2]};
    for(const auto& b : balls)
      around[3] = (std::max)(around[3], std::sqrt(squared_distance(c, {b[0], b[1], b[2]})) + b[3]);
    around[3] *= 1 + 1e-9; // (the rounding of the sums above)
    return around;
  }

  // Whether a face, inside its bounding ball, may meet the ball of radius `radius` around a source:
  // never false when it does (the distance between two points of the balls is at least the distance
  // of their centres minus both radii; the slack covers the rounding of centres and distances). A
  // face with a non-finite corner may: it joins the region, whose set-up then fails on it.
  static bool meets_a_ball(const std::array<double, 4>& face_ball, const std::vector<std::array<double, 4>>& balls, double radius)
  {
    for(const auto& b : balls)
    {
      const double d = std::sqrt(squared_distance({face_ball[0], face_ball[1], face_ball[2]}, {b[0], b[1], b[2]}));
      const double reach = radius + face_ball[3] + b[3];
      if(!(d - reach > 1e-9 * (d + reach)) || !std::isfinite(d + reach))
        return true;
    }
    return false;
  }

  // Face f is a triangle of valid halfedges bounding it; h receives them from halfedge(f).
  bool face_holds(Face_index f, std::array<Halfedge_index, 3>& h) const
  {
    if(static_cast<std::size_t>(f) >= nf_)
      return false;
    h[0] = tm_.halfedge(f);
    if(static_cast<std::size_t>(h[0]) >= nh_)
      return false;
    h[1] = tm_.next(h[0]);
    if(static_cast<std::size_t>(h[1]) >= nh_)
      return false;
    h[2] = tm_.next(h[1]);
    return static_cast<std::size_t>(h[2]) < nh_ && tm_.next(h[2]) == h[0] && h[1] != h[0] && h[2] != h[0] &&
           tm_.face(h[0]) == f && tm_.face(h[1]) == f && tm_.face(h[2]) == f;
  }

  // The conditions of check_halfedge_structure() on one halfedge (its opposite is h ^ 1, so the
  // ones on opposites hold by construction).
  bool halfedge_holds(Halfedge_index h) const
  {
    const std::size_t n = tm_.next(h), p = tm_.prev(h), t = tm_.target(h);
    if(n >= nh_ || p >= nh_ || t >= nv_)
      return false;
    const Halfedge_index hn(static_cast<typename Mesh::size_type>(n)), hp(static_cast<typename Mesh::size_type>(p));
    const Face_index f = tm_.face(h);
    const std::size_t to = tm_.target(tm_.opposite(h)), tno = tm_.target(tm_.opposite(hn));
    return tm_.prev(hn) == h && tm_.next(hp) == h && to < nv_ && to != t && tno == t && tm_.face(hn) == f &&
           tm_.face(tm_.opposite(h)) != f && (f == Mesh::null_face() || static_cast<std::size_t>(f) < nf_);
  }

  // The umbrella of v is one fan of valid halfedges ending at v, with at most one border halfedge;
  // `faces` receives its faces.
  bool umbrella_holds(Vertex_index v, std::vector<Face_index>* faces) const
  {
    const Halfedge_index first = tm_.halfedge(v);
    if(first == Mesh::null_halfedge())
      return true;
    if(static_cast<std::size_t>(first) >= nh_ || tm_.target(first) != v)
      return false;
    std::size_t steps = 0, border = 0;
    Halfedge_index h = first;
    do
    {
      if(++steps > nh_ || !halfedge_holds(h) || tm_.target(h) != v)
        return false;
      if(tm_.face(h) == Mesh::null_face())
        ++border;
      else
        faces->push_back(tm_.face(h));
      h = tm_.opposite(tm_.next(h));
    } while(h != first);
    return border <= 1;
  }

  const Mesh& tm_;
  const VertexPointMap& vpm_;
  const std::size_t nv_, nh_, nf_;
};

// build_intrinsic_triangle_mesh() for the faces of a region only: vertices and faces numbered
// among themselves (vertices in their order in the region), the region's border as the mesh's
// border.
template <class TriangleMesh, class EdgeLength, class VertexVector, class FaceVector, class VertexIdMap, class FaceIdMap>
void build_intrinsic_triangle_mesh_of_region(Intrinsic_triangle_mesh& mesh, const TriangleMesh& tm,
                                             const Reach_region<TriangleMesh>& region, const EdgeLength& edge_length,
                                             VertexVector& vertices_, FaceVector& faces_, VertexIdMap&& vertex_id,
                                             FaceIdMap&& face_id)
{
  typedef Intrinsic_triangle_mesh Mesh;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  vertices_.clear();
  vertices_.reserve(region.vertices.size());
  for(auto v : region.vertices)
  {
    put(vertex_id, v, static_cast<std::uint32_t>(vertices_.size()));
    vertices_.push_back(v);
  }
  const std::size_t nf = region.faces.size();
  FaceVector input_faces;
  input_faces.reserve(nf);
  for(face_descriptor f : region.faces)
  {
    put(face_id, f, static_cast<std::uint32_t>(input_faces.size()));
    input_faces.push_back(f);
  }
  // (the walk checked every face of the region: triangles of consistent halfedges)
  Huge_page_vector<std::uint32_t> input_corner_vertex(3 * nf), input_opposite(3 * nf);
  for(std::uint32_t position = 0; position < nf; ++position)
  {
    const halfedge_descriptor h0 = halfedge(input_faces[position], tm);
    const halfedge_descriptor h[3] = {h0, next(h0, tm), next(next(h0, tm), tm)};
    for(int k = 0; k < 3; ++k)
    {
      input_corner_vertex[3 * position + k] = get(vertex_id, source(h[k], tm));
      input_opposite[3 * position + k] = Mesh::no_halfedge;
      const halfedge_descriptor o = opposite(h[k], tm);
      if(is_border(o, tm))
        continue;
      const std::uint32_t g = get(face_id, face(o, tm));
      if(g >= nf)
        continue; // a face outside the region: its border
      const halfedge_descriptor g0 = halfedge(input_faces[g], tm);
      input_opposite[3 * position + k] = 3 * g + (o == g0 ? 0 : o == next(g0, tm) ? 1 : 2);
    }
  }
  build_from_read_faces(mesh, edge_length, vertices_, input_faces, input_corner_vertex, input_opposite, faces_, face_id);
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_INTERNAL_REACH_REGION_H
