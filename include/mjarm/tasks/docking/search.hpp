#pragma once
/// @file
/// The docking's search for a missed hole: its options (`DockingSearchOptions`), the planar
/// patterns (`SearchPath`: an Archimedean spiral at constant path speed, a Lissajous figure) and
/// what the task needs from the controller while it searches (`ContactChannel`).
/// docs/docking.md "Finding the hole".

#include <Eigen/Core>
#include <array>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/tasks/docking/scene.hpp"

namespace mjarm {

/// The planar pattern the reference follows around the point of the miss.
enum class SearchPattern {
  none,      ///< no miss detection, no search: the insertion pushes until its time is up
  spiral,    ///< Archimedean spiral r = pitch·θ/2π, constant path speed
  lissajous  ///< x = a·sin(ωt), y = a·sin(κωt), κ = (N+1)/N, a = R/√2: the square inside the
             ///< circle of radius R = max_radius, lines about pitch apart
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const SearchPattern*) {
  using E = SearchPattern;
  return std::array{EnumName{E::none, "none"}, EnumName{E::spiral, "spiral"},
                    EnumName{E::lissajous, "lissajous"}};
}

/// The pattern called @p name. @throws Error naming the closest and listing the choices.
SearchPattern search_pattern(std::string_view name);

/// Miss detection and search. A miss: during the insertion, with the tip no deeper than
/// `miss_max_depth` below the believed top face, the measured push along the insertion axis is
/// ≥ `miss_force` and the lateral measured force ≤ `miss_lateral_ratio` times it, for
/// `miss_dwell` (a flat face: no chamfer's lateral reaction, no progress). The search then moves
/// the reference in the socket's plane around the tip's position at the miss while the axial
/// force is held at `contact_force` through the controllers' force input (F_ext), trimmed by an
/// integral on the measured force (`force_gain`). A drop: the tip `drop_depth` below its height
/// at the miss; the insertion resumes straight down from there.
struct DockingSearchOptions {
  SearchPattern pattern = SearchPattern::spiral;
  double contact_force = 5.0;       ///< axial force held while searching [N] (≤ force_limit)
  double force_limit = 30.0;        ///< the force the search must stay under [N]
  double pitch = 0.004;             ///< spiral: radial gain per turn; lissajous: line spacing [m]
  double speed = 0.01;              ///< path speed (lissajous: each axis's peak speed) [m/s]
  double max_radius = 0.008;        ///< the search's extent around the miss [m]
  double timeout = 5.0;             ///< the longest search [s]
  double drop_depth = 0.001;        ///< depth gained below the miss that counts as the drop [m]
  double miss_force = 4.0;          ///< measured axial push that may be a miss [N]
  double miss_lateral_ratio = 0.3;  ///< lateral/axial measured force below which it is flat
  double miss_dwell = 0.05;         ///< how long the miss must hold [s]
  double miss_max_depth = 0.001;    ///< the tip at most this far below the top face [m]
  double force_gain = 5e-4;         ///< axial trim: reference speed per newton of error [m/(N·s)]
  double force_trim = 0.003;        ///< the trim's bound [m]
};

/// Cross-field checks (contact force ≤ limit, radius within the socket) are by hand in `check`.
constexpr auto declared_fields(const DockingSearchOptions*) {
  using S = DockingSearchOptions;
  return declare<S>(
      "docking search", field("pattern", &S::pattern, "the planar search pattern; none: off"),
      field("contact_force", &S::contact_force, "N", Range::positive(),
            "axial force held while searching (≤ force_limit)"),
      field("force_limit", &S::force_limit, "N", Range::positive(),
            "the force the search stays under"),
      field("pitch", &S::pitch, "m", Range::positive(),
            "spiral: radial gain per turn; lissajous: line spacing"),
      field("speed", &S::speed, "m/s", Range::positive(), "path speed of the search"),
      field("max_radius", &S::max_radius, "m", Range::positive(),
            "extent of the search around the miss (within the socket's top face)"),
      field("timeout", &S::timeout, "s", Range::positive(), "the longest search"),
      field("drop_depth", &S::drop_depth, "m", Range::positive(),
            "depth gained below the miss that counts as the drop into the hole"),
      field("miss_force", &S::miss_force, "N", Range::positive(),
            "measured axial push that may be a miss"),
      field("miss_lateral_ratio", &S::miss_lateral_ratio, "", Range::positive(),
            "lateral/axial measured force below which the face is flat"),
      field("miss_dwell", &S::miss_dwell, "s", Range::non_negative(),
            "how long the miss must hold"),
      field("miss_max_depth", &S::miss_max_depth, "m", Range::non_negative(),
            "the tip at most this far below the top face at a miss"),
      field("force_gain", &S::force_gain, "m/(N·s)", Range::non_negative(),
            "axial trim of the reference per newton of force error"),
      field("force_trim", &S::force_trim, "m", Range::non_negative(), "bound of the axial trim"));
}

/// @throws Error naming the field for a value out of its range, a contact force above the
///         force limit, or a radius that leaves the socket's top face (peg radius + max_radius
///         beyond the socket's outer radius, `bore_radius + chamfer + wall`).
void check(const DockingSearchOptions& options, const DockingGeometry& geometry);

/// A search pattern in the plane: offset and velocity at time t from its start. The spiral
/// keeps the path speed exactly by Newton on its arc length (one or two steps per tick).
/// `at` allocates nothing and never throws.
class SearchPath {
 public:
  struct Sample {
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();    ///< [m]
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  ///< [m/s]
    double radius = 0.0;  ///< distance from the start of the pattern [m]
  };
  explicit SearchPath(const DockingSearchOptions& options);
  /// The pattern at @p t ≥ 0 [s]; successive calls should go forward in time (Newton's start).
  Sample at(double t) noexcept;
  /// The time the pattern needs to reach max_radius [s] (+inf for lissajous: it stays inside).
  double time_to_max_radius() const noexcept;

 private:
  DockingSearchOptions options_;
  double b_;      // spiral: r = b·θ
  double theta_;  // spiral: last θ (Newton's start)
  double omega_;  // lissajous: ω
  double kappa_;  // lissajous: κ
};

/// What the docking task reads from and tells the controller: the measured wrench of the
/// environment on E (world axes, about E) and whether a contact may start the lateral release
/// (off while searching: the search moves the peg sideways by its spring).
class ContactChannel {
 public:
  virtual ~ContactChannel() = default;
  virtual const Vector6d& measured_wrench() const noexcept = 0;
  /// Off: any release is undone and none starts; on: a contact starts one again.
  virtual void set_release_armed(bool armed) noexcept = 0;
  /// True when the law has a lateral release (the centring applies to it).
  virtual bool releases() const noexcept = 0;
};

}  // namespace mjarm
