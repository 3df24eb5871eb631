// End-to-end tests of the files `prs report -o` writes: the Markdown and its plot never share a
// path, every link in the report (the plot, the failures' saved scenes and pictures) opens from
// the report's own folder, a missing output folder is named as the user gave it, and the plot
// puts two features that are not functions of each other on its axes.
#include <random>
#include <regex>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

class ReportFilesTest : public PrsTest {
 protected:
  // Records of a cube c on a fixed table t (so c-t.x is c.x less a constant), failing when
  // x > 0.8 and y > 0.3. Each failure's scene is saved as `saved_dir`/scene_I.json (path as
  // recorded) with its picture, written under `root`.
  std::string WriteRecords(const fs::path& results, const fs::path& root,
                           const std::string& saved_dir, int n = 600) {
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    fs::create_directories(root / saved_dir);
    std::string lines;
    for (int i = 0; i < n; ++i) {
      const double x = uniform(gen), y = uniform(gen);
      const bool fails = x > 0.8 && y > 0.3;
      std::string line = "{\"index\": " + std::to_string(i) + ", \"outcome\": \"" +
                         (fails ? "no-path" : "success") +
                         "\", \"features\": {\"c.x\": " + std::to_string(x) +
                         ", \"c.y\": " + std::to_string(y) + ", \"t.x\": 0.4, \"t.y\": -0.25}";
      if (fails) {
        const std::string scene = saved_dir + "/scene_" + std::to_string(i);
        std::ofstream(root / (scene + ".json")) << "{}\n";
        std::ofstream(root / (scene + ".png")) << "png";
        line += ", \"saved_scene\": \"" + scene + ".json\"";
      }
      lines += line + "}\n";
    }
    fs::create_directories(results.parent_path());
    std::ofstream(results) << lines;
    return results.string();
  }

  // `prs ARGS...` run in `folder`.
  Result RunIn(const fs::path& folder, const std::vector<std::string>& args) {
    return Run(args, "", folder);
  }

  // Every link target of the Markdown, "](TARGET)", with %20 and the like decoded.
  static std::vector<std::string> Links(const std::string& md) {
    std::vector<std::string> links;
    const std::regex link(R"re(\]\(([^)\s]+)\))re");
    for (auto it = std::sregex_iterator(md.begin(), md.end(), link); it != std::sregex_iterator();
         ++it) {
      const std::string target = (*it)[1];
      std::string decoded;
      for (size_t k = 0; k < target.size(); ++k) {
        if (target[k] == '%' && k + 2 < target.size()) {
          decoded += static_cast<char>(std::stoi(target.substr(k + 1, 2), nullptr, 16));
          k += 2;
        } else {
          decoded += target[k];
        }
      }
      links.push_back(decoded);
    }
    return links;
  }

  // The name on an SVG axis ("x" or "y"), as written (with its unit).
  static std::string AxisName(const std::string& svg, const std::string& axis) {
    std::smatch name;
    const std::regex pattern("class=\"" + axis + "-name\"[^>]*>([^<]*)</text>");
    return std::regex_search(svg, name, pattern) ? std::string(name[1]) : "";
  }
};

TEST_F(ReportFilesTest, AnSvgReportPathIsRefusedNotOverwrittenByItsPlot) {
  const std::string results = WriteRecords(dir_ / "r.jsonl", dir_, "fails");
  for (const std::string name : {"report.svg", "REPORT.SVG"}) {
    const Result r = RunIn(dir_, {"report", results, "-o", name});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("'" + name + "' is where the plot would go"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(".md"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / name));
    EXPECT_EQ(r.err.find("plot: "), std::string::npos) << r.err;
  }
  // A report whose name ends otherwise gets its plot beside it, never on itself.
  Result r = RunIn(dir_, {"report", results, "-o", "report"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("written to report (plot: report.svg)"), std::string::npos) << r.err;
  EXPECT_EQ(ReadText(dir_ / "report").rfind("# Failure report", 0), 0u);
  EXPECT_EQ(ReadText(dir_ / "report.svg").rfind("<svg", 0), 0u);
  // -o - is stdout, as for the other commands: no file named "-", and no plot.
  r = RunIn(dir_, {"report", results, "-o", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("# Failure report", 0), 0u) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "-"));
}

