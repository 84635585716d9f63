// `mjarm traj KIND --start Q… --target Q… [limits] [--json] [--out FILE.csv] [--plot DIR]`: one
// motion profile of the trajectory room, sampled, summarized against its limits, written as CSV
// or JSON and drawn with gnuplot. A kind is one build function and one row of kTrajKinds.

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/plot/gnuplot.hpp"
#include "mjarm/plot/trajectory_plot.hpp"
#include "mjarm/trajectory/jerk_limited.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm::cli {
namespace {

using Eigen::VectorXd;

// What every kind receives: boundary states and limits, one entry per axis (j_max NaN: none).
struct TrajRequest {
  VectorXd q0, qd0, qdd0, q1, qd1, qdd1;
  VectorXd v_max, a_max, j_max;
  std::optional<double> duration;  // --duration: the kind's duration instead of the shortest
};

// What every kind returns: its duration, the state at any t, the exact peaks, and notes.
struct TrajProfile {
  double duration = 0.0;
  std::function<void(double t, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd)> at;
  VectorXd peak_velocity, peak_acceleration, peak_jerk;  // infinite jerk: acceleration steps
  std::vector<std::pair<std::string, std::string>> notes;
};

// One profile kind of `mjarm traj`.
struct TrajKind {
  const char* name;
  const char* summary;
  bool moving_ends;  // accepts boundary velocities and accelerations
  TrajProfile (*build)(const TrajRequest&);
};

TrajProfile build_trapezoid(const TrajRequest& r) {
  if (r.duration)
    throw UsageError(
        "trapezoid: the duration follows from --v-max and --a-max (--duration is for "
        "quintic, smoothstep and smootherstep)");
  auto move = std::make_shared<SyncedTrapezoid>(r.q0, r.q1, r.v_max, r.a_max);
  TrajProfile p;
  p.duration = move->duration();
  p.at = [move](double t, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd) {
    move->at(t, q, qd, qdd);
    qddd.setZero();
  };
  const Eigen::Index n = r.q0.size();
  p.peak_velocity.resize(n);
  p.peak_acceleration.resize(n);
  p.peak_jerk = VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  std::string shapes;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double lambda = move->time_scale(k);
    const TrapezoidProfile& axis = move->axis(k);
    p.peak_velocity[i] = lambda * axis.peak_velocity();
    p.peak_acceleration[i] = axis.distance() > 0.0 ? lambda * lambda * axis.acceleration() : 0.0;
    shapes += (i ? ", " : "") + std::string(axis.distance() == 0.0 ? "still"
                                            : axis.triangular()    ? "triangle"
                                                                   : "trapezoid");
  }
  p.notes = {{"limiting axis", std::to_string(move->limiting_axis())},
             {"shapes", shapes},
             {"jerk", "0 inside each phase, unbounded at the switches (acceleration steps)"}};
  return p;
}

TrajProfile build_ramp(const TrajRequest& r, SmoothRamp::Kind kind) {
  const VectorXd d = r.q1 - r.q0;
  double T = 0.0;
  std::string limiting = "none";
  if (r.duration) {
    T = *r.duration;
  } else {
    for (Eigen::Index i = 0; i < d.size(); ++i) {
      const double Ti = SmoothRamp::duration_for(kind, std::abs(d[i]), r.v_max[i], r.a_max[i]);
      if (Ti > T) {
        T = Ti;
        limiting = std::to_string(i);
      }
    }
  }
  TrajProfile p;
  p.duration = T;
  const VectorXd q0 = r.q0;
  if (T == 0.0) {  // nothing moves
    p.at = [q0](double, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd) {
      q = q0;
      qd.setZero();
      qdd.setZero();
      qddd.setZero();
    };
    p.peak_velocity = p.peak_acceleration = p.peak_jerk = VectorXd::Zero(d.size());
    return p;
  }
  const SmoothRamp ramp(kind, T);
  p.at = [ramp, q0, d](double t, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd) {
    const RampSample s = ramp.at(t);
    q = q0 + s.s * d;
    qd = s.ds * d;
    qdd = s.dds * d;
    qddd = s.ddds * d;
  };
  p.peak_velocity = SmoothRamp::peak_slope(kind) / T * d.cwiseAbs();
  p.peak_acceleration = SmoothRamp::peak_curvature(kind) / (T * T) * d.cwiseAbs();
  p.peak_jerk = SmoothRamp::peak_jerk(kind) / (T * T * T) * d.cwiseAbs();
  p.notes = {
      {"limiting axis", limiting},
      {"continuity", kind == SmoothRamp::Kind::smoothstep ? "C¹: acceleration steps at both ends"
                                                          : "C²: jerk steps at both ends"}};
  return p;
}

TrajProfile build_smoothstep(const TrajRequest& r) {
  return build_ramp(r, SmoothRamp::Kind::smoothstep);
}

