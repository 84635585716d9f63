#include "replay_frames.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/plot/csv_rows.hpp"
#include "recorded_state.hpp"
#include "replay_cameras.hpp"

namespace mjarm::web_detail {
namespace {

namespace fs = std::filesystem;

void check_qpos_columns(const mjModel& m, const plot::CsvRowReader& state) {
  std::size_t recorded = 0;
  for (const std::string& h : state.header())
    if (h.size() > 2 && h.compare(0, 2, "q.") == 0) ++recorded;
  const std::vector<std::string> columns = qpos_columns(m);
  for (const std::string& column : columns) {
    if (state.find(column) < 0) {
      throw Error("replay-html: the model does not match the recording: '" + state.path().string() +
                  "' has no column '" + column + "' (the model has " + std::to_string(m.nq) +
                  " qpos coordinates, the recording " + std::to_string(recorded) + " q.* columns)");
    }
  }
  if (recorded != columns.size()) {
    throw Error("replay-html: the model does not match the recording: the model has " +
                std::to_string(m.nq) + " qpos coordinates, '" + state.path().string() + "' " +
                std::to_string(recorded) + " q.* columns");
  }
}

}  // namespace

double recorded_time(const plot::CsvRowReader& state, std::size_t column, double previous) {
  const double t = state.number(column);
  if (!std::isfinite(t)) {
    throw Error("'" + state.path().string() + "' line " + std::to_string(state.line()) + ": t is " +
                number_text(t) + ", not a finite time");
  }
  if (t < previous) {
    throw Error("'" + state.path().string() + "' line " + std::to_string(state.line()) +
                ": t = " + number_text(t) +
                " s goes back in time (the row before: " + number_text(previous) + " s)");
  }
  return t;
}

namespace {

// One state row held back until the next one says whether it is the last at or before a frame
// time: its cells of the columns the frames need, as text (parsed only when kept).
struct HeldRow {
  double t = 0.0;
  std::size_t line = 0;
  bool kept = false;
  std::vector<std::string> cells;
};

// the columns a frame reads: qpos, qvel, ctrl (−1: not recorded) and the plots' series
struct FrameColumns {
  std::vector<int> qpos, qvel, ctrl, series;
  std::vector<int> all;  // the held cells, in this order: qpos, qvel, ctrl, series
};

FrameColumns frame_columns(const mjModel& m, const plot::CsvRowReader& state,
                           const std::vector<std::string>& series) {
  FrameColumns c;
  for (const std::string& name : qpos_columns(m))
    c.qpos.push_back(static_cast<int>(state.require(name)));
  for (const std::string& name : qvel_columns(m)) c.qvel.push_back(state.find(name));
  for (int a = 0; a < m.nu; ++a) {
    const char* name = mj_id2name(&m, mjOBJ_ACTUATOR, a);
    c.ctrl.push_back(state.find(std::string("ctrl.") + (name != nullptr ? name : "")));
  }
  for (const std::string& name : series) c.series.push_back(static_cast<int>(state.require(name)));
  for (const auto* list : {&c.qpos, &c.qvel, &c.ctrl, &c.series})
    c.all.insert(c.all.end(), list->begin(), list->end());
  return c;
}

class FrameMaker {
 public:
  FrameMaker(const mjModel& m, const fs::path& path, const FrameColumns& columns,
             ReplayFrames& frames)
      : m_(m),
        path_(path),
        columns_(columns),
        frames_(frames),
        data_(mj_makeData(&m), mj_deleteData) {
    if (!data_) throw Error("replay-html: MuJoCo could not allocate the data of the model");
  }

