// The outputs of a run while it goes: every writer (particles.h5 + .xmf, fields.h5, continuum.h5,
// series.csv, probes.csv, collisions.csv; output/run_outputs.hpp opens them together or resumes
// them after a read-only check), the schedule that says when a row, a frame or a checkpoint is
// due (the first step at or after each multiple of its interval: no drift from rounding to
// steps), and the checkpoints. Nothing unstable reaches a file: the stability guard runs before
// every row, frame and checkpoint.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "integrate/gas_coupling.hpp"
#include "output/output_directory.hpp"
#include "output/run_outputs.hpp"

namespace fluidem {

class Simulation;

class RunRecorder {
public:
  /// Opens every output of sim's run in dir, or continues those of the run sim was restarted
  /// from (resume). The recorder must not outlive sim. dir nullptr: a rank of a distributed run
  /// other than the root, which keeps the schedule and takes part in the gathers, and writes
  /// nothing.
  RunRecorder(Simulation& sim, const OutputDirectory* dir, bool resume);
  ~RunRecorder();
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  /// The files of sim's run and their shapes.
  static OutputLayout layout(const Simulation& sim);
  /// About how many bytes the rest of sim's run writes (with a margin of 2).
  static double bytes_needed(const Simulation& sim);

  /// The rows and frames due at the simulation's step (the last step: all of them).
  void write_due();
  /// Whether a checkpoint is due after this step (moves the schedule on when it is).
  bool checkpoint_due();
  /// A checkpoint of a state that passed the stability checks, with its outputs on disk.
  void checkpoint();
  /// After the last step: closes the files and writes collision_overlap.csv.
  void close();
  /// On an error: what was written is flushed; the error says what went wrong.
  void close_quietly() {
    if (outputs_) outputs_->close_quietly();
  }

  double seconds() const { return seconds_; }
  const std::string& last_checkpoint() const { return last_checkpoint_; }

private:
  void write_series_rows();
  void write_frame();
  void write_continuum_frame();
  /// The store's indices in ascending particle id (empty: the store is in id order).
  const std::vector<std::uint32_t>* output_order();

  Simulation& sim_;
  const OutputDirectory* dir_;
  std::optional<RunOutputs> outputs_; ///< none without a directory

  double eps_; ///< s, the round-off allowed in the schedule
  long total_; ///< the run's last step
  CellFields cells_;
  std::vector<std::uint32_t> order_;
  long order_sorts_ = -1; ///< the stepper's sorts when order_ was computed
  double seconds_ = 0.0;
  std::string last_checkpoint_;
};

} // namespace fluidem