TrajProfile build_smootherstep(const TrajRequest& r) {
  return build_ramp(r, SmoothRamp::Kind::smootherstep);
}

TrajProfile build_quintic(const TrajRequest& r) {
  const QuinticTrajectory::State start{r.q0, r.qd0, r.qdd0}, end{r.q1, r.qd1, r.qdd1};
  TrajProfile p;
  if (r.duration) {
    p.duration = *r.duration;
    p.notes.push_back({"duration from", "--duration"});
  } else {
    const QuinticDuration d = shortest_quintic_duration(start, end, r.v_max, r.a_max);
    if (d.status != QuinticDurationStatus::ok)
      throw Error(std::string("no quintic duration keeps the limits: ") + to_string(d.status) +
                  (d.limiting_joint >= 0
                       ? " (axis " + std::to_string(d.limiting_joint) + ", " +
                             (d.velocity_limited ? "velocity" : "acceleration") + ")"
                       : std::string()));
    p.duration = d.duration;
    p.notes.push_back({"duration from", "the limits (shortest, exact)"});
    p.notes.push_back(
        {"limiting axis", d.limiting_joint < 0
                              ? std::string("none")
                              : std::to_string(d.limiting_joint) + " (" +
                                    (d.velocity_limited ? "velocity" : "acceleration") + ")"});
  }
  auto traj = std::make_shared<QuinticTrajectory>(start, end, p.duration);
  p.at = [traj](double t, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd) {
    traj->at(t, q, qd, qdd, qddd);
  };
  p.peak_velocity.resize(r.q0.size());
  p.peak_acceleration.resize(r.q0.size());
  p.peak_jerk.resize(r.q0.size());
  for (Eigen::Index i = 0; i < r.q0.size(); ++i) {
    const Quintic::Peaks peaks = traj->joint(i).peaks();
    p.peak_velocity[i] = peaks.velocity;
    p.peak_acceleration[i] = peaks.acceleration;
    p.peak_jerk[i] = peaks.jerk;
  }
  return p;
}

TrajProfile build_jerk_limited(const TrajRequest& r) {
  if (r.duration)
    throw UsageError(
        "jerk-limited: the duration is the time-optimal one under --v-max, --a-max and --j-max "
        "(--duration is for quintic, smoothstep and smootherstep)");
  const Eigen::Index n = r.q0.size();
  if (r.j_max.hasNaN()) throw UsageError("jerk-limited needs --j-max (one value or one per axis)");
  std::vector<JerkLimits> limits;
  std::vector<KinematicState> start, target;
  for (Eigen::Index i = 0; i < n; ++i) {
    limits.push_back({r.v_max[i], r.a_max[i], r.j_max[i]});
    start.push_back({r.q0[i], r.qd0[i], r.qdd0[i]});
    target.push_back({r.q1[i], r.qd1[i], r.qdd1[i]});
  }
  auto otg = std::make_shared<JerkLimitedGenerator>(limits);
  const OtgResult result = otg->calculate(start, target);  // an unreachable target throws
  if (result.status == OtgStatus::error_precision) {
    std::string check;
    if (result.end_error > OtgResult::kEndTolerance)
      check = "its end misses the target by " + compact(result.end_error) +
              " relative to the start and target (tolerance " +
              compact(OtgResult::kEndTolerance) + ")";
    else if (result.limit_excess > OtgResult::kLimitTolerance)
      check = "it exceeds a limit by " + compact(result.limit_excess) + " relative (tolerance " +
              compact(OtgResult::kLimitTolerance) + ")";
    else
      check = "an axis's profile lasts " + compact(result.sync_error) + " s more or less than " +
              compact(result.duration) + " s";
    throw Error("jerk-limited: no trajectory on axis " + std::to_string(result.failed_dof) +
                " (error_precision): " + check +
                "; limits this far apart make the motion too large for double precision (see "
                "\"Supported limits\" in docs/trajectory_otg.md)");
  }
  if (result.status != OtgStatus::working && result.status != OtgStatus::finished)
    throw Error(std::string("jerk-limited: no trajectory (") + to_string(result.status) +
                (result.failed_dof >= 0 ? ", axis " + std::to_string(result.failed_dof) : "") +
                ")");
  TrajProfile p;
  p.duration = result.duration;
  p.at = [otg, n](double t, VectorXd& q, VectorXd& qd, VectorXd& qdd, VectorXd& qddd) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const JerkSample s = otg->profile(static_cast<int>(i)).at(t);
      q[i] = s.p;
      qd[i] = s.v;
      qdd[i] = s.a;
      qddd[i] = t <= otg->duration() ? s.j : 0.0;
    }
  };
  p.peak_velocity.resize(n);
  p.peak_acceleration.resize(n);
  p.peak_jerk.resize(n);
  std::string brakes;
  for (Eigen::Index i = 0; i < n; ++i) {
    const JerkProfile& profile = otg->profile(static_cast<int>(i));
    // analytic extrema per phase, after the brake (a start beyond the limits is braked into them)
    const int brake = otg->brake_phases(static_cast<int>(i));
    const JerkExtrema e = profile.extrema(brake);
    p.peak_velocity[i] = std::max(std::abs(e.v_min), std::abs(e.v_max));
    p.peak_acceleration[i] = std::max(std::abs(e.a_min), std::abs(e.a_max));
    p.peak_jerk[i] = 0.0;
    for (int k = 0; k < profile.size(); ++k)
      if (profile.phase_duration(k) > 0.0)
        p.peak_jerk[i] = std::max(p.peak_jerk[i], std::abs(profile.jerk(k)));
    if (brake > 0) {
      const JerkExtrema b = profile.extrema();
      brakes += (brakes.empty() ? "" : "; ") + std::string("axis ") + std::to_string(i) + " for " +
                compact(otg->brake_duration(static_cast<int>(i))) + " s (peak |v| " +
                compact(std::max(std::abs(b.v_min), std::abs(b.v_max))) + ", |a| " +
                compact(std::max(std::abs(b.a_min), std::abs(b.a_max))) + " while braking)";
    }
  }
  p.notes = {{"duration from", "the limits (time-optimal, synchronized)"},
             {"limiting axis", std::to_string(result.limiting_dof)}};
  if (!brakes.empty())
    p.notes.push_back({"braking first", brakes + "; the peaks below are after the brake"});
  return p;
}

