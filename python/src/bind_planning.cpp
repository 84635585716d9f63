// planning room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_planning(py::module_&) {}

}  // namespace mjarm::python
