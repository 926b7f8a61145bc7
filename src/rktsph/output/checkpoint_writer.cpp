#include "rktsph/output/checkpoint_writer.hpp"

#include <limits>

#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/output_times.hpp"

namespace rktsph {

CheckpointWriter::CheckpointWriter(std::filesystem::path path, double interval,
                                   std::uint64_t case_hash, std::vector<CheckpointPart> parts)
    : path_(std::move(path)),
      interval_(interval),
      case_hash_(case_hash),
      parts_(std::move(parts)) {}

void CheckpointWriter::on_start(const Simulation&) {
  next_time_ = interval_ > 0.0 ? interval_ : std::numeric_limits<double>::infinity();
}

void CheckpointWriter::after_step(const Simulation& simulation) {
  // Interval 0 only when restoring a checkpoint made with another interval: nothing to write.
  if (interval_ <= 0.0) return;
  const double time = simulation.state().time;
  const double dt = simulation.time_step();
  if (!output_time_reached(time, next_time_, dt)) return;
  while (output_time_reached(time, next_time_, dt))
    next_time_ += interval_;
  // Encoded after next_time_ moves on, so a restarted run does not write this checkpoint again.
  write_file_atomically(path_, encode_checkpoint(case_hash_, parts()));
  ++written_;
}

void CheckpointWriter::save_checkpoint(CheckpointOut& out) const {
  out.put_f64(next_time_);
}

void CheckpointWriter::restore_checkpoint(CheckpointIn& in) {
  next_time_ = in.get_f64();
}

std::vector<CheckpointPart> CheckpointWriter::parts() {
  std::vector<CheckpointPart> all = parts_;
  all.push_back({"checkpoint_writer", this});
  return all;
}

}  // namespace rktsph
