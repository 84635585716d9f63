// control room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_control(py::module_&) {}

}  // namespace mjarm::python
