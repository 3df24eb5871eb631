// Drawing the progress bar: rate limiting, the terminal width, and the line's text.
#include "cli/progress.h"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace prs::cli {
namespace {

constexpr auto kShowAfter = std::chrono::seconds(1);
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kDefaultWidth = 80;

int CalcTerminalWidth() {
  winsize size{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return kDefaultWidth;
}

std::string FormatDuration(double seconds) {
  const auto s = static_cast<int64_t>(seconds + 0.5);
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, s % 3600 / 60);
}

std::string FormatBar(double fraction, int width) {
  const int filled = static_cast<int>(fraction * width);
  std::string bar(static_cast<size_t>(width), ' ');
  std::fill_n(bar.begin(), filled, '#');
  if (filled < width && filled > 0) bar[static_cast<size_t>(filled)] = '>';
  return "[" + bar + "]";
}

}  // namespace

std::string FormatProgressLine(int64_t done, int64_t total, double elapsed_s, int width) {
  const double fraction = total > 0 ? std::clamp(double(done) / double(total), 0.0, 1.0) : 1.0;
  const double rate = elapsed_s > 0 ? done / elapsed_s : 0.0;
  std::string tail =
      fmt::format(" {:3.0f}%  {}/{} scenes  {:.0f}/s", 100 * fraction, done, total, rate);
  if (rate > 0 && done < total) tail += "  ETA " + FormatDuration((total - done) / rate);
  const std::string head = "prs: ";
  const int bar_width = width - 1 - int(head.size() + tail.size()) - 2;
  if (bar_width < 10) return (head + tail.substr(1)).substr(0, std::max(width - 1, 0));
  return head + FormatBar(fraction, bar_width) + tail;
}

std::string FormatHardSceneLine(int64_t done, int64_t total, int64_t attempts, int64_t rejections,
                                double seconds, int width, const char* runs_noun) {
  const double rate = seconds > 0 ? attempts / seconds : 0.0;
  const double rejected = attempts > 0 ? 100.0 * rejections / attempts : 0.0;
  const std::string line =
      fmt::format("prs: scene {} of {}: {} {} in {}, {:.0f}/s, {:.1f}% rejected", done + 1,
                  total, attempts, runs_noun, FormatDuration(seconds), rate, rejected);
  return line.substr(0, std::max(width - 1, 0));
}

ProgressBar::ProgressBar(int64_t total, bool enabled)
    : total_(total),
      enabled_(enabled),
      begin_(Clock::now()),
      last_draw_(begin_),
      last_done_(begin_) {}

void ProgressBar::Attach(sampling::BatchOptions& options, sampling::BatchCallbacks& callbacks) {
  if (!enabled_) return;
  options.sample.live = &live_;
  if (options.sample.gibbs || options.sample.partial_rejection) runs_noun_ = "program runs";
  callbacks.tick = [this] { Tick(); };
}

ProgressBar::~ProgressBar() { Erase(); }

void ProgressBar::Update(int64_t done) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  done_ = done;
  last_done_ = now;
  attempts_at_done_ = live_.attempts.load(std::memory_order_relaxed);
  rejections_at_done_ = live_.rejections.load(std::memory_order_relaxed);
  if (now - begin_ < kShowAfter || (drawn_ && now - last_draw_ < kRedrawInterval)) return;
  const double elapsed_s = std::chrono::duration<double>(now - begin_).count();
  Draw(FormatProgressLine(done, total_, elapsed_s, CalcTerminalWidth()), now);
}

// While the batch waits for scene done_: after a second without a scene, its attempts.
void ProgressBar::Tick() {
  const Clock::time_point now = Clock::now();
  if (now - last_done_ < kShowAfter || (drawn_ && now - last_draw_ < kRedrawInterval)) return;
  const double waited_s = std::chrono::duration<double>(now - last_done_).count();
  Draw(FormatHardSceneLine(done_, total_,
                           live_.attempts.load(std::memory_order_relaxed) - attempts_at_done_,
                           live_.rejections.load(std::memory_order_relaxed) - rejections_at_done_,
                           waited_s, CalcTerminalWidth(), runs_noun_),
       now);
}

void ProgressBar::Draw(const std::string& line, Clock::time_point now) {
  last_draw_ = now;
  std::fprintf(stderr, "\r%s\033[K", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::Erase() {
  if (!drawn_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace prs::cli
