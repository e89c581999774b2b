// One preparation step for meshes straight from a scanner, built on CGAL's repair functions: the
// defects that validate_triangle_mesh() refuses (zero-length edges, non-manifold vertices, polygons)
// and those that only hurt (needles, caps, small holes, small components, isolated vertices).
#ifndef CGAL_ISOPHOTIC_METRIC_REPAIR_SCANNED_MESH_H
#define CGAL_ISOPHOTIC_METRIC_REPAIR_SCANNED_MESH_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/merge_border_vertices.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/helpers.h>

#include <boost/graph/graph_traits.hpp>

#include <cmath>
#include <cstddef>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Meshes that keep removed elements until told (CGAL::Surface_mesh) compact them, so that the indices
// of their elements run from 0 to the number of elements again.
template <typename Mesh>
auto collect_garbage_if_any(Mesh& tm, int) -> decltype(tm.collect_garbage(), void()) { tm.collect_garbage(); }
template <typename Mesh>
void collect_garbage_if_any(Mesh&, long) {}

} // namespace internal

/// \ingroup PkgIsophoticMetricValidation
/// What `repair_scanned_mesh()` did, step by step, and whether the result can be processed.
struct Scan_repair_report
{
  std::size_t faces_triangulated = 0;            ///< polygons with more than three vertices, triangulated
  std::size_t border_edges_stitched = 0;         ///< pairs of coincident border edges merged into one edge
  std::size_t boundary_vertices_merged = 0;      ///< duplicated vertices of boundary cycles merged
  std::size_t degenerate_faces_removed = 0;      ///< zero-area faces (zero-length edges included), collapsed or flipped
  std::size_t needles_and_caps_removed = 0;      ///< needles and caps found, collapsed or flipped
  std::size_t non_manifold_vertices_split = 0;   ///< non-manifold vertices, duplicated once per fan
  std::size_t components_removed = 0;            ///< small connected components removed
  std::size_t holes_filled = 0;                  ///< small holes triangulated
  std::size_t isolated_vertices_removed = 0;     ///< vertices without any face, removed
  bool valid = false;                            ///< whether the result passes `validate_triangle_mesh()`
  std::string remaining_problem;                 ///< if not valid: the message of `validate_triangle_mesh()`
};

/// \ingroup PkgIsophoticMetricValidation
/// Writes the report, one line, only the steps that changed something.
inline std::ostream& operator<<(std::ostream& out, const Scan_repair_report& r)
{
  const std::pair<std::size_t, const char*> steps[] = {
    {r.faces_triangulated, "polygons triangulated"}, {r.border_edges_stitched, "border edges stitched"},
    {r.boundary_vertices_merged, "boundary vertices merged"}, {r.degenerate_faces_removed, "degenerate faces removed"},
    {r.needles_and_caps_removed, "needles and caps removed"}, {r.non_manifold_vertices_split, "non-manifold vertices split"},
    {r.components_removed, "small components removed"}, {r.holes_filled, "holes filled"},
    {r.isolated_vertices_removed, "isolated vertices removed"}};
  bool any = false;
  for(const auto& step : steps)
    if(step.first > 0)
    {
      out << (any ? ", " : "") << step.first << " " << step.second;
      any = true;
    }
  out << (any ? "; " : "nothing to repair; ");
  return out << (r.valid ? "the mesh is valid" : "still invalid: " + r.remaining_problem);
}

