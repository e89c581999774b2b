// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Checks that a mesh can be processed by the package; every algorithm of the package calls it
// first, so that bad input raises an exception naming the offending element instead of crashing.
#ifndef CGAL_ISOPHOTIC_METRIC_VALIDATE_TRIANGLE_MESH_H
#define CGAL_ISOPHOTIC_METRIC_VALIDATE_TRIANGLE_MESH_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/internal/Element_number_map.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <boost/graph/graph_traits.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Builds an error message from pieces: message("face ", 17, " has ", 4, " vertices").
template <typename... Parts>
std::string message(const Parts&... parts)
{
  std::ostringstream out;
  out.precision(17);
  (out << ... << parts);
  return out.str();
}

// What to do about a broken halfedge structure, which no repair function can walk safely.
constexpr const char* rebuild_hint = "rebuild the mesh from its polygons, e.g. with CGAL::IO::read_polygon_mesh()";

// Checks the pointer structure of every halfedge with O(1) work per halfedge, before anything
// walks around a face or a vertex: a corrupted structure could otherwise loop forever.
template <typename TriangleMesh, typename HalfedgeIndexMap>
void check_halfedge_structure(const TriangleMesh& tm, HalfedgeIndexMap hidx)
{
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;

  for(halfedge_descriptor h : halfedges(tm))
  {
    const auto id = get(hidx, h);
    if(next(h, tm) == GT::null_halfedge() || prev(h, tm) == GT::null_halfedge() ||
       opposite(h, tm) == GT::null_halfedge())
      throw Invalid_mesh_error(message("halfedge ", id, " has a null next, prev or opposite halfedge; ", rebuild_hint));
    const halfedge_descriptor of_edge = halfedge(edge(h, tm), tm);
    if(opposite(h, tm) == h || opposite(opposite(h, tm), tm) != h ||
       (of_edge != h && of_edge != opposite(h, tm)))
      throw Invalid_mesh_error(message("halfedge ", id, " has an inconsistent opposite halfedge; ", rebuild_hint));
    if(prev(next(h, tm), tm) != h || next(prev(h, tm), tm) != h)
      throw Invalid_mesh_error(message("halfedge ", id, " has inconsistent next and prev halfedges; ", rebuild_hint));
    if(target(h, tm) == GT::null_vertex())
      throw Invalid_mesh_error(message("halfedge ", id, " has no target vertex; ", rebuild_hint));
    if(target(h, tm) != source(next(h, tm), tm))
      throw Invalid_mesh_error(message("halfedge ", id, " does not end where its next halfedge starts; ", rebuild_hint));
    if(target(h, tm) == source(h, tm))
      throw Invalid_mesh_error(message("halfedge ", id, " is a loop (same source and target vertex); ", rebuild_hint));
    if(face(h, tm) != face(next(h, tm), tm))
      throw Invalid_mesh_error(message("halfedge ", id, " and its next halfedge belong to different faces; ", rebuild_hint));
    if(face(h, tm) == face(opposite(h, tm), tm))
      throw Invalid_mesh_error(message("halfedge ", id, " has the same face on both sides of its edge; ", rebuild_hint));
  }
}

// Other meshes: no quick check (the generic one below runs).
template <typename TriangleMesh>
bool connectivity_holds_quickly(const TriangleMesh&)
{
  return false;
}

