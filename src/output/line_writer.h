// Writes lines (JSON Lines scenes) to standard output or to a file so that nobody ever sees part
// of a line: lines are buffered and written in whole-line chunks, and a file is written as
// PATH.partial and renamed to PATH only when the caller commits it (unless PATH is a device, a
// pipe or a symlink, which are written directly).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace prs::output {

class LineWriter {
 public:
  /// Writes to standard output; Commit() only flushes.
  LineWriter();
  /// Writes to `path` + ".partial" (created or truncated); Commit() renames it to `path`.
  /// When `path` exists and is not a regular file (/dev/stdout, a fifo, a symlink), writes to
  /// it directly instead. Throws std::runtime_error naming the file and the reason if it
  /// cannot be created.
  explicit LineWriter(std::string path);
  /// Writes what is buffered (ignoring errors) and closes the file, without renaming it; a
  /// PATH.partial that received no line is removed.
  ~LineWriter();
  LineWriter(const LineWriter&) = delete;
  LineWriter& operator=(const LineWriter&) = delete;

  /// Appends `line` and a newline. The buffer is written once it holds 64 KiB, or when the
  /// last write is 200 ms old, so a slow stream still shows up promptly.
  void AddLine(std::string_view line);
  /// Appends `lines`, `count` whole lines each ending in a newline (the text of a run of
  /// scenes). Text of 16 KiB or more is written at once when nothing is buffered, uncopied.
  void AddLines(std::string_view lines, int64_t count);
  /// Writes every buffered line now, with one write(2) (repeated only for a short write).
  /// Throws std::runtime_error naming the file and the reason on an I/O error.
  void Flush();
  /// Flushes; for a file also fsyncs, closes and renames PATH.partial to PATH.
  /// Throws std::runtime_error on an I/O error.
  void Commit();

  bool is_file() const { return !path_.empty(); }
  /// Where lines go until Commit(): PATH.partial, PATH when written directly, or "<stdout>".
  std::string partial_path() const;
  int64_t lines_written() const { return lines_written_; }

 private:
  /// Flush() once the buffer holds 64 KiB or the last write is 200 ms old.
  void FlushIfDue();
  void WriteAll(std::string_view bytes);
  [[noreturn]] void ThrowIoError(const char* action, const std::string& path) const;

  std::string path_;     // empty for stdout
  bool direct_ = false;  // written in place, without PATH.partial
  int fd_ = -1;
  std::string buffer_;
  int64_t buffered_lines_ = 0;
  int64_t lines_written_ = 0;
  std::chrono::steady_clock::time_point last_write_;
};

/// Writes `bytes` to `path` whole or not at all, as LineWriter commits a file (PATH.partial,
/// fsync, rename): the small files of campaigns, datasets and reports. Throws
/// std::runtime_error naming the file and the reason.
void WriteFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace prs::output
