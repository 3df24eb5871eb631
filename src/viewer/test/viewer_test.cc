// Tests of the viewer library: view records (the exact `prs sample` line plus the workspace),
// the served and self-contained pages, and the HTTP server's routes and errors, through a
// real server on a free loopback port.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <fstream>
#include <thread>

#include "output/scene_json.h"
#include "viewer/assets.h"
#include "viewer/viewer.h"

// After Eigen: included first, a macro from the system headers it pulls in breaks Eigen's.
#include <httplib.h>

namespace prs::viewer {
namespace {

using nlohmann::json;

constexpr const char* kScenario = R"(
workspace = Cuboid(Vector3D(0, 0, 1), Vector3D(0, 0, 0), 2, 2, 2)
class Box:
    width: 0.2
    length: 0.2
    height: 0.2
    color: "0.5"
a = Box at Vector3D((-0.5, 0.5), 0, 0.1)
b = Box at Vector3D(0.7, 0.7, 0.1), with color "</script><!-- x"
)";

std::unique_ptr<lang::CompiledProgram> Compile(const std::string& text) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText("test.prs", text, {}, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors());
  return program;
}

TEST(ViewRecord, HoldsTheSampleLineAndTheWorkspaceCorners) {
  auto program = Compile(kScenario);
  const sampling::SampledScene scene = sampling::SampleScene(*program, 3, 1);
  const json record = json::parse(FormatViewRecord(scene));
  EXPECT_EQ(record["line"], output::FormatSceneJson(scene));
  EXPECT_EQ(record["workspace"]["dimension"], 3);
  const json& vertices = record["workspace"]["vertices"];
  ASSERT_EQ(vertices.size(), 8u);
  for (const json& v : vertices) {
    EXPECT_NEAR(std::abs(v[0].get<double>()), 1.0, 1e-9);
    EXPECT_NEAR(std::abs(v[1].get<double>()), 1.0, 1e-9);
    EXPECT_TRUE(std::abs(v[2].get<double>()) < 1e-9 || std::abs(v[2].get<double>() - 2) < 1e-9);
  }
}

TEST(ViewRecord, HasNoWorkspaceWhenTheProgramBindsNone) {
  auto program = Compile("class C:\n    width: 1\nC at Vector3D(0, 0, 0)\n");
  const json record = json::parse(FormatViewRecord(sampling::SampleScene(*program, 0, 0)));
  EXPECT_TRUE(record["workspace"].is_null());
}

// A mesh shape's triangles travel with the record, keyed by the path the line records, both
// for a sampled scene and for a line read back from a scenes file; a mesh whose file is gone
// is left out (the page draws its box).
TEST(ViewRecord, CarriesTheMeshesOfMeshShapes) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "prs_viewer_mesh_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream obj(dir / "tri.obj");  // a tetrahedron
    obj << "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  auto program = lang::CompileText((dir / "test.prs").string(),
                                   "class T:\n    shape: Mesh(\"tri.obj\")\nT at Vector3D(0, 0, 0)\n",
                                   options, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  const sampling::SampledScene scene = sampling::SampleScene(*program, 0, 0);
  const json record = json::parse(FormatViewRecord(scene));
  const std::string path = json::parse(record["line"].get<std::string>())["objects"][0]
                               ["properties"]["shape"]["path"];
  ASSERT_TRUE(record["meshes"].contains(path)) << record["meshes"].dump();
  EXPECT_EQ(record["meshes"][path]["vertices"].size(), 12u);
  EXPECT_EQ(record["meshes"][path]["triangles"].size(), 12u);
  const json of_line = json::parse(FormatViewRecordOfLine(record["line"].get<std::string>()));
  EXPECT_EQ(of_line["meshes"], record["meshes"]);
  std::filesystem::remove_all(dir);
  std::string line = record["line"];
  line.replace(line.find(path), path.size(), path + ".gone.obj");
  EXPECT_TRUE(json::parse(FormatViewRecordOfLine(line))["meshes"].empty());
}

TEST(Page, ServedPageLinksTheScriptAndStartsWhereAsked) {
  const std::string page = MakeServedPage({"a<b>.prs", 18446744073709551615u, 4});
  EXPECT_NE(page.find("<script src=\"viewer.js\"></script>"), std::string::npos);
  EXPECT_NE(page.find("a&lt;b&gt;.prs"), std::string::npos);
  EXPECT_EQ(page.find("@PRS_"), std::string::npos);
  // The seed is a string: JavaScript numbers would round 2^64 - 1.
  EXPECT_NE(page.find("\"seed\":\"18446744073709551615\""), std::string::npos);
}

