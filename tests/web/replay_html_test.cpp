// The replay file (include/mjarm/web/replay_html.hpp): what it holds checked against the
// recording it was made from — free bodies at their recorded qpos, a hinge's link turned by its
// recorded angle (quaternion by hand, not by MuJoCo) —, the geoms MuJoCo draws and their colours,
// the recorded model, and the errors (another model, an unwritable file) that leave no file; the
// scene's textures, skybox, height field and tracking cameras (tests/web/replay_scene_model.xml).

#include "mjarm/web/replay_html.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/plot/recording.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/web/recorded_model.hpp"
#include "sim/sim_test_support.hpp"
#include "web/base64.hpp"
#include "web/replay_scene.hpp"
#include "web/replay_test_support.hpp"
#include "web/replay_textures.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// every geom type the page draws (a mesh inline), a geom hidden by its group, one fully
// transparent, a material's colour; a free cube falling on the floor and a swinging hinge
constexpr const char* kReplayModel = R"(
<mujoco model="replay">
  <option timestep="0.002"/>
  <asset>
    <material name="green" rgba="0 0.8 0 1"/>
    <texture name="checker" type="2d" builtin="checker" width="8" height="8" rgb1="1 1 1"
             rgb2="0 0 0"/>
    <material name="floor" texture="checker" texrepeat="4 4"/>
    <mesh name="wedge" vertex="0 0 0  0.1 0 0  0 0.1 0  0 0 0.1"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1" material="floor"/>
    <camera name="front" pos="0 -1.5 0.5" xyaxes="1 0 0 0 0.3 1"/>
    <body name="cube" pos="0.3 0 0.3">
      <freejoint name="cube_free"/>
      <geom name="cube_box" type="box" size="0.03 0.03 0.03" material="green"/>
      <geom name="cube_wedge" type="mesh" mesh="wedge" pos="0 0 0.03" rgba="1 0 0 1"/>
    </body>
    <body name="link" pos="-0.2 0 0.5">
      <joint name="hinge" type="hinge" axis="0 1 0" damping="0.01"/>
      <geom name="rod" type="capsule" fromto="0 0 0 0 0 -0.2" size="0.01"/>
      <geom name="knob" type="sphere" pos="0 0 -0.2" size="0.02"/>
      <geom name="drum" type="cylinder" pos="0 0 -0.1" size="0.02 0.01"/>
      <geom name="egg" type="ellipsoid" pos="0 0 -0.25" size="0.01 0.02 0.03"/>
      <geom name="hidden" type="sphere" size="0.05" group="3"/>
      <geom name="clear" type="sphere" size="0.05" rgba="1 1 1 0"/>
      <site name="tip" pos="0 0 -0.2"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="swing" joint="hinge" gear="1" ctrllimited="true" ctrlrange="-1 1"/>
  </actuator>
</mujoco>)";

constexpr int kDrawnGeoms = 7;  // all but "hidden" (group 3) and "clear" (alpha 0)

void record_replay_model(const fs::path& dir) {
  mjarm::test::record_swing(mjarm::Robot::from_string(kReplayModel), dir, 0.6);
}

using mjarm::test::data_block;
using mjarm::test::unbase64;
using mjarm::test::unbase64_floats;

class ReplayHtml : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new mjarm::test::TempDir("replay_html");
    record_replay_model(root_->path() / "rec");
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }
  static fs::path recording() { return root_->path() / "rec"; }
  static fs::path out(const std::string& name) { return root_->path() / name; }

 private:
  static mjarm::test::TempDir* root_;
};
mjarm::test::TempDir* ReplayHtml::root_ = nullptr;

TEST(ReplayBase64, MatchesTheStandardsVectors) {
  // RFC 4648, section 10
  const std::pair<std::string, std::string> vectors[] = {{"", ""},
                                                         {"f", "Zg=="},
                                                         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},
                                                         {"foob", "Zm9vYg=="},
                                                         {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(mjarm::web_detail::base64(plain.data(), plain.size()), encoded) << plain;
  }
}

