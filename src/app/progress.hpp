// Progress display: one updating line on a terminal, plain periodic lines otherwise.
#pragma once
#include <chrono>
#include <cstdio>

#include "integrate/simulation.hpp"

namespace fluidem {

class ProgressDisplay {
public:
  explicit ProgressDisplay(std::FILE* out);
  void operator()(const RunStatus& s);
  void finish();

private:
  std::FILE* out_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_, last_;
  long step_at_start_ = -1;
  bool printed_ = false;
};

} // namespace fluidem
