// Reading and atomically writing the small files of a campaign directory (campaign.json,
// sidecars, submission records). Internal to src/campaign.
#pragma once

#include <string>

#include "output/line_writer.h"

namespace prs::campaign {

/// The whole file; *ok is false when it cannot be opened (then the text is empty).
std::string ReadFileText(const std::string& path, bool* ok);

/// Writes a file whole or not at all (output/line_writer.h).
using output::WriteFileAtomically;

}  // namespace prs::campaign