TEST_F(ReplayHtml, FramesHoldTheRecordedStatesAtTheRate) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const mjarm::Robot robot = mjarm::recorded_model(rec);
  mjarm::ReplayHtmlOptions options;
  options.rate = 50.0;
  const mjarm::ReplayHtmlReport report =
      mjarm::write_replay_html(robot, rec, out("run.html"), options);
  EXPECT_EQ(report.bytes, fs::file_size(out("run.html")));
  EXPECT_EQ(report.state_rows, 300);  // 0.6 s of 2 ms steps
  EXPECT_GE(report.frames, 30);       // one per 20 ms, the last row too
  EXPECT_LE(report.frames, 32);
  EXPECT_LE(report.largest_gap, 0.02 + 1e-9);
  EXPECT_NEAR(report.rate, 50.0, 2.0);
  EXPECT_EQ(report.drawn_geoms, kDrawnGeoms);
  EXPECT_EQ(report.meshes, 1);
  EXPECT_EQ(report.cameras, 1);

  const json data = data_block(out("run.html"));
  ASSERT_EQ(data["geoms"].size(), static_cast<std::size_t>(kDrawnGeoms));
  const std::vector<float> time = unbase64_floats(data["frames"]["time"]);
  const std::vector<float> pos = unbase64_floats(data["frames"]["pos"]);
  const std::vector<float> quat = unbase64_floats(data["frames"]["quat"]);
  ASSERT_EQ(time.size(), static_cast<std::size_t>(report.frames));
  const std::size_t nbody = data["bodies"].size();
  ASSERT_EQ(pos.size(), time.size() * nbody * 3);
  ASSERT_EQ(quat.size(), time.size() * nbody * 4);
  const int cube = mj_name2id(&robot.model(), mjOBJ_BODY, "cube");
  const int link = mj_name2id(&robot.model(), mjOBJ_BODY, "link");

  // every frame is a recorded row: the cube's pose is its free joint's qpos, and the link is
  // turned about y by the hinge's angle (the swing moves it: the angles differ across frames)
  const std::vector<double> t = rec.state().numbers("t");
  std::vector<std::vector<double>> cube_q;
  for (int k = 0; k < 7; ++k)
    cube_q.push_back(rec.state().numbers("q.cube_free." + std::to_string(k)));
  const std::vector<double> hinge = rec.state().numbers("q.hinge");
  double smallest_angle = 1e9, largest_angle = -1e9;
  for (std::size_t f = 0; f < time.size(); ++f) {
    std::size_t row = 0;
    while (row + 1 < t.size() && std::abs(t[row] - time[f]) > 1e-6) ++row;
    ASSERT_NEAR(t[row], time[f], 1e-6) << "frame " << f << " is no recorded row";
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(pos[(f * nbody + cube) * 3 + k], cube_q[k][row], 1e-6) << "frame " << f;
    double norm = 0.0;
    for (int k = 0; k < 4; ++k) norm += cube_q[3 + k][row] * cube_q[3 + k][row];
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(std::abs(quat[(f * nbody + cube) * 4 + k]),
                  std::abs(cube_q[3 + k][row] / std::sqrt(norm)), 1e-6);
    }
    const double a = hinge[row];
    const double expected[4] = {std::cos(a / 2), 0.0, std::sin(a / 2), 0.0};
    const double sign = quat[(f * nbody + link) * 4] * expected[0] >= 0 ? 1.0 : -1.0;
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(sign * quat[(f * nbody + link) * 4 + k], expected[k], 1e-6) << "frame " << f;
    EXPECT_NEAR(pos[(f * nbody + link) * 3 + 0], -0.2, 1e-6);
    EXPECT_NEAR(pos[(f * nbody + link) * 3 + 2], 0.5, 1e-6);
    smallest_angle = std::min(smallest_angle, a);
    largest_angle = std::max(largest_angle, a);
  }
  EXPECT_GT(largest_angle - smallest_angle, 0.1) << "the link never swung: a weak test";
  // the falling cube moved too
  EXPECT_LT(pos[((time.size() - 1) * nbody + cube) * 3 + 2], 0.3 - 0.05);
}

