// The scene JSON writer: valid JSON in the spec §8 layout and key order, floats that stay
// floats, escaped and repaired strings, non-finite numbers as null.
#include "output/scene_json.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "lang/lang.h"
#include "sampling/sampler.h"

namespace prs::output {
namespace {

using nlohmann::json;

sampling::SampledScene MakeScene(const lang::ClassInfo& cls) {
  sampling::SampledScene sampled;
  sampled.seed = 7;
  sampled.index = 3;
  sampled.attempts = 2;
  sampled.rejections.Add({lang::RejectionKind::kCollision, "a and b", {}, "", false});
  lang::SceneObject o;
  o.name = "tr_1";
  o.cls = &cls;
  o.p_WO = {1.0, -0.25, 0.1};
  o.dimensions = {0.24, 0.45, 0.03};
  o.properties = {{"position", lang::Value(o.p_WO)},
                  {"color", lang::MakeString("grey")},
                  {"label", lang::MakeString("say \"hi\"\n\xff")},
                  {"mass", lang::Value(std::numeric_limits<double>::quiet_NaN())},
                  {"tags", lang::MakeList({lang::Value(1.0), lang::Value(true), lang::Value()})}};
  sampled.scene.objects.push_back(o);
  lang::SceneObject anonymous = o;
  anonymous.name.reset();
  sampled.scene.objects.push_back(anonymous);
  sampled.scene.params = {{"n", lang::Value(3.0)}};
  return sampled;
}

TEST(SceneJsonTest, FollowsTheSpecLayout) {
  lang::ClassInfo tray;
  tray.name = "Tray";
  const std::string line = FormatSceneJson(MakeScene(tray));
  EXPECT_EQ(line.find('\n'), std::string::npos);
  EXPECT_EQ(line.rfind("{\"format\":\"prs-scene/1\",\"seed\":7,\"index\":3,\"attempts\":2,"
                       "\"rejections\":{\"collision\":1},\"params\":{\"n\":3.0},",
                       0),
            0u)
      << line;
  const json scene = json::parse(line);
  const json& o = scene["objects"][0];
  EXPECT_EQ(o["name"], "tr_1");
  EXPECT_TRUE(scene["objects"][1]["name"].is_null());
  EXPECT_EQ(o["class"], "Tray");
  EXPECT_EQ(o["position"], json({1.0, -0.25, 0.1}));
  EXPECT_TRUE(o["position"][0].is_number_float());
  EXPECT_EQ(o["orientation"]["quaternion"], json({1.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(o["orientation"]["yaw_pitch_roll"].size(), 3u);
  EXPECT_EQ(o["dimensions"], json({0.24, 0.45, 0.03}));
  EXPECT_FALSE(o["properties"].contains("position"));
  EXPECT_EQ(o["properties"]["color"], "grey");
  EXPECT_EQ(o["properties"]["label"], "say \"hi\"\n\xEF\xBF\xBD");
  EXPECT_TRUE(o["properties"]["mass"].is_null());
  EXPECT_EQ(o["properties"]["tags"], json({1.0, true, nullptr}));
}

TEST(SceneJsonTest, NumbersRoundTripExactly) {
  lang::ClassInfo cube;
  cube.name = "Cube";
  sampling::SampledScene sampled = MakeScene(cube);
  sampled.scene.objects[0].p_WO = {0.1 + 0.2, 1e-300, -0.0};
  const json scene = json::parse(FormatSceneJson(sampled));
  EXPECT_EQ(scene["objects"][0]["position"][0].get<double>(), 0.1 + 0.2);
  EXPECT_EQ(scene["objects"][0]["position"][1].get<double>(), 1e-300);
  EXPECT_TRUE(std::signbit(scene["objects"][0]["position"][2].get<double>()));
}

// The number writer is fmt's "{}" without fmt's general float writer: every layout (fixed,
// leading zeros, trailing zeros, exponents of 2 and 3 digits, subnormals) must match fmt's.
TEST(SceneJsonTest, ShortestNumbersAreFmts) {
  std::mt19937_64 random(20261126);
  auto check = [](double x) {
    char text[32];
    const std::string mine(text, WriteShortest(x, text));
    ASSERT_EQ(mine, fmt::format("{}", x)) << "bits " << std::bit_cast<uint64_t>(x);
  };
  for (int i = 0; i < 1'000'000; ++i) {
    const double any = std::bit_cast<double>(random());
    if (std::isfinite(any)) check(any);
    check(std::uniform_real_distribution<double>(-10, 10)(random));
    check(std::ldexp(double(random() >> 11), int(random() % 140) - 70));  // wide exponents
  }
  for (int e = -330; e <= 308; ++e) {  // either side of every power of ten
    const double p = std::pow(10.0, e);
    for (double x : {p, std::nextafter(p, 0.0), std::nextafter(p, HUGE_VAL), 1.5 * p, -p}) check(x);
  }
  for (double x : {0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                   0.1, 0.3, 1e15, 1e16, 123456789012345678.0, 0.0001, 0.00001}) {
    check(x);
  }
}

// Objects a sampler copies into every scene are written from text made once per thread
// (SceneObject::fixed_id), and copies of templates from their head and a tail made once
// (SceneObject::template_id): the lines must be those written field by field, also with two
// programs of the same layout but different properties sampled in turn on one thread.
TEST(SceneJsonTest, KeptObjectsAreWrittenAsTheirFieldsSay) {
  auto compile = [](const std::string& color) {
    lang::DiagnosticEngine diagnostics;
    auto program = lang::CompileText("kept.prs",
                                     "class Box:\n    width: 0.5\n    length: 0.5\n"
                                     "    height: 0.5\n    color: \"" + color + "\"\n"
                                     "t = Box at V3D(0, 0, 0.25)\n"
                                     "c = Box at V3D((2, 3), 0.1, 0.25)\n",
                                     {}, diagnostics);
    EXPECT_FALSE(diagnostics.has_errors());
    return program;
  };
  auto red = compile("red"), blue = compile("blue");
  sampling::SceneSampler red_sampler(*red), blue_sampler(*blue);
  int kept = 0, templates = 0;
  for (uint64_t i = 0; i < 20; ++i) {
    for (sampling::SceneSampler* sampler : {&red_sampler, &blue_sampler}) {
      const sampling::SampledScene sampled = sampler->Sample(1, i);
      sampling::SampledScene plain = sampled;
      for (lang::SceneObject& o : plain.scene.objects) {
        kept += o.fixed_id != 0;
        templates += o.template_id != 0;
        o.fixed_id = 0;
        o.template_id = 0;
      }
      EXPECT_EQ(FormatSceneJson(sampled), FormatSceneJson(plain));
    }
  }
  EXPECT_GE(kept, 38);       // the table of every scene after each sampler's first
  EXPECT_GE(templates, 38);  // the random box, a copy of its template but for its position
  const json red_scene = json::parse(FormatSceneJson(red_sampler.Sample(1, 99)));
  const json blue_scene = json::parse(FormatSceneJson(blue_sampler.Sample(1, 99)));
  EXPECT_EQ(red_scene["objects"][0]["properties"]["color"], "red");
  EXPECT_EQ(blue_scene["objects"][0]["properties"]["color"], "blue");
}

}  // namespace
}  // namespace prs::output
