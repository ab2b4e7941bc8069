// `fluidem analyse OUT` and `fluidem plot OUT`: the analysis of a finished (or running) run's
// outputs (docs/analysis.md), and its pictures.
//
// analyse writes OUT/analysis/:
//   spectrum_<probe>.csv       frequency (Hz), psd (Pa^2/Hz): Welch PSD of each probe of
//                              probes.csv over [T0, T1] [Chang08 §4.2] (analysis/spectrum.hpp)
//   velocity_distribution.csv  the particle velocity fluctuations of all frames in [T0, T1],
//                              pooled [Deen07 §6.2] (analysis/velocity_distribution.hpp)
//   segregation.csv            time, s over all frames, when the particles have two sizes
//                              [Deen07 eq. 49] (analysis/segregation.hpp)
//   bubbles.csv, bubble_frames.csv  the bubbles of every frame of fields.h5, followed between
//                              frames, and per frame their count and fraction of the bed
//                              (analysis/bubbles.hpp, app/analyse_bubbles.hpp)
//   summary.csv                name, value, unit: one row per quantity (also printed)
// Bad input (no OUT, no probes.csv or particles.h5, an unknown probe, too few samples, a bad
// window or segment) is an InputError (exit 2 from run_cli).
//
// plot runs `python3 fluidem_plot.py OUT` and `python3 fluidem_analysis_plot.py OUT`. The
// scripts are looked for in $FLUIDEM_PYTHON_DIR, then in the source tree this binary was built
// from (<source>/python, found from this file's compile-time path __FILE__: works from any build
// directory of the tree), then next to an installed binary (<bin>/../share/fluidem/python). The
// interpreter is $FLUIDEM_PYTHON, else /usr/bin/python3 (Debian's matplotlib/h5py/numpy).
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "output/output_directory.hpp"

namespace fluidem {

struct AnalyseOptions {
  std::string out_dir;
  std::string probe;              ///< empty: every probe of probes.csv
  double segment_seconds = 0.0;   ///< 0: the largest power of two of samples <= n / 4
  std::optional<double> from, to; ///< window [T0, T1], s; default the second half of the run
  double void_porosity = 0.8;     ///< bubbles: cells above it are dilute (analysis/bubbles.hpp)
  /// The run's directory when the caller holds its lock (a run with output.analyse); nullptr:
  /// analyse locks it (output/output_directory.hpp) and refuses while another process writes.
  const OutputDirectory* directory = nullptr;
};

/// Analyse the run in `o.out_dir`; prints a summary to stdout. Returns 0; InputError on bad input.
int analyse(const AnalyseOptions& o);

/// Draw the run's pictures (the scripts above), analysing the run first (default window) when
/// OUT/analysis/ has no summary yet; an analysis that cannot be made (too few frames, say) is
/// reported and its pictures left out. Returns 0 or the failing script's exit code.
/// With `movie_every` > 0 it draws every movie_every-th frame instead and joins them into
/// OUT/movie.mp4 (fluidem_plot.py --movie; exit 3 without ffmpeg, the frames kept).
int plot(const std::string& out_dir, const char* argv0, int movie_every = 0);

/// Several runs side by side (`fluidem plot OUT1 OUT2 ...`): each run's pictures as plot()
/// draws them, then the curves the runs share on one figure in OUT1/analysis/ with the
/// published values of their cases (fluidem_analysis_plot.py --compare). Returns 0 or the first
/// failing exit code.
int plot_together(const std::vector<std::string>& out_dirs, const char* argv0);

/// The `analyse` and `plot` subcommands registered on the fluidem App.
struct AnalysisCommands {
  CLI::App* analyse = nullptr;
  CLI::App* plot = nullptr;
  AnalyseOptions options;
  std::vector<std::string> plot_dirs;
  bool movie = false;
  int movie_every = 1;
  bool selected() const { return *analyse || *plot; }
  int run(const char* argv0) const;
};
std::unique_ptr<AnalysisCommands> add_analysis_commands(CLI::App& app);

} // namespace fluidem