/// \ingroup PkgIsophoticMetricValidation
///
/// \brief prepares a mesh straight from a scanner for the package, with CGAL's repair functions, and
/// reports what it did.
///
/// The steps, in this order (each one prepares the next), after the isolated vertices are removed
/// (`PMP::remove_isolated_vertices()`: CGAL's repair functions require a mesh without them):
/// 1. polygons with more than three vertices are triangulated (`PMP::triangulate_faces()`);
/// 2. duplicated vertices are merged: coincident border edges are stitched (`PMP::stitch_borders()`),
///    then duplicated vertices of a boundary cycle (`PMP::merge_duplicated_vertices_in_boundary_cycles()`);
/// 3. zero-length edges are collapsed and zero-area triangles removed (`PMP::remove_degenerate_faces()`);
/// 4. needles (longest edge at least 20 times the shortest) are collapsed when their shortest edge is
///    below a tenth of the mean edge length, and caps (an angle above 175 degrees) flipped
///    (`PMP::experimental::remove_almost_degenerate_faces()`): they are not refused, but a needle's
///    normal is as noisy as its short edge is short;
/// 5. non-manifold vertices are duplicated, one copy per fan of faces (`PMP::duplicate_non_manifold_vertices()`);
/// 6. the vertices the steps above left without faces are removed, then the connected components
///    with fewer faces than `min_component_fraction` times the faces of the mesh
///    (`PMP::keep_large_connected_components()`): the debris of a scan;
/// 7. holes bounded by at most `max_hole_size` edges are triangulated and refined to the density
///    around them (`PMP::triangulate_and_refine_hole()`); the outer border of an open scan, longer,
///    stays open, and so does the border of a small piece (a component of fewer than \f$ k^2 \f$ faces
///    inside a border of \f$ k \f$ edges), which a filling would close onto itself.
///
/// The result is then checked with `validate_triangle_mesh()`; the report says whether it passed and,
/// if not, why (a corrupted halfedge structure or a non-finite coordinate is not repaired: rebuild the
/// mesh from its polygons with `CGAL::IO::read_polygon_mesh()`, which also repairs the polygon soup).
/// Vertex, face and edge descriptors of `tm` may be invalidated (a `CGAL::Surface_mesh` is compacted
/// with `collect_garbage()`).
///
/// \tparam TriangleMesh a model of `MutableFaceGraph`, `FaceListGraph` and `HalfedgeListGraph`
///         (`CGAL::Surface_mesh`, `CGAL::Polyhedron_3`)
/// \tparam NamedParameters a sequence of \ref IsophoticMetricNamedParameters "Named Parameters"
///
/// \param tm the mesh, repaired in place
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{max_hole_size}
///     \cgalParamDescription{holes bounded by at most this number of edges are filled; `0` fills none}
///     \cgalParamType{std::size_t}
///     \cgalParamDefault{`20`}
///   \cgalParamNEnd
///   \cgalParamNBegin{min_component_fraction}
///     \cgalParamDescription{components with fewer faces than this fraction of the faces of the mesh are
///                           removed; `0` keeps all}
///     \cgalParamType{double}
///     \cgalParamDefault{`0.01`}
///     \cgalParamExtra{Must be in [0, 1].}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_parameter_error if `min_component_fraction` is not in [0, 1].
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Scan_repair_report repair_scanned_mesh(TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef boost::graph_traits<TriangleMesh> Graph_traits;
  typedef typename Graph_traits::halfedge_descriptor halfedge_descriptor;
  typedef typename Graph_traits::face_descriptor face_descriptor;
  typedef typename Graph_traits::vertex_descriptor vertex_descriptor;

  const std::size_t max_hole_size = choose_parameter(get_parameter(np, internal_np::max_hole_size), std::size_t(20));
  const double min_component_fraction =
    CGAL::to_double(choose_parameter(get_parameter(np, internal_np::min_component_fraction), 0.01));
  if(!(min_component_fraction >= 0. && min_component_fraction <= 1.))
    throw Invalid_parameter_error(internal::message("min_component_fraction is ", min_component_fraction,
                                                    "; it must be in [0, 1]"));
  Scan_repair_report report;
  auto nb_faces = [&tm]() { return static_cast<std::size_t>(num_faces(tm)); };
  auto removed = [](std::size_t before, std::size_t after) { return before > after ? before - after : 0; };

  // Vertices without any face first: CGAL's repair functions take them for a broken halfedge
  // structure (remove_degenerate_faces() asserts that the mesh is valid), and scans often list
  // points that no face uses.
  report.isolated_vertices_removed = PMP::remove_isolated_vertices(tm);

  // 1. Triangles only.
  for(face_descriptor f : faces(tm))
    if(CGAL::halfedges_around_face(halfedge(f, tm), tm).size() != 3)
      ++report.faces_triangulated;
  if(report.faces_triangulated > 0)
    PMP::triangulate_faces(tm);

  // 2. Duplicated vertices: coincident border edges, then pinched boundary cycles.
  report.border_edges_stitched = PMP::stitch_borders(tm);
  const std::size_t vertices_before_merge = static_cast<std::size_t>(num_vertices(tm));
  PMP::merge_duplicated_vertices_in_boundary_cycles(tm);
  report.boundary_vertices_merged = removed(vertices_before_merge, static_cast<std::size_t>(num_vertices(tm)));

  // 3. Zero-length edges and zero-area faces (counted before: the repair collapses some, flips others).
  std::vector<face_descriptor> defective;
  PMP::degenerate_faces(tm, std::back_inserter(defective));
  report.degenerate_faces_removed = defective.size();
  if(!defective.empty())
    PMP::remove_degenerate_faces(tm);

  // 4. Needles and caps, with thresholds that leave ordinary scan triangles alone.
  double mean_edge = 0.;
  for(const auto e : edges(tm))
    mean_edge += PMP::edge_length(e, tm);
  mean_edge /= (num_edges(tm) > 0 ? double(num_edges(tm)) : 1.);
  const double cap_cosine = std::cos(175. * CGAL_PI / 180.), needle_ratio = 20.;
  for(face_descriptor f : faces(tm))
    if(PMP::is_needle_triangle_face(f, tm, needle_ratio) != Graph_traits::null_halfedge() ||
       PMP::is_cap_triangle_face(f, tm, cap_cosine) != Graph_traits::null_halfedge())
      ++report.needles_and_caps_removed;
  if(report.needles_and_caps_removed > 0)
    PMP::experimental::remove_almost_degenerate_faces(tm, cap_cosine, needle_ratio, 0.1 * mean_edge);

  // 5. One vertex per fan of faces.
  report.non_manifold_vertices_split = PMP::duplicate_non_manifold_vertices(tm);

  // 6. Debris: isolated vertices, then small components.
  report.isolated_vertices_removed += PMP::remove_isolated_vertices(tm);
  if(min_component_fraction > 0.)
  {
    const std::size_t threshold = static_cast<std::size_t>(std::ceil(min_component_fraction * double(nb_faces())));
    report.components_removed = PMP::keep_large_connected_components(tm, threshold);
  }

  // 7. Small holes (cycles collected first: filling changes the border). A cycle of k edges is a
  // hole only in a component of at least k^2 faces (its filling at the density around it takes about
  // k^2 / 5): inside a shorter border lies a small piece of surface (a loose triangle, a strip), which
  // the filling would close onto itself, back to back, leaving vertices without a normal.
  if(max_hole_size > 0)
  {
    std::vector<halfedge_descriptor> cycles;
    PMP::extract_boundary_cycles(tm, std::back_inserter(cycles));
    auto component = get(CGAL::dynamic_face_property_t<std::size_t>(), tm);
    const std::size_t number_of_components = PMP::connected_components(tm, component);
    std::vector<std::size_t> component_faces(number_of_components, 0);
    for(face_descriptor f : faces(tm))
      ++component_faces[get(component, f)];
    for(halfedge_descriptor h : cycles)
    {
      const std::size_t k = CGAL::halfedges_around_face(h, tm).size();
      if(k > max_hole_size || component_faces[get(component, face(opposite(h, tm), tm))] < k * k)
        continue;
      std::vector<face_descriptor> new_faces;
      std::vector<vertex_descriptor> new_vertices;
      PMP::triangulate_and_refine_hole(tm, h, std::back_inserter(new_faces), std::back_inserter(new_vertices));
      if(!new_faces.empty())
        ++report.holes_filled;
    }
  }

  // Vertices left without faces by the steps above.
  report.isolated_vertices_removed += PMP::remove_isolated_vertices(tm);
  internal::collect_garbage_if_any(tm, 0);

  try
  {
    validate_triangle_mesh(tm);
    report.valid = true;
  }
  catch(const Invalid_mesh_error& e)
  {
    report.remaining_problem = e.what();
  }
  return report;
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_REPAIR_SCANNED_MESH_H
