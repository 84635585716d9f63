// state by name: Data.named / Simulation.named (dm_control's physics.named.data), and state
// snapshots that restore bit for bit.
#include <mujoco/mujoco.h>

#include <string>
#include <variant>

#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/constraint_summary.hpp"
#include "mjarm/kinematics/contacts.hpp"
#include "mjarm/model/named_data.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/sim/state_snapshot.hpp"

namespace mjarm::python {
namespace {

/// An element: its name or its id.
using Element = std::variant<std::string, int>;

/// The elements of one quantity of a Data: `data.named.qpos`.
struct NamedArray {
  py::object handle;  // the mjarm.Data, kept alive
  const NamedQuantity* quantity;

  DataHandle& data() const { return handle.cast<DataHandle&>(); }
  NamedData named() const { return {data().model(), data().get()}; }

  int id_of(const Element& key) const {
    if (const auto* name = std::get_if<std::string>(&key)) return named().id(*quantity, *name);
    const int id = std::get<int>(key);
    named_slice(data().model(), *quantity, id);  // throws for an id out of range
    return id;
  }

  static std::string text(const Element& key) {
    if (const auto* name = std::get_if<std::string>(&key)) return *name;
    return std::to_string(std::get<int>(key));
  }

  /// Writable when the data is (owned, the user's) and the quantity is an input of the step.
  py::array_t<double> get(const Element& key) const {
    const int id = id_of(key);
    DataHandle& h = data();
    const NamedSlice slice = named_slice(h.model(), *quantity, id);
    double* values = named_array(h.model(), h.get(), *quantity).data() + slice.offset;
    if (h.borrowed()) return to_array(values, slice.size);
    if (h.writable() && quantity->input) return writable_view(values, slice.size, handle);
    return readonly_view(values, slice.size, handle);
  }

  void set(const Element& key, const py::handle& value) const {
    DataHandle& h = data();
    const std::string what = "named " + std::string(quantity->name);
    if (!quantity->input) {
      throw Error(what +
                  " is computed by mj_forward, not written; the inputs are qpos, qvel, "
                  "qacc_warmstart, qfrc_applied, ctrl, act, xfrc_applied, mocap_pos, "
                  "mocap_quat");
    }
    if (!h.writable()) {
      throw Error(what + ": this Data is read-only (" +
                  (h.borrowed() ? std::string("lent for one call")
                                : std::string("a Simulation's: write through "
                                              "Simulation.set_state or restore")) +
                  "); Robot.make_data() and a mujoco.MjData are writable");
    }
    const int id = id_of(key);
    const NamedSlice slice = named_slice(h.model(), *quantity, id);
    const std::string element = text(key);
    // one value may be written as a number
    const bool number = py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value);
    const py::object values_in = slice.size == 1 && number
                                     ? py::object(py::make_tuple(value))
                                     : py::reinterpret_borrow<py::object>(value);
    const Eigen::VectorXd v =
        to_vector(values_in, (what + "['" + element + "']").c_str(), slice.size);
    if (!v.allFinite()) throw Error(what + "['" + element + "']: values must be finite");
    double* values = named_array(h.model(), h.get(), *quantity).data() + slice.offset;
    std::copy(v.data(), v.data() + v.size(), values);
  }

  std::string repr() const {
    DataHandle& h = data();
    const std::vector<std::string> names = named().names(*quantity);
    std::string out =
        "named " + std::string(quantity->name) + " (" + object_kind_name(quantity->element) + "s):";
    const double* array = named_array(h.model(), h.get(), *quantity).data();
    for (int id = 0; id < static_cast<int>(names.size()); ++id) {
      if (quantity->name.starts_with("mocap_") && h.model().body_mocapid[id] < 0) continue;
      const NamedSlice slice = named_slice(h.model(), *quantity, id);
      out += "\n  " + (names[id].empty() ? "#" + std::to_string(id) : names[id]) + ":";
      for (int i = 0; i < slice.size; ++i) out += " " + number_text(array[slice.offset + i], 6);
    }
    return out;
  }
};

/// The equality constraints switched on or off, by name: `data.named.eq_active['grasp']`.
struct NamedSwitches {
  py::object handle;  // the mjarm.Data, kept alive

