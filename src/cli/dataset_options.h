// The options of `prs dataset` that say what its pictures and labels are (--camera, --size,
// --format, --label), shared with `prs campaign init --dataset`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "dataset/dataset.h"

namespace prs::cli {

struct DatasetPictureArgs {
  std::vector<std::string> cameras;
  std::string size;  // WxH; empty: each camera's aspect at 640 wide
  std::string format = "both";
  std::vector<std::string> labels;
  bool jpeg = false;
};

/// Adds --camera, --size, --format, --label and --jpeg to `command`.
void AddDatasetPictureOptions(CLI::App& command, DatasetPictureArgs& args);

/// Fills the cameras, size, formats and labels of `options`; returns the usage error to print
/// ("--size: ..."), or "" when all is well.
std::string ReadDatasetPictureArgs(const DatasetPictureArgs& args,
                                   dataset::DatasetOptions& options);

/// The error for scenes without a camera object (`where`: "scene 0 of seed 1").
std::string DescribeNoCamera(const std::string& where);

}  // namespace prs::cli