TEST_F(ReplayHtml, ContactsAtRestCarryTheCubesWeight) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const mjarm::Robot robot = mjarm::recorded_model(rec);
  mjarm::write_replay_html(robot, rec, out("contacts.html"));
  const json data = data_block(out("contacts.html"));
  const std::vector<unsigned char> offset_bytes = unbase64(data["overlays"]["contacts"]["offsets"]);
  std::vector<unsigned> offsets(offset_bytes.size() / 4);
  std::memcpy(offsets.data(), offset_bytes.data(), offsets.size() * 4);
  const std::vector<float> points = unbase64_floats(data["overlays"]["contacts"]["points"]);
  const std::size_t frames = unbase64_floats(data["frames"]["time"]).size();
  ASSERT_EQ(offsets.size(), frames + 1);
  EXPECT_EQ(offsets.front(), 0u);
  EXPECT_EQ(offsets.back() * 6, points.size());
  EXPECT_EQ(offsets[1], 0u) << "the cube starts in the air";
  // at the end the cube rests on the floor: its contacts push up with its weight in all
  const unsigned first = offsets[frames - 1], last = offsets[frames];
  ASSERT_GE(last - first, 3u) << "a resting box touches the floor at its corners";
  double up = 0.0;
  for (unsigned c = first; c < last; ++c) {
    EXPECT_NEAR(points[6 * c + 2], 0.0, 2e-3) << "a contact point on the floor";
    up += std::abs(points[6 * c + 5]);
  }
  const mjModel& m = robot.model();
  const double weight = m.body_subtreemass[mj_name2id(&m, mjOBJ_BODY, "cube")] * -m.opt.gravity[2];
  EXPECT_NEAR(up, weight, 0.25 * weight);
  // the tool and the target frames follow task.csv
  const std::vector<float> tool = unbase64_floats(data["overlays"]["tool"]);
  ASSERT_EQ(tool.size(), frames * 7);
  EXPECT_NEAR(tool[(frames - 1) * 7 + 0], rec.task().numbers("ee.x").back(), 1e-6);
}

TEST_F(ReplayHtml, ARateAboveTheRecordingsKeepsEveryRow) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  mjarm::ReplayHtmlOptions options;
  options.rate = 1000.0;  // the recording has 500 rows per second
  const mjarm::ReplayHtmlReport report =
      mjarm::write_replay_html(mjarm::recorded_model(rec), rec, out("all.html"), options);
  EXPECT_EQ(report.frames, report.state_rows);
}

TEST_F(ReplayHtml, GeomsAreDrawnInMujocosColours) {
  const mjarm::Robot robot = mjarm::Robot::from_string(kReplayModel);
  const mjModel& m = robot.model();
  float rgba[4];
  mjarm::web_detail::geom_rgba(m, mj_name2id(&m, mjOBJ_GEOM, "cube_box"), rgba);
  EXPECT_FLOAT_EQ(rgba[1], 0.8f);  // the material's, the geom's own being the default
  mjarm::web_detail::geom_rgba(m, mj_name2id(&m, mjOBJ_GEOM, "cube_wedge"), rgba);
  EXPECT_FLOAT_EQ(rgba[0], 1.0f);
  EXPECT_FALSE(mjarm::web_detail::geom_drawn(m, mj_name2id(&m, mjOBJ_GEOM, "hidden")));
  EXPECT_FALSE(mjarm::web_detail::geom_drawn(m, mj_name2id(&m, mjOBJ_GEOM, "clear")));
  const mjarm::web_detail::ReplayScene scene = mjarm::web_detail::replay_scene(m);
  std::vector<std::string> types;
  for (const json& g : scene.json["geoms"]) types.push_back(g["type"]);
  for (const char* type : {"plane", "box", "mesh", "capsule", "sphere", "cylinder", "ellipsoid"})
    EXPECT_NE(std::find(types.begin(), types.end(), type), types.end()) << type;
  // the floor's checker: its pixels once, both colours in them, repeated as its material says
  ASSERT_EQ(scene.json["textures"].size(), 1u);
  const json& texture = scene.json["textures"][0];
  const std::vector<unsigned char> pixels = mjarm::web_detail::decode_texture(
      unbase64(texture["data"]), texture["width"], texture["height"], texture["channels"]);
  ASSERT_EQ(pixels.size(),
            static_cast<std::size_t>(texture["width"].get<int>() * texture["height"].get<int>() *
                                     texture["channels"].get<int>()));
  EXPECT_NE(std::find(pixels.begin(), pixels.end(), 255), pixels.end());
  EXPECT_NE(std::find(pixels.begin(), pixels.end(), 0), pixels.end());
  for (const json& g : scene.json["geoms"]) {
    EXPECT_EQ(g["texture"].get<int>(), g["name"] == "floor" ? 0 : -1) << g["name"];
    if (g["name"] == "floor") EXPECT_FLOAT_EQ(g["texrepeat"][0].get<float>(), 4.0f);
  }
  // the mesh's four vertices and faces are in the file
  const json& mesh = scene.json["meshes"][0];
  EXPECT_EQ(unbase64_floats(mesh["vert"]).size(), 12u);
  EXPECT_EQ(unbase64(mesh["face"]).size() % 12, 0u);
  EXPECT_GE(unbase64(mesh["face"]).size(), 12u);
}

