// Whole-line buffered output over POSIX file descriptors, with write-then-rename for files.
#include "output/line_writer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace prs::output {
namespace {

constexpr size_t kFlushBytes = 64 * 1024;
constexpr auto kFlushInterval = std::chrono::milliseconds(200);

std::string PartialPathOf(const std::string& path) { return path + ".partial"; }

// Renaming over a symlink, a device (/dev/null) or a pipe would replace it instead of writing
// to it, so only absent paths and plain files take the PATH.partial route.
bool IsAbsentOrRegularFile(const std::string& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return errno == ENOENT;
  return S_ISREG(info.st_mode);
}

}  // namespace

LineWriter::LineWriter() : fd_(STDOUT_FILENO), last_write_(std::chrono::steady_clock::now()) {}

LineWriter::LineWriter(std::string path)
    : path_(std::move(path)), last_write_(std::chrono::steady_clock::now()) {
  if (path_.empty()) throw std::runtime_error("the output path is empty");
  direct_ = !IsAbsentOrRegularFile(path_);
  const std::string target = direct_ ? path_ : PartialPathOf(path_);
  fd_ = ::open(target.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) ThrowIoError("cannot create", target);
}

LineWriter::~LineWriter() {
  try {
    Flush();
  } catch (const std::exception&) {
    // Destructors must not throw; a caller that cares calls Flush() or Commit() itself.
  }
  if (is_file() && fd_ >= 0) {
    ::close(fd_);
    // Nothing was written (the first scene failed): an empty PATH.partial would only say
    // "partial results" where there are none.
    if (!direct_ && lines_written_ == 0) std::remove(partial_path().c_str());
  }
}

void LineWriter::AddLine(std::string_view line) {
  buffer_.append(line);
  buffer_.push_back('\n');
  ++buffered_lines_;
  FlushIfDue();
}

void LineWriter::AddLines(std::string_view lines, int64_t count) {
  if (buffer_.empty() && lines.size() >= kFlushBytes / 4 && fd_ >= 0) {
    WriteAll(lines);
    lines_written_ += count;
    last_write_ = std::chrono::steady_clock::now();
    return;
  }
  buffer_.append(lines);
  buffered_lines_ += count;
  FlushIfDue();
}

void LineWriter::FlushIfDue() {
  if (buffer_.size() >= kFlushBytes ||
      std::chrono::steady_clock::now() - last_write_ >= kFlushInterval) {
    Flush();
  }
}

void LineWriter::Flush() {
  last_write_ = std::chrono::steady_clock::now();
  if (buffer_.empty() || fd_ < 0) return;
  WriteAll(buffer_);
  buffer_.clear();
  lines_written_ += buffered_lines_;
  buffered_lines_ = 0;
}

void LineWriter::Commit() {
  Flush();
  if (!is_file() || direct_) return;
  const std::string partial = PartialPathOf(path_);
  if (::fsync(fd_) != 0) ThrowIoError("cannot write", partial);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) ThrowIoError("cannot write", partial);
  if (std::rename(partial.c_str(), path_.c_str()) != 0) ThrowIoError("cannot create", path_);
}

std::string LineWriter::partial_path() const {
  if (!is_file()) return "<stdout>";
  return direct_ ? path_ : PartialPathOf(path_);
}

void LineWriter::WriteAll(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;  // no progress and no error code: report it as an I/O error
    if (n <= 0) ThrowIoError("cannot write", partial_path());
    bytes.remove_prefix(static_cast<size_t>(n));
  }
}

void LineWriter::ThrowIoError(const char* action, const std::string& path) const {
  throw std::runtime_error(std::string(action) + " '" + path + "': " + std::strerror(errno));
}

void WriteFileAtomically(const std::string& path, std::string_view bytes) {
  LineWriter writer(path);
  writer.AddLines(bytes, 0);
  writer.Commit();
}

}  // namespace prs::output