TEST(Page, StandalonePageEmbedsScriptAndRecordsSafely) {
  auto program = Compile(kScenario);
  const std::vector<std::string> records = {
      FormatViewRecord(sampling::SampleScene(*program, 0, 5)),
      FormatViewRecord(sampling::SampleScene(*program, 0, 6))};
  const std::string page = MakeStandalonePage({"test.prs", 0, 5}, records);
  EXPECT_EQ(page.find("src=\"viewer.js\""), std::string::npos);
  EXPECT_GT(page.size(), ViewerScript().size());
  // The object's colour holds "</script><!--": escaped, it cannot end the element early, so
  // exactly the two real script elements close.
  size_t closings = 0;
  for (size_t at = page.find("</script>"); at != std::string::npos; at = page.find("</script>", at + 1))
    ++closings;
  EXPECT_EQ(closings, 2u);
  EXPECT_EQ(page.find("<!-- x"), std::string::npos);
  // The configuration parses back to the records.
  const size_t begin = page.find("application/json\">") + 18;
  const json config = json::parse(page.substr(begin, page.find("</script>", begin) - begin));
  EXPECT_EQ(config["mode"], "embedded");
  EXPECT_EQ(config["start"], "5");
  ASSERT_EQ(config["records"].size(), 2u);
  EXPECT_EQ(config["records"][1], json::parse(records[1]));
}

TEST(Assets, ScriptBundlesThreeAndTheTemplateHasItsSlots) {
  EXPECT_GT(ViewerScript().size(), 100'000u);  // three.js is inside, not fetched
  EXPECT_NE(ViewerScript().find("WebGLRenderer"), std::string_view::npos);
  for (const char* slot : {"@PRS_TITLE@", "@PRS_CONFIG@", "@PRS_SCRIPT@"})
    EXPECT_NE(PageTemplate().find(slot), std::string_view::npos) << slot;
}

// A server on a free port, listening on its own thread for the test's lifetime.
class ServerTest : public testing::Test {
 protected:
  void SetUp() override {
    program_ = Compile(kScenario);
    server_ = std::make_unique<ViewerServer>(*program_, sampling::SampleOptions{},
                                             PageInfo{"test.prs", 7, 0});
    port_ = server_->Bind(0);
    listener_ = std::thread([this] { server_->Listen(); });
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
  }
  void TearDown() override {
    while (listener_.joinable()) {  // Stop() only acts once Listen() runs
      server_->Stop();
      if (client_->Get("/")) continue;
      listener_.join();
    }
  }

  std::unique_ptr<lang::CompiledProgram> program_;
  std::unique_ptr<ViewerServer> server_;
  int port_ = 0;
  std::thread listener_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(ServerTest, ServesPageAndScript) {
  auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("\"seed\":\"7\""), std::string::npos);
  auto script = client_->Get("/viewer.js");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->body, std::string(ViewerScript()));
  EXPECT_NE(script->get_header_value("Content-Type").find("javascript"), std::string::npos);
}

TEST_F(ServerTest, SceneIsTheSampleLineAndViewWrapsIt) {
  const std::string expected =
      output::FormatSceneJson(sampling::SampleScene(*program_, 7, 3));
  auto scene = client_->Get("/scene?seed=7&index=3");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->status, 200);
  EXPECT_EQ(scene->body, expected);
  auto view = client_->Get("/view?seed=7&index=3");
  ASSERT_TRUE(view);
  EXPECT_EQ(json::parse(view->body)["line"], expected);
  auto other = client_->Get("/scene?seed=7&index=4");
  ASSERT_TRUE(other);
  EXPECT_NE(other->body, expected);
}

TEST_F(ServerTest, BadQueriesAreJsonErrorsNamingTheParameter) {
  auto missing = client_->Get("/scene?seed=1");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 400);
  EXPECT_NE(json::parse(missing->body)["error"]["message"].get<std::string>().find("'index'"),
            std::string::npos);
  auto negative = client_->Get("/view?seed=-1&index=0");
  ASSERT_TRUE(negative);
  EXPECT_EQ(negative->status, 400);
  EXPECT_NE(json::parse(negative->body)["error"]["message"].get<std::string>().find("got '-1'"),
            std::string::npos);
  auto unknown = client_->Get("/nothing");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  EXPECT_EQ(json::parse(unknown->body)["error"]["id"], "not-found");
}

TEST(ServerErrors, ImpossibleSceneIsLocatedError) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileText("bad.prs", "x = 1\nrequire x > 2\n", {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  sampling::SampleOptions options;
  options.max_attempts = 5;
  ViewerServer server(*program, options, {"bad.prs", 0, 0});
  const int port = server.Bind(0);
  std::thread listener([&] { server.Listen(); });
  httplib::Client client("127.0.0.1", port);
  auto reply = client.Get("/view?seed=0&index=0");
  while (true) {  // stop, as in ServerTest
    server.Stop();
    if (!client.Get("/")) break;
  }
  listener.join();
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->status, 422);
  const std::string message = json::parse(reply->body)["error"]["message"];
  EXPECT_NE(message.find("bad.prs:2:"), std::string::npos) << message;
}

TEST(ServerErrors, BindingATakenPortThrowsNamingIt) {
  auto program = Compile(kScenario);
  ViewerServer first(*program, {}, {"a", 0, 0});
  const int port = first.Bind(0);
  ViewerServer second(*program, {}, {"a", 0, 0});
  try {
    second.Bind(port);
    FAIL() << "bound a taken port";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(port)),
              std::string::npos);
  }
}

}  // namespace
}  // namespace prs::viewer