// A Surface_mesh without removed elements, read through its index arrays in a few streaming
// passes: true when every condition of validate_triangle_mesh_connectivity() holds. Its opposite
// halfedges are implicit (h ^ 1), so the conditions on them hold by construction; the umbrella
// of a vertex is one fan when the walk around it meets all the halfedges that end at it (counted
// beforehand, instead of a flag per halfedge). False as soon as a condition fails (the generic
// check then finds the first offending element and names it), and for a mesh with removed
// elements.
template <typename Point>
bool connectivity_holds_quickly(const CGAL::Surface_mesh<Point>& tm)
{
  typedef CGAL::Surface_mesh<Point> Mesh;
  typedef typename Mesh::Vertex_index Vertex_index;
  typedef typename Mesh::Halfedge_index Halfedge_index;
  typedef typename Mesh::Face_index Face_index;
  if(tm.has_garbage())
    return false;
  const std::size_t nv = tm.num_vertices(), nh = tm.num_halfedges(), nf = tm.num_faces();
  if(nh >= (std::numeric_limits<std::uint32_t>::max)() / 2)
    return false;

  // 1. Pointer structure; how many halfedges end at each vertex.
  Huge_page_vector<std::uint32_t> ending_at(nv, 0);
  for(std::size_t i = 0; i < nh; ++i)
  {
    const Halfedge_index h(static_cast<typename Mesh::size_type>(i));
    const std::size_t n = tm.next(h), t = tm.target(h);
    if(n >= nh || t >= nv)
      return false;
    const Halfedge_index hn(static_cast<typename Mesh::size_type>(n));
    const Face_index f = tm.face(h);
    // (prev(next(h)) == h for every h makes next a permutation and prev its inverse: next(prev(h))
    // == h follows; the others read the halfedge pair of next(h), one cache line)
    if(tm.prev(hn) != h || tm.target(tm.opposite(h)) == Vertex_index(t) ||
       tm.target(tm.opposite(hn)) != Vertex_index(t) || tm.face(hn) != f || tm.face(tm.opposite(h)) == f ||
       (f != Mesh::null_face() && static_cast<std::size_t>(f) >= nf))
      return false;
    ++ending_at[t];
  }
  // 2. Faces are triangles.
  for(std::size_t i = 0; i < nf; ++i)
  {
    const Face_index f(static_cast<typename Mesh::size_type>(i));
    const Halfedge_index h = tm.halfedge(f);
    if(static_cast<std::size_t>(h) >= nh || tm.face(h) != f)
      return false;
    const Halfedge_index h1 = tm.next(h), h2 = tm.next(h1);
    if(h1 == h || h2 == h || tm.next(h2) != h)
      return false;
  }
  // 3. Vertices point to a halfedge ending at them, around which one fan with at most one
  //    border halfedge holds every halfedge ending at them.
  for(std::size_t i = 0; i < nv; ++i)
  {
    const Vertex_index v(static_cast<typename Mesh::size_type>(i));
    const Halfedge_index first = tm.halfedge(v);
    if(first == Mesh::null_halfedge())
    {
      if(ending_at[i] != 0)
        return false;
      continue;
    }
    if(static_cast<std::size_t>(first) >= nh || tm.target(first) != v)
      return false;
    std::uint32_t steps = 0, border = 0;
    Halfedge_index h = first;
    do
    {
      if(++steps > ending_at[i])
        return false;
      border += tm.face(h) == Mesh::null_face();
      h = tm.opposite(tm.next(h));
    } while(h != first);
    if(steps != ending_at[i] || border > 1)
      return false;
  }
  return true;
}

} // namespace internal

namespace internal {

// Steps 1-3 of validate_triangle_mesh(): the halfedge structure, triangles, manifold vertices.
// Meshes given by their edge lengths are checked by this part only (their points are not used).
template <typename TriangleMesh>
void validate_triangle_mesh_connectivity(const TriangleMesh& tm)
{
  using internal::message;

  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;

  if(internal::connectivity_holds_quickly(tm))
    return;

  const auto vidx = CGAL::get_initialized_vertex_index_map(tm);
  const auto hidx = CGAL::get_initialized_halfedge_index_map(tm);
  const auto fidx = CGAL::get_initialized_face_index_map(tm);

  // 1. Pointer structure (after this, walking around faces and vertices terminates).
  internal::check_halfedge_structure(tm, hidx);

  for(vertex_descriptor v : vertices(tm))
  {
    const halfedge_descriptor h = halfedge(v, tm);
    if(h != GT::null_halfedge() && target(h, tm) != v)
      throw Invalid_mesh_error(message("vertex ", get(vidx, v), " points to a halfedge that does not end at it"));
  }

  // 2. Faces are triangles.
  for(face_descriptor f : faces(tm))
  {
    const halfedge_descriptor h = halfedge(f, tm);
    if(h == GT::null_halfedge() || face(h, tm) != f)
      throw Invalid_mesh_error(message("face ", get(fidx, f), " points to a halfedge that does not bound it"));
    const std::size_t degree = CGAL::halfedges_around_face(h, tm).size();
    if(degree != 3)
      throw Invalid_mesh_error(message("face ", get(fidx, f), " has ", degree,
                                       " vertices; a triangle mesh is required (", internal::scan_repair_hint, ")"));
  }

  // 3. Manifold vertices: one umbrella of faces each, at most one border halfedge in it.
  //    Every halfedge must be reached by walking around its target from halfedge(target), and the
  //    walk must meet at most one border halfedge: the two ways a pinched vertex (several fans, what
  //    PMP::non_manifold_vertices() reports) shows, so this one walk is the whole test.
  {
    internal::Halfedge_number_map<TriangleMesh> reached(tm); // 1 once reached
    for(halfedge_descriptor h : halfedges(tm))
      put(reached, h, 0);
    const std::size_t nb_halfedges = static_cast<std::size_t>(num_halfedges(tm));
    for(vertex_descriptor v : vertices(tm))
    {
      if(halfedge(v, tm) == GT::null_halfedge())
        continue; // isolated vertex: allowed, no edge uses it
      std::size_t steps = 0, border = 0;
      for(halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, tm), tm))
      {
        if(++steps > nb_halfedges)
          throw Invalid_mesh_error(message("vertex ", get(vidx, v), " has a corrupted cycle of incident halfedges"));
        put(reached, h, 1);
        border += is_border(h, tm);
      }
      if(border > 1) // fans joined through their border halfedges into one cycle
        throw Invalid_mesh_error(message("vertex ", get(vidx, v), " is non-manifold: its incident faces form several fans (",
                                         scan_repair_hint, ")"));
    }
    for(halfedge_descriptor h : halfedges(tm))
      if(get(reached, h) != 1)
        throw Invalid_mesh_error(message("vertex ", get(vidx, target(h, tm)),
                                         " is non-manifold: its incident faces form several fans (",
                                         internal::scan_repair_hint, ")"));
  }
}

} // namespace internal

