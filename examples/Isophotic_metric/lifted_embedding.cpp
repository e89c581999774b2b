// Lifts a triangle mesh to R^6 and compares isophotic and Euclidean edge lengths.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Isophotic_metric.h>

#include <cmath>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
namespace IM = CGAL::Isophotic_metric;

int main(int argc, char* argv[])
{
  const std::string filename = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh))
  {
    std::cerr << "Cannot read " << filename << std::endl;
    return 1;
  }

  /// [lift]
  // X(v) = (sqrt(w) p, sqrt(w') L n): weights as in Fig. 7 of the paper, made
  // dimensionless by the length scale L (the bounding-box diagonal).
  auto lifted = mesh.add_property_map<vertex_descriptor, IM::Lifted_point>("v:lifted").first;
  const double L = IM::suggested_weight_length_scale(mesh);
  const auto np = IM::parameters::euclidean_weight(0.2)
                                 .isophotic_weight(0.8)
                                 .weight_length_scale(L);
  try
  {
    IM::compute_lifted_embedding(mesh, lifted, np);
  }
  catch(const IM::Error& e) // bad input: the message names the element
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  /// [lift]

  /// [named parameters]
  // The package's parameters chain with CGAL's, and CGAL's functions accept the
  // whole pack: they ignore the tags they do not know.
  const auto with_points = IM::parameters::vertex_point_map(mesh.points())
                                          .euclidean_weight(0.2);
  const double area = CGAL::Polygon_mesh_processing::area(mesh, with_points);
  /// [named parameters]

  /// [lengths]
  // Edges that cross a feature are much longer in the isophotic metric.
  std::size_t crossing = 0;
  for(auto e : edges(mesh))
  {
    const double euclidean = std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)),
                                                              mesh.point(target(e, mesh))));
    if(IM::edge_isophotic_length(e, mesh, lifted) > 5 * std::sqrt(0.2) * euclidean)
      ++crossing;
  }
  /// [lengths]

  std::cout << "area " << area << "; " << crossing << " of " << num_edges(mesh)
            << " edges are more than 5 times longer than sqrt(w) times their Euclidean length" << std::endl;
  return 0;
}
