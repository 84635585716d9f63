#pragma once
/// @file
/// `OffscreenRenderer`: pictures of a model's state without a window, display or GPU (EGL on
/// Mesa's surfaceless platform; a GPU is used when Mesa has a driver for it).

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/render/camera.hpp"
#include "mjarm/render/image.hpp"

namespace mjarm {

/// A ball drawn into every picture that is not part of the model (a target, a pick point).
struct RenderMarker {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    ///< centre in W [m]
  double radius = 0.02;                                  ///< [m], > 0
  std::array<float, 4> rgba = {0.2f, 0.9f, 0.3f, 0.6f};  ///< colour and opacity, each in [0, 1]
};

/// What the scene shows and which effects are drawn.
struct RenderOptions {
  bool shadows = true;      ///< shadows cast by the model's lights
  bool reflections = true;  ///< reflective materials (the bundled floor reflects a little)
  bool skybox = true;       ///< the model's skybox texture, if any
  /// Geom groups drawn (MJCF `group` 0…5); MuJoCo's default shows 0, 1 and 2.
  std::array<bool, mjNGROUP> geom_groups = {true, true, true, false, false, false};
  /// Site groups drawn; the bundled arms put their sites in group 3, hidden by default.
  std::array<bool, mjNGROUP> site_groups = {true, true, true, false, false, false};
  /// Balls added to the scene after the model's geoms (decoration: they cast no shadow).
  std::vector<RenderMarker> markers;
};

/// The switches of `RenderOptions`; the group masks and markers are set by hand.
constexpr auto declared_fields(const RenderOptions*) {
  using S = RenderOptions;
  return declare<S>("render", field("shadows", &S::shadows, "shadows cast by the model's lights"),
                    field("reflections", &S::reflections, "reflective materials"),
                    field("skybox", &S::skybox, "the model's skybox texture, if any"));
}

/// Renders a `Robot`'s scene at a given `mjData` state into RGB images of a fixed size.
///
/// Each renderer owns its OpenGL context (made current on the calling thread for the duration
/// of each call, then released), its MuJoCo scene and a scratch `mjData`: the caller's `mjData`
/// is only read (copied), never written. Several renderers may exist at once or one after
/// another; one renderer must be used by one thread at a time. The buffer is sized to the
/// requested image, which may exceed the model's `visual/global offwidth × offheight`: the
/// renderer passes MuJoCo a shallow copy of the model header with those two numbers replaced,
/// the shared `mjModel` itself is never modified.
///
/// Cost, for planning video: with Mesa's software rasteriser (llvmpipe, no GPU) a 640×480 frame
/// of the bundled Panda takes about 0.13 s of CPU time with shadows and the model's 4×
/// multisampling (0.08 s without shadows); creating a renderer about 0.3 s. See
/// docs/rendering.md.
/// Largest of MuJoCo's offscreen buffers a renderer makes [bytes]: 1 GiB, the most Mesa's
/// software rasteriser (llvmpipe) allocates for one buffer; 8192×8192 with 4× multisampling.
inline constexpr long long kMaxOffscreenBufferBytes = 1LL << 30;

class OffscreenRenderer {
 public:
  /// Creates the OpenGL context and MuJoCo's rendering resources for @p robot.
  /// @param robot  shared model (kept alive by the renderer: copies of `Robot` share the model)
  /// @param width  image width [pixels], ≥ 1
  /// @param height image height [pixels], ≥ 1
  /// @throws Error when a size is < 1 or larger than the OpenGL implementation allows
  ///         (GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS), when one of MuJoCo's buffers
  ///         (width × height × 4 bytes × the model's `visual/quality offsamples`) would exceed
  ///         `kMaxOffscreenBufferBytes` (the message names every limit), when
  ///         no headless OpenGL context can be made (the message names the EGL call and the
  ///         Debian packages of a driver), or for an invalid marker (see `RenderMarker`).
  OffscreenRenderer(const Robot& robot, int width, int height, RenderOptions options = {});
  ~OffscreenRenderer();
  OffscreenRenderer(OffscreenRenderer&&) noexcept;
  OffscreenRenderer& operator=(OffscreenRenderer&&) noexcept;
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Renders @p data (a state of this renderer's model, kinematics computed, e.g. after
  /// `mj_forward`/`mj_step`) seen by @p camera into @p out, row 0 at the top. @p out is resized
  /// when its size differs, so reusing one `Image` allocates nothing per frame.
  /// @throws Error after `close()`, when @p data was made for another model, when a named
  ///         camera, site or body does not exist (listing those that do), when the camera
  ///         numbers are out of range (distance ≤ 0, |elevation| ≥ 90°, not finite), or when a
  ///         free or follow camera is so far away that the whole model lies beyond the far
  ///         clipping plane (visual/map zfar × statistic extent from it: an empty picture).
  void render(const mjData& data, const CameraSpec& camera, Image& out);
  /// As above, and the depth: @p depth gets width·height distances from the camera's plane
  /// along its axis [m], row 0 the top, from OpenGL's depth buffer linearized with MuJoCo's
  /// near and far planes (`visual/map` znear and zfar times the model's extent); where nothing
  /// is drawn, the far plane. Allocation-free after the first call at this size.
  void render(const mjData& data, const CameraSpec& camera, Image& out, std::vector<float>& depth);

  /// Same as above, into a new image.
  Image render(const mjData& data, const CameraSpec& camera);

  /// The pinhole camera MuJoCo uses for @p camera at state @p data (what `render` would see),
  /// for projecting world points into the image with `project`.
  /// @throws Error as `render` does.
  CameraView view(const mjData& data, const CameraSpec& camera);

  /// Changes what later frames show.
  /// @throws Error for an invalid marker (the options in force are kept).
  void set_options(const RenderOptions& options);
  /// The options in force.
  const RenderOptions& options() const;
  /// The robot whose states it renders.
  const Robot& robot() const;

  /// Frees the OpenGL context and every resource; later calls throw. Idempotent.
  void close() noexcept;
  /// False after `close()` (and for a moved-from renderer).
  bool is_open() const noexcept;

  int width() const noexcept { return width_; }    ///< [pixels]
  int height() const noexcept { return height_; }  ///< [pixels]
  /// The OpenGL implementation in use, e.g. "Mesa llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 …".
  const std::string& gl_description() const;

 private:
  void render_into(const mjData& data, const CameraSpec& camera, Image& out,
                   std::vector<float>* depth);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace mjarm
