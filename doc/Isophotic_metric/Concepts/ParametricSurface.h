/*!
\ingroup PkgIsophoticMetricConcepts
\cgalConcept

A regular parametric surface `x(u,v)` over a rectangle of the parameter plane.  The derivatives are
optional (detected at compile time; finite differences are used when they are absent); the third
fundamental form needs the second derivatives, as it differentiates the normal.
*/
class ParametricSurface
{
public:
  /// The point `x(u,v)`.
  Eigen::Vector3d point(double u, double v) const;
  /// Optional: the first partial derivatives `x_u`, `x_v`.
  void partial_derivatives(double u, double v, Eigen::Vector3d& xu, Eigen::Vector3d& xv) const;
  /// Optional: the second partial derivatives `x_uu`, `x_uv`, `x_vv`.
  void second_partial_derivatives(double u, double v, Eigen::Vector3d& xuu, Eigen::Vector3d& xuv,
                                  Eigen::Vector3d& xvv) const;
};
