// `mjarm render MODEL [--q …|--keyframe NAME] [camera] [--size WxH] --out image.png`: a still
// picture of a model at a configuration, rendered headless.

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "mjarm/render/png.hpp"

namespace mjarm::cli {
namespace {

// --q values fill qpos from the start and must end on a joint boundary (the 7 arm joints of
// panda_hand, or all nq coordinates); the rest keep qpos0. Values outside a joint's range are
// refused unless @p allow_outside_range (check_joint_ranges).
std::string apply_q(const Robot& robot, const std::vector<double>& q, mjData& d,
                    bool allow_outside_range) {
  const mjModel& m = robot.model();
  const int n = static_cast<int>(q.size());
  bool boundary = n == m.nq;
  for (int j = 0; j < m.njnt && !boundary; ++j) boundary = m.jnt_qposadr[j] == n;
  if (n > m.nq || !boundary) {
    std::string names;
    for (const auto& joint : robot.joints()) names += (names.empty() ? "" : ", ") + joint.name;
    throw UsageError("--q got " + std::to_string(n) + " values; model '" + robot.name() +
                     "' takes up to nq = " + std::to_string(m.nq) +
                     " coordinates in qpos order, ending at a joint boundary (joints: " + names +
                     ")");
  }
  for (int i = 0; i < n; ++i) d.qpos[i] = q[static_cast<std::size_t>(i)];
  std::vector<int> given;  // the joints whose coordinates --q sets
  for (int j = 0; j < m.njnt; ++j)
    if (m.jnt_qposadr[j] < n) given.push_back(j);
  const auto outside =
      check_joint_ranges(robot, given, Eigen::Map<const Eigen::VectorXd>(d.qpos, m.nq), "--q",
                         allow_outside_range,
                         std::string("pass ") + kAllowOutsideRangeFlag + " to draw it anyway");
  return outside.empty() ? "--q" : "--q (outside the joint ranges)";
}

// A copy of @p robot's model whose geoms outside the subtree of body @p root (it and its
// descendants) are in group 5, which is not drawn: the picture shows that subtree alone (a
// silhouette to compare with another renderer's, tests/web).
Robot robot_with_only_subtree(const Robot& robot, const std::string& root) {
  const int top = mj_name2id(&robot.model(), mjOBJ_BODY, root.c_str());
  if (top < 0)
    throw UsageError("--only-subtree: model '" + robot.name() + "' has no body '" + root + "'");
  std::shared_ptr<mjModel> copy(mj_copyModel(nullptr, &robot.model()), mj_deleteModel);
  if (!copy) throw Error("render: MuJoCo could not copy the model");
  for (int g = 0; g < copy->ngeom; ++g) {
    int body = copy->geom_bodyid[g];
    while (body > 0 && body != top) body = copy->body_parentid[body];
    if (body != top) copy->geom_group[g] = mjNGROUP - 1;
  }
  return Robot::from_model(std::shared_ptr<const mjModel>(copy), robot.source());
}

}  // namespace

Command add_render_command(CLI::App& root) {
  struct Options {
    std::string model;
    std::vector<double> q;
    std::string keyframe;
    std::string camera;
    std::string follow;
    std::vector<double> lookat;
    double distance = 0.0;
    double azimuth = 135.0;
    double elevation = -25.0;
    std::string size = "640x480";
    std::string out;
    bool no_shadows = false;
    std::string only_subtree;
    bool allow_outside_range = false;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "render", "render a still picture of a model to PNG, headless (no display or GPU needed)");
  app->footer(
      "Camera: a model camera (--camera), a free camera (--lookat with --distance, --azimuth, "
      "--elevation), a camera following a site or body (--follow), or by default a free camera "
      "framing the robot. Azimuth: heading of the view about +z from +x [deg]; elevation: "
      "negative looks down [deg].");
  add_model_argument(*app, options->model)->required();
  auto* q = app->add_option("--q", options->q,
                            "qpos values in model order (all nq, or the leading joints; the "
                            "rest stay at qpos0) [rad or m]")
                ->check(finite_number())
                ->expected(1, -1);
  app->add_option("--keyframe,--key", options->keyframe, "take the configuration from a keyframe")
      ->excludes(q);
  add_allow_outside_range_flag(*app, options->allow_outside_range);
  auto* camera = app->add_option("--camera", options->camera, "a named camera of the model");
  auto* follow = app->add_option("--follow", options->follow,
                                 "look at this site (or body), e.g. the end effector");
  auto* lookat = app->add_option("--lookat", options->lookat, "point looked at, world x y z [m]")
                     ->check(finite_number())
                     ->expected(3);
  auto* distance = app->add_option("--distance", options->distance,
                                   "camera distance to the look-at point [m]; default: framing")
                       ->check(finite_number());
  auto* azimuth =
      app->add_option("--azimuth", options->azimuth, "heading of the view about +z, from +x [deg]")
          ->capture_default_str()
          ->check(finite_number());
  auto* elevation = app->add_option("--elevation", options->elevation,
                                    "pitch of the view, negative looks down [deg]")
                        ->capture_default_str()
                        ->check(finite_number());
  camera->excludes(follow)->excludes(lookat)->excludes(distance)->excludes(azimuth)->excludes(
      elevation);
  follow->excludes(lookat);
  app->add_option("--size", options->size, "image size WIDTHxHEIGHT [pixels]")
      ->capture_default_str()
      ->check(pixel_size());
  app->add_option("--out", options->out, "PNG file to write")->required();
  app->add_flag("--no-shadows", options->no_shadows, "draw without shadows");
  app->add_option("--only-subtree", options->only_subtree,
                  "draw only the geoms of this body and its descendants, on a plain background "
                  "(no skybox, shadows or reflections): a silhouette to compare");
  add_json_flag(*app, options->json);

  return {app, [options, distance] {
            check_output_file(options->out, "--out");  // before the model loads or GL starts
            const Robot robot =
                options->only_subtree.empty()
                    ? load_model(options->model)
                    : robot_with_only_subtree(load_model(options->model), options->only_subtree);
            DataPtr data = robot.make_data();
            std::string configuration = "qpos0";
            if (!options->keyframe.empty()) {
              const std::vector<double> qpos = robot.keyframe_qpos(options->keyframe);
              for (int i = 0; i < robot.nq(); ++i)
                data->qpos[i] = qpos[static_cast<std::size_t>(i)];
              configuration = "keyframe '" + options->keyframe + "'";
            } else if (!options->q.empty()) {
              configuration = apply_q(robot, options->q, *data, options->allow_outside_range);
            }
            mj_forward(&robot.model(), data.get());

            CameraSpec spec;
            const bool has_distance = distance->count() > 0;
            if (!options->camera.empty()) {
              spec = CameraSpec::model_camera(options->camera);
            } else if (!options->follow.empty()) {
              spec = CameraSpec::follow(options->follow, has_distance ? options->distance : 1.0,
                                        options->azimuth, options->elevation);
            } else if (!options->lookat.empty() && has_distance) {
              const Eigen::Vector3d lookat(options->lookat[0], options->lookat[1],
                                           options->lookat[2]);
              spec = CameraSpec::free_camera(lookat, options->distance, options->azimuth,
                                             options->elevation);
            } else {
              // framing the robot fills in what was not given
              spec = frame_robot(robot, *data, options->azimuth, options->elevation);
              if (!options->lookat.empty())
                spec.lookat =
                    Eigen::Vector3d(options->lookat[0], options->lookat[1], options->lookat[2]);
              if (has_distance) spec.distance = options->distance;
            }

            const PixelSize size = parse_pixel_size(options->size);
            RenderOptions render_options;
            render_options.shadows = !options->no_shadows;
            if (!options->only_subtree.empty()) {
              render_options.shadows = render_options.reflections = render_options.skybox = false;
            }
            OffscreenRenderer renderer(robot, size.width, size.height, render_options);
            const Image image = renderer.render(*data, spec);
            // Ctrl-C or SIGTERM while the PNG is written: the old file is kept and nothing is
            // left beside it (a signal before this point ends the process: nothing written yet)
            const InterruptGuard interrupts;
            {
              FileWriter file(options->out, FileWriter::Mode::replace, "PNG");
              write_png(image, file);
              stop_writing_if_interrupted("render", options->out);
              file.commit();
            }

            if (options->json) {
              Json doc;
              doc["model"] = robot.name();
              doc["configuration"] = configuration;
              doc["qpos"] = vector_json(Eigen::Map<const Eigen::VectorXd>(data->qpos, robot.nq()));
              doc["camera"] = {{"kind", to_string(spec.kind)}, {"description", spec.describe()}};
              doc["width"] = image.width;
              doc["height"] = image.height;
              doc["out"] = options->out;
              doc["opengl"] = renderer.gl_description();
              print_json(doc);
              return report_interrupt_after_writing("render", options->out);
            }
            print_fields(std::cout, {{"model", robot.name()},
                                     {"configuration", configuration},
                                     {"camera", spec.describe()},
                                     {"size", std::to_string(image.width) + "×" +
                                                  std::to_string(image.height) + " pixels"},
                                     {"OpenGL", renderer.gl_description()},
                                     {"wrote", options->out}});
            report_interrupt_after_writing("render", options->out);
          }};
}

}  // namespace mjarm::cli
