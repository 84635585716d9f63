// MuJoCo 3.x position actuators with dampratio: the damping gain follows from the reflected
// inertia at qpos0, m = sum_j dof_M0[j] / moment_j^2 over the dofs the actuator moves, as
// kv = dampratio * 2 * sqrt(kp * m). We compile the translated model once with MuJoCo 2.2.2 to
// get dof_M0 (the mass-matrix diagonal at qpos0, armature included) and the actuator moments.

#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

std::unique_ptr<mjModel, ModelDeleter> compile(const std::string& xml,
                                               const std::vector<MjcfSourceLine>& lines) {
  // the document is served from memory; its asset paths are absolute, so they load from disk
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* name = "mjarm_dampratio_probe.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw Error("MJCF translation: cannot create the in-memory file for the dampratio probe");
  }
  const int idx = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[idx], xml.data(), xml.size());
  char err[1024] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), err, sizeof(err));
  if (!m) {
    throw Error(std::string("MJCF translation: dampratio needs the model's inertia, but the "
                            "translated model does not compile in MuJoCo 2.2.2: ") +
                to_source_lines(err, lines));
  }
  return std::unique_ptr<mjModel, ModelDeleter>(m);
}

}  // namespace

void resolve_dampratios(XmlNode& root, const std::vector<PendingDampratio>& pending,
                        std::vector<std::string>& warnings) {
  if (pending.empty()) return;
  std::vector<MjcfSourceLine> lines;
  const std::string xml = write_document(root, &lines);
  const auto m = compile(xml, lines);
  const std::unique_ptr<mjData, DataDeleter> d(mj_makeData(m.get()));
  // transmission moments at qpos0 (mj_makeData starts there)
  mj_kinematics(m.get(), d.get());
  mj_comPos(m.get(), d.get());
  mj_tendon(m.get(), d.get());
  mj_transmission(m.get(), d.get());

  std::vector<XmlNode*> actuators;
  for (auto& section : root.children) {
    if (section.tag != "actuator") continue;
    for (auto& a : section.children) actuators.push_back(&a);
  }
  const int nv = m->nv;
  for (const PendingDampratio& p : pending) {
    const int i = static_cast<int>(p.actuator_index);
    if (i >= m->nu || p.actuator_index >= actuators.size()) {
      throw Error("MJCF translation: actuator count changed while resolving dampratio");
    }
    double mass = 0;
    for (int j = 0; j < nv; ++j) {
      const double trn = d->actuator_moment[i * nv + j];
      if (trn * trn > mjMINVAL) mass += m->dof_M0[j] / (trn * trn);
    }
    const double kp = m->actuator_gainprm[i * mjNGAIN];
    std::vector<double> bias(m->actuator_biasprm + i * mjNBIAS,
                             m->actuator_biasprm + (i + 1) * mjNBIAS);
    bias[2] = -p.dampratio * 2 * std::sqrt(kp * mass);
    XmlNode& act = *actuators[p.actuator_index];
    const std::string before = "biasprm=\"" + *act.find("biasprm") + "\"";
    act.set("biasprm", format_numbers(bias));
    if (p.warning_index < warnings.size()) {
      std::string& w = warnings[p.warning_index];
      const std::size_t at = w.rfind(before);
      if (at != std::string::npos) {
        w.replace(at, before.size(), "biasprm=\"" + *act.find("biasprm") + "\"");
      }
    }
  }
}

}  // namespace mjarm::mjcf_detail
