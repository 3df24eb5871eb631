// Reading the JSON Lines files `prs` writes (records, scenes), for the end-to-end tests.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {

/// Every line of `path` as JSON, each expected to be an object.
inline std::vector<nlohmann::json> ReadRecords(const fs::path& path) {
  std::vector<nlohmann::json> records;
  std::stringstream lines(ReadText(path));
  for (std::string line; std::getline(lines, line);) {
    records.push_back(nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false));
    EXPECT_TRUE(records.back().is_object()) << "not a JSON record: " << line;
  }
  return records;
}

}  // namespace prs::cli
