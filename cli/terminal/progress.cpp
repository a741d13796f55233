#include "terminal/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace eqhb::cli {

namespace {
// Redraws per second on a terminal; seconds between plain lines elsewhere.
constexpr double kTerminalInterval = 0.1;
constexpr double kPlainInterval = 5.0;
}  // namespace

std::string formatDuration(double seconds) {
  char text[32];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds);
    std::snprintf(text, sizeof text, "%d min %02d s", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60);
    std::snprintf(text, sizeof text, "%d h %02d min", m / 60, m % 60);
  }
  return text;
}

ProgressLine::ProgressLine(ProgressMode mode, std::string label)
    : terminal_(isatty(STDERR_FILENO) != 0), label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
  enabled_ = mode == ProgressMode::kAlways || (mode == ProgressMode::kAuto && terminal_);
  last_print_ = start_ - std::chrono::hours(1);
}

ProgressLine::~ProgressLine() {
  if (printed_ && !finished_ && terminal_) std::fputc('\n', stderr);
}

double ProgressLine::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressLine::update(double fraction, const std::string& count, const std::string& detail) {
  if (!enabled_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (since < (terminal_ ? kTerminalInterval : kPlainInterval)) return;
  last_print_ = now;
  print(fraction, count, detail, false);
}

void ProgressLine::message(const std::string& text) {
  if (enabled_ && terminal_ && last_width_ > 0 && !finished_) {
    std::fprintf(stderr, "\r%s\r", std::string(last_width_, ' ').c_str());
    last_width_ = 0;
    last_print_ = std::chrono::steady_clock::now() - std::chrono::hours(1);  // redraw at the next update
  }
  std::fprintf(stderr, "%s\n", text.c_str());
  std::fflush(stderr);
}

void ProgressLine::finish(const std::string& detail) {
  if (!enabled_ || finished_) return;
  print(1.0, "done", detail, true);
  finished_ = true;
}

void ProgressLine::print(double fraction, const std::string& count, const std::string& detail, bool last) {
  const double elapsed = elapsedSeconds();
  std::string line = label_ + "  " + count + "  elapsed " + formatDuration(elapsed);
  if (!last && fraction > 0 && fraction <= 1)
    line += "  ETA " + formatDuration(elapsed * (1 - fraction) / fraction);
  if (!detail.empty()) line += "  " + detail;
  if (terminal_) {
    // Pad over the rest of a longer previous line.
    const size_t width = line.size();
    if (width < last_width_) line.append(last_width_ - width, ' ');
    last_width_ = width;
    std::fprintf(stderr, "\r%s%s", line.c_str(), last ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  std::fflush(stderr);
  printed_ = true;
}

}  // namespace eqhb::cli
