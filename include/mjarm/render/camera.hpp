#pragma once
/// @file
/// Where a rendered picture is seen from: `CameraSpec` (what the caller asks for) and
/// `CameraView` (the resulting pinhole camera in the world), with the projection of world
/// points to pixels.
///
/// Conventions (MuJoCo's free camera, world frame W with +z up):
/// - azimuth a [deg] is the heading of the viewing direction about +z, measured from +x towards
///   +y: a = 0 looks along +x (the camera sits on the −x side of the look-at point), a = 90 looks
///   along +y (camera on the −y side).
/// - elevation e [deg] is the pitch of the viewing direction: e < 0 looks down (the camera is
///   above the look-at point), e = 0 is horizontal; |e| < 90.
/// - the camera sits at p_WC = lookat − distance·f with the unit viewing direction
///   f = (cos e cos a, cos e sin a, sin e); image up is the world +z tilted into the image plane.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// How the camera is placed.
enum class CameraKind {
  model,   ///< a <camera> of the model, by name (pose and field of view from the model)
  free,    ///< look-at point, distance, azimuth and elevation in the world
  follow   ///< like `free`, with the look-at point on a site or body, re-read every frame
};

constexpr auto declared_names(const CameraKind*) {
  using K = CameraKind;
  return std::array{EnumName{K::model, "model", "a camera of the model, by name"},
                    EnumName{K::free, "free", "look-at point, distance, azimuth and elevation"},
                    EnumName{K::follow, "follow", "like free, looking at a site or body"}};
}

/// A camera request. Build one with the factories; fields not used by a kind are ignored.
struct CameraSpec {
  CameraKind kind = CameraKind::free;
  std::string name;  ///< model: camera name; follow: site name, or body name when no site has it
  Eigen::Vector3d lookat = Eigen::Vector3d(0.0, 0.0, 0.5);  ///< free: point looked at, in W [m]
  double distance = 2.0;     ///< free/follow: camera to look-at point [m], > 0
  double azimuth = 135.0;    ///< free/follow: [deg], see the file comment
  double elevation = -25.0;  ///< free/follow: [deg], negative looks down, |e| < 90

  /// The model camera called @p name.
  static CameraSpec model_camera(std::string name);
  /// A free camera looking at @p lookat (W, [m]) from @p distance [m] at @p azimuth and
  /// @p elevation [deg].
  static CameraSpec free_camera(const Eigen::Vector3d& lookat, double distance, double azimuth,
                                double elevation);
  /// A camera that keeps site (or body) @p frame at the image centre, from @p distance [m] at
  /// @p azimuth and @p elevation [deg] (fixed directions in W: it translates, never rotates).
  static CameraSpec follow(std::string frame, double distance, double azimuth, double elevation);

  /// One line for logs and `--json`: "free lookat [0, 0, 0.5] distance 2 azimuth 135 …".
  std::string describe() const;
};

/// Checked where a view is made of it (`free_camera_view`), with the camera's own wording.
constexpr auto declared_fields(const CameraSpec*) {
  using S = CameraSpec;
  return declare<S>(
      "camera", field("kind", &S::kind, "how the camera is placed"),
      field("name", &S::name, "model: camera name; follow: site or body name"),
      field("lookat", &S::lookat, "m", Range::finite(), "free: point looked at, in W"),
      field("distance", &S::distance, "m", Range::positive(), "camera to look-at point"),
      field("azimuth", &S::azimuth, "deg", Range::finite(), "direction about the vertical"),
      field("elevation", &S::elevation, "deg", Range{-90.0, 90.0, true, true, false},
            "negative looks down"));
}

/// A free camera that frames everything but the world body at state @p data: it looks at the
/// centre of the bounding box of those bodies' geoms (planes excluded) from @p azimuth and
/// @p elevation [deg], far enough that the box's bounding sphere fits the vertical field of view
/// with a margin. For a whole-scene default picture and video.
/// @throws Error when the model has no geom outside the world body or the angles are invalid.
CameraSpec frame_robot(const Robot& robot, const mjData& data, double azimuth = 135.0,
                       double elevation = -25.0);

/// A pinhole camera in the world, as OpenGL uses it: position, unit viewing direction, unit image
/// up, and the vertical field of view. Image right is forward × up.
struct CameraView {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< p_WC, camera centre in W [m]
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();  ///< unit viewing direction in W
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();       ///< unit image-up direction in W, ⊥ forward
  double fovy = 45.0;                                  ///< vertical field of view [deg], in (0, 180)
};

/// The view of a free camera by the conventions of the file comment, with field of view @p fovy
/// [deg] (MuJoCo takes it from the model's visual/global fovy).
/// @throws Error when @p distance is not > 0, |@p elevation| ≥ 90 or anything is not finite.
CameraView free_camera_view(const Eigen::Vector3d& lookat, double distance, double azimuth,
                            double elevation, double fovy);

/// Projects world point @p p_W into an image of @p width × @p height pixels seen by @p view.
/// @return (u, v, depth): u [pixels] from the left edge, v [pixels] from the top edge (pixel
///         (x, y) covers u ∈ [x, x+1), v ∈ [y, y+1)), depth [m] along the viewing direction;
///         depth ≤ 0 means the point is behind the camera and u, v are meaningless.
Eigen::Vector3d project(const CameraView& view, int width, int height, const Eigen::Vector3d& p_W);

}  // namespace mjarm
