#include "mjarm/render/offscreen_renderer.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "egl_context.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {
namespace {

// room for every model geom plus decorations (frames, contact markers) drawn later by overlays
constexpr int kMaxSceneGeoms = 5000;

std::string name_list(const mjModel& m, mjtObj type) {
  std::string list;
  for (const auto& name : object_names(m, type)) {
    if (name.empty()) continue;
    list += list.empty() ? name : ", " + name;
  }
  return list.empty() ? "(none)" : list;
}

const RenderOptions& checked(const RenderOptions& options) {
  for (const RenderMarker& marker : options.markers) {
    const bool colour = std::all_of(marker.rgba.begin(), marker.rgba.end(),
                                    [](float c) { return c >= 0.0f && c <= 1.0f; });
    if (!marker.position.allFinite() || !std::isfinite(marker.radius) || !(marker.radius > 0.0) ||
        !colour)
      throw Error("render marker: needs a finite position, a radius > 0 m and rgba in [0, 1]");
  }
  return options;
}

/// Refuses a camera placed so far from the model that none of it can be drawn: the model's
/// bounding sphere (statistic center, radius extent) lies wholly beyond the far clipping plane
/// (visual/map zfar × extent). A huge look-at point or distance (1e308 becomes infinite in the
/// renderer's single precision) would otherwise give an empty picture and report success.
void check_model_in_view(const mjModel& m, const std::string& model, const Eigen::Vector3d& p_WC) {
  const Eigen::Vector3d centre(m.stat.center[0], m.stat.center[1], m.stat.center[2]);
  const double gap = (p_WC - centre).stableNorm() - m.stat.extent;  // no overflow near 1e308
  const double zfar = m.vis.map.zfar * m.stat.extent;
  if (gap > zfar) {
    const auto text = [](double v) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.4g", v);
      return std::string(buffer);
    };
    throw Error("camera at [" + text(p_WC.x()) + ", " + text(p_WC.y()) + ", " + text(p_WC.z()) +
                "] m is " + text(gap) + " m from model '" + model + "' (centre [" +
                text(centre.x()) + ", " + text(centre.y()) + ", " + text(centre.z()) +
                "] m, extent " + text(m.stat.extent) + " m), beyond the far clipping plane at " +
                text(zfar) +
                " m (visual/map zfar × extent): the picture would show nothing of it; move the "
                "look-at point or the distance closer");
  }
}

/// Refuses, before MuJoCo allocates anything, a size beyond the current context's OpenGL limits
/// or a buffer beyond kMaxOffscreenBufferBytes, naming the limits.
void check_buffer_size(const mjModel& m, int width, int height) {
  GLint renderbuffer = 0;
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  const std::string size = std::to_string(width) + "×" + std::to_string(height);
  const std::string limits = "GL_MAX_RENDERBUFFER_SIZE " + std::to_string(renderbuffer) +
                             ", GL_MAX_VIEWPORT_DIMS " + std::to_string(viewport[0]) + "×" +
                             std::to_string(viewport[1]);
  const bool too_wide =
      (renderbuffer > 0 && width > renderbuffer) || (viewport[0] > 0 && width > viewport[0]);
  const bool too_high =
      (renderbuffer > 0 && height > renderbuffer) || (viewport[1] > 0 && height > viewport[1]);
  if (too_wide || too_high)
    throw Error("render size " + size + " exceeds this OpenGL's limits (" + limits + ")");
  // MuJoCo's offscreen buffer holds `offsamples` samples of 4 bytes (RGBA8; depth-stencil
  // likewise) per pixel
  const int samples = std::max(1, m.vis.quality.offsamples);
  const long long bytes = 4LL * width * height * samples;
  if (bytes > kMaxOffscreenBufferBytes) {
    const long long pixels = kMaxOffscreenBufferBytes / (4LL * samples);
    const long long side = static_cast<long long>(std::sqrt(static_cast<double>(pixels)));
    throw Error("render size " + size + " is too large: MuJoCo's offscreen buffer with " +
                std::to_string(samples) + " samples per pixel (visual/quality offsamples) would " +
                "take " + std::to_string(bytes >> 20) + " MiB, the limit is " +
                std::to_string(kMaxOffscreenBufferBytes >> 20) + " MiB (" + std::to_string(pixels) +
                " pixels, e.g. " + std::to_string(side) + "×" + std::to_string(side) +
                "); OpenGL: " + limits);
  }
}