/// \ingroup PkgIsophoticMetricValidation
///
/// \brief checks that `tm` is a triangle mesh the package can process, and throws otherwise.
///
/// The mesh may be open, may have several connected components and isolated vertices.
/// It must have:
/// - a valid halfedge structure (the conditions of `CGAL::is_valid_polygon_mesh()`,
///   except that vertices without incident halfedge are allowed),
/// - triangular faces only,
/// - manifold vertices only (see `CGAL::Polygon_mesh_processing::non_manifold_vertices()`),
/// - finite vertex coordinates,
/// - edges of non-zero length (the two end points differ).
///
/// Elements are named by their index in the order of `vertices(tm)`, `halfedges(tm)` and
/// `faces(tm)` (the index maps of `CGAL::get_initialized_vertex_index_map()` and its siblings),
/// an edge by the indices of its two vertices.
///
/// The cost is linear in the size of the mesh. (Bounded one-shot calls check only the part of the mesh
/// their bound reaches, with the same conditions and messages: see \ref IsophoticMetricReach.)
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph`
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the mesh
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a class model of `ReadablePropertyMap` with
///                    `boost::graph_traits<TriangleMesh>::%vertex_descriptor` as key type and
///                    `%Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_mesh_error if one of the conditions above does not hold; the message names
///         the first offending halfedge, face, vertex or edge.
template <typename TriangleMesh,
          typename NamedParameters = parameters::Default_named_parameters>
void validate_triangle_mesh(const TriangleMesh& tm,
                            const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using internal::message;

  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::edge_descriptor edge_descriptor;

  internal::validate_triangle_mesh_connectivity(tm);

  const auto vidx = CGAL::get_initialized_vertex_index_map(tm);
  // 4. Geometry: finite coordinates, edges of non-zero length.
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));
  for(vertex_descriptor v : vertices(tm))
  {
    const auto& p = get(vpm, v);
    if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
       !std::isfinite(CGAL::to_double(p.z())))
      throw Invalid_mesh_error(message("vertex ", get(vidx, v), " has a non-finite coordinate (",
                                       CGAL::to_double(p.x()), ", ", CGAL::to_double(p.y()), ", ",
                                       CGAL::to_double(p.z()), "); remove it or its faces, or fix the file"));
  }
  for(edge_descriptor e : edges(tm))
  {
    const vertex_descriptor a = source(e, tm), b = target(e, tm);
    const auto& pa = get(vpm, a);
    const auto& pb = get(vpm, b);
    if(CGAL::to_double(pa.x()) == CGAL::to_double(pb.x()) && CGAL::to_double(pa.y()) == CGAL::to_double(pb.y()) &&
       CGAL::to_double(pa.z()) == CGAL::to_double(pb.z()))
      throw Invalid_mesh_error(message("edge (", get(vidx, a), ", ", get(vidx, b),
                                       ") has zero length: its two vertices are at the same point (",
                                       internal::scan_repair_hint, ")"));
  }
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_VALIDATE_TRIANGLE_MESH_H
