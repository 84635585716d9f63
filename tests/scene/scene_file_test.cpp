#include "mjarm/scene/scene_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"
#include "support/unreadable_paths.hpp"

namespace mjarm {
namespace {

using test::error_of;

const std::filesystem::path kExample =
    std::filesystem::path(MJARM_MODELS_DIR) / "scenes" / "pick_table.yaml";

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// a small scene whose one line (line 6) is replaced by each bad-input test
std::string small_scene(const std::string& line6) {
  return "name: small\n"
         "arena: {table: true}\n"
         "objects:\n"
         "  - name: cube\n"
         "    shape: box\n" +
         line6 + "\n" + "    pos: [0.5, 0, 0.45]\n";
}

TEST(SceneFile, TheExampleComposesThePandaWithItsHandObjectsAndSensors) {
  ASSERT_TRUE(is_scene_file(kExample));
  const Scene scene = load_scene_file(kExample);
  EXPECT_EQ(scene.name(), "pick_table");
  const Robot robot = scene.compile();
  EXPECT_EQ(robot.nq(), 7 + 2 + 7 + 7);
  EXPECT_EQ(robot.nu(), 9);
  EXPECT_EQ(robot.sensors().size(), 4u);
  const mjModel& m = robot.model();
  const int weld = try_find_object(m, mjOBJ_EQUALITY, "grasp");
  ASSERT_GE(weld, 0);
  EXPECT_EQ(m.eq_active0[weld], 0);
  const int finger = robot.actuator("panda/hand/finger_left");
  EXPECT_EQ(m.actuator_ctrlrange[2 * finger + 1], 0.012);
  EXPECT_EQ(m.actuator_gainprm[finger * mjNGAIN], 3200.0);
  EXPECT_NEAR(m.geom_size[3 * robot.geom("cube/geom")], 0.0075, 1e-15);
  // the fixture has no joint
  EXPECT_EQ(m.body_jntnum[robot.body("bin")], 0);
  // the home key puts the arm at the panda's home
  const auto home = robot.keyframe_qpos("home");
  EXPECT_EQ(home[static_cast<std::size_t>(m.jnt_qposadr[robot.joint("panda/joint4")])], -2.356);
}

TEST(SceneFile, JsonReadsTheSameWay) {
  const auto file = test::scratch() / "small.json";
  std::ofstream(file) << R"({"name": "js", "arena": {"table": {"height": 0.5}},
    "robots": [{"name": "arm", "model": "arm6", "pos": [-1, 0, 0]}],
    "objects": [{"name": "ball", "shape": "sphere", "size": [0.02], "pos": [0.5, 0, 0.55]}]})";
  const Robot robot = load_scene_file(file).compile();
  EXPECT_EQ(robot.name(), "js");
  EXPECT_EQ(robot.nq(), 8 + 7);
  const mjModel& m = robot.model();
  EXPECT_NEAR(m.geom_size[3 * robot.geom("arena/table_top") + 2], 0.02, 1e-15);
}

