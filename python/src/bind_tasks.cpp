// tasks room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_tasks(py::module_&) {}

}  // namespace mjarm::python
