#include "output/run_outputs.hpp"

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
  safe_file::replace(dir_ + "/case.resolved.toml",
                     fmt::format("# fluidem {}, run {}: the fully resolved case of this run; "
                                 "running it reproduces the run.\n{}",
                                 version, run_id_, resolved_case));
}

RunOutputs RunOutputs::start(const OutputDirectory& dir, const OutputLayout& layout,
                             const std::string& resolved_case, const std::string& version) {
  RunOutputs o(dir, layout);
  o.run_id_ = new_run_id();
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
  // 1. Check every file, read-only.
  const auto checked = [&](auto&& check) {
    try {
      check();
    } catch (const std::runtime_error& e) {
      throw InputError(e.what());
    }
  };
  checked([&] {
    H5mdWriter::resume(dir.file("particles.h5"), marks.frame_times, marks.run_id, layout.particles,
                       layout.dimension, layout.box, layout.layers, true);
  });
  for (const auto& [name, columns] : layout.csv)
    checked([&] { SeriesWriter::resume(dir.file(name), columns, marks.csv.at(name), true); });
  if (layout.fields)
    checked([&] {
      FieldsWriter::resume(dir.file("fields.h5"), marks.frame_times, marks.run_id,
                           layout.fields->grid, layout.fields->scalars, layout.fields->vectors,
                           true);
    });
  if (layout.continuum)
    checked([&] {
      FieldsWriter::resume(dir.file("continuum.h5"), marks.continuum_times, marks.run_id,
                           layout.continuum->grid, layout.continuum->scalars,
                           layout.continuum->vectors, true);
    });
  // 2. Cut each back to the checkpoint (atomically, file by file: cutting again is harmless, so
  //    an interruption here leaves a directory that the same restart continues).
  RunOutputs o(dir, layout);
  o.run_id_ = marks.run_id;
  o.particles_ = std::make_unique<H5mdWriter>(
      H5mdWriter::resume(dir.file("particles.h5"), marks.frame_times, marks.run_id,
                         layout.particles, layout.dimension, layout.box, layout.layers));
  for (const auto& [name, columns] : layout.csv)
    o.csv_[name] = std::make_unique<SeriesWriter>(
        SeriesWriter::resume(dir.file(name), columns, marks.csv.at(name)));
  if (layout.fields)
    o.fields_ = std::make_unique<FieldsWriter>(
        FieldsWriter::resume(dir.file("fields.h5"), marks.frame_times, marks.run_id,
                             layout.fields->grid, layout.fields->scalars, layout.fields->vectors));
  if (layout.continuum)
    o.continuum_ = std::make_unique<FieldsWriter>(FieldsWriter::resume(
        dir.file("continuum.h5"), marks.continuum_times, marks.run_id, layout.continuum->grid,
        layout.continuum->scalars, layout.continuum->vectors));
  o.frame_times_ = marks.frame_times;
  o.continuum_times_ = marks.continuum_times;
  write_particles_xdmf(dir.file("particles.xmf"), "particles.h5", layout.particles, o.frame_times_);
  if (layout.fields)
    write_fields_xdmf(dir.file("fields.xmf"), "fields.h5", layout.fields->grid,
                      layout.fields->scalars, layout.fields->vectors, o.frame_times_);
  if (layout.continuum)
    write_fields_xdmf(dir.file("continuum.xmf"), "continuum.h5", layout.continuum->grid,
                      layout.continuum->scalars, layout.continuum->vectors, o.continuum_times_);
  o.write_resolved_case(resolved_case, version);
  return o;
}

void RunOutputs::frame_written(double time) {
  frame_times_.push_back(time);
  write_particles_xdmf(dir_ + "/particles.xmf", "particles.h5", layout_.particles, frame_times_);
  if (layout_.fields)
    write_fields_xdmf(dir_ + "/fields.xmf", "fields.h5", layout_.fields->grid,
                      layout_.fields->scalars, layout_.fields->vectors, frame_times_);
}

void RunOutputs::continuum_written(double time) {
  continuum_times_.push_back(time);
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
