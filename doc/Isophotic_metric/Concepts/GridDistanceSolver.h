/*!
\ingroup PkgIsophoticMetricConcepts
\cgalConcept

A distance solver on a grid, as the grid-mask morphology (`dilate_grid_mask()`, `erode_grid_mask()`,
`open_grid_mask()`, `close_grid_mask()`) needs it: it computes the distance field to a set of grid
nodes given as a mask, and the mask's domain is the solver's grid (for a narrow-band solver, only the
band's nodes count).

\cgalHasModel `CGAL::Isophotic_metric::Parametric_surface_distance` (masks over the nodes of a `Grid_2`)
\cgalHasModel `CGAL::Isophotic_metric::Implicit_surface_distance` (masks over the nodes of a `Grid_3`; only band nodes count)
*/
class GridDistanceSolver
{
public:
  /// The grid type, `CGAL::Isophotic_metric::Grid_2` or `CGAL::Isophotic_metric::Grid_3`.
  typedef unspecified_type Grid;
  /// The distance field type, `CGAL::Isophotic_metric::Distance_field_2` or
  /// `CGAL::Isophotic_metric::Distance_field_3`: it has a public `std::vector<double> distance`
  /// with one value per grid node, `+inf` where no source is reachable.
  typedef unspecified_type Field;
  /// A point source type (`Eigen::Vector2d` or `Eigen::Vector3d`).
  typedef unspecified_type Point;

  /// The grid the masks and fields live on.
  const Grid& grid() const;

  /// The nodes `n` where distances are computed (`domain()[n] != 0`), one entry per grid node:
  /// every node of a parametric grid, the band of a narrow-band solver.
  std::vector<char> domain() const;

  /// The distance field to the point `sources` and to the nodes `n` with `source_mask[n] != 0`
  /// (`source_mask` has one entry per grid node, or is empty).
  Field distance_field(const std::vector<Point>& sources, const std::vector<char>& source_mask) const;
};
