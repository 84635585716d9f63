// kinematics room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_kinematics(py::module_&) {}

}  // namespace mjarm::python