TEST_F(ReportFilesTest, AMissingOutputFolderIsNamedAsGiven) {
  const std::string results = WriteRecords(dir_ / "r.jsonl", dir_, "fails");
  const Result r = RunIn(dir_, {"report", results, "-o", "no/such/report.md"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("the folder 'no/such' does not exist"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("create it"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(".partial"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no"));
  // A file where the folder should be.
  std::ofstream(dir_ / "plain") << "x";
  const Result file = RunIn(dir_, {"report", results, "-o", "plain/report.md"});
  EXPECT_EQ(file.exit_code, 1);
  EXPECT_NE(file.err.find("'plain' is not a folder"), std::string::npos) << file.err;
}

// The report in a folder two levels below where prs ran: its links climb back up to the saved
// scenes, and each opens from the report's folder.
TEST_F(ReportFilesTest, EveryLinkOpensFromTheReportsFolder) {
  const std::string results = WriteRecords(dir_ / "runs" / "r.jsonl", dir_, "failed scenes");
  fs::create_directories(dir_ / "reports" / "today");
  const Result r = RunIn(dir_, {"report", "runs/r.jsonl", "-o", "reports/today/report.md"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path folder = dir_ / "reports" / "today";
  const std::string md = ReadText(folder / "report.md");
  const std::vector<std::string> links = Links(md);
  int scenes = 0, pictures = 0, plots = 0;
  for (const std::string& link : links) {
    EXPECT_TRUE(fs::path(link).is_relative()) << link;
    EXPECT_TRUE(fs::exists(folder / link)) << link << " from " << folder << "\n" << md;
    scenes += link.find("../../failed scenes/scene_") == 0 && fs::path(link).extension() == ".json";
    pictures +=
        link.find("../../failed scenes/scene_") == 0 && fs::path(link).extension() == ".png";
    plots += link == "report.svg";
  }
  EXPECT_GE(scenes, 1) << md;
  EXPECT_EQ(scenes, pictures) << md;
  EXPECT_EQ(plots, 1) << md;
  EXPECT_NE(md.find("](../../failed%20scenes/scene_"), std::string::npos)
      << "a space breaks a link";
  EXPECT_NE(r.err.find("(plot: reports/today/report.svg)"), std::string::npos) << r.err;

  // Run from elsewhere, with the saved scenes recorded relative to the results' folder (prs test
  // ran there): the links still find them.
  const std::string moved = WriteRecords(dir_ / "lab" / "r.jsonl", dir_ / "lab", "fails");
  fs::create_directories(dir_ / "elsewhere");
  const Result away = RunIn(dir_ / "elsewhere", {"report", moved, "-o", "report.md"});
  ASSERT_EQ(away.exit_code, 0) << away.err;
  const std::string away_md = ReadText(dir_ / "elsewhere" / "report.md");
  int found = 0;
  for (const std::string& link : Links(away_md)) {
    EXPECT_TRUE(fs::exists(dir_ / "elsewhere" / link)) << link << "\n" << away_md;
    found += link.find("../lab/fails/scene_") == 0;
  }
  EXPECT_GE(found, 2) << away_md;
}

// A fixed table makes c-t.x equal to c.x less a constant: the plot must not draw one against
// the other (a diagonal line) but c.x against c.y, where the failures fill a corner.
TEST_F(ReportFilesTest, ThePlotsAxesAreTwoDifferentFeatures) {
  const std::string results = WriteRecords(dir_ / "r.jsonl", dir_, "fails", 1500);
  const Result r = RunIn(dir_, {"report", results, "-o", "report.md"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = ReadText(dir_ / "report.svg");
  const std::string x = AxisName(svg, "x"), y = AxisName(svg, "y");
  EXPECT_TRUE(x == "c.x (m)" || x == "c-t.x (m)") << x;
  EXPECT_TRUE(y == "c.y (m)" || y == "c-t.y (m)") << y;
  const std::string md = ReadText(dir_ / "report.md");
  const std::string x_name = x.substr(0, x.size() - 4), y_name = y.substr(0, y.size() - 4);
  EXPECT_NE(md.find("![" + y_name + " against " + x_name + "](report.svg)"), std::string::npos)
      << md;
}

}  // namespace
}  // namespace prs::cli
