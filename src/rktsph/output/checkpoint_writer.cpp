#include "rktsph/output/checkpoint_writer.hpp"

#include "rktsph/output/atomic_file.hpp"

namespace rktsph {

CheckpointWriter::CheckpointWriter(std::filesystem::path path, double interval,
                                   std::uint64_t case_hash, std::vector<CheckpointPart> parts)
    : path_(std::move(path)),
      schedule_(interval),
      case_hash_(case_hash),
      parts_(std::move(parts)) {}

void CheckpointWriter::after_step(const Simulation& simulation) {
  // Interval 0 (also when restoring a checkpoint made with another interval): never due.
  if (!schedule_.due(simulation.state().time, simulation.time_step())) return;
  // Encoded after the schedule moves on, so a restarted run does not write this checkpoint again.
  write_file_atomically(path_, encode_checkpoint(case_hash_, parts()));
  ++written_;
}

void CheckpointWriter::save_checkpoint(CheckpointOut& out) const {
  out.put_f64(schedule_.next_time());
}

void CheckpointWriter::restore_checkpoint(CheckpointIn& in) {
  schedule_.set_next_time(in.get_f64());
}

std::vector<CheckpointPart> CheckpointWriter::parts() {
  std::vector<CheckpointPart> all = parts_;
  all.push_back({"checkpoint_writer", this});
  return all;
}

}  // namespace rktsph
