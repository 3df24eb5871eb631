// The campaign tests' directories: a fresh path per test under the system's temporary
// directory (removed first), named after the test and the process.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace prs::campaign {

/// TMP/prs_campaign_test_PID_TESTNAME, not existing.
inline std::string MakeTestCampaignDir() {
  const std::string dir = (std::filesystem::temp_directory_path() /
                           ("prs_campaign_test_" + std::to_string(::getpid()) + "_" +
                            testing::UnitTest::GetInstance()->current_test_info()->name()))
                              .string();
  std::filesystem::remove_all(dir);
  return dir;
}

}  // namespace prs::campaign
