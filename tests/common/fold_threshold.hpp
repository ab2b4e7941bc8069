// Tests that exercise the folded step (Simulation::step) on beds sparser than the default
// threshold of Simulation::fold_pairs_per_particle: the threshold lowered for the guard's life.
#pragma once
#include "integrate/simulation.hpp"

namespace fluidem::test {

class FoldThreshold {
public:
  explicit FoldThreshold(double pairs) : saved_(Simulation::fold_pairs_per_particle()) {
    Simulation::set_fold_pairs_per_particle(pairs);
  }
  ~FoldThreshold() { Simulation::set_fold_pairs_per_particle(saved_); }
  FoldThreshold(const FoldThreshold&) = delete;
  FoldThreshold& operator=(const FoldThreshold&) = delete;

private:
  double saved_;
};

} // namespace fluidem::test