// The side of the shadow map for a width × height picture: the model's (MuJoCo's default 4096)
// at most, and no more than the power of two at or above 4 × the picture's longer side. Every
// frame draws and clears the whole map: at 4096² it is most of a small frame's cost in llvmpipe,
// for detail a small picture cannot show. Pictures of 513 pixels or more a side keep 4096.
int shadow_map_side(int model_side, int width, int height) {
  const long long wanted = 4LL * std::max(width, height);
  long long side = 1;
  while (side < wanted) side *= 2;
  return static_cast<int>(std::min<long long>(model_side, side));
}

}  // namespace

struct OffscreenRenderer::Impl {
  Robot robot;
  RenderOptions options;
  std::unique_ptr<render_detail::EglContext> context;
  mjrContext gpu{};
  mjvScene scene{};
  mjvOption vis_options{};
  DataPtr scratch;                // copy of the caller's state: mjv_updateScene writes its mjData
  std::vector<std::uint8_t> row;  // one image row, for flipping OpenGL's bottom-up rows
  bool gpu_made = false;
  bool scene_made = false;

  explicit Impl(const Robot& r, RenderOptions o) : robot(r), options(o) {}

  ~Impl() { free_all(); }

  void free_all() noexcept {
    if (gpu_made && context) {
      try {
        render_detail::EglContext::Scope current(*context);
        mjr_freeContext(&gpu);
      } catch (...) {
        // the context cannot be made current: its resources go with it below
      }
    }
    gpu_made = false;
    context.reset();
    if (scene_made) mjv_freeScene(&scene);
    scene_made = false;
    scratch.reset();
  }

  void apply_options() {
    for (int g = 0; g < mjNGROUP; ++g) {
      vis_options.geomgroup[g] = options.geom_groups[static_cast<std::size_t>(g)] ? 1 : 0;
      vis_options.sitegroup[g] = options.site_groups[static_cast<std::size_t>(g)] ? 1 : 0;
    }
    scene.flags[mjRND_SHADOW] = options.shadows ? 1 : 0;
    scene.flags[mjRND_REFLECTION] = options.reflections ? 1 : 0;
    scene.flags[mjRND_SKYBOX] = options.skybox ? 1 : 0;
  }

  // appends the options' marker balls to the scene (as many as fit)
  void add_markers() noexcept {
    for (const RenderMarker& marker : options.markers) {
      if (scene.ngeom >= scene.maxgeom) return;
      mjvGeom* g = scene.geoms + scene.ngeom++;
      const mjtNum size[3] = {marker.radius, marker.radius, marker.radius};
      const mjtNum pos[3] = {marker.position.x(), marker.position.y(), marker.position.z()};
      mjv_initGeom(g, mjGEOM_SPHERE, size, pos, nullptr, marker.rgba.data());
      g->category = mjCAT_DECOR;
    }
  }

