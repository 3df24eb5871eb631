// The harness of the end-to-end tests of the built `prs` binary: a fresh directory per test,
// and Run(), which runs `prs ARGS...` and captures its exit code, stdout and stderr.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace prs::cli {

namespace fs = std::filesystem;

inline fs::path RepoRoot() {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  return dir ? fs::path(dir) : fs::path(PRS_DEFAULT_SOURCE_DIR);
}

inline std::string Example(const std::string& name) {
  return (RepoRoot() / "examples" / name).string();
}

inline std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::string Quote(const std::string& arg) {
  std::string quoted = "'";
  for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// A fresh directory per test, with the scenario files the test writes into it.
class PrsTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("prs_cli_test_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }

  // Runs `prs ARGS...` through the shell, capturing stdout and stderr; `env` is put before it
  // ("PATH=/x NAME=value"), and it runs in `folder` when one is given.
  Result Run(const std::vector<std::string>& args, const std::string& env = "",
             const fs::path& folder = {}) {
    std::string command = folder.empty() ? "" : "cd " + Quote(folder.string()) + " && ";
    command += (env.empty() ? "" : "env " + env + " ") + Quote(PRS_BINARY);
    for (const std::string& arg : args) command.append(" ").append(Quote(arg));
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    command.append(" >").append(Quote(out.string())).append(" 2>").append(Quote(err.string()));
    const int status = std::system(command.c_str());
    Result result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = ReadText(out);
    result.err = ReadText(err);
    return result;
  }

  // Runs `prs ARGS... --threads T` for T = 1 and 2, checks that both succeed with the same
  // output, and returns the first's.
  std::string RunOnOneAndTwoThreads(const std::vector<std::string>& args) {
    std::string outputs[2];
    for (const int threads : {1, 2}) {
      std::vector<std::string> with = args;
      with.insert(with.end(), {"--threads", std::to_string(threads)});
      const Result r = Run(with);
      EXPECT_EQ(r.exit_code, 0) << r.err;
      outputs[threads - 1] = r.out;
    }
    EXPECT_EQ(outputs[0], outputs[1]);
    return outputs[0];
  }

  fs::path dir_;
};

}  // namespace prs::cli