TEST(SceneFile, WrongTypesNameTheLineAndTheKey) {
  std::string message =
      error_of([] { parse_scene(small_scene("    mass: heavy"), ".", "s.yaml"); });
  EXPECT_TRUE(
      mentions(message, "s.yaml:6: key 'mass' in object 'cube' expects a number, got 'heavy'"))
      << message;
  message = error_of([] { parse_scene(small_scene("    size: [0.1, x, 0.1]"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:6: key 'size'")) << message;
  message = error_of([] { parse_scene(small_scene("    friction: {a: 1}"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:6: key 'friction' in object 'cube' expects a list"))
      << message;
  message = error_of([] { parse_scene(small_scene("    rgba: [1, 0.5]"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:6: key 'rgba' in object 'cube' expects 4 numbers, got 2"))
      << message;
  message = error_of([] { parse_scene("name: x\nrobots: {name: a}\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: key 'robots' expects a list")) << message;
}

TEST(SceneFile, UnknownKeysNameTheLineAndTheClosestKey) {
  std::string message =
      error_of([] { parse_scene(small_scene("    frction: [1, 0, 0]"), ".", "s.yaml"); });
  EXPECT_TRUE(
      mentions(message, "s.yaml:6: unknown key 'frction' in object 'cube'; closest: friction"))
      << message;
  message = error_of([] { parse_scene("name: x\nrobot: []\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: unknown key 'robot' in the scene; closest: robots"))
      << message;
}

TEST(SceneFile, BadPartsNameTheEntryAndTheReason) {
  std::string message = error_of([] { parse_scene(small_scene("    mass: -2"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:4: object 'cube': box object 'cube' mass must be positive"))
      << message;
  message = error_of([] { parse_scene("robots:\n  - {name: a, model: pnda}\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: robot 'a': unknown robot 'pnda'; closest: panda"))
      << message;
  message = error_of([] {
    parse_scene(
        "robots:\n  - name: a\n    model: panda\n    gripper: {model: franka_hand, frame: "
        "flange}\n",
        ".", "s.yaml");
  });
  EXPECT_TRUE(mentions(message, "unknown attachment frame 'flange'")) << message;
  message = error_of([] { parse_scene("objects:\n  - {name: c, shape: cub}\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: unknown object shape 'cub'; closest: box")) << message;
  message = error_of([] { parse_scene(small_scene("    shape: sphere"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:6: key 'shape' appears twice in object 'cube'")) << message;
  message = error_of([] { parse_scene("objects:\n  - {shape: box}\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: object #1 needs the key 'name'")) << message;
  message = error_of([] { parse_scene("name: [unclosed\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:")) << message;
  EXPECT_TRUE(mentions(message, "not valid YAML or JSON")) << message;
  message = error_of([] {
    parse_scene("objects:\n  - {name: m, shape: mesh, mesh: meshes/none.obj}\n", "/tmp/nowhere",
                "s.yaml");
  });
  EXPECT_TRUE(
      mentions(message, "mesh file '/tmp/nowhere/meshes/none.obj' does not exist (object 'm')"))
      << message;
  EXPECT_TRUE(mentions(error_of([] { load_scene_file("/nonexistent/scene.yaml"); }),
                       "scene file '/nonexistent/scene.yaml' does not exist"));
}

// issue 29, item 6: the second document of a YAML file was dropped without a word
TEST(SceneFile, ASecondDocumentIsRefused) {
  const std::string first = "name: one\narena:\n";
  std::string message =
      error_of([&] { parse_scene(first + "---\nname: two\nrobots: []\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message,
                       "s.yaml:4: a second document starts here (the first at line 1); "
                       "a scene file holds one scene"))
      << message;
  // JSON read as YAML: a second value is a second document too
  message = error_of([] { parse_scene("{\"name\": \"a\"}\n{\"name\": \"b\"}\n", ".", "s.json"); });
  EXPECT_TRUE(mentions(message, "s.json:2: a second document starts here")) << message;
  // empty documents hold nothing that could be lost: a leading or trailing '---' is fine
  EXPECT_EQ(parse_scene("---\n" + first + "---\n", ".", "s.yaml").name(), "one");
}

// found by the fuzzer (fuzz/regressions/scene): a lone ',' made yaml-cpp 0.7's LoadAll collect
// empty documents until memory ran out (`mjarm info` hung); it is refused where the parser stops
TEST(SceneFile, AStreamTheYamlParserCannotGetPastIsRefused) {
  for (const std::string text : {",", "name: one\n,\n", "]\n", "{\"name\": \"a\"}\n}\n"}) {
    SCOPED_TRACE(text);
    const std::string message = error_of([&] { parse_scene(text, ".", "s.yaml"); });
    EXPECT_TRUE(mentions(message, "s.yaml:")) << message;
    EXPECT_TRUE(mentions(message, "not valid YAML or JSON")) << message;
  }
  // a document per '---' still counts as progress
  EXPECT_EQ(parse_scene("---\n---\n---\nname: one\n", ".", "s.yaml").name(), "one");
}

// issue 29, item 5: `xyaxes: [0, 0, 0, 0, 0, 0]` was read as "no xyaxes" and the camera looked
// along the parent's −z; an edit's zero quaternion compiled into a zero rotation matrix
TEST(SceneFile, DegenerateFramesAreRefusedNamingTheLineElementAndAttribute) {
  const auto error_in = [](const std::string& text) {
    return error_of([&] { parse_scene(text, ".", "s.yaml"); });
  };
  std::string message =
      error_in("cameras:\n  - {name: c, pos: [1, 0, 1], xyaxes: [0, 0, 0, 0, 0, 0]}\n");
  EXPECT_TRUE(mentions(message, "s.yaml:2: camera 'c': xyaxes has a zero x axis")) << message;
  message = error_in("cameras:\n  - {name: c, xyaxes: [0, 1, 0, 0, -1, 0]}\n");
  EXPECT_TRUE(mentions(message, "s.yaml:2: camera 'c': xyaxes has its y axis parallel")) << message;
  message =
      error_in("cameras:\n  - name: c\n    xyaxes: [0, 1, 0, 0, 0, 1]\n    quat: [1, 0, 0, 0]\n");
  EXPECT_TRUE(mentions(message, "s.yaml:4: camera 'c' has both 'xyaxes' and 'quat': give one"))
      << message;
  message = error_in("objects:\n  - {name: b, quat: [0, 0, 0, 0]}\n");
  EXPECT_TRUE(mentions(message, "s.yaml:2: object 'b': box object 'b': quat is a zero quaternion"))
      << message;
  message = error_in("sites:\n  - {name: t, quat: [.nan, 0, 0, 1]}\n");
  EXPECT_TRUE(mentions(message, "site 't': quat holds a value that is not finite")) << message;
  const std::string ball = "objects:\n  - {name: b, shape: sphere, size: [0.02]}\nedits:\n";
  message = error_in(ball + "  - {element: body, name: b, set: {quat: [0, 0, 0, 0]}}\n");
  EXPECT_TRUE(mentions(message, "s.yaml:4: edit #1: body 'b': quat is a zero quaternion"))
      << message;
  message = error_in(ball + "  - {element: body, name: b, set: {zaxis: [0, 0, 0]}}\n");
  EXPECT_TRUE(mentions(message, "body 'b': zaxis is a zero vector")) << message;
  message = error_in(ball + "  - {element: body, name: b, set: {axisangle: [0, 0, 0, 1]}}\n");
  EXPECT_TRUE(mentions(message, "body 'b': axisangle has a zero axis")) << message;
  message = error_in(ball + "  - {element: body, name: b, set: {euler: [.inf, 0, 0]}}\n");
  EXPECT_TRUE(mentions(message, "body 'b': euler must be finite numbers")) << message;
  // one edit, two orientations: the last one won without a word
  message = error_in(ball +
                     "  - {element: body, name: b, set: {quat: [1, 0, 0, 0], euler: [0, 0, 1]}}\n");
  EXPECT_TRUE(mentions(message,
                       "s.yaml:4: edit #1 gives body 'b' two orientations, 'quat' and "
                       "'euler': give one"))
      << message;
  message =
      error_in(ball + "  - {element: body, name: b, set: {pos: [0, 0, 1], pos: [0, 0, 2]}}\n");
  EXPECT_TRUE(mentions(message, "s.yaml:4: attribute 'pos' appears twice in edit #1")) << message;
}

// issue 29, smaller: "scene.YAML" was read as MJCF ("malformed XML … line 1")
TEST(SceneFile, TheExtensionIsReadInAnyCase) {
  for (const char* name : {"s.yaml", "s.YAML", "s.Yml", "s.yml", "s.JSON", "s.json"})
    EXPECT_TRUE(is_scene_file(name)) << name;
  for (const char* name : {"s.xml", "s.yaml.xml", "yaml", "s.yam"})
    EXPECT_FALSE(is_scene_file(name)) << name;
  const auto file = test::scratch() / "upper.YAML";
  std::ofstream(file) << "name: upper\narena:\n";
  EXPECT_EQ(load_scene_file(file).name(), "upper");
}

// issue 29, item 4: a mass of 1e308 or a position of 1e300 loaded ("load warnings (0)") and
// failed at the first step; the positions, sizes and masses a scene gives are bounded by
// MuJoCo's mjMAXVAL, named with their line, the number in its shortest form
TEST(SceneFile, HugeMassesPositionsAndSizesAreRefusedWithTheirLine) {
  std::string message =
      error_of([] { parse_scene(small_scene("    mass: 1e308"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:4: object 'cube': box object 'cube' mass holds 1e+308, "
                                "beyond 1e+10 (MuJoCo's mjMAXVAL"))
      << message;
  message = error_of([] { parse_scene(small_scene("    size: [1e300, 0.1, 0.1]"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "size holds 1e+300, beyond 1e+10")) << message;
  message = error_of(
      [] { parse_scene("objects:\n  - {name: c, pos: [0, -1e300, 0]}\n", ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "s.yaml:2: object 'c': box object 'c' pos holds -1e+300"))
      << message;
  message = error_of([] {
    parse_scene("sites:\n  - {name: s, pos: [0, 0, 1e11]}\n", ".", "s.yaml");
  });
  EXPECT_TRUE(mentions(message, "site 's' pos holds 1e+11")) << message;
  // the positive-mass rule prints its number short too (it was -1000000000.000000)
  message = error_of([] { parse_scene(small_scene("    mass: -1e9"), ".", "s.yaml"); });
  EXPECT_TRUE(mentions(message, "mass must be positive [kg], got -1e+09")) << message;
}

// issue 16, items 6 and 7: a scene file is a user file like a model: read only when it is a
// regular file within the size limit, and a FIFO, a device, a folder or a symbolic link loop is
// named for what it is (all were "does not exist"; a huge file was read whole)
TEST(SceneFile, OnlyRegularFilesOfBoundedSizeAreRead) {
  for (const test::UnreadablePath& bad : test::unreadable_paths(
           test::scratch() / "scene_files", "scene", ".yaml", kMaxTextFileBytes + 1)) {
    const std::string message = test::error_without_blocking(
        bad.path, [](const std::filesystem::path& p) { load_scene_file(p); });
    EXPECT_TRUE(mentions(message, "scene file '" + bad.path.string() + "'")) << message;
    EXPECT_TRUE(mentions(message, bad.expected)) << message;
  }
}

// the same for an object's mesh: a FIFO or /dev/zero was "does not exist"
TEST(SceneFile, AnObjectsMeshIsARegularFileOfBoundedSize) {
  for (const test::UnreadablePath& bad : test::unreadable_paths(
           test::scratch() / "scene_meshes", "mesh", ".stl", kMaxDataFileBytes + 1)) {
    const std::string message = test::error_without_blocking(bad.path, [](const auto& p) {
      parse_scene("objects:\n  - {name: m, shape: mesh, mesh: '" + p.string() + "'}\n", ".",
                  "s.yaml");
    });
    EXPECT_TRUE(mentions(message, "s.yaml:2: object 'm': mesh file '" + bad.path.string() + "'"))
        << message;
    EXPECT_TRUE(mentions(message, bad.expected)) << message;
  }
}

// issue 16, item 7's rule for the XML depth limit, in YAML: yaml-cpp refuses deep nesting with
// the message "bad file"; the error says what the limit is instead
TEST(SceneFile, NestingBeyondTheParsersLimitIsNamed) {
  const std::string deep = "name: [" + std::string(600, '[') + std::string(601, ']') + "\n";
  const std::string message = error_of([&] { parse_scene(deep, ".", "deep.yaml"); });
  EXPECT_TRUE(mentions(message, "deep.yaml:1: nested more than")) << message;
  EXPECT_TRUE(mentions(message, "levels deep, the limit of the YAML parser (yaml-cpp)")) << message;
  EXPECT_FALSE(mentions(message, "bad file")) << message;
  // well within the limit: read (and refused only for what it holds)
  const std::string shallow = "name: [" + std::string(50, '[') + std::string(51, ']') + "\n";
  EXPECT_FALSE(mentions(error_of([&] { parse_scene(shallow, ".", "s.yaml"); }), "nested"));
}

}  // namespace
}  // namespace mjarm