  // Copies the caller's state into the scratch data and turns @p spec into MuJoCo's camera.
  mjvCamera prepare(const mjData& data, const CameraSpec& spec) {
    if (!context) throw Error("OffscreenRenderer used after close()");
    const mjModel& m = robot.model();
    // an mjData's arena sizes come from its model: a mismatch means another model's data
    if (data.narena != scratch->narena || data.nbuffer != scratch->nbuffer)
      throw Error("OffscreenRenderer: the mjData was not made for model '" + robot.name() + "'");
    mj_copyData(scratch.get(), &m, &data);

    mjvCamera camera;
    mjv_defaultCamera(&camera);
    switch (spec.kind) {
      case CameraKind::model: {
        const int id = mj_name2id(&m, mjOBJ_CAMERA, spec.name.c_str());
        if (id < 0)
          throw Error("camera '" + spec.name + "' not found in model '" + robot.name() +
                      "'; cameras: " + name_list(m, mjOBJ_CAMERA) +
                      " (or use a free or follow camera)");
        camera.type = mjCAMERA_FIXED;
        camera.fixedcamid = id;
        return camera;
      }
      case CameraKind::free:
      case CameraKind::follow: {
        Eigen::Vector3d lookat = spec.lookat;
        if (spec.kind == CameraKind::follow) {
          // our own follow camera: MuJoCo's tracking camera follows bodies only
          if (const int site = mj_name2id(&m, mjOBJ_SITE, spec.name.c_str()); site >= 0) {
            lookat = Eigen::Map<const Eigen::Vector3d>(scratch->site_xpos + 3 * site);
          } else if (const int body = mj_name2id(&m, mjOBJ_BODY, spec.name.c_str()); body >= 0) {
            lookat = Eigen::Map<const Eigen::Vector3d>(scratch->xpos + 3 * body);
          } else {
            throw Error("follow camera: no site or body '" + spec.name + "' in model '" +
                        robot.name() + "'; sites: " + name_list(m, mjOBJ_SITE) +
                        "; bodies: " + name_list(m, mjOBJ_BODY));
          }
        }
        // validates the numbers with the messages of the documented conventions
        const CameraView view = free_camera_view(lookat, spec.distance, spec.azimuth,
                                                 spec.elevation, m.vis.global.fovy);
        check_model_in_view(m, robot.name(), view.position);
        camera.type = mjCAMERA_FREE;
        for (int i = 0; i < 3; ++i) camera.lookat[i] = lookat[i];
        camera.distance = spec.distance;
        camera.azimuth = spec.azimuth;
        camera.elevation = spec.elevation;
        return camera;
      }
    }
    throw Error("unknown camera kind");
  }
};

OffscreenRenderer::OffscreenRenderer(const Robot& robot, int width, int height,
                                     RenderOptions options)
    : width_(width), height_(height) {
  if (width < 1 || height < 1)
    throw Error("render size must be at least 1×1 pixels, got " + std::to_string(width) + "×" +
                std::to_string(height));
  install_mujoco_handlers();
  auto impl = std::make_unique<Impl>(robot, checked(options));
  const mjModel& m = impl->robot.model();
  impl->context = std::make_unique<render_detail::EglContext>();
  {
    render_detail::EglContext::Scope current(*impl->context);
    check_buffer_size(m, width, height);
    // MuJoCo sizes its offscreen buffer from visual/global offwidth/offheight; the shared model
    // stays untouched: a header copy (sharing every array) carries the requested size
    mjModel sized = m;
    sized.vis.global.offwidth = width;
    sized.vis.global.offheight = height;
    sized.vis.quality.shadowsize = shadow_map_side(m.vis.quality.shadowsize, width, height);
    mjr_defaultContext(&impl->gpu);
    try {
      mjr_makeContext(&sized, &impl->gpu, mjFONTSCALE_100);
    } catch (const Error& e) {
      // a limit no query shows (the driver's memory): say what was asked for
      throw Error("OpenGL could not make a " + std::to_string(width) + "×" +
                  std::to_string(height) + " offscreen buffer with " +
                  std::to_string(std::max(1, m.vis.quality.offsamples)) + " samples per pixel (" +
                  e.what() + "); try a smaller size");
    }
    impl->gpu_made = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &impl->gpu);
    if (impl->gpu.currentBuffer != mjFB_OFFSCREEN || impl->gpu.offWidth != width ||
        impl->gpu.offHeight != height)
      throw Error("OpenGL could not make a " + std::to_string(width) + "×" +
                  std::to_string(height) + " offscreen buffer");
  }
  mjv_defaultScene(&impl->scene);
  mjv_makeScene(&m, &impl->scene, kMaxSceneGeoms);
  impl->scene_made = true;
  mjv_defaultOption(&impl->vis_options);
  impl->apply_options();
  impl->scratch = impl->robot.make_data();
  impl->row.resize(static_cast<std::size_t>(width) * 3);
  impl_ = std::move(impl);
}

OffscreenRenderer::~OffscreenRenderer() = default;
OffscreenRenderer::OffscreenRenderer(OffscreenRenderer&&) noexcept = default;
OffscreenRenderer& OffscreenRenderer::operator=(OffscreenRenderer&&) noexcept = default;

