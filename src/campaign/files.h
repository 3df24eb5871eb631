// Reading and atomically writing the small files of a campaign directory (campaign.json,
// sidecars, submission records). Internal to src/campaign.
#pragma once

#include <string>

namespace prs::campaign {

/// The whole file; *ok is false when it cannot be opened (then the text is empty).
std::string ReadFileText(const std::string& path, bool* ok);

/// Writes `text` (empty, or ending in a newline) to `path` atomically: PATH.partial, fsync,
/// rename. Throws what output::LineWriter throws.
void WriteFileAtomically(const std::string& path, const std::string& text);

}  // namespace prs::campaign
