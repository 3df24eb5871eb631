// End-to-end tests of `prs view` as a program: bad flags (exit 2), scenario errors (exit 1,
// located), --html pages holding exactly `prs sample`'s scenes, and the server: its URL on
// stdout, its scene endpoint, a port already in use, and a clean stop on SIGTERM.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <httplib.h>

namespace prs::viewer {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string TableCube() {
  const char* root = std::getenv("PRS_SOURCE_DIR");
  return (fs::path(root ? root : PRS_DEFAULT_SOURCE_DIR) / "examples" / "table_cube.prs").string();
}

// A `prs` process: stdout into a pipe (to read the URL) or a file, stderr into a file.
class PrsProcess {
 public:
  PrsProcess(const std::vector<std::string>& args, const fs::path& dir, bool pipe_stdout)
      : err_path_(dir / ("stderr" + std::to_string(++count_) + ".txt")),
        out_path_(dir / ("stdout" + std::to_string(count_) + ".txt")) {
    int fds[2] = {-1, -1};
    if (pipe_stdout && ::pipe(fds) != 0) throw std::runtime_error("pipe failed");
    pid_ = ::fork();
    if (pid_ == 0) Exec(args, pipe_stdout ? fds[1] : -1);
    if (pipe_stdout) {
      ::close(fds[1]);
      out_fd_ = fds[0];
    }
  }
  ~PrsProcess() {
    if (pid_ > 0 && exit_code_ < 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) ::close(out_fd_);
  }

  // The first line on the piped stdout (the viewer's URL).
  std::string ReadLine() {
    std::string line;
    char c = 0;
    while (::read(out_fd_, &c, 1) == 1 && c != '\n') line += c;
    return line;
  }
  int Wait() {
    if (exit_code_ >= 0) return exit_code_;
    int status = 0;
    ::waitpid(pid_, &status, 0);
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return exit_code_;
  }
  void Signal(int signal_number) { ::kill(pid_, signal_number); }
  std::string err() const { return Slurp(err_path_); }
  std::string out() const { return Slurp(out_path_); }

 private:
  [[noreturn]] void Exec(const std::vector<std::string>& args, int out_fd) {
    const int err = ::open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int out = out_fd >= 0 ? out_fd : ::open(out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, STDERR_FILENO);
    ::dup2(out, STDOUT_FILENO);
    std::vector<char*> argv = {const_cast<char*>(PRS_BINARY)};
    for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    ::execv(PRS_BINARY, argv.data());
    ::_exit(127);
  }

  static inline int count_ = 0;  // each process gets its own output files
  fs::path err_path_, out_path_;
  pid_t pid_ = -1;
  int out_fd_ = -1;
  int exit_code_ = -1;
};

class ViewCliTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("prs_view_cli_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `prs ARGS...` to the end; stdout and stderr are in out() and err().
  std::unique_ptr<PrsProcess> Run(const std::vector<std::string>& args) {
    auto process = std::make_unique<PrsProcess>(args, dir_, false);
    process->Wait();
    return process;
  }

  fs::path dir_;
};

TEST_F(ViewCliTest, BadFlagsAreUsageErrorsNamingTheFlag) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"view", TableCube(), "-n", "3"}, "--html"},
      {{"view", TableCube(), "--port", "70000"}, "expects an integer from 0 to 65535, got '70000'"},
      {{"view", TableCube(), "--html", "x.html", "--port", "8000"}, "excludes"},
      {{"view", TableCube(), "--html", "x.html", "-n", "0"}, "expects an integer from 1"},
      {{"view", TableCube(), "-s", "-1"}, "got '-1'"},
      {{"view"}, "FILE"},
  };
  for (const auto& [args, message] : cases) {
    auto process = Run(args);
    EXPECT_EQ(process->Wait(), 2) << args.back();
    EXPECT_NE(process->err().find(message), std::string::npos) << process->err();
    EXPECT_NE(process->err().find("prs: error:"), std::string::npos) << process->err();
  }
}

TEST_F(ViewCliTest, ScenarioErrorIsLocatedAndExitsOne) {
  std::ofstream(dir_ / "bad.prs") << "x = 1\ny = x +\n";
  auto process = Run({"view", (dir_ / "bad.prs").string()});
  EXPECT_EQ(process->Wait(), 1);
  EXPECT_NE(process->err().find("bad.prs:2:"), std::string::npos) << process->err();
  EXPECT_EQ(process->out(), "");  // no URL: nothing is served
}

TEST_F(ViewCliTest, HtmlPageHoldsTheSampledScenes) {
  const fs::path page = dir_ / "scenes.html";
  auto view = Run({"view", TableCube(), "-s", "3", "--start", "2", "--html", page.string(), "-n", "2"});
  ASSERT_EQ(view->Wait(), 0) << view->err();
  auto sample = Run({"sample", TableCube(), "-s", "3", "--start", "2", "-n", "2", "-q"});
  ASSERT_EQ(sample->Wait(), 0);
  const std::string html = Slurp(page);
  EXPECT_EQ(html.find("viewer.js"), std::string::npos);  // the script is inline
  const std::string marker = "type=\"application/json\">";
  const size_t begin = html.find(marker) + marker.size();
  const json config = json::parse(html.substr(begin, html.find("</script>", begin) - begin));
  std::istringstream lines(sample->out());
  std::string line;
  for (const json& record : config["records"]) {
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(record["line"], line);
  }
  EXPECT_EQ(config["records"].size(), 2u);
  EXPECT_EQ(config["start"], "2");
}

TEST_F(ViewCliTest, HtmlSamplingFailureWritesNothing) {
  std::ofstream(dir_ / "never.prs") << "x = Range(0, 1)\nrequire x > 2\n";
  const fs::path page = dir_ / "never.html";
  auto process = Run({"view", (dir_ / "never.prs").string(), "--html", page.string(),
                      "--max-attempts", "20"});
  EXPECT_EQ(process->Wait(), 3) << process->err();
  EXPECT_NE(process->err().find("never.prs:2:"), std::string::npos) << process->err();
  EXPECT_FALSE(fs::exists(page));
}

TEST_F(ViewCliTest, ServesScenesOnLoopbackAndStopsOnSigterm) {
  PrsProcess server({"view", TableCube(), "-s", "5"}, dir_, true);
  const std::string url = server.ReadLine();
  ASSERT_EQ(url.rfind("http://127.0.0.1:", 0), 0u) << url;
  const int port = std::stoi(url.substr(17));
  httplib::Client client("127.0.0.1", port);
  auto scene = client.Get("/scene?seed=5&index=1");
  ASSERT_TRUE(scene);
  auto sample = Run({"sample", TableCube(), "-s", "5", "--start", "1", "-q"});
  EXPECT_EQ(scene->body + "\n", sample->out());
  auto bad = client.Get("/scene?seed=5&index=a");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  // A second viewer on the same port is refused, with the address in the message.
  auto second = Run({"view", TableCube(), "--port", std::to_string(port)});
  EXPECT_EQ(second->Wait(), 1);
  EXPECT_NE(second->err().find("127.0.0.1:" + std::to_string(port)), std::string::npos);
  server.Signal(SIGTERM);
  EXPECT_EQ(server.Wait(), 0);
  EXPECT_NE(server.err().find("viewer stopped"), std::string::npos) << server.err();
}

}  // namespace
}  // namespace prs::viewer
