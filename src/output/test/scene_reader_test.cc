// Reading scene lines back: every example's scenes, written, read and written again, give the
// same line (to the last digit of orientations); the objects read carry their classes, poses,
// sizes, properties and shapes; a bad line is refused with what is wrong.
#include "output/scene_reader.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "output/scene_json.h"
#include "sampling/test/scene_checks.h"

namespace prs::output {
namespace {

using sampling::testing_checks::CompileExample;

// Two scene lines are the same but for rounding in orientations: a rotation read from its
// quaternion and written again goes through a rotation matrix, which may move the last digit.
void ExpectSameScene(const std::string& a, const std::string& b) {
  nlohmann::json x = nlohmann::json::parse(a), y = nlohmann::json::parse(b);
  ASSERT_EQ(x["objects"].size(), y["objects"].size());
  for (size_t i = 0; i < x["objects"].size(); ++i) {
    nlohmann::json& p = x["objects"][i]["orientation"];
    nlohmann::json& q = y["objects"][i]["orientation"];
    for (const char* key : {"quaternion", "yaw_pitch_roll"}) {
      for (size_t k = 0; k < p[key].size(); ++k) {
        EXPECT_NEAR(p[key][k].get<double>(), q[key][k].get<double>(), 2e-15) << i << key;
      }
    }
    p = nullptr;
    q = nullptr;
  }
  EXPECT_EQ(x, y) << "beyond orientations: everything the same";
}

TEST(SceneReaderTest, EveryExampleSceneReadsBackToTheSameLine) {
  for (const char* example : {"table_cube.prs", "constructs.prs", "pantry_shapes.prs",
                              "kitchen_meshes.prs", "table_cube_reachable_visible.prs"}) {
    SCOPED_TRACE(example);
    const auto program = CompileExample(example);
    ASSERT_TRUE(program);
    sampling::SceneSampler sampler(*program);
    SceneReader reader;
    for (uint64_t i = 0; i < 5; ++i) {
      const std::string line = FormatSceneJson(sampler.Sample(3, i));
      std::vector<std::string> warnings;
      const sampling::SampledScene read = reader.Read(line, &warnings);
      EXPECT_TRUE(warnings.empty());
      ExpectSameScene(FormatSceneJson(read), line);
    }
  }
}

TEST(SceneReaderTest, ObjectsKeepClassPoseSizePropertiesAndShapes) {
  const auto program = CompileExample("pantry_shapes.prs");
  ASSERT_TRUE(program);
  const sampling::SampledScene drawn = sampling::SceneSampler(*program).Sample(1, 2);
  SceneReader reader;
  const sampling::SampledScene read = reader.Read(FormatSceneJson(drawn));
  EXPECT_EQ(read.seed, 1u);
  EXPECT_EQ(read.index, 2u);
  EXPECT_EQ(read.attempts, drawn.attempts);
  ASSERT_EQ(read.scene.objects.size(), drawn.scene.objects.size());
  int primitives = 0;
  for (size_t i = 0; i < read.scene.objects.size(); ++i) {
    const lang::SceneObject& a = drawn.scene.objects[i];
    const lang::SceneObject& b = read.scene.objects[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.cls->name, b.cls->name);
    EXPECT_EQ(a.p_WO, b.p_WO);
    EXPECT_LT(a.R_WO.angularDistance(b.R_WO), 1e-12);
    EXPECT_EQ(a.dimensions, b.dimensions);
    EXPECT_EQ(a.primitive, b.primitive);
    EXPECT_EQ(a.mesh == nullptr, b.mesh == nullptr);
    primitives += b.primitive.has_value();
    for (const char* property : {"mass", "color"}) {
      const lang::Value* x = a.FindProperty(property);
      const lang::Value* y = b.FindProperty(property);
      ASSERT_EQ(x == nullptr, y == nullptr) << property;
    }
  }
  EXPECT_GT(primitives, 0) << "pantry_shapes has cylinders";
  EXPECT_EQ(read.scene.objects[0].cls, reader.Read(FormatSceneJson(drawn)).scene.objects[0].cls)
      << "one class per name";
}

TEST(SceneReaderTest, BadLinesSayWhatIsWrong) {
  SceneReader reader;
  auto message = [&](const std::string& line) {
    try {
      reader.Read(line);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("(read)");
  };
  EXPECT_EQ(message("{\"format\":"), "not valid JSON");
  EXPECT_EQ(message(R"({"seed":1,"index":2,"outcome":"success"})"),
            "not a scene: \"format\" is not \"prs-scene/1\"");
  EXPECT_EQ(message(R"({"format":"prs-scene/1","seed":-1,"index":2,"objects":[]})"),
            "the scene: \"seed\" and \"index\" must be whole numbers from 0");
  EXPECT_EQ(message(R"({"format":"prs-scene/1","seed":1,"index":2,"objects":[{"name":"a"}]})"),
            "object 0: no \"class\"");
  EXPECT_EQ(message(R"({"format":"prs-scene/1","seed":1,"index":2,"objects":[{"name":"a",)"
                    R"("class":"Cube","position":[0,0],"orientation":{},"dimensions":[1,1,1]}]})"),
            "object 0: \"position\" is not 3 numbers");
  std::string deep = R"({"format":"prs-scene/1","seed":1,"index":2,"params":{"p":)";
  deep += std::string(1100, '[') + std::string(1100, ']') + R"(},"objects":[]})";
  EXPECT_NE(message(deep).find("nests more than 1000 levels"), std::string::npos);
}

}  // namespace
}  // namespace prs::output
