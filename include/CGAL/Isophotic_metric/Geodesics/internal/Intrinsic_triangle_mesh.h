// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A compact, index-based copy of a triangle mesh's connectivity together with its edge lengths.
// The exact geodesic engine runs on this structure only: geodesics on a piecewise-flat surface
// depend on edge lengths alone, so the same code serves 3D meshes, the R^6-lifted mesh of the
// isophotic metric, and user-given edge lengths.
#ifndef CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_INTRINSIC_TRIANGLE_MESH_H
#define CGAL_ISOPHOTIC_METRIC_GEODESICS_INTERNAL_INTRINSIC_TRIANGLE_MESH_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Geodesics/internal/Huge_page_chunk.h>
#include <CGAL/Isophotic_metric/internal/Element_number_map.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// 2D vector used for triangle unfolding.
struct Vec2
{
  double x, y;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// (coordinates are lengths of a mesh: no overflow concern that would call for std::hypot)
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double length_of(double x, double y) { return std::sqrt(x * x + y * y); }

template <class T, class = void>
struct Is_streamable : std::false_type {};
template <class T>
struct Is_streamable<T, std::void_t<decltype(std::declval<std::ostream&>() << std::declval<const T&>())>>
  : std::true_type {};

/// Names a mesh element in error messages: its own printed form where it has one (e.g. `v17`,
/// `f3` for Surface_mesh), else its position in the mesh's iteration order.
template <class Descriptor>
std::string describe_element(const char* kind, const Descriptor& d, std::size_t position)
{
  std::ostringstream s;
  if constexpr(Is_streamable<Descriptor>::value)
    s << kind << " " << d;
  else
    s << kind << " #" << position;
  return s.str();
}

/// Connectivity and edge lengths of a triangle mesh, with faces numbered 0..F-1 and the three
/// halfedges of face `f` numbered `3f, 3f+1, 3f+2`. Halfedge `3f+k` goes from corner `k` to corner
/// `k+1 (mod 3)` of `f`; corner 0 is `source(halfedge(f))`, corner 1 `target(halfedge(f))`,
/// corner 2 `target(next(halfedge(f)))` (the convention of CGAL's `Face_location`).
/// The face lies on the left of its halfedges (positive y in a halfedge's frame).
class Intrinsic_triangle_mesh
{
public:
  static constexpr std::uint32_t no_halfedge = std::numeric_limits<std::uint32_t>::max();

  std::size_t number_of_vertices() const { return vertex_first_corner_.size() - 1; }
  std::size_t number_of_faces() const { return corner_vertex_.size() / 3; }

  std::size_t number_of_corners() const { return corner_vertex_.size(); }

