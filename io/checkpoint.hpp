// SPDX-License-Identifier: MIT
// io/checkpoint.hpp — restart checkpoints of `nmm run` (`[output] checkpoint_every`, `nmm run
// CASE --restart DIR`): the state of the analysis after a step, bit for bit, and what the
// output files held then, so that a restarted run continues exactly where the interrupted
// one was (docs/output.md, "checkpoint.nmm").
#pragma once

#include "io/vtk_writer.hpp"
#include "mesh/geometry.hpp"
#include "solver/time_stepper.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace nmm {

/// The checkpoint's name in the output folder.
inline constexpr const char* checkpoint_file_name = "checkpoint.nmm";

/// What run_case() carries besides the analysis (the stepper, its model and contacts).
struct CheckpointRun {
  long step = 0;                    ///< the last completed step
  long written = -1;                ///< the last step written as a step file
  long output_steps = 0;            ///< step files written
  double max_penetration = 0.0;     ///< deepest of any step so far, m
  double wall_seconds = 0.0;        ///< of the run so far, s
  std::uintmax_t history_bytes = 0; ///< history.csv's size after the step's row
  std::uintmax_t blocks_bytes = 0;  ///< blocks.csv's size after the last output step's rows
  /// What the block tracker carries from step to step (BlockTracker::state()).
  Eigen::VectorXd block_motion;
  std::vector<PvdSeries::Entry> pvd;
  /// Output points at the start (displacements count from them) and the monitors' starts.
  std::vector<Point2> initial_points;
  std::vector<Point2> monitor_starts;
};

/// What identifies the model a checkpoint belongs to: a hash of the model's state before
/// the first step (geometry, covers, elements, initial stresses).
[[nodiscard]] std::uint64_t model_fingerprint(const Model& model);

/// A hash of a file's bytes (the case file: a restart with an edited case is warned about),
/// 0 when it cannot be read.
[[nodiscard]] std::uint64_t file_hash(const std::filesystem::path& file);

/// Writes @p file atomically (a reader sees the last whole checkpoint, never a partial one).
/// @throws InputError naming the file when it cannot be written.
void write_checkpoint(const std::filesystem::path& file,
                      const CheckpointRun& run,
                      const TimeStepper& stepper,
                      std::uint64_t fingerprint,
                      std::uint64_t case_hash);

/// Reads @p file into @p stepper (before its first step) and returns the rest.
/// @param warnings  gets a warning when the case file changed since the checkpoint.
/// @throws InputError naming the file and what to do when it is missing, damaged, of
///         another version or byte order, or of another model (@p fingerprint differs).
[[nodiscard]] CheckpointRun read_checkpoint(const std::filesystem::path& file,
                                            TimeStepper& stepper,
                                            std::uint64_t fingerprint,
                                            std::uint64_t case_hash,
                                            std::vector<std::string>& warnings);

} // namespace nmm
