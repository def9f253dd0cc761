// Scene files (unidist/adapters/scene.h): a full scene reads back every field, defaults apply, relative model
// paths resolve against the scene's folder, bodies naming the same model share one model; and every bad input —
// not JSON, unknown or missing keys, wrong types, bad numbers, duplicate names, a dynamic half-space, a missing
// model file — is one InputError naming the scene, the body and the field.
#include "error_of.h"
#include "scratch_files.h"
#include "unidist/adapters/scene.h"

#include <gtest/gtest.h>

namespace {

using unidist::testing::errorOf;

class SceneFiles : public unidist::testing::ScratchFiles {
 protected:
  /// Parsing `text` fails with a message holding every fragment.
  void expectError(const std::string& text, std::initializer_list<const char*> fragments) {
    const std::string msg = errorOf([&] { unidist::parseScene(text, ".", "s.json"); });
    EXPECT_EQ(msg.rfind("s.json: ", 0), 0u) << msg;
    for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "message: " << msg << "\nexpected: " << f;
  }
};

TEST_F(SceneFiles, ReadsEveryField) {
  write("cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const std::string path = write("scene.json", R"({"gravity": [0, 0, -2], "dt": 0.01, "steps": 7,
    "bodies": [{"name": "floor", "model": "plane:nx=0,ny=0,nz=1,d=0", "static": true},
               {"name": "a", "model": "cube.obj", "pose": [1, 2, 3, 0, 0, 0, 2], "mass": 2.5, "friction": 0.3,
                "restitution": 0.1, "tolerance": 1e-5, "linear_velocity": [1, 0, 0], "angular_velocity": [0, 0, 1]},
               {"name": "b", "model": "cube.obj", "mass": 1}]})");
  const unidist::Scene s = unidist::loadScene(path);
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0, 0, -2));
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.steps, 7);
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_TRUE(s.bodies[0].isStatic);
  EXPECT_EQ(s.bodies[0].model->type(), unidist::ModelType::Plane);
  const unidist::SceneBody& a = s.bodies[1];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.model->type(), unidist::ModelType::Mesh);
  EXPECT_TRUE(a.pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(a.pose.linear().isApprox(Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()))));
  EXPECT_EQ(a.mass, 2.5);
  EXPECT_EQ(a.friction, 0.3);
  EXPECT_EQ(a.restitution, 0.1);
  EXPECT_EQ(a.tolerance, 1e-5);
  EXPECT_EQ(a.linearVelocity, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(a.angularVelocity, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(s.bodies[2].model.get(), a.model.get()) << "one model per source";
  EXPECT_EQ(s.bodies[2].friction, 0.5);
  EXPECT_TRUE(s.bodies[2].pose.isApprox(Eigen::Isometry3d::Identity()));
}

TEST_F(SceneFiles, DefaultsApply) {
  const unidist::Scene s = unidist::parseScene(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}]})", ".", "s.json");
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_GT(s.dt, 0);
  EXPECT_GT(s.steps, 0);
  EXPECT_EQ(s.bodies[0].restitution, 0);
  EXPECT_LT(s.bodies[0].tolerance, 0);
}

TEST_F(SceneFiles, BadInputIsNamed) {
  expectError("{", {"not valid JSON"});
  expectError("[]", {"top level", "JSON object"});
  expectError(R"({"bodies": [], "gravity": [0,0,1]})", {"bodies", "non-empty"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}], "gravty": [0,0,1]})", {"unknown key \"gravty\""});
  expectError(R"({"steps": 10})", {"missing key \"bodies\""});
  expectError(R"({"bodies": [{"model": "sphere:r=1", "mass": 1}]})", {"bodies[0]", "missing key \"name\""});
  expectError(R"({"bodies": [{"name": "b", "mass": 1}]})", {"bodies[0]", "missing key \"model\""});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1"}]})", {"\"b\"", "missing key \"mass\""});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "static": true, "mass": 1}]})", {"\"b\"", "static body has no mass"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": -1}]})", {"\"b\"", "mass", "> 0"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "colour": 3}]})", {"\"b\"", "unknown key \"colour\""});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "friction": -0.1}]})", {"friction", ">= 0"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "restitution": 2}]})", {"restitution", "[0, 1]"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "pose": [0,0,0,1,0,0]}]})", {"pose", "7 numbers"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "pose": [0,0,0,0,0,0,0]}]})", {"pose", "quaternion is zero"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1, "pose": [0,0,"x",1,0,0,0]}]})", {"pose[2]", "number"});
  expectError(R"({"dt": 0, "bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}]})", {"dt", "> 0"});
  expectError(R"({"steps": 1.5, "bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}]})", {"steps", "integer"});
  expectError(R"({"steps": -1, "bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}]})", {"steps", "integer"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=1", "mass": 1}, {"name": "b", "model": "sphere:r=1", "mass": 1}]})",
              {"bodies[1]", "duplicate body name \"b\""});
  expectError(R"({"bodies": [{"name": "f", "model": "plane:nx=0,ny=0,nz=1,d=0", "mass": 1}]})", {"\"f\"", "unbounded", "static"});
  expectError(R"({"bodies": [{"name": "b", "model": "sphere:r=-1", "mass": 1}]})", {"\"b\"", "model", "r must be > 0"});
  expectError(R"({"bodies": [{"name": "b", "model": "nowhere.obj", "mass": 1}]})", {"\"b\"", "nowhere.obj"});
  expectError(R"({"bodies": [{"name": "b", "model": 3, "mass": 1}]})", {"\"b\"", "model", "string"});
}

TEST_F(SceneFiles, MissingSceneFileIsNamed) {
  const std::string msg = errorOf([] { unidist::loadScene("/nonexistent/scene.json"); });
  EXPECT_NE(msg.find("/nonexistent/scene.json"), std::string::npos) << msg;
}

}  // namespace
