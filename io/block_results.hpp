// SPDX-License-Identifier: MIT
// io/block_results.hpp — the motion of every block as a rigid body (centroid, displacement,
// rotation, velocity, angular velocity), its state (resting, sliding, rotating, free), and
// blocks.csv, one row per block per output step (docs/output.md, "blocks.csv").
#pragma once

#include "contact/contact_system.hpp"
#include "io/history.hpp"
#include "io/row_file.hpp"
#include "manifold/model.hpp"
#include "solver/time_stepper.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace nmm {

/// What blocks.csv says of one block.
struct BlockMotion {
  Point2 centroid = Point2::Zero();     ///< current centroid, m
  Point2 displacement = Point2::Zero(); ///< of the centroid since the start, m
  double rotation = 0.0;                ///< since the start, rad, counter-clockwise
  Point2 velocity = Point2::Zero();     ///< of the centroid, m/s
  double angular_velocity = 0.0;        ///< rad/s, counter-clockwise
  /// Largest distance from the centroid to a vertex of the block now, m: the block's size
  /// for its state (block_states()).
  double radius = 0.0;
};

/// The state column of blocks.csv (docs/output.md lists the rules).
enum class BlockState { resting, sliding, rotating, free, excavated };

/// "resting", "sliding", "rotating", "free", "excavated".
[[nodiscard]] const char* block_state_name(BlockState state);

/// Follows every block of a model as a rigid body fitted to its material. With X the
/// position of a material point at the start and x its position now, a block's centroid is
/// the mean of x over its material (weighted by area at the start) and its displacement
/// that mean minus the mean of X; its rotation is the angle of the least-squares rigid fit
/// x ~ R(theta) (X - Xc) + xc over the material (2D Kabsch: theta = atan2 of the integrals
/// of (X - Xc) x (x - xc) and (X - Xc) . (x - xc)), taken continuous from step to step (the
/// fit's angle is known modulo a turn; the nearest to the last step's is kept). The
/// integrals are exact for any motion that is affine on each element polygon (every rigid
/// motion, DDA blocks, order-0 NMM elements): each polygon is a fan of triangles over its
/// vertices, the motion linear on each. Velocity and angular velocity are the same fit of
/// the velocity field, v ~ vc + omega J (x - xc), over the material now.
class BlockTracker {
public:
  /// @param initial_points  step_points() of @p model at the start (what displacements count
  ///                        from).
  BlockTracker(const Model& model, std::vector<Point2> initial_points);

  /// After each step of length @p dt: the fit of every block now, and the rate of its
  /// centroid and rotation over the step (what motions() gives with step_rates). Reads
  /// @p model only.
  void update(const Model& model, double dt);

  /// The motion of every block now (at the last update(); at the start before any).
  /// @param velocity     raw velocity of every unknown (TimeStepper::velocity()).
  /// @param step_rates   take velocity and angular velocity as the last step's motion over
  ///                     its time step instead of the velocity field: Shi's static steps
  ///                     reset the velocity to zero at the end of every step.
  [[nodiscard]] std::vector<BlockMotion>
  motions(const Model& model, const Eigen::VectorXd& velocity, bool step_rates) const;

  /// Displacement of every block's centroid since the start, at the last update(), m.
  [[nodiscard]] std::vector<Point2> displacements() const;

  /// The material region holding the largest part of each block (its `material`).
  [[nodiscard]] const std::vector<int>& block_regions() const noexcept { return regions_; }

  /// What update() carries from step to step (for a restart checkpoint) and its reverse.
  [[nodiscard]] Eigen::VectorXd state() const;
  /// @throws InputError when @p state is not one of a model with as many blocks.
  void restore(const Eigen::VectorXd& state);

private:
  /// Centroid and rotation fit of one block, the rotation continued from the last update's.
  struct Fit {
    Point2 centroid = Point2::Zero();
    double rotation = 0.0;
  };
  [[nodiscard]] std::vector<Fit> fit(const Model& model) const;

