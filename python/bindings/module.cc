// The extension module behind the Python package movseg (python/movseg/__init__.py).
#include "bindings.h"
#include "fields.h"

PYBIND11_MODULE(_movseg, module) {
  module.doc() = "movseg: moving object segmentation for freely moving cameras";
  module.attr("__version__") = MOVSEG_VERSION;
  movseg::python::bindParams(module);
  movseg::python::bindResult(module);
  movseg::python::bindSegmenter(module);
  // The field tables, for the type stubs' generator (python/tools/stubgen.py).
  module.def("_param_fields", [] { return movseg::python::fieldTable(movseg::paramFields()); });
  module.def("_diagnostic_fields",
             [] { return movseg::python::fieldTable(movseg::diagnosticFields()); });
}
