// The observer that writes checkpoints (docs/input-reference.md, "Checkpoint and restart"). It
// sits outside the step like every other output: after a step, once the simulated time has
// reached the next multiple of output.checkpoint_interval, it gathers the sections of every part
// of the run and replaces <run folder>/checkpoint.bin whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "rktsph/core/checkpoint.hpp"
#include "rktsph/output/output_schedule.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

class CheckpointWriter final : public Observer, public Checkpointed {
 public:
  /// `parts` are the other parts of the run (the simulation, the output observers); the writer
  /// adds its own section. They must outlive it, and the observers among them must be added to
  /// the simulation before the writer, so that a checkpoint holds their state after the step.
  CheckpointWriter(std::filesystem::path path, double interval, std::uint64_t case_hash,
                   std::vector<CheckpointPart> parts);

  void after_step(const Simulation& simulation) override;
  void save_checkpoint(CheckpointOut& out) const override;
  void restore_checkpoint(CheckpointIn& in) override;

  /// Every part with its section, this writer last.
  std::vector<CheckpointPart> parts();
  long checkpoints_written() const { return written_; }

 private:
  std::filesystem::path path_;
  OutputSchedule schedule_;
  std::uint64_t case_hash_;
  std::vector<CheckpointPart> parts_;
  long written_ = 0;
};

}  // namespace rktsph
