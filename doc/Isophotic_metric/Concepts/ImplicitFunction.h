/*!
\ingroup PkgIsophoticMetricConcepts
\cgalConcept

A function `F : R^3 -> R` whose zero level set is the surface (negative inside by convention,
so that `grad F` points outwards).  A signed distance function (`|grad F| = 1`) gives the
simplest expressions, but any regular `F` works.  `F` must be finite at every node of the grid it
is used on.  The derivatives are optional (detected at compile time; central differences are used
when they are absent).

\cgalHasModel `CGAL::Isophotic_metric::Sampled_function_3`
*/
class ImplicitFunction
{
public:
  /// The value `F(x)`.
  double operator()(const Eigen::Vector3d& x) const;
  /// Optional: the gradient of `F` at `x`.
  Eigen::Vector3d gradient(const Eigen::Vector3d& x) const;
  /// Optional: the Hessian of `F` at `x`.
  Eigen::Matrix3d hessian(const Eigen::Vector3d& x) const;
};
