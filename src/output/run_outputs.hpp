// The files of one run in its (locked) output directory, started anew or continued after a
// restart: particles.h5 + particles.xmf, series.csv, and as the case asks probes.csv,
// collisions.csv, fields.h5 + fields.xmf, continuum.h5 + continuum.xmf, case.resolved.toml.
//
// Every run has a run id (32 hex digits, random) written into each HDF5 file and the header of
// case.resolved.toml; its checkpoints record it with what the run had written (OutputMarks: the
// frames' times, each CSV file's size and hash). Continuing a run checks every file against
// those marks first, read-only — another run's file, one that stops short of the checkpoint (a
// gap), a missing or an unexpected file is an InputError before anything is touched — and only
// then drops what was written after the checkpoint, each file atomically (a copy renamed over
// it).
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "output/fields_writer.hpp"
#include "output/h5md_writer.hpp"
#include "output/output_directory.hpp"
#include "output/series_writer.hpp"

namespace fluidem {

/// What files a run writes, and their shapes.
struct OutputLayout {
  std::size_t particles = 0;
  int dimension = 3;
  H5mdBox box;
  bool layers = false;
  /// CSV files by name (series.csv always; probes.csv, collisions.csv when the case has them).
  std::map<std::string, std::vector<std::string>> csv;
  struct Grid {
    FieldGrid grid;
    std::vector<std::string> scalars, vectors;
  };
  std::optional<Grid> fields;    ///< fields.h5: one frame with every particle frame
  std::optional<Grid> continuum; ///< continuum.h5: one frame per averaging interval
};

/// What a run has written so far, as its checkpoints record it.
struct OutputMarks {
  std::string run_id;                  ///< empty: unknown (a checkpoint of an older fluidem)
  std::vector<double> frame_times;     ///< particles.h5 and fields.h5
  std::vector<double> continuum_times; ///< continuum.h5
  std::map<std::string, SeriesWriter::Mark> csv;
};

/// A new random run id: 32 hexadecimal digits.
std::string new_run_id();

class RunOutputs {
public:
  /// New files for a new run (`dir` must not hold another run's: the caller decides that),
  /// with a new run id. `resolved_case`: the text of case.resolved.toml after its header;
  /// `case_file`: the case file's absolute path, recorded in that header (`# case file: ...`)
  /// for the tools that look up the case's published values next to it (fluidem plot).
  static RunOutputs start(const OutputDirectory& dir, const OutputLayout& layout,
                          const std::string& resolved_case, const std::string& version,
                          const std::string& case_file = {});
  /// Continue the files of the run that wrote `marks` (from its checkpoint): every file is
  /// checked first (InputError naming the file and what is wrong: another run's, a gap, a
  /// missing or unexpected file, a checkpoint without marks), then cut back to the marks.
  /// The header's case file is the one the run was started from.
  static RunOutputs resume(const OutputDirectory& dir, const OutputLayout& layout,
                           const OutputMarks& marks, const std::string& resolved_case,
                           const std::string& version);

  SeriesWriter& csv(const std::string& name) { return *csv_.at(name); }
  bool has_csv(const std::string& name) const { return csv_.count(name) > 0; }
  H5mdWriter& particles() { return *particles_; }
  FieldsWriter* fields() { return fields_.get(); }
  FieldsWriter* continuum() { return continuum_.get(); }

  /// After a particle frame (and its fields frame) at `time`: the XDMF indexes list it.
  void frame_written(double time);
  /// After a continuum frame at `time`.
  void continuum_written(double time);
  /// The run's id and what it has written (for its checkpoints).
  OutputMarks marks() const;
  const std::string& run_id() const { return run_id_; }
  /// Flush the HDF5 files (the CSV files flush every row).
  void flush();
  /// Close everything, reporting failures (OutputError). Also after an error: what can be
  /// flushed is flushed, and nothing is thrown (close_quietly).
  void close();
  void close_quietly() noexcept;

private:
  RunOutputs(const OutputDirectory& dir, const OutputLayout& layout);
  void write_resolved_case(const std::string& resolved_case, const std::string& version) const;
  /// The XDMF indexes of particles.h5 (and fields.h5) for frame_times_; of continuum.h5.
  void write_frame_indexes() const;
  void write_continuum_index() const;

  std::string dir_;
  OutputLayout layout_;
  std::string run_id_;
  std::string case_file_; ///< absolute path of the case file the run was started from, or ""
  std::unique_ptr<H5mdWriter> particles_;
  std::unique_ptr<FieldsWriter> fields_, continuum_;
  std::map<std::string, std::unique_ptr<SeriesWriter>> csv_;
  std::vector<double> frame_times_, continuum_times_;
};

} // namespace fluidem