  // the frame of @p row; false (and `stopped` said) when its qpos is not finite
  bool add(const HeldRow& row, const std::vector<std::string>& header) {
    mjData& d = *data_;
    mj_resetData(&m_, &d);
    std::size_t cell = 0;
    auto next = [&](int column) {
      const std::string& text = row.cells[cell++];
      if (column < 0) return 0.0;
      if (text.empty()) return std::nan("");
      const auto value = number_from_text(text);
      if (!value) {
        throw Error("'" + path_.string() + "' column '" + header[static_cast<std::size_t>(column)] +
                    "' line " + std::to_string(row.line) + ": '" + text + "' is not a number");
      }
      return *value;
    };
    for (int i = 0; i < m_.nq; ++i) {
      d.qpos[i] = next(columns_.qpos[static_cast<std::size_t>(i)]);
      if (!std::isfinite(d.qpos[i])) {
        const std::string column =
            header[static_cast<std::size_t>(columns_.qpos[static_cast<std::size_t>(i)])];
        if (frames_.time.empty()) {
          throw Error("'" + path_.string() + "' line " + std::to_string(row.line) + ": " + column +
                      " is " + number_text(d.qpos[i]) + " in the first row: nothing to replay");
        }
        frames_.stopped =
            "the recording's " + column + " is " + number_text(d.qpos[i]) +
            " at t = " + number_text(row.t, 6) + " s (state.csv line " + std::to_string(row.line) +
            ", a diverged run?): the replay ends at t = " + number_text(frames_.time.back(), 6) +
            " s";
        return false;
      }
    }
    for (int i = 0; i < m_.nv; ++i) d.qvel[i] = next(columns_.qvel[static_cast<std::size_t>(i)]);
    for (int a = 0; a < m_.nu; ++a) d.ctrl[a] = next(columns_.ctrl[static_cast<std::size_t>(a)]);
    for (const int column : columns_.series)
      frames_.series[header[static_cast<std::size_t>(column)]].push_back(next(column));
    mj_forward(&m_, &d);
    for (int b = 0; b < m_.nbody; ++b) {
      for (int i = 0; i < 3; ++i) frames_.pos.push_back(static_cast<float>(d.xpos[3 * b + i]));
      for (int i = 0; i < 4; ++i) frames_.quat.push_back(static_cast<float>(d.xquat[4 * b + i]));
    }
    // the cameras that move (mj_forward posed them: mj_camlight)
    for (int c = 0; c < m_.ncam; ++c) {
      if (!camera_moves(m_, c)) continue;
      mjtNum q[4];
      mju_mat2Quat(q, d.cam_xmat + 9 * c);
      for (int i = 0; i < 3; ++i)
        frames_.camera_pos.push_back(static_cast<float>(d.cam_xpos[3 * c + i]));
      for (int i = 0; i < 4; ++i) frames_.camera_quat.push_back(static_cast<float>(q[i]));
    }
    for (int c = 0; c < d.ncon; ++c) {
      const mjContact& contact = d.contact[c];
      if (contact.exclude != 0) continue;
      mjtNum local[6], world[3];
      mj_contactForce(&m_, &d, c, local);
      // the contact frame's rows are its axes in world coordinates (normal first)
      mju_mulMatTVec(world, contact.frame, local, 3, 3);
      for (int i = 0; i < 3; ++i) frames_.contacts.push_back(static_cast<float>(contact.pos[i]));
      for (int i = 0; i < 3; ++i) frames_.contacts.push_back(static_cast<float>(world[i]));
    }
    frames_.contact_offsets.push_back(static_cast<unsigned>(frames_.contacts.size() / 6));
    if (!frames_.time.empty())
      frames_.largest_gap = std::max(frames_.largest_gap, row.t - frames_.time.back());
    frames_.time.push_back(row.t);
    return true;
  }

