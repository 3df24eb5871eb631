// The catalogue of bad programs that get past the parser: each tests/lang/bad/run_*.prs is
// compiled (imports from examples/) and, if it compiles, sampled; the rendered diagnostic
// must equal the .expected file next to it, byte for byte: position, caret and wording.
// Run with PRS_UPDATE_EXPECTED=1 to rewrite the .expected files after a deliberate change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sampling/sampler.h"

namespace prs::sampling {
namespace {

namespace fs = std::filesystem;

fs::path RepoRoot() {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  return dir ? fs::path(dir) : fs::path(PRS_DEFAULT_SOURCE_DIR);
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> BadProgramNames() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(RepoRoot() / "tests/lang/bad")) {
    const std::string name = entry.path().stem().string();
    if (name.rfind("run_", 0) == 0 && entry.path().extension() == ".prs") names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Compiles and samples one program; returns every diagnostic, rendered, and their ids.
std::string CompileAndSample(const std::string& relative_path, std::vector<std::string>* ids) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {"examples"};
  auto program = lang::CompileFile(relative_path, options, diagnostics);
  std::string rendered;
  for (const lang::Diagnostic& d : diagnostics.diagnostics()) {
    ids->push_back(d.id);
    rendered += lang::RenderDiagnostic(d, program->sources);
  }
  if (diagnostics.has_errors()) return rendered;
  SampleOptions sample_options;
  sample_options.max_attempts = 200;
  try {
    SampleScene(*program, /*seed=*/1, /*index=*/0, sample_options);
    ADD_FAILURE() << relative_path << " compiled and sampled without any error";
  } catch (const lang::ScenarioError& error) {
    ids->push_back(error.diagnostic().id);
    rendered += lang::RenderDiagnostic(error.diagnostic(), program->sources);
  }
  return rendered;
}

class BadProgramTest : public testing::TestWithParam<std::string> {};

TEST_P(BadProgramTest, GivesTheExpectedDiagnostic) {
  // Paths in messages are relative to the repository root, as a user running from it sees.
  fs::current_path(RepoRoot());
  const std::string program = "tests/lang/bad/" + GetParam() + ".prs";
  const fs::path expected_path = RepoRoot() / ("tests/lang/bad/" + GetParam() + ".expected");
  std::vector<std::string> ids;
  const std::string rendered = CompileAndSample(program, &ids);
  ASSERT_FALSE(ids.empty()) << program << " produced no diagnostic";
  for (const std::string& id : ids) {
    EXPECT_TRUE(lang::IsKnownDiagnosticId(id)) << "id missing from the catalogue: " << id;
  }
  if (std::getenv("PRS_UPDATE_EXPECTED")) {
    std::ofstream(expected_path, std::ios::binary) << rendered;
  }
  ASSERT_TRUE(fs::exists(expected_path)) << "missing " << expected_path;
  EXPECT_EQ(rendered, ReadText(expected_path));
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadProgramTest, testing::ValuesIn(BadProgramNames()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

// Together with the parser's catalogue (parse_*.prs), the issue asks for at least 40.
TEST(BadProgramCatalogueTest, HasAtLeastFortyPrograms) {
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(RepoRoot() / "tests/lang/bad")) {
    if (entry.path().extension() == ".prs" && entry.path().stem().string().rfind("mod_", 0) != 0) {
      ++count;
    }
  }
  EXPECT_GE(count, 40u);
}

}  // namespace
}  // namespace prs::sampling
