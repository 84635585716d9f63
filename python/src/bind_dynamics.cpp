// dynamics room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_dynamics(py::module_&) {}

}  // namespace mjarm::python
