// trajectory room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_trajectory(py::module_&) {}

}  // namespace mjarm::python
