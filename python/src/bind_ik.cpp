// ik room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_ik(py::module_&) {}

}  // namespace mjarm::python
