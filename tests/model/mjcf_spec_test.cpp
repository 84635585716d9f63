// MJCF parsed into an editable mjSpec (parse_mjcf_file) and compiled from one
// (Robot::from_spec): the same model as Robot::from_file, errors that name the file and line.

#include "mjarm/model/mjcf_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "mjarm/model/robot.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

using test::error_of;

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::filesystem::path write_model(const std::string& name, const std::string& text) {
  const auto file = test::scratch() / name;
  std::ofstream(file) << text;
  return file;
}

TEST(MjcfSpec, AParsedFileCompilesToTheModelFromFileLoads) {
  // includes, textures, default classes, keyframes: the bundled panda with its hand
  const auto file = Robot::models_dir() / "panda_hand.xml";
  const SpecPtr spec = parse_mjcf_file(file);
  const Robot from_spec = Robot::from_spec(*spec, "spec 'panda_hand'");
  const Robot from_file = Robot::from_file(file);
  EXPECT_EQ(from_spec.source(), "<string>");
  EXPECT_EQ(from_spec.name(), from_file.name());
  const mjModel& a = from_spec.model();
  const mjModel& b = from_file.model();
  ASSERT_EQ(a.nq, b.nq);
  ASSERT_EQ(a.nbody, b.nbody);
  ASSERT_EQ(a.ngeom, b.ngeom);
  ASSERT_EQ(a.nkey, b.nkey);
  for (int i = 0; i < 3 * a.nbody; ++i) EXPECT_EQ(a.body_pos[i], b.body_pos[i]) << i;
  for (int i = 0; i < a.nbody; ++i) EXPECT_EQ(a.body_mass[i], b.body_mass[i]) << i;
  for (int i = 0; i < 3 * a.ngeom; ++i) EXPECT_EQ(a.geom_size[i], b.geom_size[i]) << i;
  for (int i = 0; i < a.nq * a.nkey; ++i) EXPECT_EQ(a.key_qpos[i], b.key_qpos[i]) << i;
}

TEST(MjcfSpec, ParseErrorsNameTheFileAndTheLine) {
  const auto bad = write_model("spec_bad.xml", R"(<mujoco>
  <worldbody>
    <body name="b">
      <geom sise="0.1"/>
    </body>
  </worldbody>
</mujoco>)");
  std::string message = error_of([&] { parse_mjcf_file(bad); });
  EXPECT_TRUE(mentions(message, "cannot load '" + bad.string() + "'")) << message;
  EXPECT_TRUE(mentions(message, "sise")) << message;
  EXPECT_TRUE(mentions(message, "line 4")) << message;
  const auto urdf = write_model("spec_robot.urdf", "<robot name=\"r\"><link name=\"a\"/></robot>");
  message = error_of([&] { parse_mjcf_file(urdf); });
  EXPECT_TRUE(mentions(message, "the root element must be <mujoco>")) << message;
  message = error_of([&] { parse_mjcf_file(test::scratch() / "no_such_model.xml"); });
  EXPECT_TRUE(mentions(message, "does not exist")) << message;
}

TEST(MjcfSpec, FromSpecRefusesASpecThatDoesNotCompileOrHoldsNonFiniteNumbers) {
  const SpecPtr spec(mj_makeSpec());
  mjsBody* body = mjs_addBody(mjs_findBody(spec.get(), "world"), nullptr);
  mjs_setName(body->element, "b");
  mjsGeom* geom = mjs_addGeom(body, nullptr);
  geom->size[0] = -0.1;
  std::string message = error_of([&] { Robot::from_spec(*spec, "spec 'b'"); });
  EXPECT_TRUE(mentions(message, "spec 'b' does not compile: ")) << message;
  EXPECT_TRUE(mentions(message, "size")) << message;
  geom->size[0] = 0.1;
  EXPECT_EQ(Robot::from_spec(*spec, "spec 'b'").model().nbody, 2);
  body->pos[0] = std::numeric_limits<double>::infinity();
  message = error_of([&] { Robot::from_spec(*spec, "spec 'b'"); });
  EXPECT_TRUE(mentions(message, "spec 'b'")) << message;
  EXPECT_TRUE(mentions(message, "body 'b'")) << message;
}

}  // namespace
}  // namespace mjarm
