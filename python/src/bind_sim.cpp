// sim room bindings.
#include "bindings.hpp"

namespace mjarm::python {

void bind_sim(py::module_&) {}

}  // namespace mjarm::python
