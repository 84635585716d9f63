// render room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_render(py::module_&) {}

}  // namespace mjarm::python
