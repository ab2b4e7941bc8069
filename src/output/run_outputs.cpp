#include "output/run_outputs.hpp"

#include <fstream>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.hpp"
#include "output/fields_xdmf.hpp"
#include "output/safe_file.hpp"
#include "output/xdmf_writer.hpp"

namespace fluidem {

namespace {

std::string names(const std::map<std::string, std::vector<std::string>>& m) {
  std::string s;
  for (const auto& [name, columns] : m) s += (s.empty() ? "" : ", ") + name;
  return s;
}

constexpr const char* kCaseFileMark = "# case file: ";

/// The case file recorded in the header of an earlier case.resolved.toml, or "".
std::string recorded_case_file(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int k = 0; k < 3 && std::getline(in, line); ++k)
    if (line.rfind(kCaseFileMark, 0) == 0) return line.substr(std::string(kCaseFileMark).size());
  return {};
}

} // namespace

std::string new_run_id() {
  std::random_device rd;
  std::string id;
  for (int k = 0; k < 4; ++k) id += fmt::format("{:08x}", static_cast<std::uint32_t>(rd()));
  return id;
}

RunOutputs::RunOutputs(const OutputDirectory& dir, const OutputLayout& layout)
    : dir_(dir.path()), layout_(layout) {}

void RunOutputs::write_resolved_case(const std::string& resolved_case,
                                     const std::string& version) const {
  const std::string from =
      case_file_.empty() ? std::string() : fmt::format("{}{}\n", kCaseFileMark, case_file_);
  safe_file::replace(dir_ + "/case.resolved.toml",
                     fmt::format("# fluidem {}, run {}: the fully resolved case of this run; "
                                 "running it reproduces the run.\n{}{}",
                                 version, run_id_, from, resolved_case));
}

RunOutputs RunOutputs::start(const OutputDirectory& dir, const OutputLayout& layout,
                             const std::string& resolved_case, const std::string& version,
                             const std::string& case_file) {
  RunOutputs o(dir, layout);
  o.run_id_ = new_run_id();
  o.case_file_ = case_file;
  o.write_resolved_case(resolved_case, version);
  o.particles_ =
      std::make_unique<H5mdWriter>(dir.file("particles.h5"), layout.particles, layout.dimension,
                                   version, layout.box, std::string(), layout.layers, o.run_id_);
  for (const auto& [name, columns] : layout.csv)
    o.csv_[name] = std::make_unique<SeriesWriter>(dir.file(name), columns);
  if (layout.fields)
    o.fields_ = std::make_unique<FieldsWriter>(dir.file("fields.h5"), layout.fields->grid,
                                               layout.fields->scalars, layout.fields->vectors,
                                               version, o.run_id_);
  if (layout.continuum)
    o.continuum_ = std::make_unique<FieldsWriter>(dir.file("continuum.h5"), layout.continuum->grid,
                                                  layout.continuum->scalars,
                                                  layout.continuum->vectors, version, o.run_id_);
  return o;
}

