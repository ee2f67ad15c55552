// A progress bar on stderr for long stages, through OpenVDB's interrupter interface; silent when
// stderr is not a terminal or with --quiet.
#pragma once

#include <openvdb/util/NullInterrupter.h>
#include <unistd.h>

#include <cstdio>
#include <string>

namespace fcc::cli {

class ProgressBar : public openvdb::util::NullInterrupter {
 public:
  explicit ProgressBar(bool quiet) : enabled_(!quiet && ::isatty(2)) {}
  void start(const char* name) override {
    name_ = name ? name : "";
    last_ = -1;
    draw(0);
  }
  void end() override {
    if (enabled_ && last_ >= 0) std::fprintf(stderr, "\r%-70s\r", "");
  }
  bool wasInterrupted(int percent) override {
    if (percent >= 0) draw(percent);
    return false;
  }

 private:
  void draw(int percent) {
    if (!enabled_ || percent == last_) return;
    last_ = percent;
    constexpr int kWidth = 30;
    const int filled = percent * kWidth / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", name_.c_str(), filled, "##############################",
                 kWidth - filled, "", percent);
    std::fflush(stderr);
  }
  bool enabled_;
  std::string name_;
  int last_ = -1;
};

}  // namespace fcc::cli
