// kinematics room: FK, Jacobians, J̇q̇, manipulability, singularity reports, workspace sampling.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/kinematics/body_poses.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/kinematics/singularity.hpp"
#include "mjarm/kinematics/singularity_kind.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm::python {
namespace {

std::vector<std::string> kind_names(const std::vector<SingularityKind>& kinds) {
  std::vector<std::string> names;
  for (const SingularityKind k : kinds) names.emplace_back(to_string(k));
  return names;
}

}  // namespace

void bind_kinematics(py::module_& m) {
  def_enum<JacobianFrame>(m, "JacobianFrame", "How the rows of a frame Jacobian are expressed.");

  py::class_<ChainKinematics>(m, "ChainKinematics",
                              "Forward kinematics and Jacobians of a Chain on the chain's own "
                              "bodies (agrees with mj_kinematics + mj_jacSite to ~1e-15).")
      .def(py::init<const Chain&>(), py::arg("chain"))
      .def_property_readonly("chain", &ChainKinematics::chain,
                             "the chain whose kinematics are evaluated")
      .def(
          "set_fixed_qpos",
          [](ChainKinematics& k, py::handle qpos) {
            k.set_fixed_qpos(to_vector(qpos, "qpos", k.chain().robot().nq()));
          },
          py::arg("qpos"), "configuration (nq,) of the joints outside the chain")
      .def(
          "update",
          [](ChainKinematics& k, py::handle q) {
            const Eigen::VectorXd v = to_vector(q, "q", k.chain().size());
            k.chain().check(v);
            return k.update(v);
          },
          py::arg("q"), "Pose X_WE of the chain's frame at joint values q (n,).")
      .def_property_readonly(
          "pose", [](const ChainKinematics& k) { return k.pose(); },
          "X_WE from the last update (a copy)")
      .def(
          "jacobian",
          [](const ChainKinematics& k, JacobianFrame frame) {
            Matrix6Xd J(6, k.chain().size());
            k.jacobian(J, frame);
            return J;
          },
          py::arg("frame") = JacobianFrame::world_aligned,
          "6 x n frame Jacobian at the last update, rows linear first [v; w].")
      .def(
          "bias_acceleration",
          [](const ChainKinematics& k, py::handle qd) {
            return k.bias_acceleration(to_vector(qd, "qd", k.chain().size()));
          },
          py::arg("qd"),
          "J̇ q̇ (6,) at the last update, world-aligned, for joint velocities qd (n,).")
      .def(
          "axis",
          [](const ChainKinematics& k, int i) {
            if (i < 0 || i >= k.chain().size()) throw Error("axis: joint index out of range");
            return Eigen::Vector3d(k.axis(i));
          },
          py::arg("i"), "world axis of chain joint i at the last update")
      .def(
          "anchor",
          [](const ChainKinematics& k, int i) {
            if (i < 0 || i >= k.chain().size()) throw Error("anchor: joint index out of range");
            return Eigen::Vector3d(k.anchor(i));
          },
          py::arg("i"), "world anchor of chain joint i at the last update [m]");

  m.def(
      "forward_kinematics",
      [](const Chain& chain, py::handle q) {
        return forward_kinematics(chain, to_vector(q, "q", chain.size()));
      },
      py::arg("chain"), py::arg("q"),
      "X_WE at q (n,), other joints at qpos0 (builds a ChainKinematics per call).");
  m.def(
      "frame_pose",
      [](const Robot& robot, const DataHandle& d, py::handle frame) {
        const mjData& data = data_of(robot, d, "frame_pose");
        return frame_pose(robot.model(), data, find_frame(robot, frame.cast<std::string>()));
      },
      py::arg("robot"), py::arg("data"), py::arg("frame"),
      "The pose of a site or body read from MuJoCo's data (after forward).");

  def_enum<JacobianBlock>(m, "JacobianBlock");
  def_enum<SingularityStatus>(m, "SingularityStatus");
  auto manipulability_options = py::class_<ManipulabilityOptions>(m, "ManipulabilityOptions");
  manipulability_options.def(py::init<>());
  def_fields(manipulability_options);
  py::class_<ManipulabilityResult>(m, "ManipulabilityResult")
      .def_readonly("manipulability", &ManipulabilityResult::manipulability,
                    "Yoshikawa manipulability w = √det(J·Jᵀ)")
      .def_readonly("sigma_max", &ManipulabilityResult::sigma_max, "largest singular value σmax")
      .def_readonly("sigma_min", &ManipulabilityResult::sigma_min, "smallest singular value σmin")
      .def_readonly("condition_number", &ManipulabilityResult::condition_number,
                    "σmax/σmin; +inf when the status is singular")
      .def_readonly("status", &ManipulabilityResult::status, "regular, near-singular or singular");
  py::class_<Manipulability>(m, "Manipulability",
                             "Manipulability measures of a chain, with the analytic gradient.")
      .def(py::init<const Chain&, const ManipulabilityOptions&>(), py::arg("chain"),
           py::arg("options") = ManipulabilityOptions{})
      .def_property_readonly("rows", &Manipulability::rows,
                             "number of Jacobian rows measured (6 or 3)")
      .def(
          "evaluate",
          [](Manipulability& mm, py::handle q) {
            return mm.evaluate(to_vector(q, "q", mm.chain().size()));
          },
          py::arg("q"))
      .def(
          "gradient",
          [](Manipulability& mm, py::handle q) {
            Eigen::VectorXd g(mm.chain().size());
            const ManipulabilityResult r = mm.evaluate(to_vector(q, "q", mm.chain().size()), g);
            return py::make_tuple(r, g);
          },
          py::arg("q"), "(result, dw/dq (n,))")
      .def_property_readonly(
          "singular_values",
          [](const Manipulability& mm) { return Eigen::VectorXd(mm.singular_values()); },
          "singular values of the measured block, decreasing (min(m, n),)")
      .def_property_readonly(
          "jacobian_block",
          [](const Manipulability& mm) { return Eigen::MatrixXd(mm.jacobian_block()); },
          "the measured block of J_WE at the last evaluation, world-aligned (m, n)");
  m.def(
      "manipulability",
      [](const Chain& chain, py::handle q, const ManipulabilityOptions& o) {
        return manipulability(chain, to_vector(q, "q", chain.size()), o);
      },
      py::arg("chain"), py::arg("q"), py::arg("options") = ManipulabilityOptions{});

  auto thresholds = py::class_<SingularityThresholds>(m, "SingularityThresholds");
  thresholds.def(py::init<>());
  def_fields(thresholds);
  auto entry =
      py::class_<SingularityEntry>(m, "SingularityEntry", "The measures of one configuration.");
  def_readonly_fields(entry);
  entry.def_property_readonly(
      "kinds", [](const SingularityEntry& e) { return kind_names(e.kinds); },
      "'wrist', 'elbow', 'shoulder' or 'unclassified'");
  m.def(
      "singularity_report",
      [](const Chain& chain, const std::vector<std::pair<std::string, py::object>>& extra,
         const ManipulabilityOptions& o, const SingularityThresholds& t) {
        std::vector<NamedConfiguration> named;
        for (const auto& [name, q] : extra)
          named.push_back({name, to_vector(q, name.c_str(), chain.size())});
        return singularity_report(chain, named, o, t).entries;
      },
      py::arg("chain"), py::arg("extra") = std::vector<std::pair<std::string, py::object>>{},
      py::arg("options") = ManipulabilityOptions{}, py::arg("thresholds") = SingularityThresholds{},
      "Entries for qpos0, centre, every keyframe and the (name, q) pairs in extra.");
  auto scan = py::class_<SingularityScan>(m, "SingularityScan", "Result of a random scan.");
  def_readonly_fields(scan);
  m.def(
      "scan_singularities",
      [](const Chain& chain, std::size_t samples, std::uint64_t seed, std::size_t keep_worst) {
        py::gil_scoped_release release;
        return scan_singularities(chain, samples, seed, keep_worst);
      },
      py::arg("chain"), py::arg("samples"), py::arg("seed"), py::arg("keep_worst") = 10,
      "Seeded random scan keeping the lowest-sigma_min samples (GIL released).");

  py::class_<BodyPoses>(m, "BodyPoses",
                        "Forward kinematics of every body at once (mj_kinematics on a scratch "
                        "data of its own): each link's world frame, not only the end frame.")
      .def(py::init<const Robot&>(), py::arg("robot"))
      .def(
          "update",
          [](BodyPoses& b, py::handle qpos) {
            b.update(to_vector(qpos, "qpos"));
            return &b;
          },
          py::arg("qpos"), py::return_value_policy::reference_internal,
          "All poses at the full configuration qpos (nq,); returns self.")
      .def(
          "update_chain",
          [](BodyPoses& b, const Chain& chain, py::handle q) {
            b.update(chain, to_vector(q, "q", chain.size()));
            return &b;
          },
          py::arg("chain"), py::arg("q"), py::return_value_policy::reference_internal,
          "All poses at the chain's joint values q (the other joints at qpos0); returns self.")
      .def(
          "pose", [](const BodyPoses& b, std::string_view name) { return b.pose(name); },
          py::arg("body"), "X_WB of the body called body")
      .def_property_readonly("names", &BodyPoses::names, "the bodies in id order, world first")
      .def_property_readonly(
          "positions",
          [](const BodyPoses& b) {
            Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P(b.size(), 3);
            for (int i = 0; i < b.size(); ++i) P.row(i) = b.pose(i).p;
            return P;
          },
          "body origins, world (nbody, 3) [m]")
      .def_property_readonly(
          "rotations",
          [](const BodyPoses& b) {
            py::array_t<double> R({b.size(), 3, 3});
            auto r = R.mutable_unchecked<3>();
            for (int i = 0; i < b.size(); ++i)
              for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k) r(i, j, k) = b.pose(i).R(j, k);
            return R;
          },
          "body orientations R_WB (nbody, 3, 3)")
      .def("__len__", &BodyPoses::size);

  py::class_<WorkspaceResult>(m, "WorkspaceResult")
      .def_readonly("samples", &WorkspaceResult::samples,
                    "samples drawn (fewer than asked when interrupted)")
      .def_readonly("seed", &WorkspaceResult::seed, "seed of the samples")
      .def_readonly("lower", &WorkspaceResult::lower, "bounding-box minimum (3,) [m]")
      .def_readonly("upper", &WorkspaceResult::upper, "bounding-box maximum (3,) [m]")
      .def_readonly("centroid", &WorkspaceResult::centroid, "mean frame position, world (3,) [m]")
      .def_readonly("p_WB", &WorkspaceResult::p_WB, "the chain's base (3,) [m]")
      .def_readonly("max_reach_from_base", &WorkspaceResult::max_reach_from_base,
                    "max |p_WE − p_WB| [m]")
      .def_readonly("max_reach_from_origin", &WorkspaceResult::max_reach_from_origin,
                    "max |p_WE| [m]")
      .def_readonly("min_manipulability", &WorkspaceResult::min_manipulability,
                    "smallest manipulability over the samples (0 when not computed)")
      .def_readonly("max_manipulability", &WorkspaceResult::max_manipulability,
                    "largest manipulability over the samples (0 when not computed)")
      .def_readonly("mean_manipulability", &WorkspaceResult::mean_manipulability,
                    "mean manipulability over the samples (0 when not computed)")
      .def_property_readonly(
          "points",
          [](const WorkspaceResult& r) {
            Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P(r.points.size(), 3);
            for (std::size_t i = 0; i < r.points.size(); ++i) P.row(i) = r.points[i].p_WE;
            return P;
          },
          "frame positions (samples, 3) [m]")
      .def_property_readonly(
          "manipulabilities",
          [](const WorkspaceResult& r) {
            Eigen::VectorXd w(r.points.size());
            for (std::size_t i = 0; i < r.points.size(); ++i) w[i] = r.points[i].manipulability;
            return w;
          },
          "w per sample (samples,)")
      .def("write_csv", &WorkspaceResult::write_csv, py::arg("path"));
  m.def(
      "sample_workspace",
      [](const Chain& chain, std::size_t samples, std::uint64_t seed, bool compute_manipulability,
         bool keep_points) {
        WorkspaceOptions o;
        o.samples = samples;
        o.seed = seed;
        o.compute_manipulability = compute_manipulability;
        o.keep_points = keep_points;
        py::gil_scoped_release release;
        return sample_workspace(chain, o);
      },
      py::arg("chain"), py::arg("samples") = 10000, py::arg("seed") = 1,
      py::arg("compute_manipulability") = true, py::arg("keep_points") = true,
      "Seeded Monte-Carlo workspace sampling (GIL released).");
}

}  // namespace mjarm::python