RunOutputs RunOutputs::resume(const OutputDirectory& dir, const OutputLayout& layout,
                              const OutputMarks& marks, const std::string& resolved_case,
                              const std::string& version) {
  const std::string where = fmt::format("cannot continue the outputs in '{}'", dir.path());
  if (marks.run_id.empty())
    throw InputError(where + ": the checkpoint does not record which outputs it belongs to (it "
                             "was written by an older fluidem); continue it into a new directory "
                             "with --out");
  std::map<std::string, std::vector<std::string>> recorded;
  for (const auto& [name, mark] : marks.csv) recorded[name];
  std::map<std::string, std::vector<std::string>> wanted;
  for (const auto& [name, columns] : layout.csv) wanted[name];
  if (recorded != wanted)
    throw InputError(fmt::format(
        "{}: the run being continued wrote {}, this one would write {} (output.probe and "
        "output.collisions cannot change when a run continues in the same directory; continue "
        "it into a new directory with --out)",
        where, names(recorded), names(wanted)));
  // Each writer's resume, with check_only: first all of them only check, read-only; then each
  // cuts its file back to the checkpoint (atomically, file by file: cutting again is harmless,
  // so an interruption here leaves a directory that the same restart continues).
  const auto particles = [&](bool check_only) {
    return H5mdWriter::resume(dir.file("particles.h5"), marks.frame_times, marks.run_id,
                              layout.particles, layout.dimension, layout.box, layout.layers,
                              check_only);
  };
  const auto series = [&](const std::string& name, bool check_only) {
    return SeriesWriter::resume(dir.file(name), layout.csv.at(name), marks.csv.at(name),
                                check_only);
  };
  const auto fields = [&](const char* file, const OutputLayout::Grid& f,
                          const std::vector<double>& times, bool check_only) {
    return FieldsWriter::resume(dir.file(file), times, marks.run_id, f.grid, f.scalars, f.vectors,
                                check_only);
  };
  try {
    particles(true);
    for (const auto& [name, columns] : layout.csv) series(name, true);
    if (layout.fields) fields("fields.h5", *layout.fields, marks.frame_times, true);
    if (layout.continuum) fields("continuum.h5", *layout.continuum, marks.continuum_times, true);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  RunOutputs o(dir, layout);
  o.run_id_ = marks.run_id;
  o.particles_ = std::make_unique<H5mdWriter>(particles(false));
  for (const auto& [name, columns] : layout.csv)
    o.csv_[name] = std::make_unique<SeriesWriter>(series(name, false));
  if (layout.fields)
    o.fields_ = std::make_unique<FieldsWriter>(
        fields("fields.h5", *layout.fields, marks.frame_times, false));
  if (layout.continuum)
    o.continuum_ = std::make_unique<FieldsWriter>(
        fields("continuum.h5", *layout.continuum, marks.continuum_times, false));
  o.frame_times_ = marks.frame_times;
  o.continuum_times_ = marks.continuum_times;
  o.case_file_ = recorded_case_file(dir.path() + "/case.resolved.toml");
  o.write_frame_indexes();
  if (layout.continuum) o.write_continuum_index();
  o.write_resolved_case(resolved_case, version);
  return o;
}

void RunOutputs::frame_written(double time) {
  frame_times_.push_back(time);
  write_frame_indexes();
}

void RunOutputs::continuum_written(double time) {
  continuum_times_.push_back(time);
  write_continuum_index();
}

void RunOutputs::write_frame_indexes() const {
  write_particles_xdmf(dir_ + "/particles.xmf", "particles.h5", layout_.particles, frame_times_);
  if (layout_.fields)
    write_fields_xdmf(dir_ + "/fields.xmf", "fields.h5", layout_.fields->grid,
                      layout_.fields->scalars, layout_.fields->vectors, frame_times_);
}

void RunOutputs::write_continuum_index() const {
  write_fields_xdmf(dir_ + "/continuum.xmf", "continuum.h5", layout_.continuum->grid,
                    layout_.continuum->scalars, layout_.continuum->vectors, continuum_times_);
}

OutputMarks RunOutputs::marks() const {
  OutputMarks m;
  m.run_id = run_id_;
  m.frame_times = frame_times_;
  m.continuum_times = continuum_times_;
  for (const auto& [name, writer] : csv_) m.csv[name] = writer->mark();
  return m;
}

void RunOutputs::flush() {
  if (fields_) fields_->flush();
  if (continuum_) continuum_->flush();
  particles_->flush();
}

void RunOutputs::close() {
  for (auto& [name, writer] : csv_) writer->close();
  if (fields_) fields_->close();
  if (continuum_) continuum_->close();
  particles_->close();
}

void RunOutputs::close_quietly() noexcept {
  for (auto& [name, writer] : csv_) try {
      writer->close();
    } catch (...) {
    }
  for (auto* w : {fields_.get(), continuum_.get()})
    if (w != nullptr) try {
        w->close();
      } catch (...) {
      }
  try {
    particles_->close();
  } catch (...) {
  }
}

} // namespace fluidem