TEST_F(ReplayHtml, TheRecordedModelIsTheSimulatedOne) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const mjarm::Robot recorded = mjarm::recorded_model(rec);
  const mjarm::Robot original = mjarm::Robot::from_string(kReplayModel);
  EXPECT_EQ(recorded.model().nq, original.model().nq);
  EXPECT_EQ(recorded.model().nbody, original.model().nbody);
  EXPECT_EQ(recorded.model().ngeom, original.model().ngeom);
  EXPECT_EQ(recorded.model().nmeshvert, original.model().nmeshvert);
}

TEST_F(ReplayHtml, AnotherModelOrNoModelIsRefusedAndWritesNothing) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const mjarm::Robot other = mjarm::Robot::bundled("planar2");
  try {
    mjarm::write_replay_html(other, rec, out("other.html"));
    ADD_FAILURE() << "no error";
  } catch (const mjarm::Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not match the recording"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("q."), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out("other.html")));

  const fs::path bare = out("bare");
  fs::create_directories(bare);
  for (const char* file : {"state.csv", "task.csv", "events.csv", "summary.json"})
    fs::copy_file(recording() / file, bare / file);
  try {
    mjarm::recorded_model(mjarm::plot::Recording::load(bare));
    ADD_FAILURE() << "no error";
  } catch (const mjarm::Error& e) {
    EXPECT_NE(std::string(e.what()).find("--model"), std::string::npos) << e.what();
  }
}

