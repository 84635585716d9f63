// `mjarm traj KIND --start Q… --target Q… [limits] [--json] [--out FILE.csv] [--plot DIR]`: one
// motion profile of the trajectory room, sampled, summarized against its limits, written as CSV
// or JSON and drawn with gnuplot: a `JointMove` of the library (trajectory/joint_move.hpp).

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "field_options.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "mjarm/plot/trajectory_plot.hpp"
#include "mjarm/trajectory/joint_move.hpp"

namespace mjarm::cli {
namespace {

using Eigen::VectorXd;

// the kind's row of the library's table (the command line checked the name)
const ProfileKindInfo& traj_kind(const std::string& name) {
  return profile_kind_info(parse_enum<ProfileKind>(name, "kind", "KIND"));
}

// what the move says besides its samples, e.g. {"limiting axis", "0 (velocity)"}
std::vector<std::pair<std::string, std::string>> traj_notes(const JointMove& move) {
  const auto axis_or_none = [](Eigen::Index i) {
    return i < 0 ? std::string("none") : std::to_string(i);
  };
  switch (move.kind()) {
    case ProfileKind::trapezoid: {
      const auto& trapezoid = std::get<SyncedTrapezoid>(move.profile());
      std::string shapes;
      for (std::size_t k = 0; k < trapezoid.size(); ++k) {
        const TrapezoidProfile& axis = trapezoid.axis(k);
        shapes += (k ? ", " : "") + std::string(axis.distance() == 0.0 ? "still"
                                                : axis.triangular()    ? "triangle"
                                                                       : "trapezoid");
      }
      return {{"limiting axis", std::to_string(trapezoid.limiting_axis())},
              {"shapes", shapes},
              {"jerk", "0 inside each phase, unbounded at the switches (acceleration steps)"}};
    }
    case ProfileKind::smoothstep:
    case ProfileKind::smootherstep:
      if (move.duration() == 0.0) return {};  // nothing moves
      return {{"limiting axis", axis_or_none(move.limiting_axis())},
              {"continuity", move.kind() == ProfileKind::smoothstep
                                 ? "C¹: acceleration steps at both ends"
                                 : "C²: jerk steps at both ends"}};
    case ProfileKind::quintic: {
      const std::optional<QuinticDuration>& d = move.quintic_duration();
      if (!d) return {{"duration from", "--duration"}};
      return {
          {"duration from", "the limits (shortest, exact)"},
          {"limiting axis", d->limiting_joint < 0
                                ? std::string("none")
                                : std::to_string(d->limiting_joint) + " (" +
                                      (d->velocity_limited ? "velocity" : "acceleration") + ")"}};
    }
    case ProfileKind::jerk_limited: {
      const auto& otg = std::get<JerkLimitedGenerator>(move.profile());
      std::vector<std::pair<std::string, std::string>> notes{
          {"duration from", "the limits (time-optimal, synchronized)"},
          {"limiting axis", std::to_string(move.limiting_axis())}};
      std::string brakes;
      for (int i = 0; i < otg.dofs(); ++i) {
        if (otg.brake_phases(i) == 0) continue;
        const JerkExtrema b = otg.profile(i).extrema();
        brakes += (brakes.empty() ? "" : "; ") + std::string("axis ") + std::to_string(i) +
                  " for " + compact(otg.brake_duration(i)) + " s (peak |v| " +
                  compact(std::max(std::abs(b.v_min), std::abs(b.v_max))) + ", |a| " +
                  compact(std::max(std::abs(b.a_min), std::abs(b.a_max))) + " while braking)";
      }
      if (!brakes.empty())
        notes.push_back({"braking first", brakes + "; the peaks below are after the brake"});
      return notes;
    }
  }
  return {};
}

// e.g. "axis 0: peak |v| 3.75 > v max 0.18"
std::string violation_text(const LimitViolation& v) {
  const char* what = v.quantity == LimitViolation::Quantity::velocity       ? "v"
                     : v.quantity == LimitViolation::Quantity::acceleration ? "a"
                                                                            : "j";
  return "axis " + std::to_string(v.axis) + ": peak |" + what + "| " + number_text(v.peak) + " > " +
         what + " max " + number_text(v.limit);
}

// @p values as n entries: one value for all, or n values
VectorXd traj_per_axis(const std::vector<double>& values, Eigen::Index n, const char* option,
                       double fallback, bool positive) {
  if (values.empty()) return VectorXd::Constant(n, fallback);
  if (values.size() != 1 && static_cast<Eigen::Index>(values.size()) != n)
    throw UsageError(std::string(option) + " needs " +
                     (n == 1 ? std::string("1 value") : "1 or " + std::to_string(n) + " values") +
                     " (one per axis), got " + std::to_string(values.size()));
  VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v[i] = values.size() == 1 ? values[0] : values[static_cast<std::size_t>(i)];
    if (positive && !(v[i] > 0.0))
      throw UsageError(std::string(option) + " must be positive, got " + compact(v[i]));
  }
  return v;
}

// a profile beyond its limits fails the command (after its report) unless --allow-violation
void fail_on_violation(const std::vector<std::string>& violations, bool allowed) {
  if (violations.empty() || allowed) return;
  throw Error("the profile breaks its limits (" + join(violations, "; ") +
              "); no CSV or plot was written; pass --allow-violation to accept it");
}

void write_traj_csv(const std::string& path, const std::vector<double>& t,
                    const std::array<std::vector<VectorXd>, 4>& x) {
  FileWriter out(path, FileWriter::Mode::replace, "trajectory CSV");
  const Eigen::Index n = x[0].front().size();
  out.write("t");
  char number[32];
  for (const char* name : {"q", "qd", "qdd", "qddd"})
    for (Eigen::Index i = 0; i < n; ++i) {
      std::snprintf(number, sizeof(number), ",%s%ld", name, static_cast<long>(i));
      out.write(number);
    }
  out.write("\n");
  for (std::size_t s = 0; s < t.size(); ++s) {
    // Ctrl-C: stop at once, the partial CSV removed and the old file kept
    if (s % 1024 == 0) stop_writing_if_interrupted("traj", path);
    out.write(number,
              static_cast<std::size_t>(std::snprintf(number, sizeof(number), "%.17g", t[s])));
    for (std::size_t k = 0; k < 4; ++k)
      for (Eigen::Index i = 0; i < n; ++i)
        out.write(number, static_cast<std::size_t>(
                              std::snprintf(number, sizeof(number), ",%.17g", x[k][s][i])));
    out.write("\n");
  }
  stop_writing_if_interrupted("traj", path);
  out.commit();  // the whole CSV or the old file: a write error names the file and the reason
}

}  // namespace

