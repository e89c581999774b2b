#include "module.h"
namespace isophotic_metric_python {
void bind_morphology(py::module_&) {}
}