TEST_F(ReplayHtml, AnUnwritableFileIsAnErrorNamingIt) {
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(recording());
  const fs::path nowhere = out("missing-folder") / "run.html";
  try {
    mjarm::write_replay_html(mjarm::recorded_model(rec), rec, nowhere);
    ADD_FAILURE() << "no error";
  } catch (const mjarm::Error& e) {
    EXPECT_NE(std::string(e.what()).find(nowhere.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(nowhere));
  mjarm::ReplayHtmlOptions options;
  options.rate = 0.0;
  EXPECT_THROW(mjarm::write_replay_html(mjarm::recorded_model(rec), rec, out("r.html"), options),
               mjarm::Error);
}

// The scene test model's run, written by hand: the cart slides along x as q = 0.5 sin(3t) for 1 s
// of 2 ms rows (the recording's files as the recorder names them; no controller, no task).
fs::path write_cart_recording(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream state(dir / "state.csv"), task(dir / "task.csv");
  state << "t,q.cart_x\n";
  task << "t\n";
  for (int i = 0; i <= 500; ++i) {
    const double t = 0.002 * i;
    state << t << "," << 0.5 * std::sin(3.0 * t) << "\n";
    task << t << "\n";
  }
  std::ofstream(dir / "events.csv") << "t,kind,message\n0,phase,slide\n";
  std::ofstream(dir / "summary.json") << R"({"model": "replay_scene", "status": "ok"})";
  return dir;
}

const fs::path kSceneModel = fs::path(MJARM_SOURCE_DIR) / "tests/web/replay_scene_model.xml";

TEST(ReplayTextures, PixelsComeBackAsTheyWereAndALargeTextureIsHalved) {
  // a small picture within the budget: kept whole, every byte back
  std::vector<unsigned char> small(40 * 24 * 3);
  for (std::size_t i = 0; i < small.size(); ++i) small[i] = static_cast<unsigned char>(i * 7 % 251);
  const mjarm::web_detail::EncodedTexture kept =
      mjarm::web_detail::encode_texture(small.data(), 40, 24, 3);
  EXPECT_EQ(kept.width, 40);
  EXPECT_EQ(kept.height, 24);
  EXPECT_EQ(mjarm::web_detail::decode_texture(kept.deflated, 40, 24, 3), small);
  // a cube strip (6 faces of 64²) of noise over a budget of 4 KiB: halved to faces of 16² (the
  // smallest halved), still a strip, each pixel the mean of the 4×4 it stands for
  std::vector<unsigned char> strip(64 * 384 * 3);
  unsigned seed = 1;
  for (unsigned char& byte : strip) {
    seed = seed * 1103515245u + 12345u;
    byte = static_cast<unsigned char>(seed >> 24);
  }
  const mjarm::web_detail::EncodedTexture halved =
      mjarm::web_detail::encode_texture(strip.data(), 64, 384, 3, 4096);
  ASSERT_EQ(halved.width, 16);
  ASSERT_EQ(halved.height, 96);
  const std::vector<unsigned char> pixels =
      mjarm::web_detail::decode_texture(halved.deflated, 16, 96, 3);
  ASSERT_EQ(pixels.size(), 16u * 96u * 3u);
  double worst = 0.0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 16; ++x)
      for (int k = 0; k < 3; ++k) {
        double sum = 0.0;
        for (int dy = 0; dy < 4; ++dy)
          for (int dx = 0; dx < 4; ++dx) sum += strip[((4 * y + dy) * 64 + 4 * x + dx) * 3 + k];
        worst = std::max(worst, std::abs(pixels[(y * 16 + x) * 3 + k] - sum / 16.0));
      }
  EXPECT_LE(worst, 1.0) << "two roundings of a mean of four";
}

TEST(ReplayTextures, TheBundledFloorAndSkyStaySmall) {
  const mjarm::Robot robot = mjarm::Robot::bundled("arm6");
  const mjarm::web_detail::ReplayScene scene = mjarm::web_detail::replay_scene(robot.model());
  ASSERT_GE(scene.json["skybox"].get<int>(), 0);
  std::size_t bytes = 0;
  for (const json& texture : scene.json["textures"]) {
    bytes += texture["data"].get<std::string>().size();
    EXPECT_LE(texture["data"].get<std::string>().size(),
              mjarm::web_detail::kTextureBudget * 4 / 3 + 4);
  }
  const json& sky = scene.json["textures"][scene.json["skybox"].get<int>()];
  EXPECT_EQ(sky["type"], "skybox");
  EXPECT_EQ(sky["height"].get<int>(), 6 * sky["width"].get<int>());
  EXPECT_LE(bytes, 100u * 1024u) << "the floor and the sky, base64";
}

TEST(ReplayHtmlScene, TexturesSkyboxHeightFieldAndTrackingCamerasAreInThePage) {
  mjarm::test::TempDir root("replay_scene");
  const fs::path rec_dir = write_cart_recording(root.path() / "rec");
  const mjarm::plot::Recording rec = mjarm::plot::Recording::load(rec_dir);
  const mjarm::Robot robot = mjarm::Robot::from_file(kSceneModel);
  const mjModel& m = robot.model();
  const mjarm::ReplayHtmlReport report =
      mjarm::write_replay_html(robot, rec, root.path() / "scene.html");
  EXPECT_EQ(report.drawn_geoms, 8);  // floor, hill, crate, die, pyramid, ball, drum, cart
  const json data = data_block(root.path() / "scene.html");

  // every texture once, its pixels as MuJoCo holds them (small: none halved)
  ASSERT_EQ(data["textures"].size(), 3u) << "sky, grid (on six geoms), dice";
  const int sky = data["skybox"];
  ASSERT_GE(sky, 0);
  EXPECT_EQ(data["textures"][sky]["type"], "skybox");
  for (const json& texture : data["textures"]) {
    const int width = texture["width"], height = texture["height"], channels = texture["channels"];
    ASSERT_EQ(width, texture["source_width"].get<int>());
    int tex = -1;
    for (int t = 0; t < m.ntex; ++t)
      if (m.tex_width[t] == width && m.tex_height[t] == height) tex = t;
    ASSERT_GE(tex, 0);
    const std::vector<unsigned char> encoded = unbase64(texture["data"]);
    const std::vector<unsigned char> pixels =
        mjarm::web_detail::decode_texture(encoded, width, height, channels);
    EXPECT_TRUE(std::equal(pixels.begin(), pixels.end(), m.tex_data + m.tex_adr[tex]))
        << texture["type"];
  }
  std::map<std::string, json> geoms;
  for (const json& g : data["geoms"]) geoms[g["name"]] = g;
  EXPECT_EQ(geoms["crate"]["texture"], geoms["floor"]["texture"]);
  EXPECT_EQ(geoms["crate"]["texture"], geoms["pyramid"]["texture"]);
  EXPECT_EQ(data["textures"][geoms["die"]["texture"].get<int>()]["type"], "cube");
  EXPECT_TRUE(geoms["floor"]["texuniform"].get<bool>());
  EXPECT_EQ(geoms["cart_box"]["texture"], -1);

  // the pyramid's texture coordinates, per face corner
  const json& mesh = data["meshes"][geoms["pyramid"]["mesh"].get<int>()];
  const std::vector<float> uv = unbase64_floats(mesh["texcoord"]);
  ASSERT_EQ(uv.size(), static_cast<std::size_t>(6 * m.mesh_facenum[0]));
  for (int f = 0; f < m.mesh_facenum[0]; ++f)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c)
        EXPECT_EQ(uv[(3 * f + k) * 2 + c], m.mesh_texcoord[2 * m.mesh_facetexcoord[3 * f + k] + c]);

  // the height field: its grid and size
  EXPECT_EQ(geoms["hill"]["type"], "hfield");
  ASSERT_EQ(geoms["hill"]["hfield"], 0);
  const json& hill = data["hfields"][0];
  EXPECT_EQ(hill["nrow"], 4);
  EXPECT_EQ(hill["ncol"], 5);
  EXPECT_FLOAT_EQ(hill["size"][3].get<float>(), 0.05f);
  const std::vector<float> elevation = unbase64_floats(hill["data"]);
  ASSERT_EQ(elevation.size(), 20u);
  EXPECT_TRUE(std::equal(elevation.begin(), elevation.end(), m.hfield_data));
  EXPECT_FLOAT_EQ(*std::max_element(elevation.begin(), elevation.end()), 1.0f);

  // the cameras: the one riding the cart needs no poses; the tracking one keeps its offset from
  // the cart and its orientation, the aimed one looks at the cart — at every frame
  std::map<std::string, int> track;
  for (const json& c : data["cameras"]) track[c["name"]] = c["track"];
  EXPECT_EQ(track["rider"], -1);
  ASSERT_GE(track["follow"], 0);
  ASSERT_GE(track["aim"], 0);
  const json& poses = data["camera_poses"];
  ASSERT_EQ(poses["cameras"].size(), 2u);
  const std::vector<float> time = unbase64_floats(data["frames"]["time"]);
  const std::vector<float> pos = unbase64_floats(poses["pos"]);
  const std::vector<float> quat = unbase64_floats(poses["quat"]);
  ASSERT_EQ(pos.size(), time.size() * 2 * 3);
  ASSERT_EQ(quat.size(), time.size() * 2 * 4);
  const std::vector<double> t = rec.state().numbers("t");
  const std::vector<double> q = rec.state().numbers("q.cart_x");
  double worst_pos = 0.0, worst_aim = 0.0, travel = 0.0;
  for (std::size_t f = 0; f < time.size(); ++f) {
    std::size_t row = 0;
    while (row + 1 < t.size() && std::abs(t[row] - time[f]) > 1e-6) ++row;
    const double cart[3] = {q[row], 0.0, 0.2};
    const std::size_t follow = f * 2 + static_cast<std::size_t>(track["follow"]);
    const double expected[3] = {cart[0], -1.8, 1.2};
    for (int k = 0; k < 3; ++k)
      worst_pos = std::max(worst_pos, std::abs(pos[follow * 3 + k] - expected[k]));
    // the tracking camera turned as at the start: x along the world's x
    EXPECT_NEAR(std::abs(quat[follow * 4 + 0]), std::cos(std::acos(0.49828388) / 2), 1e-5);
    // the aimed camera's −z axis (its view) points from it to the cart
    const std::size_t aim = f * 2 + static_cast<std::size_t>(track["aim"]);
    mjtNum qa[4], mat[9];
    for (int k = 0; k < 4; ++k) qa[k] = quat[aim * 4 + k];
    mju_normalize4(qa);
    mju_quat2Mat(mat, qa);
    double to[3] = {cart[0] - pos[aim * 3], cart[1] - pos[aim * 3 + 1], cart[2] - pos[aim * 3 + 2]};
    const double norm = std::sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
    for (int k = 0; k < 3; ++k)
      worst_aim = std::max(worst_aim, std::abs(-mat[3 * k + 2] - to[k] / norm));
    travel = std::max(travel, std::abs(q[row]));
  }
  EXPECT_GT(travel, 0.4) << "the cart barely moved: a weak test";
  EXPECT_LT(worst_pos, 1e-6) << "the tracking camera's position";
  EXPECT_LT(worst_aim, 1e-6) << "the aimed camera's view";
}

}  // namespace