// the kinds of `mjarm traj`; a new kind is a build function and a row here
const std::array kTrajKinds{
    TrajKind{"trapezoid", "trapezoidal velocity, every axis finishing together (rest to rest)",
             false, build_trapezoid},
    TrajKind{"quintic", "quintic polynomial, any start and target (p, v, a); shortest duration",
             true, build_quintic},
    TrajKind{"smoothstep", "x²(3 − 2x) ramp, C¹ (rest to rest)", false, build_smoothstep},
    TrajKind{"smootherstep", "6x⁵ − 15x⁴ + 10x³ ramp, C², minimum jerk (rest to rest)", false,
             build_smootherstep},
    TrajKind{"jerk-limited",
             "time-optimal under velocity, acceleration and jerk limits (needs --j-max), any "
             "start and target (p, v, a); a start beyond the limits brakes first",
             true, build_jerk_limited},
};

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
  std::vector<std::string> names;
  std::string kinds_help;
  for (const TrajKind& kind : kTrajKinds) {
    names.push_back(kind.name);
    kinds_help += std::string("\n  ") + kind.name + ": " + kind.summary;
  }
  CLI::App* app = root.add_subcommand(
      "traj", "sample a motion profile (trapezoid, quintic, smoothstep, …) against its limits");
  app->footer("Kinds:" + kinds_help +
              "\nLimits take one value for every axis or one per axis; the defaults are those of "
              "the classic trapezoid (0.18 m/s, 0.9 m/s²). Without --duration each kind takes "
              "its shortest duration within the limits. --plot needs gnuplot (Debian: apt-get "
              "install gnuplot-nox).");
  app->add_option("KIND", options->kind, "profile kind: " + join(names, " | "))
      ->required()
      ->check(CLI::IsMember(names));
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
        const TrajKind& kind = *std::find_if(kTrajKinds.begin(), kTrajKinds.end(),
                                             [&](const TrajKind& k) { return o.kind == k.name; });
        const auto n = static_cast<Eigen::Index>(o.start.size());
        if (static_cast<Eigen::Index>(o.target.size()) != n)
          throw UsageError("--start has " + std::to_string(n) + " values but --target has " +
                           std::to_string(o.target.size()));
        TrajRequest r;
        r.q0 = Eigen::Map<const VectorXd>(o.start.data(), n);
        r.q1 = Eigen::Map<const VectorXd>(o.target.data(), n);
        r.qd0 = traj_per_axis(o.start_velocity, n, "--start-velocity", 0.0, false);
        r.qdd0 = traj_per_axis(o.start_acceleration, n, "--start-acceleration", 0.0, false);
        r.qd1 = traj_per_axis(o.target_velocity, n, "--target-velocity", 0.0, false);
        r.qdd1 = traj_per_axis(o.target_acceleration, n, "--target-acceleration", 0.0, false);
        r.v_max = traj_per_axis(o.v_max, n, "--v-max", TrapezoidProfile::kDefaultMaxVelocity, true);
        r.a_max =
            traj_per_axis(o.a_max, n, "--a-max", TrapezoidProfile::kDefaultMaxAcceleration, true);
        r.j_max =
            traj_per_axis(o.j_max, n, "--j-max", std::numeric_limits<double>::quiet_NaN(), true);
        if (!std::isnan(o.duration)) {
          if (!(o.duration > 0.0))
            throw UsageError("--duration must be positive, got " + compact(o.duration) + " s");
          r.duration = o.duration;
        }
        const bool moving = r.qd0.any() || r.qdd0.any() || r.qd1.any() || r.qdd1.any();
        if (moving && !kind.moving_ends)
          throw UsageError(std::string(kind.name) +
                           " moves from rest to rest: boundary velocities and accelerations "
                           "need a kind that takes them (quintic, jerk-limited)");
        const TrajProfile profile = kind.build(r);

        // samples at the rate, and the end
        const double steps = std::floor(profile.duration * o.rate);
        if (steps > 1e6)
          throw UsageError("T = " + compact(profile.duration) + " s at --rate " + compact(o.rate) +
                           " Hz gives over 10⁶ samples: lower --rate");
        std::vector<double> t;
        for (double k = 0; k <= steps; ++k) t.push_back(k / o.rate);
        if (t.back() < profile.duration) t.push_back(profile.duration);
        std::array<std::vector<VectorXd>, 4> x;
        for (auto& series : x) series.assign(t.size(), VectorXd::Zero(n));
        for (std::size_t s = 0; s < t.size(); ++s)
          profile.at(t[s], x[0][s], x[1][s], x[2][s], x[3][s]);
        // each peak beyond its limit, e.g. "axis 0: peak |v| 3.75 > v max 0.18"
        std::vector<std::string> violations;
        for (Eigen::Index i = 0; i < n; ++i) {
          const auto check = [&](double peak, double limit, const char* what) {
            if (peak > limit * (1 + 1e-9))  // a NaN limit (no jerk limit) is never broken
              violations.push_back("axis " + std::to_string(i) + ": peak |" + what + "| " +
                                   number_text(peak) + " > " + what + " max " +
                                   number_text(limit));
          };
          check(profile.peak_velocity[i], r.v_max[i], "v");
          check(profile.peak_acceleration[i], r.a_max[i], "a");
          check(profile.peak_jerk[i], r.j_max[i], "j");
        }
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
                         (n == 1 ? " axis" : " axes") + ", T = " + compact(profile.duration) + " s";
          series.unit = o.unit;
          series.t = t;
          for (Eigen::Index i = 0; i < n; ++i) series.axes.push_back("axis " + std::to_string(i));
          for (std::size_t k = 0; k < 4; ++k) {
            series.values[k].assign(static_cast<std::size_t>(n), std::vector<double>(t.size()));
            for (std::size_t s = 0; s < t.size(); ++s)
              for (Eigen::Index i = 0; i < n; ++i)
                series.values[k][static_cast<std::size_t>(i)][s] = x[k][s][i];
          }
          const std::array<const VectorXd*, 3> limits{&r.v_max, &r.a_max, &r.j_max};
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
          document["duration"] = profile.duration;
          document["within_limits"] = within;
          document["limits"] = {{"velocity", vector_json(r.v_max)},
                                {"acceleration", vector_json(r.a_max)}};
          document["limits"]["jerk"] = Json::array();
          for (Eigen::Index i = 0; i < n; ++i)
            document["limits"]["jerk"].push_back(bound_json(
                std::isnan(r.j_max[i]) ? std::numeric_limits<double>::infinity() : r.j_max[i]));
          document["peaks"] = {{"velocity", vector_json(profile.peak_velocity)},
                               {"acceleration", vector_json(profile.peak_acceleration)}};
          document["peaks"]["jerk"] = Json::array();  // null: unbounded (acceleration steps)
          for (Eigen::Index i = 0; i < n; ++i)
            document["peaks"]["jerk"].push_back(bound_json(profile.peak_jerk[i]));
          document["notes"] = Json::object();
          for (const auto& [key, value] : profile.notes) document["notes"][key] = value;
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
            {"duration", fixed(profile.duration, 6) + " s"},
            {"within limits", within ? "yes" : "NO"}};
        for (const auto& note : profile.notes) fields.push_back(note);
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
          table.add_row({std::to_string(i), fixed(r.q0[i]), fixed(r.q1[i]),
                         fixed(profile.peak_velocity[i]), fixed(r.v_max[i]),
                         fixed(profile.peak_acceleration[i]), fixed(r.a_max[i]),
                         fixed(profile.peak_jerk[i]),
                         std::isnan(r.j_max[i]) ? std::string("-") : fixed(r.j_max[i])});
        std::cout << '\n';
        table.print(std::cout);
        if (interrupts) report_interrupt_after_writing("traj", o.out.empty() ? plot_path : o.out);
        fail_on_violation(violations, o.allow_violation);
      }};
}

}  // namespace mjarm::cli