  DataHandle& data() const { return handle.cast<DataHandle&>(); }

  int id_of(const Element& key) const {
    const mjModel& m = data().model();
    if (const auto* name = std::get_if<std::string>(&key))
      return find_object(m, mjOBJ_EQUALITY, *name);
    const int id = std::get<int>(key);
    if (id < 0 || id >= m.neq) {
      throw Error("named eq_active: the model has " + std::to_string(m.neq) +
                  " equality constraints, no number " + std::to_string(id));
    }
    return id;
  }

  bool get(const Element& key) const { return data().get().eq_active[id_of(key)] != 0; }

  /// A simulation's switch goes through the simulation (its own bookkeeping); a writable Data's
  /// is written.
  void set(const Element& key, bool on) const {
    DataHandle& h = data();
    const int id = id_of(key);
    if (h.kind == DataHandle::Kind::simulation) {
      h.owner.cast<Simulation&>().set_equality_active(id, on);
    } else if (h.writable()) {
      h.get().eq_active[id] = on ? 1 : 0;
    } else {
      throw Error("named eq_active: this Data was lent for one call and is read-only");
    }
  }
};

/// Every quantity of a Data by element name: `data.named`.
struct NamedView {
  py::object handle;
};

NamedView named_view(py::object handle) {
  handle.cast<DataHandle&>().get();  // a call's handle after its call: the usual error
  return {std::move(handle)};
}

}  // namespace

