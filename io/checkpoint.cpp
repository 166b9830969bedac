// SPDX-License-Identifier: MIT
#include "io/checkpoint.hpp"

#include "io/atomic_file.hpp"
#include "mesh/error.hpp"
#include "mesh/state_archive.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>

namespace nmm {

namespace {

namespace fs = std::filesystem;

// Version 2 (2026-11-26): the stepper's counters include friction_terms; version 3, augmentations;
// version 4 (2026-11-28), locks_beyond_friction and max_lock_excess; version 5 (the same day),
// slides_against_motion and slide_feed_work; version 6 (2026-11-28), the linear solver's
// conjugate-gradient iterations and fallbacks, the steps they skip (PcgSolver::carried()),
// and the last step's accelerations (their first guess); version 7 (2026-11-29),
// coupled_friction_tries and coupled_friction_iterations; version 8 (2026-12-02), the energy
// balance's terms (EnergyLedger) and the bonded contacts open at the end of the step (yielded
// in tension: they start the next step open); version 9 (the same day), blocks.csv's size and
// the block tracker's state.
constexpr std::string_view magic = "nmm checkpoint, version 9\n";
constexpr std::int64_t byte_order = 0x0102030405060708;

/// 64-bit FNV-1a: a fingerprint, not a defence against tampering.
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  }
  return hash;
}

/// The bytes of @p file, or nothing when it cannot be opened or read (a folder, say: the
/// stream opens it and fails at the first read by throwing).
std::optional<std::string> read_bytes(const fs::path& file) {
  std::error_code error;
  if (fs::is_directory(file, error))
    return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in)
    return std::nullopt;
  try {
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << value;
  return out.str();
}

} // namespace

std::uint64_t model_fingerprint(const Model& model) {
  StateWriter out;
  model.save_state(out);
  out.put(static_cast<std::int64_t>(model.n_dofs()));
  out.put(static_cast<std::int64_t>(model.order));
  return fnv1a(out.bytes());
}

std::uint64_t file_hash(const fs::path& file) {
  const std::optional<std::string> bytes = read_bytes(file);
  return bytes ? fnv1a(*bytes) : 0;
}

void write_checkpoint(const fs::path& file,
                      const CheckpointRun& run,
                      const TimeStepper& stepper,
                      std::uint64_t fingerprint,
                      std::uint64_t case_hash) {
  StateWriter out;
  out.put(byte_order);
  out.put(static_cast<std::int64_t>(fingerprint));
  out.put(static_cast<std::int64_t>(case_hash));
  out.section("RUN.");
  out.put(static_cast<std::int64_t>(run.step));
  out.put(static_cast<std::int64_t>(run.written));
  out.put(static_cast<std::int64_t>(run.output_steps));
  out.put(run.max_penetration);
  out.put(run.wall_seconds);
  out.put(static_cast<std::int64_t>(run.history_bytes));
  out.put(static_cast<std::int64_t>(run.blocks_bytes));
  out.put(run.block_motion);
  out.put_count(run.pvd.size());
  for (const PvdSeries::Entry& entry : run.pvd) {
    out.put(entry.time);
    out.put(static_cast<std::int64_t>(entry.part));
    out.put(entry.file);
  }
  out.put(run.initial_points);
  out.put(run.monitor_starts);
  stepper.save_state(out);
  out.section("END.");
  // A checksum of everything before it: a damaged file is refused, not restarted from.
  out.put(static_cast<std::int64_t>(fnv1a(out.bytes())));
  write_file_atomically(file, [&](const fs::path& tmp) {
    std::ofstream stream(tmp, std::ios::binary | std::ios::trunc);
    stream.write(magic.data(), static_cast<std::streamsize>(magic.size()));
    stream.write(out.bytes().data(), static_cast<std::streamsize>(out.bytes().size()));
    stream.flush();
    return static_cast<bool>(stream);
  });
}

CheckpointRun read_checkpoint(const fs::path& file,
                              TimeStepper& stepper,
                              std::uint64_t fingerprint,
                              std::uint64_t case_hash,
                              std::vector<std::string>& warnings) {
  const std::string name = file.string();
  std::error_code error;
  if (fs::is_directory(file, error))
    throw InputError(name + " is a folder, not a checkpoint file (nmm writes its checkpoint "
                            "under that name); remove or rename the folder, and run the case "
                            "from the start without --restart");
  const std::optional<std::string> read = read_bytes(file);
  if (!read) {
    throw InputError("no checkpoint " + name +
                     " to restart from: a run writes it when it stops (completed, interrupted "
                     "or by --steps) and every [output] checkpoint_every steps; give the "
                     "output folder of such a run to --restart");
  }
  const std::string& bytes = *read;
  if (bytes.compare(0, magic.size(), magic) != 0)
    throw InputError(name +
                     " is not a checkpoint of this version of nmm (it does not start "
                     "with \"" +
                     std::string(magic.substr(0, magic.size() - 1)) +
                     "\"); run the case from the start without --restart");
  const std::string_view body = std::string_view(bytes).substr(magic.size());
  std::int64_t checksum = 0;
  if (body.size() >= sizeof checksum)
    std::memcpy(&checksum, body.data() + body.size() - sizeof checksum, sizeof checksum);
  if (body.size() < sizeof checksum ||
      static_cast<std::uint64_t>(checksum) != fnv1a(body.substr(0, body.size() - sizeof checksum)))
    throw InputError(name + " is damaged (its checksum does not match its " +
                     std::to_string(bytes.size()) +
                     " bytes: cut short or changed); restart from another copy or run the "
                     "case from the start without --restart");
  StateReader in(body.substr(0, body.size() - sizeof checksum), name);
  if (in.integer() != byte_order)
    in.fail("it was written on a machine of the other byte order");
  const auto stored_fingerprint = static_cast<std::uint64_t>(in.integer());
  if (stored_fingerprint != fingerprint) {
    throw InputError(name + " was written for another model (fingerprint " +
                     hex(stored_fingerprint) + ", this case gives " + hex(fingerprint) +
                     "): the geometry, the cover mesh, the materials' models or the initial "
                     "stresses changed since; a restart continues the same model, so run the "
                     "case from the start without --restart");
  }
  if (static_cast<std::uint64_t>(in.integer()) != case_hash) {
    warnings.push_back("the case file changed since the checkpoint " + name +
                       " was written; the restarted run continues the same model with the "
                       "case's new values (loads, analysis and output settings)");
  }
  in.section("RUN.");
  CheckpointRun run;
  run.step = static_cast<long>(in.integer());
  run.written = static_cast<long>(in.integer());
  run.output_steps = static_cast<long>(in.integer());
  run.max_penetration = in.real();
  run.wall_seconds = in.real();
  run.history_bytes = static_cast<std::uintmax_t>(in.integer());
  run.blocks_bytes = static_cast<std::uintmax_t>(in.integer());
  run.block_motion = in.vector();
  run.pvd.resize(in.count());
  for (PvdSeries::Entry& entry : run.pvd) {
    entry.time = in.real();
    entry.part = static_cast<int>(in.integer());
    entry.file = in.text();
  }
  run.initial_points = in.points();
  run.monitor_starts = in.points();
  stepper.load_state(in);
  in.section("END.");
  if (!in.at_end())
    in.fail("it has bytes after its end");
  if (run.step != stepper.counters().steps)
    in.fail("its step " + std::to_string(run.step) + " is not the stepper's " +
            std::to_string(stepper.counters().steps));
  return run;
}

} // namespace nmm