Command add_traj_command(CLI::App& root) {
  struct Options {
    std::string kind;
    std::vector<double> start, target, start_velocity, start_acceleration, target_velocity,
        target_acceleration, v_max, a_max, j_max;
    double duration = std::numeric_limits<double>::quiet_NaN();
    double rate = 250.0;
    std::string unit = "m";
    std::string out;
    std::string plot;
    std::string size = "1280x1200";
    bool allow_violation = false;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  std::string kinds_help;
  for (const ProfileKindInfo& kind : profile_kinds())
    kinds_help += std::string("\n  ") + kind.name + ": " + kind.summary;
  CLI::App* app = root.add_subcommand(
      "traj", "sample a motion profile (trapezoid, quintic, smoothstep, …) against its limits");
  app->footer("Kinds:" + kinds_help +
              "\nLimits take one value for every axis or one per axis; the defaults are those of "
              "the classic trapezoid (0.18 m/s, 0.9 m/s²). Without --duration each kind takes "
              "its shortest duration within the limits. --plot needs gnuplot (Debian: apt-get "
              "install gnuplot-nox).");
  app->add_option("KIND", options->kind, "profile kind: " + join(enum_names<ProfileKind>(), " | "))
      ->required()
      ->check(name_of<ProfileKind>("kind"));
  const auto vector_option = [&](const char* name, std::vector<double>& values, const char* help) {
    return app->add_option(name, values, help)
        ->check(finite_number())
        ->expected(1, -1)
        ->delimiter(',');
  };
  vector_option("--start", options->start, "start positions, one per axis [u]")->required();
  vector_option("--target", options->target, "target positions, one per axis [u]")->required();
  vector_option("--start-velocity", options->start_velocity,
                "start velocities [u/s] (quintic, jerk-limited)");
  vector_option("--start-acceleration", options->start_acceleration,
                "start accelerations [u/s²] (quintic, jerk-limited)");
  vector_option("--target-velocity", options->target_velocity,
                "target velocities [u/s] (quintic, jerk-limited)");
  vector_option("--target-acceleration", options->target_acceleration,
                "target accelerations [u/s²] (quintic, jerk-limited)");
  vector_option("--v-max", options->v_max, "velocity limits [u/s] (default 0.18)");
  vector_option("--a-max", options->a_max, "acceleration limits [u/s²] (default 0.9)");
  vector_option("--j-max", options->j_max,
                "jerk limits [u/s³]: the jerk-limited kind's, drawn on the plot for every kind "
                "(default none)");
  app->add_option("--duration", options->duration,
                  "the duration T [s] instead of the shortest within the limits (quintic, "
                  "smoothstep, smootherstep)")
      ->check(finite_number());
  app->add_option("--rate", options->rate, "samples per second of the output [Hz]")
      ->capture_default_str()
      ->check(finite_number())
      ->check(number_in(1.0, 1e6));
  app->add_option("--unit", options->unit, "the position unit, for labels (m, rad, …)")
      ->capture_default_str();
  app->add_option("--out", options->out, "write the samples as CSV (t, q…, qd…, qdd…, qddd…)");
  app->add_option("--plot", options->plot,
                  "draw DIR/trajectory.png: position, velocity, acceleration, jerk vs limits");
  app->add_option("--size", options->size, "plot size WIDTHxHEIGHT [pixels]")
      ->capture_default_str()
      ->check(pixel_size({200, 300}));
  app->add_flag("--allow-violation", options->allow_violation,
                "accept a profile whose peaks break its limits (exit 0, outputs written); "
                "without it such a profile is reported and the command fails (exit 1)");
  add_json_flag(*app, options->json);

  return {
      app, [options] {
        const Options& o = *options;
        // outputs first: a path that cannot be written is a usage error before any work
        if (!o.out.empty()) check_output_file(o.out, "--out");
        if (!o.plot.empty()) {
          check_output_folder(o.plot, "--plot");
          plot::find_gnuplot();
        }
        const ProfileKindInfo& kind = traj_kind(o.kind);
        const auto n = static_cast<Eigen::Index>(o.start.size());
        if (static_cast<Eigen::Index>(o.target.size()) != n)
          throw UsageError("--start has " + std::to_string(n) + " values but --target has " +
                           std::to_string(o.target.size()));
        JointMoveRequest r;
        r.start = Eigen::Map<const VectorXd>(o.start.data(), n);
        r.target = Eigen::Map<const VectorXd>(o.target.data(), n);
        r.start_velocity = traj_per_axis(o.start_velocity, n, "--start-velocity", 0.0, false);
        r.start_acceleration =
            traj_per_axis(o.start_acceleration, n, "--start-acceleration", 0.0, false);
        r.target_velocity = traj_per_axis(o.target_velocity, n, "--target-velocity", 0.0, false);
        r.target_acceleration =
            traj_per_axis(o.target_acceleration, n, "--target-acceleration", 0.0, false);
        r.max_velocity =
            traj_per_axis(o.v_max, n, "--v-max", TrapezoidProfile::kDefaultMaxVelocity, true);
        r.max_acceleration =
            traj_per_axis(o.a_max, n, "--a-max", TrapezoidProfile::kDefaultMaxAcceleration, true);
        r.max_jerk =
            traj_per_axis(o.j_max, n, "--j-max", std::numeric_limits<double>::quiet_NaN(), true);
        if (!std::isnan(o.duration)) {
          if (!(o.duration > 0.0))
            throw UsageError("--duration must be positive, got " + compact(o.duration) + " s");
          r.duration = o.duration;
        }
        // what the kind does not take is a usage error, named by its option
        const bool moving = r.start_velocity.any() || r.start_acceleration.any() ||
                            r.target_velocity.any() || r.target_acceleration.any();
        if (moving && !kind.moving_ends)
          throw UsageError(std::string(kind.name) +
                           " moves from rest to rest: boundary velocities and accelerations "
                           "need a kind that takes them (quintic, jerk-limited)");
        if (r.duration && kind.kind == ProfileKind::trapezoid)
          throw UsageError(
              "trapezoid: the duration follows from --v-max and --a-max (--duration is for "
              "quintic, smoothstep and smootherstep)");
        if (r.duration && !kind.given_duration)
          throw UsageError(std::string(kind.name) +
                           ": the duration is the time-optimal one under --v-max, --a-max and "
                           "--j-max (--duration is for quintic, smoothstep and smootherstep)");
        if (kind.jerk_limit && r.max_jerk.hasNaN())
          throw UsageError(std::string(kind.name) + " needs --j-max (one value or one per axis)");
        const JointMove move(kind.kind, r);
        const double duration = move.duration();
        const TrajectoryPeaks& peaks = move.peaks();
        const std::vector<std::pair<std::string, std::string>> notes = traj_notes(move);

        // samples at the rate, and the end
        const double steps = std::floor(duration * o.rate);
        if (steps > 1e6)
          throw UsageError("T = " + compact(duration) + " s at --rate " + compact(o.rate) +
                           " Hz gives over 10⁶ samples: lower --rate");
        std::vector<double> t;
        for (double k = 0; k <= steps; ++k) t.push_back(k / o.rate);
        if (t.back() < duration) t.push_back(duration);
        std::array<std::vector<VectorXd>, 4> x;
        for (auto& series : x) series.assign(t.size(), VectorXd::Zero(n));
        TrajectorySample sample(n);
        for (std::size_t s = 0; s < t.size(); ++s) {
          move.at(t[s], sample);
          x[0][s] = sample.position;
          x[1][s] = sample.velocity;
          x[2][s] = sample.acceleration;
          x[3][s] = sample.jerk;
        }
        std::vector<std::string> violations;
        for (const LimitViolation& v : move.violations()) violations.push_back(violation_text(v));
        const bool within = violations.empty();
        // a profile that breaks its limits writes nothing unless accepted
        const bool write = within || o.allow_violation;

        // Ctrl-C or SIGTERM while the CSV is written or gnuplot draws: nothing half-written is
        // left, an old CSV is kept (exit 130/143); a signal before this point ends the process
        // with nothing written yet
        std::optional<InterruptGuard> interrupts;
        if (write && (!o.out.empty() || !o.plot.empty())) interrupts.emplace();
        if (write && !o.out.empty()) write_traj_csv(o.out, t, x);
        std::string plot_path;
        if (write && !o.plot.empty()) {
          plot::TrajectorySeries series;
          series.title = std::string(kind.name) + ", " + std::to_string(n) +
                         (n == 1 ? " axis" : " axes") + ", T = " + compact(duration) + " s";
          series.unit = o.unit;
          series.t = t;
          for (Eigen::Index i = 0; i < n; ++i) series.axes.push_back("axis " + std::to_string(i));
          for (std::size_t k = 0; k < 4; ++k) {
            series.values[k].assign(static_cast<std::size_t>(n), std::vector<double>(t.size()));
            for (std::size_t s = 0; s < t.size(); ++s)
              for (Eigen::Index i = 0; i < n; ++i)
                series.values[k][static_cast<std::size_t>(i)][s] = x[k][s][i];
          }
          const std::array<const VectorXd*, 3> limits{&r.max_velocity, &r.max_acceleration,
                                                      &r.max_jerk};
          for (std::size_t k = 1; k < 4; ++k)
            series.limits[k].assign(limits[k - 1]->data(), limits[k - 1]->data() + n);
          const PixelSize size = parse_pixel_size(o.size);
          plot::PlotOptions plot_options;
          plot_options.width = size.width;
          plot_options.height = size.height;
          // Ctrl-C stops gnuplot; what it drew and its data are removed (exit 130)
          try {
            plot_path = plot::plot_trajectory(series, o.plot, plot_options).path.string();
          } catch (const Error& e) {
            if (interrupt_requested()) throw InterruptedError(e.what(), interrupt_signal());
            throw;
          }
        }

        if (o.json) {
          Json document;
          document["kind"] = kind.name;
          document["axes"] = n;
          document["duration"] = duration;
          document["within_limits"] = within;
          document["limits"] = {{"velocity", vector_json(r.max_velocity)},
                                {"acceleration", vector_json(r.max_acceleration)}};
          document["limits"]["jerk"] = Json::array();
          for (Eigen::Index i = 0; i < n; ++i)
            document["limits"]["jerk"].push_back(number_or_null(r.max_jerk[i]));  // NaN: none
          document["peaks"] = {{"velocity", vector_json(peaks.velocity)},
                               {"acceleration", vector_json(peaks.acceleration)}};
          document["peaks"]["jerk"] = Json::array();  // null: unbounded (acceleration steps)
          for (Eigen::Index i = 0; i < n; ++i)
            document["peaks"]["jerk"].push_back(number_or_null(peaks.jerk[i]));
          document["notes"] = Json::object();
          for (const auto& [key, value] : notes) document["notes"][key] = value;
          document["violations"] = violations;
          if (write && !o.out.empty()) document["csv"] = o.out;
          if (!plot_path.empty()) document["plot"] = plot_path;
          document["rate"] = o.rate;
          document["samples"] = Json::array();
          for (std::size_t s = 0; s < t.size(); ++s)
            document["samples"].push_back({{"t", t[s]},
                                           {"q", vector_json(x[0][s])},
                                           {"qd", vector_json(x[1][s])},
                                           {"qdd", vector_json(x[2][s])},
                                           {"qddd", vector_json(x[3][s])}});
          print_json(document);
          if (interrupts) report_interrupt_after_writing("traj", o.out.empty() ? plot_path : o.out);
          return fail_on_violation(violations, o.allow_violation);
        }
        std::vector<std::pair<std::string, std::string>> fields{
            {"kind", kind.name},
            {"axes", std::to_string(n)},
            {"duration", fixed(duration, 6) + " s"},
            {"within limits", within ? "yes" : "NO"}};
        for (const auto& note : notes) fields.push_back(note);
        fields.push_back({"samples", std::to_string(t.size()) + " at " + compact(o.rate) + " Hz"});
        if (write && !o.out.empty()) fields.push_back({"csv", o.out});
        if (!plot_path.empty()) fields.push_back({"plot", plot_path});
        print_fields(std::cout, fields);
        Table table({{"axis"},
                     {"start [" + o.unit + "]"},
                     {"target [" + o.unit + "]"},
                     {"peak |v|"},
                     {"v max"},
                     {"peak |a|"},
                     {"a max"},
                     {"peak |j|"},
                     {"j max"}});
        for (Eigen::Index i = 0; i < n; ++i)
          table.add_row({std::to_string(i), fixed(r.start[i]), fixed(r.target[i]),
                         fixed(peaks.velocity[i]), fixed(r.max_velocity[i]),
                         fixed(peaks.acceleration[i]), fixed(r.max_acceleration[i]),
                         fixed(peaks.jerk[i]),
                         std::isnan(r.max_jerk[i]) ? std::string("-") : fixed(r.max_jerk[i])});
        std::cout << '\n';
        table.print(std::cout);
        if (interrupts) report_interrupt_after_writing("traj", o.out.empty() ? plot_path : o.out);
        fail_on_violation(violations, o.allow_violation);
      }};
}

}  // namespace mjarm::cli