void OffscreenRenderer::render(const mjData& data, const CameraSpec& camera, Image& out) {
  render_into(data, camera, out, nullptr);
}

void OffscreenRenderer::render(const mjData& data, const CameraSpec& camera, Image& out,
                               std::vector<float>& depth) {
  render_into(data, camera, out, &depth);
}

void OffscreenRenderer::render_into(const mjData& data, const CameraSpec& camera, Image& out,
                                    std::vector<float>* depth) {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  Impl& s = *impl_;
  mjvCamera cam = s.prepare(data, camera);
  if (out.width != width_ || out.height != height_ || out.rgb.size() != out.pixels() * 3) {
    out.width = width_;
    out.height = height_;
    out.rgb.resize(out.pixels() * 3);
  }
  const mjModel& m = s.robot.model();
  {
    render_detail::EglContext::Scope current(*s.context);
    mjv_updateScene(&m, s.scratch.get(), &s.vis_options, nullptr, &cam, mjCAT_ALL, &s.scene);
    s.add_markers();
    const mjrRect viewport{0, 0, width_, height_};
    mjr_setBuffer(mjFB_OFFSCREEN, &s.gpu);
    mjr_render(viewport, &s.scene, &s.gpu);
    if (depth != nullptr) depth->resize(out.pixels());
    mjr_readPixels(out.rgb.data(), depth != nullptr ? depth->data() : nullptr, viewport, &s.gpu);
  }
  if (depth != nullptr) {
    // the depth buffer's [0, 1] back to distances: d = near / (1 − z·(1 − near/far))
    const double extent = m.stat.extent;
    const double near = m.vis.map.znear * extent, far = m.vis.map.zfar * extent;
    for (float& z : *depth) z = static_cast<float>(near / (1.0 - z * (1.0 - near / far)));
    const std::size_t width = static_cast<std::size_t>(width_);
    for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
      std::swap_ranges(depth->begin() + static_cast<std::ptrdiff_t>(width * top),
                       depth->begin() + static_cast<std::ptrdiff_t>(width * (top + 1)),
                       depth->begin() + static_cast<std::ptrdiff_t>(width * bottom));
    }
  }
  // OpenGL's row 0 is the bottom: swap rows so that row 0 is the top
  const std::size_t stride = static_cast<std::size_t>(width_) * 3;
  for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
    std::uint8_t* a = out.at(0, top);
    std::uint8_t* b = out.at(0, bottom);
    std::memcpy(s.row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, s.row.data(), stride);
  }
}

Image OffscreenRenderer::render(const mjData& data, const CameraSpec& camera) {
  Image image;
  render(data, camera, image);
  return image;
}

CameraView OffscreenRenderer::view(const mjData& data, const CameraSpec& camera) {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  Impl& s = *impl_;
  mjvCamera cam = s.prepare(data, camera);
  mjv_updateCamera(&s.robot.model(), s.scratch.get(), &cam, &s.scene);
  // the two eyes coincide without stereo; their average is the camera
  const mjvGLCamera gl = mjv_averageCamera(&s.scene.camera[0], &s.scene.camera[1]);
  CameraView v;
  for (int i = 0; i < 3; ++i) {
    v.position[i] = gl.pos[i];
    v.forward[i] = gl.forward[i];
    v.up[i] = gl.up[i];
  }
  v.forward.normalize();
  v.up.normalize();
  v.fovy = 2.0 * std::atan2(0.5 * (gl.frustum_top - gl.frustum_bottom), gl.frustum_near) * 180.0 /
           std::numbers::pi;
  return v;
}

void OffscreenRenderer::set_options(const RenderOptions& options) {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  impl_->options = checked(options);
  impl_->apply_options();
}

const RenderOptions& OffscreenRenderer::options() const {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  return impl_->options;
}

const Robot& OffscreenRenderer::robot() const {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  return impl_->robot;
}

void OffscreenRenderer::close() noexcept { impl_.reset(); }

bool OffscreenRenderer::is_open() const noexcept { return impl_ != nullptr; }

const std::string& OffscreenRenderer::gl_description() const {
  if (!impl_) throw Error("OffscreenRenderer used after close()");
  return impl_->context->description();
}

}  // namespace mjarm