  static std::uint32_t face(std::uint32_t h) { return h / 3; }
  static std::uint32_t next(std::uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
  static std::uint32_t prev(std::uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }

  /// Vertex at the start of halfedge (equivalently: at corner) `h`.
  std::uint32_t source(std::uint32_t h) const { return corner_vertex_[h]; }
  std::uint32_t target(std::uint32_t h) const { return corner_vertex_[next(h)]; }
  /// The twin halfedge in the neighbouring face, or `no_halfedge` on the mesh boundary.
  std::uint32_t opposite(std::uint32_t h) const { return opposite_[h]; }
  /// Length of the edge of `h`, in units of `length_unit()`.
  double length(std::uint32_t h) const { return length_[h]; }
  /// The unit of every length and distance inside the engine, a power of two near the median edge
  /// length: the engine's numbers stay near 1 whatever the model's units (squared lengths of a
  /// model at 1e-160 would be subnormal, products of four lengths in an area overflow at 1e80),
  /// and converting to the caller's units is exact.
  double length_unit() const { return length_unit_; }

  /// Corners (halfedges starting at `v`) of the faces around vertex `v`.
  const std::uint32_t* corners_begin(std::uint32_t v) const { return vertex_corners_.data() + vertex_first_corner_[v]; }
  const std::uint32_t* corners_end(std::uint32_t v) const { return vertex_corners_.data() + vertex_first_corner_[v + 1]; }

  /// True where shortest paths may bend: boundary vertices, saddles (angle sum above 2*pi) and
  /// the ends of needle edges (below).
  bool is_pseudo_source_candidate(std::uint32_t v) const { return bends_geodesics_[v] != 0; }

  /// True at the ends of an edge shorter than `needle_ratio` times another edge of one of its
  /// faces. Straight geodesics passing between two vertices that close cross the edges around
  /// them within rounding of the vertices, where windows cannot represent them: the pair acts as
  /// one vertex, whose angle sum is theirs together, and each end bends geodesics in every
  /// direction (its windows are lengths of real paths, at most twice the needle's length longer
  /// than the ones they stand for).
  bool bends_geodesics_in_every_direction(std::uint32_t v) const { return bends_geodesics_[v] == 2; }
  static constexpr double needle_ratio = 1e-6;

  /// Position of the third corner of face(h) in the frame of `h`: source at (0,0), target at
  /// (length(h),0), the face on the positive side.
  Vec2 apex(std::uint32_t h) const { return unfold_apex(length_[h], length_[prev(h)], length_[next(h)]); }

  /// Angle of face(h) at source(h), in [0, pi].
  double corner_angle(std::uint32_t h) const
  {
    const Vec2 c = apex(h);
    return std::atan2(c.y, c.x);
  }

  /// The third corner of a triangle with base (0,0)-(a,0) and sides b (from the origin) and c
  /// (from (a,0)), above the base. Stable for needles and caps: the textbook forms
  /// x = (a^2 + b^2 - c^2) / 2a and y = sqrt(b^2 - x^2) lose all digits of x when a << b ~ c (b^2 - c^2
  /// cancels) and half of those of y when the height is small (b^2 - x^2 cancels). Here b^2 - c^2 is
  /// formed as (b - c)(b + c), where b - c is exact when it is small (Sterbenz), and y is twice the
  /// area of Kahan's formula over a, accurate to a few ulps whatever the shape. x is kept within
  /// [-b, b]: lengths that violate the triangle inequality by a rounding (a flat triangle) give
  /// |x| > b, by the violation over a, and the apex then lay as much too far from (a,0) (a needle
  /// of 1.8e-13 off by 1e-17: its long edge 6e-5 too long, and the distances along it with it).
  static Vec2 unfold_apex(double a, double b, double c)
  {
    const double x = std::clamp((a * a + (b - c) * (b + c)) / (2 * a), -b, b);
    return {x, 2 * kahan_area(a, b, c) / a};
  }

  /// Area of a triangle from its side lengths (Kahan, "Miscalculating area and angles of a
  /// needle-like triangle", 2014): sorted p >= q >= r, the factors are formed with parentheses as
  /// written, each exact or with one rounding. Zero for lengths that violate the triangle
  /// inequality by rounding.
  static double kahan_area(double a, double b, double c)
  {
    // (sorted without branches: this runs for every face a propagation crosses)
    const double p = std::max(std::max(a, b), c), r = std::min(std::min(a, b), c);
    const double q = std::max(std::min(a, b), std::min(std::max(a, b), c));
    const double product = (p + (q + r)) * (r - (p - q)) * (r + (p - q)) * (p + (q - r));
    return 0.25 * std::sqrt(std::max(0.0, product));
  }

  /// Positions of the three corners of face(h) in the frame of `h`, indexed by local corner 0,1,2.
  std::array<Vec2, 3> corner_positions(std::uint32_t h) const
  {
    std::array<Vec2, 3> p;
    p[h % 3] = {0, 0};
    p[(h + 1) % 3] = {length_[h], 0};
    p[(h + 2) % 3] = apex(h);
    return p;
  }

  template <class EdgeLength, class VertexVector, class FaceVector, class FaceIdMap>
  friend void build_from_read_faces(Intrinsic_triangle_mesh&, const EdgeLength&, const VertexVector&, const FaceVector&,
                                    const Huge_page_vector<std::uint32_t>&, const Huge_page_vector<std::uint32_t>&,
                                    FaceVector&, FaceIdMap&&);

private:
  Huge_page_vector<std::uint32_t> corner_vertex_;
  Huge_page_vector<std::uint32_t> opposite_;
  Huge_page_vector<double> length_;
  Huge_page_vector<std::uint32_t> vertex_first_corner_{0};
  Huge_page_vector<std::uint32_t> vertex_corners_;
  Huge_page_vector<unsigned char> bends_geodesics_;
  double length_unit_ = 1;
};

/// The `k`-th smallest (0-based) of positive finite numbers, as `std::nth_element` finds it but
/// in two linear passes: a histogram of the leading 16 bits (sign, exponent and 4 bits of the
/// mantissa, in the order of the values for positive numbers) picks the bucket of rank `k`, and
/// only that bucket is sorted partially.
inline double kth_smallest_positive(const double* first, std::size_t n, std::size_t k)
{
  auto bucket = [](double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return static_cast<std::uint32_t>(bits >> 48);
  };
  std::vector<std::uint32_t> count(std::size_t(1) << 16, 0);
  for(std::size_t i = 0; i < n; ++i)
    ++count[bucket(first[i])];
  std::uint32_t b = 0;
  std::size_t below = 0;
  while(below + count[b] <= k)
    below += count[b++];
  std::vector<double> in_bucket;
  in_bucket.reserve(count[b]);
  for(std::size_t i = 0; i < n; ++i)
    if(bucket(first[i]) == b)
      in_bucket.push_back(first[i]);
  std::nth_element(in_bucket.begin(), in_bucket.begin() + (k - below), in_bucket.end());
  return in_bucket[k - below];
}

/// The exponent `e` of `frexp` (x = m 2^e, 0.5 <= m < 1) of the `k`-th smallest (0-based) of
/// positive finite numbers, from a histogram of their exponents (one pass, no sorting).
inline int frexp_exponent_of_kth_smallest(const double* first, std::size_t n, std::size_t k)
{
  std::array<std::uint32_t, 2048> count{};
  for(std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t bits;
    std::memcpy(&bits, &first[i], sizeof bits);
    ++count[bits >> 52]; // the biased exponent: the order of positive numbers
  }
  std::size_t biased = 0, below = 0;
  while(below + count[biased] <= k)
    below += count[biased++];
  if(biased != 0) // normal numbers: m 2^e with e = biased exponent - 1022
    return static_cast<int>(biased) - 1022;
  std::vector<double> subnormal; // (they share the biased exponent 0, not the exponent of frexp)
  std::copy_if(first, first + n, std::back_inserter(subnormal), [](double x) { return !std::isnormal(x); });
  std::nth_element(subnormal.begin(), subnormal.begin() + k, subnormal.end());
  int exponent;
  std::frexp(subnormal[k], &exponent);
  return exponent;
}

/// The angle atan2(y, x) of the vector (x, y), y >= 0, within 1e-12 (odd polynomial of degree 15 on
/// |t| <= tan(pi/8) after an exact-in-exact-arithmetic reduction; the polynomial's error there is
/// 1.4e-13; one division), or NaN for x = y = 0. For deciding comparisons of angle sums: where
/// the bound cannot decide, the caller uses std::atan2.
inline double approximate_atan2(double y, double x)
{
  constexpr double pi = 3.14159265358979323846;
  constexpr double c[8] = {0.9999999999941781,   -0.3333333316754277, 0.19999986211516835, -0.14285197603107297,
                           0.11100775807435093, -0.08972165221395394, 0.06895204208553055, -0.03643033659722185};
  const double ax = std::abs(x), small = (std::min)(y, ax), large = (std::max)(y, ax);
  // atan(small / large) in [0, pi/4]: directly up to tan(pi/8), else pi/4 + atan((s - l) / (s + l))
  // (selections rather than branches: the cases come in no predictable order)
  const bool reduce = small > 0.41421356237309503 * large;
  const double t = (reduce ? small - large : small) / (reduce ? small + large : large), t2 = t * t;
  double p = c[7];
  for(int i = 6; i >= 0; --i)
    p = p * t2 + c[i];
  const double below_diagonal = (reduce ? pi / 4 : 0.) + p * t;
  const double angle = y <= ax ? below_diagonal : pi / 2 - below_diagonal;
  return x >= 0 ? angle : pi - angle;
}

/// Reads the faces of `tm` in the order of `faces(tm)` (their `position`, written to `face_id`) into
/// `input_faces` and, for the halfedge `3 position + k` from corner `k` to corner `k + 1` of each,
/// the number of its source vertex (`vertex_id`) and the position of its opposite halfedge
/// (`no_halfedge` on the boundary), checking that every face is a triangle. The arrays of corners
/// are sized for the faces.
template <class TriangleMesh, class FaceVector, class VertexIdMap, class FaceIdMap>
void read_faces(const TriangleMesh& tm, const VertexIdMap& vertex_id, FaceIdMap& face_id, FaceVector& input_faces,
                Huge_page_vector<std::uint32_t>& input_corner_vertex, Huge_page_vector<std::uint32_t>& input_opposite)
{
  typedef Intrinsic_triangle_mesh Mesh;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor face_descriptor;

  const std::size_t nf = input_corner_vertex.size() / 3;
  input_faces.clear();
  input_faces.reserve(nf);
  std::fill(input_opposite.begin(), input_opposite.end(), Mesh::no_halfedge);
  Huge_page_vector<halfedge_descriptor> input_halfedges(3 * nf);
  for(face_descriptor f : faces(tm))
  {
    const std::uint32_t position = static_cast<std::uint32_t>(input_faces.size());
    input_faces.push_back(f);
    put(face_id, f, position);
    const halfedge_descriptor h0 = halfedge(f, tm);
    halfedge_descriptor h = h0;
    int k = 0;
    do
    {
      if(k == 3)
        throw Invalid_mesh_error(describe_element("face", f, position) + " has more than 3 vertices; a triangle mesh is required (" +
                                 scan_repair_hint + ")");
      if(face(h, tm) != f)
        throw Invalid_mesh_error("invalid halfedge structure around " + describe_element("face", f, position));
      input_halfedges[3 * position + k] = h;
      h = next(h, tm);
      ++k;
    } while(h != h0);
    if(k != 3)
      throw Invalid_mesh_error(describe_element("face", f, position) + " has " + std::to_string(k) + " vertices; a triangle mesh is required (" +
                               scan_repair_hint + ")");
  }
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
  {
    input_corner_vertex[h] = get(vertex_id, source(input_halfedges[h], tm));
    const halfedge_descriptor o = opposite(input_halfedges[h], tm);
    if(is_border(o, tm))
      continue; // the mesh boundary
    const std::uint32_t g = get(face_id, face(o, tm));
    if(g >= nf)
      throw Invalid_mesh_error("invalid halfedge structure around " + describe_element("face", input_faces[Mesh::face(h)], Mesh::face(h)));
    // (without branches: which of the three it is cannot be predicted)
    const std::uint32_t k = (input_halfedges[3 * g + 1] == o) + 2 * (input_halfedges[3 * g + 2] == o);
    if(!(input_halfedges[3 * g + k] == o))
      throw Invalid_mesh_error("invalid halfedge structure around " + describe_element("face", input_faces[Mesh::face(h)], Mesh::face(h)));
    input_opposite[h] = 3 * g + k;
  }
}

/// Other meshes: no quick reading (`read_faces()` runs).
template <class TriangleMesh, class FaceVector, class VertexIdMap, class FaceIdMap>
bool read_faces_quickly(const TriangleMesh&, const VertexIdMap&, FaceIdMap&, FaceVector&, Huge_page_vector<std::uint32_t>&,
                        Huge_page_vector<std::uint32_t>&)
{
  return false;
}

/// `read_faces()` for a Surface_mesh without removed elements, through its index arrays: the
/// corners of a face come with its three halfedges (corner k is the target of halfedge k - 1),
/// and the opposite of a halfedge, its twin h ^ 1, from the position where its own face put it,
/// instead of a search among the halfedges of that face. The same arrays; false, with nothing
/// decided, where the structure is not the expected one (`read_faces()` then names the problem).
template <class Point, class FaceVector, class VertexIdMap, class FaceIdMap>
bool read_faces_quickly(const CGAL::Surface_mesh<Point>& tm, const VertexIdMap& vertex_id, FaceIdMap& face_id,
                        FaceVector& input_faces, Huge_page_vector<std::uint32_t>& input_corner_vertex,
                        Huge_page_vector<std::uint32_t>& input_opposite)
{
  typedef CGAL::Surface_mesh<Point> SM;
  typedef typename SM::Halfedge_index Halfedge_index;
  typedef typename SM::Face_index Face_index;
  typedef Intrinsic_triangle_mesh Mesh;
  const std::size_t nf = input_corner_vertex.size() / 3, nh = tm.num_halfedges();
  if(tm.has_garbage() || nf != tm.num_faces() || nh >= Mesh::no_halfedge)
    return false;
  Huge_page_vector<std::uint32_t> input_halfedges(3 * nf), position_of_halfedge(nh, Mesh::no_halfedge);
  for(std::uint32_t position = 0; position < nf; ++position)
  {
    const Face_index f(position);
    const Halfedge_index h0 = tm.halfedge(f);
    if(static_cast<std::size_t>(h0) >= nh)
      return false;
    const Halfedge_index h1 = tm.next(h0);
    if(static_cast<std::size_t>(h1) >= nh)
      return false;
    const Halfedge_index h2 = tm.next(h1);
    if(static_cast<std::size_t>(h2) >= nh || tm.next(h2) != h0 || h1 == h0 || h2 == h0 || tm.face(h0) != f ||
       tm.face(h1) != f || tm.face(h2) != f)
      return false;
    const Halfedge_index h[3] = {h0, h1, h2};
    for(int k = 0; k < 3; ++k)
    {
      // (the source of h[k], as a generic walk reads it: the target of its twin, in its cache line)
      if(tm.target(tm.opposite(h[k])) != tm.target(h[(k + 2) % 3]))
        return false;
      input_halfedges[3 * position + k] = static_cast<std::uint32_t>(h[k]);
      position_of_halfedge[static_cast<std::size_t>(h[k])] = 3 * position + k;
      input_corner_vertex[3 * position + k] = get(vertex_id, tm.target(h[(k + 2) % 3]));
    }
  }
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
  {
    const Halfedge_index o = tm.opposite(Halfedge_index(input_halfedges[h]));
    input_opposite[h] = position_of_halfedge[static_cast<std::size_t>(o)];
    if(input_opposite[h] == Mesh::no_halfedge && tm.face(o) != SM::null_face())
      return false; // (a halfedge of a face that does not list it)
  }
  input_faces.clear();
  input_faces.reserve(nf);
  for(std::uint32_t position = 0; position < nf; ++position)
  {
    input_faces.push_back(Face_index(position));
    put(face_id, Face_index(position), position);
  }
  return true;
}

/// The part of `build_intrinsic_triangle_mesh()` after the reading: from the faces read
/// (`input_faces`, in the order their `position` refers to, with the vertex numbers of their corners and
/// the positions of their opposite halfedges) and the vertices numbered (`vertices_`).
template <class EdgeLength, class VertexVector, class FaceVector, class FaceIdMap>
void build_from_read_faces(Intrinsic_triangle_mesh& mesh, const EdgeLength& edge_length, const VertexVector& vertices_,
                           const FaceVector& input_faces, const Huge_page_vector<std::uint32_t>& input_corner_vertex,
                           const Huge_page_vector<std::uint32_t>& input_opposite, FaceVector& faces_, FaceIdMap&& face_id);

/// Builds the structure from any BGL triangle mesh; `edge_length(u, v)` returns the length of
/// the edge joining vertices u and v (called once per edge, after the vertices are numbered).
/// Throws Invalid_mesh_error on non-triangle faces, border or halfedge inconsistencies, and
/// non-finite, zero or triangle-inequality-violating lengths. `vertices_` and `faces_` (vectors of
/// vertex and face descriptors) receive the descriptors in index order (vertices in the order of `vertices(tm)`), `vertex_id` and
/// `face_id` (writable property maps) the index of every descriptor.
template <class TriangleMesh, class EdgeLength, class VertexVector, class FaceVector, class VertexIdMap, class FaceIdMap>
void build_intrinsic_triangle_mesh(Intrinsic_triangle_mesh& mesh, const TriangleMesh& tm, const EdgeLength& edge_length,
                                   VertexVector& vertices_, FaceVector& faces_, VertexIdMap&& vertex_id, FaceIdMap&& face_id)
{
  typedef Intrinsic_triangle_mesh Mesh;
  typedef boost::graph_traits<TriangleMesh> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;

  vertices_.clear();
  vertices_.reserve(static_cast<std::size_t>(num_vertices(tm)));
  for(vertex_descriptor v : vertices(tm))
  {
    put(vertex_id, v, static_cast<std::uint32_t>(vertices_.size()));
    vertices_.push_back(v);
  }

  const std::size_t nf = static_cast<std::size_t>(std::distance(faces(tm).begin(), faces(tm).end()));
  if(nf >= Mesh::no_halfedge / 3)
    throw Invalid_mesh_error("mesh too large: more than 1.4e9 faces");

  // The mesh is read in its own order (`position` of a face in faces(tm), used in messages) into
  // flat arrays first: corner vertices and opposite halfedges by position. Everything after works
  // on these arrays. (temporaries from mappings kept for reuse, see Huge_page_chunk.h: a loop of
  // one-shot calls reuses them without page faults)
  FaceVector input_faces;
  Huge_page_vector<std::uint32_t> input_corner_vertex(3 * nf), input_opposite(3 * nf);
  if(!read_faces_quickly(tm, vertex_id, face_id, input_faces, input_corner_vertex, input_opposite))
    read_faces(tm, vertex_id, face_id, input_faces, input_corner_vertex, input_opposite);
  build_from_read_faces(mesh, edge_length, vertices_, input_faces, input_corner_vertex, input_opposite, faces_, face_id);
}

template <class EdgeLength, class VertexVector, class FaceVector, class FaceIdMap>
void build_from_read_faces(Intrinsic_triangle_mesh& mesh, const EdgeLength& edge_length, const VertexVector& vertices_,
                           const FaceVector& input_faces, const Huge_page_vector<std::uint32_t>& input_corner_vertex,
                           const Huge_page_vector<std::uint32_t>& input_opposite, FaceVector& faces_, FaceIdMap&& face_id)
{
  typedef Intrinsic_triangle_mesh Mesh;
  typedef typename VertexVector::value_type vertex_descriptor;
  const std::size_t nf = input_faces.size();
  faces_.clear();

  // Faces are numbered breadth-first across edges, so that neighbouring faces (and their
  // halfedges) lie close together in memory: a propagation front then walks through memory
  // nearly in order (on a Loop-subdivided mesh, whose new faces are appended far from their
  // parents, the full propagation at 829k faces got about 1.1x faster).
  Huge_page_vector<std::uint32_t> position_of(nf); // new face index -> position in iteration order
  Huge_page_vector<std::uint32_t> index_of(nf, Mesh::no_halfedge); // position -> new face index
  {
    std::size_t count = 0;
    for(std::uint32_t start = 0; start < nf; ++start)
    {
      if(index_of[start] != Mesh::no_halfedge)
        continue;
      index_of[start] = static_cast<std::uint32_t>(count);
      position_of[count++] = start;
      for(std::size_t k = count - 1; k < count; ++k)
        for(int i = 0; i < 3; ++i)
        {
          const std::uint32_t o = input_opposite[3 * position_of[k] + i];
          if(o != Mesh::no_halfedge && index_of[Mesh::face(o)] == Mesh::no_halfedge)
          {
            index_of[Mesh::face(o)] = static_cast<std::uint32_t>(count);
            position_of[count++] = Mesh::face(o);
          }
        }
    }
  }

  mesh.corner_vertex_.resize(3 * nf);
  mesh.opposite_.resize(3 * nf);
  faces_.reserve(nf);
  for(std::uint32_t fi = 0; fi < nf; ++fi)
  {
    const std::uint32_t position = position_of[fi];
    faces_.push_back(input_faces[position]);
    put(face_id, input_faces[position], fi);
    for(std::uint32_t k = 0; k < 3; ++k)
    {
      mesh.corner_vertex_[3 * fi + k] = input_corner_vertex[3 * position + k];
      const std::uint32_t o = input_opposite[3 * position + k];
      mesh.opposite_[3 * fi + k] = o == Mesh::no_halfedge ? o : 3 * index_of[Mesh::face(o)] + o % 3;
    }
  }
  // Names a face of the new numbering in a message.
  auto describe_face = [&](std::uint32_t fi) { return describe_element("face", faces_[fi], position_of[fi]); };

  mesh.length_.resize(3 * nf);
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
  {
    const std::uint32_t o = mesh.opposite_[h];
    const vertex_descriptor u = vertices_[mesh.corner_vertex_[h]], v = vertices_[mesh.corner_vertex_[Mesh::next(h)]];
    if(u == v)
      throw Invalid_mesh_error("an edge of " + describe_face(Mesh::face(h)) + " is a loop at " + describe_element("vertex", u, mesh.corner_vertex_[h]));
    const double len = (o != Mesh::no_halfedge && o < h) ? mesh.length_[o] : static_cast<double>(edge_length(u, v));
    if(!(len > 0) || !std::isfinite(len))
    {
      std::ostringstream msg;
      msg << "edge (" << describe_element("vertex", u, mesh.corner_vertex_[h]) << ", "
          << describe_element("vertex", v, mesh.corner_vertex_[Mesh::next(h)]) << ") has "
          << (std::isfinite(len) ? "zero" : "non-finite") << " length (" << len
          << (std::isfinite(len) ? "); if the mesh is a scan, " : "); check the coordinates or the edge lengths")
          << (std::isfinite(len) ? scan_repair_hint : "");
      throw Invalid_mesh_error(msg.str());
    }
    mesh.length_[h] = len;
  }

  // Triangle inequality (up to rounding) so that every face can be unfolded.
  for(std::uint32_t f = 0; f < nf; ++f)
  {
    const double a = mesh.length_[3 * f], b = mesh.length_[3 * f + 1], c = mesh.length_[3 * f + 2];
    const double slack = 1e-12 * (a + b + c);
    if(a > b + c + slack || b > a + c + slack || c > a + b + slack)
      throw Invalid_mesh_error(describe_face(f) + " violates the triangle inequality (edge lengths " +
                               std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(c) +
                               "); check the edge lengths, or if the face is a degenerate face of a scan, " + scan_repair_hint);
  }

  // Lengths in units of a power of two near the median edge (exact scaling, see length_unit()).
  mesh.length_unit_ = 1;
  if(nf > 0)
  {
    const int exponent = frexp_exponent_of_kth_smallest(mesh.length_.data(), mesh.length_.size(), mesh.length_.size() / 2);
    mesh.length_unit_ = std::ldexp(1.0, exponent);
    const double inverse_unit = std::ldexp(1.0, -exponent); // (a product by it is ldexp, when finite)
    for(double& len : mesh.length_)
      len = std::isfinite(inverse_unit) ? len * inverse_unit : std::ldexp(len, -exponent);
  }

  // Corners around each vertex (compressed rows), in increasing order.
  const std::size_t nv = vertices_.size();
  mesh.vertex_first_corner_.assign(nv + 1, 0);
  for(std::uint32_t v : mesh.corner_vertex_)
    ++mesh.vertex_first_corner_[v + 1];
  for(std::size_t v = 0; v < nv; ++v)
    mesh.vertex_first_corner_[v + 1] += mesh.vertex_first_corner_[v];
  mesh.vertex_corners_.resize(3 * nf);
  Huge_page_vector<std::uint32_t> fill(mesh.vertex_first_corner_.begin(), mesh.vertex_first_corner_.end() - 1);
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
    mesh.vertex_corners_[fill[mesh.corner_vertex_[h]]++] = h;

  // Boundary vertices and saddles (angle sum above 2 pi by more than its rounding, 1e-13 plus
  // 2 pi n^2 2^-53 for n corners; the sum of corner_angle() in increasing corner order) may bend
  // geodesics. (An excess of 1e-12, left at a vertex by the damage of its faces, casts a shadow
  // wider than the windows' tolerances beyond a few edges: a vertex lying exactly in it was 0.2 %
  // too far with a threshold of 1e-9.) The angle sum of an inner vertex is first bounded with
  // approximate_atan2(): each corner's angle within 1e-11 of corner_angle() (whose std::atan2
  // rounds by less than an ulp of pi), and sums of n terms below 2 pi n rounding by less than
  // 2 pi n^2 2^-53 in both. Only where that bound cannot decide is the sum of corner_angle()
  // formed (flat vertices of CAD parts, at 2 pi within rounding, need it): the decisions are
  // those of that sum, without an std::atan2 for most corners.
  mesh.bends_geodesics_.assign(nv, 0);
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
    if(mesh.opposite_[h] == Mesh::no_halfedge)
    {
      mesh.bends_geodesics_[mesh.corner_vertex_[h]] = 1;
      mesh.bends_geodesics_[mesh.corner_vertex_[Mesh::next(h)]] = 1;
    }
  Huge_page_vector<double> approximate_sum(nv, 0.0);
  for(std::uint32_t f = 0; f < nf; ++f)
  {
    const double* l = &mesh.length_[3 * f];
    const double four_area = 4 * Mesh::kahan_area(l[0], l[1], l[2]); // (symmetric in its arguments)
    for(int k = 0; k < 3; ++k)
    {
      // apex(3f + k) = (x, y) = (a^2 + (b - c)(b + c), 4 area) / 2a, of the same angle
      const double a = l[k], b = l[(k + 2) % 3], c = l[(k + 1) % 3];
      const double product = (b - c) * (b + c), x = a * a + product;
      // x is rounded differently in apex() (a fused multiply-add or not), by less than
      // 2^-51 (a^2 + |product|): an angle error below 64 * 2^-51 where this holds, else NaN
      // (the vertex is then decided by its sum of corner_angle())
      const bool well_conditioned = a * a + std::abs(product) + four_area <= 64 * (std::max)(four_area, std::abs(x));
      approximate_sum[mesh.corner_vertex_[3 * f + k]] +=
        well_conditioned ? approximate_atan2(four_area, x) : std::numeric_limits<double>::quiet_NaN();
    }
  }
  const double two_pi = 2 * 3.14159265358979323846;
  for(std::size_t v = 0; v < nv; ++v)
  {
    if(mesh.bends_geodesics_[v])
      continue;
    const std::uint32_t* first = mesh.corners_begin(static_cast<std::uint32_t>(v));
    const std::uint32_t* last = mesh.corners_end(static_cast<std::uint32_t>(v));
    const double n = static_cast<double>(last - first);
    const double threshold = two_pi + 1e-13 + two_pi * n * n * 0x1p-53;
    const double bound = n * (1e-11 + two_pi * 0x1p-52) + 2 * two_pi * n * n * 0x1p-53;
    if(approximate_sum[v] > threshold + bound)
      mesh.bends_geodesics_[v] = 1;
    else if(!(approximate_sum[v] < threshold - bound))
    {
      double angle_sum = 0;
      for(const std::uint32_t* h = first; h != last; ++h)
        angle_sum += mesh.corner_angle(*h);
      mesh.bends_geodesics_[v] = angle_sum > threshold;
    }
  }
  for(std::uint32_t h = 0; h < 3 * nf; ++h)
    if(mesh.length_[h] <= Mesh::needle_ratio * std::max(mesh.length_[Mesh::next(h)], mesh.length_[Mesh::prev(h)]))
      mesh.bends_geodesics_[mesh.corner_vertex_[h]] = mesh.bends_geodesics_[mesh.corner_vertex_[Mesh::next(h)]] = 2;
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif
