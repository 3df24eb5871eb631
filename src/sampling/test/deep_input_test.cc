// Stack-depth regressions: programs whose syntax trees would be hundreds of thousands of levels
// deep (long flat chains of operators, calls, subscripts, prefixes) must give the located
// "too deeply" diagnostic, never a stack overflow, in every stage that walks the tree (parser,
// resolver, renderer, destructor); trees just under the limit must compile and evaluate on a
// worker thread's stack; runaway evaluation depth through user functions is a located error.
#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "sampling/batch.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

constexpr int kTerms = 100'000;

// `head` followed by `n` copies of `piece`.
std::string Repeat(const std::string& head, const std::string& piece, int n) {
  std::string out = head;
  out.reserve(head.size() + piece.size() * n);
  for (int i = 0; i < n; ++i) out += piece;
  return out;
}

struct Compiled {
  std::unique_ptr<lang::CompiledProgram> program;
  lang::DiagnosticEngine diagnostics;
  std::string rendered;
};

std::unique_ptr<Compiled> Compile(const std::string& text) {
  auto c = std::make_unique<Compiled>();
  c->program = lang::CompileText("deep.prs", text, {}, c->diagnostics);
  for (const lang::Diagnostic& d : c->diagnostics.diagnostics()) {
    c->rendered += lang::RenderDiagnostic(d, c->program->sources);
  }
  return c;
}

struct DeepCase {
  const char* name;
  std::string text;
};

// Each form of chain the grammar allows, 100,000 terms long, on one line.
std::vector<DeepCase> DeepCases() {
  return {
      {"sum", Repeat("x = 1", " + 1", kTerms)},
      {"product", Repeat("x = 1", " * 1", kTerms)},
      {"and", Repeat("x = True", " and True", kTerms)},
      {"or", Repeat("x = False", " or False", kTerms)},
      {"power", Repeat("x = 1", " ** 1", kTerms)},
      {"negation", Repeat("x = ", "-", kTerms) + "1"},
      {"not", Repeat("x = ", "not ", kTerms) + "True"},
      {"calls", Repeat("def f():\n    return f\nx = f", "()", kTerms)},
      {"method calls", Repeat("x = Vector3D(1, 0, 0)", ".normalized()", kTerms)},
      {"subscripts", Repeat("x = [0]", "[0]", kTerms)},
      {"attributes", Repeat("x = Vector3D(1, 0, 0)", ".x", kTerms)},
      {"relative to", Repeat("x = Vector3D(1, 0, 0)", " relative to Vector3D(0, 0, 0)", kTerms)},
      {"offset by", Repeat("x = Vector3D(1, 0, 0)", " offset by Vector3D(0, 0, 0)", kTerms)},
      {"conditionals", Repeat("x = 1", " if True else 1", kTerms)},
      {"brackets", Repeat("x = ", "(", kTerms) + "1" + std::string(kTerms, ')')},
      {"lists", Repeat("x = ", "[", kTerms) + "1" + std::string(kTerms, ']')},
      {"sum in a requirement", Repeat("require 1", " + 1", kTerms) + " > 0"},
      {"sum in a specifier", "class Box:\n    width: 1\n    length: 1\n    height: 1\nb = Box at " +
                                 Repeat("Vector3D(0, 0, 0)", " + Vector3D(0, 0, 0)", kTerms)},
  };
}

TEST(DeepInputTest, EveryLongChainIsALocatedErrorNotACrash) {
  for (const DeepCase& c : DeepCases()) {
    SCOPED_TRACE(c.name);
    auto compiled = Compile(c.text);
    ASSERT_TRUE(compiled->diagnostics.has_errors());
    EXPECT_NE(compiled->rendered.find("nested too deeply"), std::string::npos)
        << compiled->rendered.substr(0, 2000);
    EXPECT_NE(compiled->rendered.find("deep.prs:"), std::string::npos);
    // The renderer shows a window of the 100,000-term line, not all of it.
    EXPECT_LT(compiled->rendered.size(), 2000u) << compiled->rendered.substr(0, 2000);
  }
}

TEST(DeepInputTest, OneErrorThenTheNextStatementParses) {
  auto compiled = Compile(Repeat("x = 1", " + 1", kTerms) + "\ny = (\n");
  // Recovery at the next statement: the unclosed bracket on line 2 is reported too.
  EXPECT_EQ(compiled->diagnostics.error_count(), 2) << compiled->rendered.substr(0, 3000);
}

// A chain of `terms` operators of the given kind just under the parser's limit.
std::string ChainProgram(int terms) {
  return "class Box:\n    width: 0.1\n    length: 0.1\n    height: 0.1\n"
         "n = " +
         Repeat("Range(0, 1)", " + 1", terms) +
         "\n"
         "b = Box at Vector3D(n, 0, 0)\n";
}

TEST(DeepInputTest, TreesUnderTheLimitCompileAndSampleOnWorkerThreads) {
  auto compiled = Compile(ChainProgram(390));
  ASSERT_FALSE(compiled->diagnostics.has_errors()) << compiled->rendered.substr(0, 2000);
  const std::atomic<bool> never{false};
  BatchOptions options;
  options.count = 4;
  options.threads = 2;
  options.cancel = &never;
  std::vector<double> xs;
  SampleBatch(*compiled->program, options, {nullptr, [&](BatchScene&& s) {
                                              xs.push_back(s.sampled.scene.objects[0].p_WO.x());
                                            }});
  ASSERT_EQ(xs.size(), 4u);
  for (double x : xs) {
    EXPECT_GE(x, 390);
    EXPECT_LE(x, 391);
  }
  auto too_tall = Compile(ChainProgram(kTerms));
  EXPECT_TRUE(too_tall->diagnostics.has_errors());
}

TEST(DeepInputTest, DeepEvaluationThroughRecursiveCallsIsALimitError) {
  // Each call evaluates a tall tree before recursing: the call-depth limit times the tree
  // height must still fit a thread's stack, or be refused with a located error.
  const std::string text = "def f(k):\n    return " +
                           Repeat("(f(k - 1) if k > 0 else 0)", " + 1", 390) + "\nx = f(1000)\n";
  auto compiled = Compile(text);
  ASSERT_FALSE(compiled->diagnostics.has_errors()) << compiled->rendered.substr(0, 2000);
  std::string error;
  std::thread worker([&] {
    try {
      SampleScene(*compiled->program, 1, 0);
    } catch (const lang::ScenarioError& e) {
      error = e.what();
    }
  });
  worker.join();
  EXPECT_NE(error.find("nested deeper than 2000 levels"), std::string::npos)
      << error.substr(0, 2000);
}

}  // namespace
}  // namespace prs::sampling