 private:
  const mjModel& m_;
  const fs::path& path_;
  const FrameColumns& columns_;
  ReplayFrames& frames_;
  std::unique_ptr<mjData, decltype(&mj_deleteData)> data_;
};

}  // namespace

StateScan scan_state(const mjModel& m, const fs::path& state_csv) {
  plot::CsvRowReader state(state_csv, "recorded table");
  check_qpos_columns(m, state);
  const std::size_t t = state.require("t");
  StateScan scan;
  double previous = -std::numeric_limits<double>::infinity();
  while (state.next()) {
    previous = recorded_time(state, t, previous);
    if (scan.rows == 0) scan.first = previous;
    ++scan.rows;
  }
  if (scan.rows == 0)
    throw Error("'" + state_csv.string() +
                "' has no rows (the run never ticked): nothing to replay");
  scan.last = previous;
  return scan;
}

ReplayFrames replay_frames(const mjModel& m, const fs::path& state_csv, double rate,
                           const std::vector<std::string>& series) {
  plot::CsvRowReader state(state_csv, "recorded table");
  check_qpos_columns(m, state);
  const std::size_t t_column = state.require("t");
  const FrameColumns columns = frame_columns(m, state, series);
  ReplayFrames frames;
  for (int c = 0; c < m.ncam; ++c)
    if (camera_moves(m, c)) frames.cameras.push_back(c);
  FrameMaker maker(m, state_csv, columns, frames);

  HeldRow held;
  held.cells.resize(columns.all.size());
  auto hold = [&](double t) {
    held.t = t;
    held.line = state.line();
    held.kept = false;
    for (std::size_t i = 0; i < columns.all.size(); ++i) {
      const int column = columns.all[i];
      if (column >= 0) held.cells[i].assign(state.cell(static_cast<std::size_t>(column)));
    }
  };
  auto keep = [&] {
    if (held.kept) return true;
    held.kept = true;
    return maker.add(held, state.header());
  };
  if (!state.next())
    throw Error("'" + state_csv.string() +
                "' has no rows (the run never ticked): nothing to replay");
  const double t0 = recorded_time(state, t_column, -std::numeric_limits<double>::infinity());
  hold(t0);
  keep();
  // frame k at t0 + k/rate shows the last row at or before it (a millionth of a period of slack:
  // 1/60 s is no whole number of 2 ms steps in binary); the held row is at or before frame k's
  // time until a row after it comes
  const double slack = 1e-6 / rate;
  double k = 1.0;
  while (state.next()) {
    const double t = recorded_time(state, t_column, held.t);
    if (t > t0 + k / rate + slack) {
      if (!keep()) return frames;
      // the next frame time at which this row is the last: the first whose time is not before it
      k = std::max(k + 1.0, std::ceil((t - slack - t0) * rate));
      while (t0 + k / rate + slack < t) k += 1.0;
    }
    hold(t);
  }
  keep();  // the last row
  return frames;
}

std::vector<std::size_t> every_kth(std::size_t n, std::size_t k) {
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(k, 1)) keep.push_back(i);
  if (n > 0 && keep.back() != n - 1) keep.push_back(n - 1);
  return keep;
}

ReplayFrames select_frames(const ReplayFrames& frames, const std::vector<std::size_t>& keep) {
  ReplayFrames out;
  out.stopped = frames.stopped;
  out.cameras = frames.cameras;
  const std::size_t nbody = frames.time.empty() ? 0 : frames.pos.size() / 3 / frames.time.size();
  const std::size_t ncam = frames.cameras.size();
  for (std::size_t f : keep) {
    out.camera_pos.insert(
        out.camera_pos.end(), frames.camera_pos.begin() + static_cast<std::ptrdiff_t>(f * ncam * 3),
        frames.camera_pos.begin() + static_cast<std::ptrdiff_t>((f + 1) * ncam * 3));
    out.camera_quat.insert(
        out.camera_quat.end(),
        frames.camera_quat.begin() + static_cast<std::ptrdiff_t>(f * ncam * 4),
        frames.camera_quat.begin() + static_cast<std::ptrdiff_t>((f + 1) * ncam * 4));
    out.pos.insert(out.pos.end(), frames.pos.begin() + static_cast<std::ptrdiff_t>(f * nbody * 3),
                   frames.pos.begin() + static_cast<std::ptrdiff_t>((f + 1) * nbody * 3));
    out.quat.insert(out.quat.end(),
                    frames.quat.begin() + static_cast<std::ptrdiff_t>(f * nbody * 4),
                    frames.quat.begin() + static_cast<std::ptrdiff_t>((f + 1) * nbody * 4));
    out.contacts.insert(
        out.contacts.end(),
        frames.contacts.begin() + static_cast<std::ptrdiff_t>(frames.contact_offsets[f] * 6),
        frames.contacts.begin() + static_cast<std::ptrdiff_t>(frames.contact_offsets[f + 1] * 6));
    out.contact_offsets.push_back(static_cast<unsigned>(out.contacts.size() / 6));
    for (const auto& [name, values] : frames.series) out.series[name].push_back(values[f]);
    if (!out.time.empty())
      out.largest_gap = std::max(out.largest_gap, frames.time[f] - out.time.back());
    out.time.push_back(frames.time[f]);
  }
  return out;
}

}  // namespace mjarm::web_detail
