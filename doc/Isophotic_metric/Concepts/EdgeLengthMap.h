/*!
\ingroup PkgIsophoticMetricConcepts
\cgalConcept

The metric length of every edge of a triangle mesh `tm`, as the named parameter `edge_length_map`
of `CGAL::Isophotic_metric::Metric_mesh` (and of every function and solver that takes the metric)
expects it. With such a map a user brings an intrinsic metric of their own: exact polyhedral
geodesics on a piecewise-flat surface depend on its edge lengths only.

A model is a `ReadablePropertyMap` whose key type is either
`boost::graph_traits<TriangleMesh>::%halfedge_descriptor` or
`boost::graph_traits<TriangleMesh>::%edge_descriptor`, and whose value type is convertible to
`double` by `CGAL::to_double()`.

Requirements on the values, checked when the prepared mesh is built:
- every length is finite and positive (`Invalid_mesh_error` otherwise);
- the three lengths of every face satisfy the triangle inequality, up to a relative \f$ 10^{-12} \f$
  (`Invalid_mesh_error` naming the face otherwise);
- keyed by halfedges, the two halfedges of an edge between two faces hold the same length
  (`Invalid_parameter_error` naming the edge otherwise); border halfedges are not read.

\cgalHasModel `CGAL::dynamic_edge_property_t<double>` and `CGAL::dynamic_halfedge_property_t<double>`
maps (`get(CGAL::dynamic_edge_property_t<double>(), tm)`), `Surface_mesh` property maps of edges or
halfedges with `double` values, and any `boost::associative_property_map` with those keys.
*/
class EdgeLengthMap
{
public:
  /// The length of the edge of `key` (a halfedge or an edge descriptor).
  friend double get(const EdgeLengthMap& map, const key_type& key);
};