  std::vector<Point2> initial_points_;
  /// Per block: the area and centroid at the start, and a point of the block at the start
  /// (the origin of its sums, for rounding far from the global origin).
  std::vector<double> area_;
  std::vector<Point2> initial_centroid_;
  std::vector<Point2> origin_;
  std::vector<int> regions_;
  std::vector<Fit> last_;
  /// The last step's rate of each block: centroid velocity and angular velocity.
  std::vector<Point2> rate_;
  std::vector<double> angular_rate_;
};

/// The state of every block: not moving (|vc| + |omega| radius at most @p speed_tolerance,
/// m/s) -> resting; no closed contact and no support -> free; the instantaneous centre of
/// rotation inside the circle of radius `radius` about the centroid (|vc| < |omega| radius)
/// -> rotating; a contact of the block sliding -> sliding; else resting (moving with its
/// contacts locked: carried, or vibrating on its springs); a block all of whose elements a
/// `[[stage]]` excavated -> excavated.
/// @param contact  the contacts of the last step; null when the model has none.
[[nodiscard]] std::vector<BlockState> block_states(const Model& model,
                                                   const ContactSystem* contact,
                                                   const Scene& scene,
                                                   std::span<const BlockMotion> motions,
                                                   double speed_tolerance);

/// blocks.csv's name in the output folder.
inline constexpr const char* blocks_file_name = "blocks.csv";

/// A block moves (for its state) when its fastest point, |vc| + |omega| radius, is faster
/// than this many model sizes (TimeStepper::model_size()) per second.
inline constexpr double block_speed_tolerance = 1e-4;

/// The header of blocks.csv, without the newline.
inline constexpr const char* blocks_header =
    "step,time,block,material,x,y,ux,uy,rotation,vx,vy,omega,state";

/// blocks.csv: the rows of every block at each output step, each step's rows by one write
/// (RowFile), reals with 17 significant digits.
class BlocksWriter {
public:
  /// Creates (truncates) @p file, empty until the first step's rows come with the header.
  /// @p materials: each block's material name.
  BlocksWriter(std::filesystem::path file, std::vector<std::string> materials);
  /// Continues @p file after a restart from its first @p keep_bytes bytes (RowFile).
  BlocksWriter(std::filesystem::path file,
               std::vector<std::string> materials,
               std::uintmax_t keep_bytes);

  /// Appends one row per block. @pre one motion and one state per block.
  void write_step(long step,
                  double time,
                  std::span<const BlockMotion> motions,
                  std::span<const BlockState> states);

  [[nodiscard]] std::uintmax_t bytes() const noexcept { return rows_.bytes(); }

private:
  std::vector<std::string> materials_;
  RowFile rows_;
};

/// What `nmm run` keeps of the blocks: the tracker, updated after every step, and
/// blocks.csv, written at every output step; the moved blocks for summary.json.
class BlockOutput {
public:
  /// A new blocks.csv in @p file, or, with @p keep_bytes, the one of a restart continued
  /// from its first keep_bytes bytes (the tracker's state then comes from restore()).
  /// @param region_names  each material region's name (by PhysicalMesh::regions index).
  /// @param step_rates    BlockTracker::motions()' step_rates (Shi's static steps).
  /// @param speed_tolerance  block_states()' tolerance, m/s.
  BlockOutput(const Model& model,
              std::vector<Point2> initial_points,
              const std::vector<std::string>& region_names,
              const std::filesystem::path& file,
              std::optional<std::uintmax_t> keep_bytes,
              bool step_rates,
              double speed_tolerance);

  /// After each step of length @p dt.
  void update(const Model& model, double dt) { tracker_.update(model, dt); }
  /// The rows of every block of @p model (the one @p stepper moves) now.
  void write_step(long step, double time, const Model& model, const TimeStepper& stepper);
  /// The blocks whose centroid moved farther than @p threshold, by block id.
  [[nodiscard]] std::vector<MovedBlock> moved_blocks(double threshold) const;

  [[nodiscard]] std::uintmax_t bytes() const noexcept { return writer_.bytes(); }
  [[nodiscard]] const BlockTracker& tracker() const noexcept { return tracker_; }
  void restore(const Eigen::VectorXd& state) { tracker_.restore(state); }

private:
  BlockTracker tracker_;
  std::vector<std::string> materials_;
  BlocksWriter writer_;
  bool step_rates_ = false;
  double speed_tolerance_ = 0.0;
};

} // namespace nmm