void bind_state(py::module_& m) {
  auto array = py::class_<NamedArray>(
      m, "NamedArray",
      "One mjData array by element name: a[name] (or a[id]) is the element's values, a view into "
      "the data (writable for the step's inputs of a writable Data), a[name] = values writes "
      "them. A ball joint covers 4 qpos and 3 qvel, a free joint 7 and 6.");
  array.def("__getitem__", &NamedArray::get, py::arg("element"))
      .def("__setitem__", &NamedArray::set, py::arg("element"), py::arg("values"))
      .def("__len__",
           [](const NamedArray& a) { return named_count(a.data().model(), *a.quantity); })
      .def_property_readonly(
          "names", [](const NamedArray& a) { return a.named().names(*a.quantity); },
          "the elements' names in id order ('' for an unnamed one)")
      .def(
          "size",
          [](const NamedArray& a, const Element& key) {
            return named_slice(a.data().model(), *a.quantity, a.id_of(key)).size;
          },
          py::arg("element"), "how many values the element covers")
      .def_property_readonly(
          "quantity", [](const NamedArray& a) { return std::string(a.quantity->name); },
          "the mjData field")
      .def_property_readonly(
          "input", [](const NamedArray& a) { return a.quantity->input; },
          "True for an input of the next step (writable), False for a result of mj_forward")
      .def("__repr__", &NamedArray::repr);

  auto view = py::class_<NamedView>(
      m, "NamedData",
      "mjData by element name, as dm_control's physics.named.data: named.qpos['joint1'], "
      "named.site_xpos['attachment_site'], named.ctrl['joint2'] = 1.5; unknown names raise "
      "mjarm.Error with the closest.");
  for (const NamedQuantity& q : named_quantities()) {
    const NamedQuantity* quantity = &q;
    const std::string doc = std::string(q.doc) + (q.input ? "" : " (computed by mj_forward)");
    view.def_property_readonly(
        std::string(q.name).c_str(),
        [quantity](const NamedView& v) {
          return NamedArray{v.handle, quantity};
        },
        doc.c_str());
  }

  py::class_<NamedSwitches>(m, "NamedSwitches",
                            "The equality constraints by name: s[name] is True when active; "
                            "s[name] = False switches one off (a simulation's too: the next "
                            "step sees it).")
      .def("__getitem__", &NamedSwitches::get, py::arg("equality"))
      .def("__setitem__", &NamedSwitches::set, py::arg("equality"), py::arg("active"))
      .def("__len__", [](const NamedSwitches& s) { return s.data().model().neq; })
      .def_property_readonly(
          "names",
          [](const NamedSwitches& s) { return object_names(s.data().model(), mjOBJ_EQUALITY); },
          "the equality constraints' names in id order ('' for an unnamed one)");
  view.def_property_readonly(
      "eq_active", [](const NamedView& v) { return NamedSwitches{v.handle}; },
      "equality constraints switched on (True) or off, by name");

  py::class_<ConstraintSummary> summary(
      m, "ConstraintSummary",
      "What the constraint solver had to do: rows by kind, active rows, the largest force, the "
      "solver's iterations.");
  def_readonly_fields(summary);

  py::class_<StateSnapshot>(
      m, "StateSnapshot",
      "Everything in mjData that determines the next step (MuJoCo's mjSTATE_INTEGRATION), "
      "with the model's signature: restore it and step, and the trajectory is the one that "
      "followed it, bit for bit.")
      .def_property_readonly("time", &StateSnapshot::time, "simulated time [s]")
      .def_property_readonly(
          "values",
          [](const StateSnapshot& s) {
            return to_array(s.values().data(), static_cast<Eigen::Index>(s.values().size()));
          },
          "a copy of the values, in mj_getState's order")
      .def_property_readonly("signature", &StateSnapshot::signature, "the model's signature")
      .def("__eq__", &StateSnapshot::operator==, py::arg("other"))
      .def("__repr__", [](const StateSnapshot& s) {
        return "<StateSnapshot t=" + std::to_string(s.time()) + " (" +
               std::to_string(s.values().size()) + " values)>";
      });

  auto contact = py::class_<ContactForce>(
      m, "ContactForce",
      "One active contact: the geoms and bodies (ids and names), where, how far, and the force "
      "geom1 exerts on geom2 in world axes, split into its normal and friction parts.");
  def_readonly_fields(contact);
  contact.def_property_readonly(
      "frame", [](const ContactForce& c) { return Eigen::Matrix3d(c.frame); },
      "contact frame, world (3, 3): rows are the normal and the two tangents");

  auto data = py::reinterpret_borrow<py::class_<DataHandle>>(m.attr("Data"));
  data.def(
      "constraint_summary", [](const DataHandle& h) { return constraint_summary(h.get()); },
      "The constraint rows of the data by kind (after mj_forward or a step).");
  data.def(
      "contact_forces", [](const DataHandle& h) { return contact_forces(h.model(), h.get()); },
      "Every active contact (after mj_forward or a step), in MuJoCo's order.");
  data.def_property_readonly("named", &named_view, "every mjData array by element name (NamedData)")
      .def(
          "snapshot", [](const DataHandle& h) { return StateSnapshot::of(h.model(), h.get()); },
          "The state that determines the next step.")
      .def(
          "restore",
          [](DataHandle& h, const StateSnapshot& s, bool forward) {
            if (!h.writable()) {
              throw Error(
                  "Data.restore: only data from Robot.make_data() or a mujoco.MjData; use "
                  "Simulation.restore for a simulation's");
            }
            s.restore(h.model(), h.get());
            if (forward) mj_forward(&h.model(), &h.get());
          },
          py::arg("snapshot"), py::arg("forward") = true,
          "Writes the snapshot's state (the next step is the one after the snapshot); with "
          "forward, mj_forward recomputes the derived quantities. Refuses a snapshot of another "
          "model.");

  auto sim = py::reinterpret_borrow<py::class_<Simulation>>(m.attr("Simulation"));
  sim.def_property_readonly(
         "named",
         [](py::object self) {
           auto& s = self.cast<Simulation&>();
           return named_view(py::cast(DataHandle(s.robot(), &s.data(), self)));
         },
         "the simulation's mjData by element name (read-only views)")
      .def("snapshot", &Simulation::snapshot,
           "The state that determines the next tick (not the controllers' own state).")
      .def("restore", &Simulation::restore, py::arg("snapshot"),
           "Puts a snapshot back: the ticks that follow are the ones that followed it (stateless "
           "controllers); clears a fault.");
}

}  // namespace mjarm::python
