// Tests for the parser: the paper's Figure 1, a model file, each statement form and the
// ProbRobScene operators, checked through a compact S-expression dump of the AST.
#include "lang/parser.h"

#include <gtest/gtest.h>

#include "lang/test/ast_dump.h"

namespace prs::lang {
namespace {

using testing::Dump;

const std::vector<std::string> kModelClasses = {"Table", "Robot", "Tray", "Cube", "Camera",
                                                "Cup",   "Plate", "Chair", "Robot"};

struct ParseResult {
  SourceManager sources;
  DiagnosticEngine diags;
  Module module;
  std::vector<std::string> imported;  // modules import_classes was asked for
};

std::unique_ptr<ParseResult> ParseText(const std::string& text) {
  auto r = std::make_unique<ParseResult>();
  FileId f = r->sources.AddFile("test.prs", text);
  ParseOptions options;
  options.import_classes = [&r = *r](const std::string& module, SourceSpan) {
    r.imported.push_back(module);
    return std::optional<std::vector<std::string>>(kModelClasses);
  };
  r->module = Parse(f, r->sources, r->diags, options);
  return r;
}

std::string Errors(const ParseResult& r) {
  std::string out;
  for (const Diagnostic& d : r.diags.diagnostics()) out += RenderDiagnostic(d, r.sources);
  return out;
}

// Parses `text` (after `from model import *`), expects no errors, and returns the dump of
// every statement but the import, one per line.
std::string DumpProgram(const std::string& text) {
  auto r = ParseText("from model import *\n" + text);
  EXPECT_EQ(Errors(*r), "");
  std::string out;
  for (size_t i = 1; i < r->module.body.size(); ++i) {
    out += (i > 1 ? "\n" : "") + Dump(*r->module.body[i]);
  }
  return out;
}

constexpr const char* kFigure1 =
    "t = Table on V3D(0,0,0)\n"
    "r1 = Robot on (top back t) - V3D(0.4, 0, 0)\n"
    "r2 = Robot on (top back t) + V3D(0.4, 0, 0)\n"
    "\n"
    "tr_1 = Tray completely on t, \n"
    "            ahead of r1,\n"
    "            left of t\n"
    "            \n"
    "tr_2 = Tray completely on t,\n"
    "            ahead of r2,\n"
    "            right of t\n"
    "\n"
    "Cube completely on tr_1\n"
    "\n"
    "Camera at V3D((-0.1, 0.1),\n"
    "              (-0.1, 0.1), \n"
    "              (1.9, 2.1)),\n"
    "       facing V3D(0, 0, -1)\n";

// A docstring is dropped wherever it stands among `;`-separated statements (this crashed).
TEST(ParserTest, DocstringBeforeSemicolonIsDropped) {
  auto r = ParseText("\"doc\"; x = 1\nif True:\n    \"doc\"; y = 2; \"more\"\n");
  EXPECT_EQ(Errors(*r), "");
  ASSERT_EQ(r->module.body.size(), 2u);
  for (const StmtPtr& stmt : r->module.body) EXPECT_NE(stmt, nullptr);
  const auto& branch = std::get<IfStmt>(r->module.body[1]->node).branches[0].second;
  ASSERT_EQ(branch.size(), 1u);
  EXPECT_NE(branch[0], nullptr);
}

TEST(ParserTest, PaperFigure1) {
  auto r = ParseText(std::string("from model import *\n") + kFigure1);
  ASSERT_EQ(Errors(*r), "");
  EXPECT_EQ(r->imported, std::vector<std::string>{"model"});
  ASSERT_EQ(r->module.body.size(), 8u);  // the import and Figure 1's 7 statements
  const auto& body = r->module.body;
  EXPECT_EQ(Dump(*body[1]), "(= t (create Table (on (call V3D 0 0 0))))");
  EXPECT_EQ(Dump(*body[2]), "(= r1 (create Robot (on (- (side top back t) (call V3D 0.4 0 0)))))");
  EXPECT_EQ(Dump(*body[3]), "(= r2 (create Robot (on (+ (side top back t) (call V3D 0.4 0 0)))))");
  EXPECT_EQ(Dump(*body[4]),
            "(= tr_1 (create Tray (completely on t) (ahead of r1) (left of t)))");
  EXPECT_EQ(Dump(*body[5]),
            "(= tr_2 (create Tray (completely on t) (ahead of r2) (right of t)))");
  EXPECT_EQ(Dump(*body[6]), "(expr (create Cube (completely on tr_1)))");
  EXPECT_EQ(Dump(*body[7]),
            "(expr (create Camera (at (call V3D (tuple (neg 0.1) 0.1) (tuple (neg 0.1) 0.1) "
            "(tuple 1.9 2.1))) (facing (call V3D 0 0 (neg 1)))))");

  // Node shapes, checked directly as well as through the dump.
  const auto& assign = std::get<AssignStmt>(body[4]->node);
  const auto& create = std::get<CreateObject>(assign.value->node);
  ASSERT_EQ(create.specifiers.size(), 3u);
  EXPECT_EQ(create.specifiers[0].kind, SpecifierKind::kCompletelyOn);
  EXPECT_EQ(create.specifiers[1].kind, SpecifierKind::kAheadOf);
  EXPECT_EQ(create.specifiers[2].kind, SpecifierKind::kLeftOf);
  EXPECT_EQ(create.specifiers[1].distance, nullptr);
  const auto& camera = std::get<CreateObject>(std::get<ExprStmt>(body[7]->node).expr->node);
  const auto& v3d = std::get<CallExpr>(camera.specifiers[0].target->node);
  ASSERT_EQ(v3d.args.size(), 3u);
  EXPECT_EQ(std::get<TupleExpr>(v3d.args[2].value->node).elements.size(), 2u);
  EXPECT_EQ(camera.specifiers[1].kind, SpecifierKind::kFacing);
}

TEST(ParserTest, Figure1SpansPointAtTheSource) {
  auto r = ParseText(std::string("from model import *\n") + kFigure1);
  const auto& assign = std::get<AssignStmt>(r->module.body[4]->node);
  const auto& create = std::get<CreateObject>(assign.value->node);
  std::string_view text = r->sources.text(0);
  auto slice = [&](SourceSpan s) { return text.substr(s.begin, s.end - s.begin); };
  EXPECT_EQ(slice(assign.targets[0].span), "tr_1");
  EXPECT_EQ(slice(create.class_name.span), "Tray");
  EXPECT_EQ(slice(create.specifiers[0].span), "completely on t");
  EXPECT_EQ(slice(create.specifiers[2].span), "left of t");
  EXPECT_EQ(slice(r->module.body[6]->span), "Cube completely on tr_1");
  const auto& side = std::get<SidePointExpr>(
      std::get<BinaryExpr>(std::get<CreateObject>(
          std::get<AssignStmt>(r->module.body[2]->node).value->node).specifiers[0].target->node)
          .lhs->node);
  EXPECT_EQ(slice(side.keyword_span), "top back");
}

TEST(ParserTest, ModelFile) {
  auto r = ParseText(R"("""Models for the table-cube world."""
import math
width = 3
length = 3
height = 3
workspace = Cuboid(Vector3D(0, 0, height / 2.0), Vector3D(0, 0, 0), width, length, height)
floor = Rectangle3D(width, length, Vector3D(0, 0, 0), Vector3D(0, 0, 0))
class Table:
    width: 1.8
    length: 0.8
    height: 0.8
    color: "0.5"
    model_name: 'table'
class Cube(Object):
    width: 0.05
    length: self.width
    height: 0.05
)");
  ASSERT_EQ(Errors(*r), "");
  const auto& body = r->module.body;
  ASSERT_EQ(body.size(), 8u);  // the docstring is dropped
  EXPECT_EQ(Dump(*body[0]), "(import math)");
  EXPECT_EQ(Dump(*body[1]), "(= width 3)");
  EXPECT_EQ(Dump(*body[4]),
            "(= workspace (call Cuboid (call Vector3D 0 0 (/ height 2)) (call Vector3D 0 0 0) "
            "width length height))");
  EXPECT_EQ(Dump(*body[6]),
            "(class Table width:1.8 length:0.8 height:0.8 color:\"0.5\" model_name:\"table\")");
  EXPECT_EQ(Dump(*body[7]), "(class Cube(Object) width:0.05 length:(. self width) height:0.05)");
}

TEST(ParserTest, ClassesDefinedInTheFileAreKnownAfterwards) {
  auto r = ParseText("class Box:\n    width: 1\nb = Box on t\nc = Box\n");
  ASSERT_EQ(Errors(*r), "");
  EXPECT_EQ(Dump(*r->module.body[1]), "(= b (create Box (on t)))");
  EXPECT_EQ(Dump(*r->module.body[2]), "(= c (class Box))");
}

TEST(ParserTest, CreationExamples) {
  EXPECT_EQ(DumpProgram("r = Robot on (top back table).position - Vector3D(0.4, 0, 0), "
                        "with color \"0.5\"\n"),
            "(= r (create Robot (on (- (. (side top back table) position) "
            "(call Vector3D 0.4 0 0))) (with color \"0.5\")))");
  EXPECT_EQ(DumpProgram("Camera at Vector3D(table.x + (-0.1, 0.1), table.y + (-0.1, 0.1), "
                        "(1.9, 2.1))\n"),
            "(expr (create Camera (at (call Vector3D (+ (. table x) (tuple (neg 0.1) 0.1)) "
            "(+ (. table y) (tuple (neg 0.1) 0.1)) (tuple 1.9 2.1)))))");
  EXPECT_EQ(DumpProgram("cup_2 = Cup completely on table_1, aligned with cup_1 by \"y\"\n"),
            "(= cup_2 (create Cup (completely on table_1) (aligned with cup_1 axis y)))");
  EXPECT_EQ(DumpProgram("c2 = Cube right of c1 by 0.2, above c1 by 0.2, ahead of c1 by 0.1\n"),
            "(= c2 (create Cube (right of c1 by 0.2) (above c1 by 0.2) (ahead of c1 by 0.1)))");
  EXPECT_EQ(DumpProgram("c1 = Cube below Vector3D(0.0, 0.0, 2.5), with width 0.3\n"),
            "(= c1 (create Cube (below (call Vector3D 0 0 2.5)) (with width 0.3)))");
  EXPECT_EQ(DumpProgram("plate = Plate on Vector3D(belt.x, belt.y - 0.75, belt.z + 0.081)\n"),
            "(= plate (create Plate (on (call Vector3D (. belt x) (- (. belt y) 0.75) "
            "(+ (. belt z) 0.081)))))");
  EXPECT_EQ(DumpProgram("cube_2 = Cube on cube_1\n"), "(= cube_2 (create Cube (on cube_1)))");
  EXPECT_EQ(DumpProgram("chair = Chair facing Vector3D(1, 0, 0)\n"),
            "(= chair (create Chair (facing (call Vector3D 1 0 0))))");
}

TEST(ParserTest, EverySpecifierForm) {
  EXPECT_EQ(DumpProgram("Cube in r, at p, behind a by 1, below b, aligned with c on x, "
                        "aligned with d along z, beyond e by 2 from f, facing toward g, "
                        "facing towards h, with yaw 0.5\n"),
            "(expr (create Cube (in r) (at p) (behind a by 1) (below b) "
            "(aligned with c axis x) (aligned with d axis z) (beyond e by 2 from f) "
            "(facing toward g) (facing toward h) (with yaw 0.5)))");
}

TEST(ParserTest, SpecifierListEndsAtACommaThatStartsNoSpecifier) {
  EXPECT_EQ(DumpProgram("f(Cube on t, 3, Tray at p, with_x=1)\n"),
            "(expr (call f (create Cube (on t)) 3 (create Tray (at p)) with_x=1))");
  EXPECT_EQ(DumpProgram("x = Uniform(Cube, Tray)\n"), "(= x (call Uniform (class Cube) (class Tray)))");
}

TEST(ParserTest, ClassInIsACreationButNameInIsMembership) {
  EXPECT_EQ(DumpProgram("a = Cube in r\nb = x in lst\nc = x not in lst\n"),
            "(= a (create Cube (in r)))\n(= b (in x lst))\n(= c (not in x lst))");
}

TEST(ParserTest, Requirements) {
  EXPECT_EQ(DumpProgram("require (right tr_1).x + 0.2 < table.x\n"),
            "(require null (< (+ (. (side right tr_1) x) 0.2) (. table x)))");
  EXPECT_EQ(DumpProgram("require[0.5] c.x > 0\n"), "(require 0.5 (> (. c x) 0))");
  // `settled` followed by an expression is the keyword; alone, or before an operator, a name.
  EXPECT_EQ(DumpProgram("require settled c.z > 0.5\n"), "(require settled null (> (. c z) 0.5))");
  EXPECT_EQ(DumpProgram("require[0.5] settled (c.z > 0.5)\n"),
            "(require settled 0.5 (> (. c z) 0.5))");
  EXPECT_EQ(DumpProgram("require settled\n"), "(require null settled)");
  EXPECT_EQ(DumpProgram("require settled and ok\n"), "(require null (and settled ok))");
}

TEST(ParserTest, ForLoopWithCreation) {
  EXPECT_EQ(DumpProgram("for i in range(DiscreteRange(1, 4)):\n    Cube on table\n"),
            "(for i (call range (call DiscreteRange 1 4)) [(expr (create Cube (on table)))])");
  EXPECT_EQ(DumpProgram("for a, b in pairs:\n    pass\n"), "(for a,b pairs [(pass)])");
}

TEST(ParserTest, ParamsFunctionsAndControlFlow) {
  EXPECT_EQ(DumpProgram("param n = 3, m = 'a'\n"), "(param n=3 m=\"a\")");
  EXPECT_EQ(DumpProgram("def f(a, b=2):\n    return a + b\n"),
            "(def f (a b=2) [(return (+ a b))])");
  EXPECT_EQ(DumpProgram("def g():\n    return\n"), "(def g () [(return null)])");
  EXPECT_EQ(DumpProgram("if a: x = 1\nelif b:\n    pass\nelse:\n    y = 2\n"),
            "(if a [(= x 1)] b [(pass)] else [(= y 2)])");
  EXPECT_EQ(DumpProgram("while n > 0:\n    n -= 1\n    if n == 2:\n        break\n"
                        "    continue\n"),
            "(while (> n 0) [(-= n 1) (if (== n 2) [(break)]) (continue)])");
}

TEST(ParserTest, AssignmentForms) {
  EXPECT_EQ(DumpProgram("a, b = 1, 2\n(c, d) = p\nf = (1,)\ng = ()\nh = (1)\nx *= 2\n"),
            "(= a,b unpack (tuple 1 2))\n(= c,d unpack p)\n(= f (tuple 1))\n(= g (tuple))\n"
            "(= h 1)\n(*= x 2)");
}

TEST(ParserTest, TrailingCommaAtTopLevelContinuesTheStatement) {
  // The Figure 1 rule: `e = 1,` continues onto the next line, unlike in Python.
  auto r = ParseText("e = 1,\n2\n");
  ASSERT_EQ(Errors(*r), "");
  EXPECT_EQ(Dump(*r->module.body[0]), "(= e (tuple 1 2))");
}

TEST(ParserTest, Precedence) {
  EXPECT_EQ(DumpProgram("x = -2 ** 2 ** 3\n"), "(= x (neg (** 2 (** 2 3))))");
  EXPECT_EQ(DumpProgram("x = 1 + 2 * 3 - 4 // 5 % 6 / 7\n"),
            "(= x (- (+ 1 (* 2 3)) (/ (% (// 4 5) 6) 7)))");
  EXPECT_EQ(DumpProgram("x = not a == b and c or d\n"),
            "(= x (or (and (not (== a b)) c) d))");
  EXPECT_EQ(DumpProgram("x = a if c else b if d else e\n"),
            "(= x (if c a (if d b e)))");
  EXPECT_EQ(DumpProgram("x = a + b relative to c * d offset by e\n"),
            "(= x (offset (relative (+ a b) (* c d)) e))");
  EXPECT_EQ(DumpProgram("x = a is not None and b is c\n"),
            "(= x (and (is not a None) (is b c)))");
}

TEST(ParserTest, ComparisonChainsBecomeCompareChain) {
  auto r = ParseText("y = 0 < x <= 1 != z\n");
  ASSERT_EQ(Errors(*r), "");
  EXPECT_EQ(Dump(*r->module.body[0]), "(= y (chain 0 < x <= 1 != z))");
  const auto& chain = std::get<CompareChain>(std::get<AssignStmt>(r->module.body[0]->node).value->node);
  EXPECT_EQ(chain.operands.size(), 4u);
  EXPECT_EQ(chain.op_spans.size(), 3u);
}

TEST(ParserTest, PostfixAndLiterals) {
  EXPECT_EQ(DumpProgram("x = f(1, k=2)(3).a[0].b\n"),
            "(= x (. (index (. (call (call f 1 k=2) 3) a) 0) b))");
  EXPECT_EQ(DumpProgram("x = 'ab' \"cd\"\n"), "(= x \"abcd\")");
  EXPECT_EQ(DumpProgram("x = [1, [True, None], {'a': 1, 2: False}]\n"),
            "(= x (list 1 (list True None) (dict \"a\":1 2:False)))");
  EXPECT_EQ(DumpProgram("x = {}\ny = []\n"), "(= x (dict))\n(= y (list))");
  EXPECT_EQ(DumpProgram("x = Discrete({Cube: 0.5, Tray: 0.5})\n"),
            "(= x (call Discrete (dict (class Cube):0.5 (class Tray):0.5)))");
}

TEST(ParserTest, SidePoints) {
  EXPECT_EQ(DumpProgram("a = top back of t\nb = (top back t)\nc = front of x.y\n"
                        "d = back left t\ne = bottom of (t)\nf = top front of t\n"),
            "(= a (side top back t))\n(= b (side top back t))\n(= c (side front (. x y)))\n"
            "(= d (side back left t))\n(= e (side bottom t))\n(= f (side top front t))");
}

TEST(ParserTest, SideWordsAreStillNames) {
  EXPECT_EQ(DumpProgram("top = 3\nx = top\ny = top + left\nz = f(front, back)\n"
                        "w = right.x\n"),
            "(= top 3)\n(= x top)\n(= y (+ top left))\n(= z (call f front back))\n"
            "(= w (. right x))");
}

TEST(ParserTest, DistanceFrom) {
  EXPECT_EQ(DumpProgram("d = distance from a + b to c.position * 2\ndistance = 3\n"),
            "(= d (distance (+ a b) (* (. c position) 2)))\n(= distance 3)");
}

TEST(ParserTest, ImportHookNulloptSuppressesUnknownClassErrors) {
  auto r = std::make_unique<ParseResult>();
  FileId f = r->sources.AddFile("t.prs", "from missing import *\nc = Widget on t\n");
  ParseOptions options;
  options.import_classes = [](const std::string&, SourceSpan) {
    return std::optional<std::vector<std::string>>();
  };
  r->module = Parse(f, r->sources, r->diags, options);
  EXPECT_EQ(Errors(*r), "");
  EXPECT_EQ(Dump(*r->module.body[1]), "(= c (create Widget (on t)))");
}

TEST(ParserTest, RecoveryKeepsTheGoodStatements) {
  auto r = ParseText("a = 1\nb = 2 +\nc = 3\nif x\n    d = 4\ne = 5\n");
  EXPECT_EQ(r->diags.error_count(), 2u);
  ASSERT_EQ(r->module.body.size(), 3u);
  EXPECT_EQ(Dump(*r->module.body[2]), "(= e 5)");
}

TEST(ParserTest, ErrorsInsideBlocksRecoverWithinTheBlock) {
  auto r = ParseText("def f():\n    x = )\n    return 1\ny = 2\n");
  EXPECT_EQ(r->diags.error_count(), 1u);
  ASSERT_EQ(r->module.body.size(), 2u);
  EXPECT_EQ(Dump(*r->module.body[0]), "(def f () [(return 1)])");
}

}  // namespace
}  // namespace prs::lang
