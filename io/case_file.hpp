// SPDX-License-Identifier: MIT
// io/case_file.hpp — the case file (TOML) as a plain value tree with every default applied.
// The keys, units, defaults and ranges are documented in docs/case-file.md; the shape is
// DESIGN.md's contract "Case file (TOML)".
#pragma once

#include "io/fos_spec.hpp"
#include "manifold/bolt.hpp"
#include "manifold/boundary_conditions.hpp"
#include "manifold/material.hpp"
#include "mesh/geometry.hpp"
#include "mesh/joint_set.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nmm {

/// `[cover_mesh] kind`: how the mathematical mesh is made.
enum class CoverMeshKind {
  regular, ///< equilateral triangles in rows along x (DESIGN.md "Command line")
  gmsh     ///< the triangulation gmsh makes of the geometry
};

/// `[materials.NAME] model`: which kind of cover the region is discretised with.
enum class MaterialModel { nmm, dda, vem };

/// `[[load]]`: which of the four load forms an entry is.
enum class LoadKind {
  gravity,  ///< `gravity = [gx, gy]` (m/s^2) on every material with a density
  point,    ///< `point = "P"`, `force = [fx, fy]` (N)
  traction, ///< `curve = "C"`, `traction = [tx, ty]` (Pa)
  pressure  ///< `curve = "C"`, `pressure = p` (Pa, positive pushes into the material)
};

/// `[analysis] kind`.
enum class AnalysisKind {
  dynamic,     ///< "dynamic": velocity carried over between steps
  quasi_static ///< "static": Shi's static analysis, velocity reset every step
};

/// `[analysis] solver`.
enum class LinearSolverKind { cholmod, pcg };

/// `[cover_mesh]`: the mathematical mesh and the cover functions.
struct CoverMeshSpec {
  CoverMeshKind kind = CoverMeshKind::regular;
  /// Triangle edge length (m), > 0. Required.
  double size = 0.0;
  /// Line of `size` in the case file, for later messages.
  int size_line = 0;
  /// Cover function order for NMM regions: 0 or 1.
  int order = 0;
  /// Refuse to build a math mesh with more triangles than this (guards against a size
  /// given in millimetres), > 0.
  std::int64_t max_triangles = 5'000'000;
  /// Covers smaller than this fraction of their math node's star get no unknowns of their
  /// own but the extension of a nearby element's field (docs/cover-mesher.md), in [0, 0.5).
  double min_cover_area_ratio = 1e-3;
  /// Largest chord deviation when gmsh curves are sampled to polylines (m); 0 = automatic
  /// (1e-2 of `size`, chords no longer than `size`; GeometryReadOptions). Refused (> 0)
  /// with a .msh geometry, whose curves are its mesh.
  double curve_tolerance = 0.0;
  /// With kind = "gmsh" and a .geo: the .geo's own mesh sizes and Fields grade the
  /// triangles, `size` the largest edge (make_gmsh_math_mesh()); false: uniform triangles.
  bool geometry_sizes = false;
};

/// `[materials.NAME]`: one Physical Surface of the geometry.
struct MaterialSpec {
  /// The table name, which must be a Physical Surface name of the geometry.
  std::string name;
  /// Line of `[materials.NAME]` (or of the key NAME) in the case file, for later messages.
  int line = 0;
  MaterialModel model = MaterialModel::nmm;
  /// kg/m^3, > 0; 0 only when it was left out in a static analysis without gravity.
  double density = 0.0;
  /// Young's modulus (Pa), > 0.
  double young = 0.0;
  /// Poisson's ratio, -1 < poisson < 0.5.
  double poisson = 0.0;
  PlaneCondition plane = PlaneCondition::strain;
  /// Out-of-plane thickness (m) of a plane-stress material, > 0; 1 for plane strain.
  double thickness = 1.0;
  /// Initial velocity (m/s) of every point of the material.
  Eigen::Vector2d initial_velocity = Eigen::Vector2d::Zero();
  /// Initial angular velocity (rad/s, counter-clockwise) of each block about its centroid.
  double initial_angular_velocity = 0.0;
  /// Initial stress (Pa) as (sxx, syy, sxy); tension positive. With `[in_situ]`: the field's
  /// stress at the surface (ElasticMaterial::initial_stress).
  Eigen::Vector3d initial_stress = Eigen::Vector3d::Zero();
  /// With `[in_situ]`: the field's growth per metre of depth (Pa/m) and the surface's y (m)
  /// (ElasticMaterial::initial_stress_gradient, initial_stress_surface); else zero.
  Eigen::Vector3d initial_stress_gradient = Eigen::Vector3d::Zero();
  double initial_stress_surface = 0.0;
  /// `exact_rotation`: an `nmm` or `vem` region's blocks turn by each step's rotation exactly
  /// (ElasticMaterial::exact_rotation). `dda` regions do not take it (they always do).
  bool exact_rotation = false;
};

/// Mohr-Coulomb strength of a joint or of a contact (`[joints.NAME]`, `[contact]`).
struct JointProperties {
  /// Degrees, in [0, 90).
  double friction_angle_degrees = 0.0;
  /// Pa, >= 0.
  double cohesion = 0.0;
  /// Pa, >= 0.
  double tensile_strength = 0.0;
  /// `normal_stiffness` and `shear_stiffness`: the joint's own spring stiffness per unit
  /// length of contact, Pa/m, > 0 when given; 0 when absent (the penalty).
  double normal_stiffness = 0.0;
  double shear_stiffness = 0.0;
};

/// `[joints.NAME]`: one Physical Curve that cuts the material.
struct JointSpec {
  std::string name;
  /// Line of `[joints.NAME]` (or of the key NAME) in the case file.
  int line = 0;
  JointProperties properties;
};

/// `[[joint_set]]`: joints generated from a set's angle, spacing, trace, gap and origin
/// (docs/case-file.md; io/joint_set_table.cpp reads it, io/joint_sets.cpp generates them).
struct JointSetSpec {
  /// The `[joints.NAME]` whose properties the joints take (`joint`).
  std::string joint;
  /// `region`: the Physical Surface the joints are clipped to; empty: all material.
  std::string region;
  /// Line of this `[[joint_set]]` header in the case file.
  int line = 0;
  /// Everything else; `regions` is filled from `region` against the geometry.
  JointSetParameters parameters;
};

/// `[[boundary]]`: fixed displacement components on a named curve or point.
struct BoundarySpec {
  /// Name of the Physical Curve (when is_curve) or Physical Point.
  std::string target;
  bool is_curve = true;
  /// Which components are fixed (at least one is true).
  bool fix_x = false;
  bool fix_y = false;
  /// `method`: exact elimination or Shi's stiff springs (stiffness from [analysis] penalty).
  SupportMethod method = SupportMethod::exact;
  /// Line of this `[[boundary]]` header in the case file.
  int line = 0;
  /// The `[[stage]]` it starts with (a `[[stage.boundary]]`), 0: from the start.
  int stage = 0;
};

/// `[[load]]`: one load with an optional linear ramp in time.
struct LoadSpec {
  LoadKind kind = LoadKind::gravity;
  /// Physical Point (kind point) or Physical Curve (traction, pressure) name; empty for
  /// gravity.
  std::string target;
  /// gravity (m/s^2), force (N) or traction (Pa), by kind; zero for pressure.
  Eigen::Vector2d vector = Eigen::Vector2d::Zero();
  /// Pa, positive pushes into the material; kind pressure only.
  double pressure = 0.0;
  /// Kind pressure: the water surface (m, a y coordinate); below it the pressure grows by
  /// water_unit_weight per metre of depth (added to `pressure`).
  std::optional<double> water_level;
  /// N/m^3.
  double water_unit_weight = 9810.0;
  /// Ramp (s): zero before ramp_start, linear to full at ramp_end, full after.
  /// Both 0 (the default) mean full from t = 0.
  double ramp_start = 0.0;
  double ramp_end = 0.0;
  /// Line of this `[[load]]` header in the case file.
  int line = 0;
  /// The `[[stage]]` it starts with (a `[[stage.load]]`), 0: from the start.
  int stage = 0;

  /// The fraction of the load applied at @p time (s): 0 before the ramp, 1 after it.
  [[nodiscard]] double factor_at(double time) const noexcept;
};

/// `[analysis]`: time stepping, contact and solver settings.
struct AnalysisSpec {
  AnalysisKind kind = AnalysisKind::dynamic;
  /// Number of time steps, 1..1e8. Required without `[[stage]]` tables; with them, not
  /// given and the sum of theirs.
  int steps = 0;
  /// Time step (s); empty for "auto" (chosen from max_step_displacement).
  std::optional<double> time_step;
  /// Line of `time_step` (or of `[analysis]`) in the case file, for later messages.
  int time_step_line = 0;
  /// Largest displacement in a step as a fraction of the model size (Shi's g2), (0, 0.5].
  double max_step_displacement = 0.01;
  /// Contact and penalty-boundary spring stiffness as a multiple of the largest Young's
  /// modulus (Shi's g0), > 0. Unused when penalty_stiffness is set.
  double penalty = 40.0;
  /// Absolute spring stiffness (N/m), > 0, instead of penalty.
  std::optional<double> penalty_stiffness;
  /// Deepest penetration a closed contact may keep (m), > 0: augmented-Lagrange passes
  /// (ContactOptions::penetration_tolerance); empty: the penalty springs alone.
  std::optional<double> penetration_tolerance;
  /// Most open-close iterations per step, 1..100; empty: the scene's budget
  /// (open_close_limit() in solver/open_close.hpp: 6 to 30).
  std::optional<int> open_close_max;
  LinearSolverKind solver = LinearSolverKind::cholmod;
  /// Residual over right-hand side at which a conjugate-gradient solve stops (solver = "pcg").
  double pcg_tolerance = 1e-10;
  /// With "pcg": the tolerance of the solves on which contacts' modes are decided (the
  /// last solve of an open-close iteration is to pcg_tolerance).
  double pcg_mode_tolerance = 1e-6;
  /// Energy balance residual over its largest term above which a step warns, (0, 1]
  /// (StepperOptions::energy_tolerance).
  double energy_tolerance = 0.05;
  /// ... and above which the run stops (>= energy_tolerance); empty: only the energy check.
  std::optional<double> energy_error_limit;
  /// Shi's dynamic ratio k01, (0, 1] (StepperOptions::velocity_ratio).
  double velocity_ratio = 1.0;
  /// Most times a step may be cut (to a third, or to fit max_step_displacement) before the
  /// run stops, 0..50.
  int max_step_cuts = 10;
  /// Stop when this time (s) is reached, even before `steps`; empty: run all steps.
  std::optional<double> end_time;
  /// Solve the loads at time 0 statically with every touching contact locked before the
  /// first step (TimeStepper::equilibrate()); displacements count from that state.
  bool initial_equilibrium = false;
  /// Not a case-file key: `nmm fos` sets it for its trials (StepperOptions::
  /// static_chatter_slides).
  bool static_chatter_slides = false;
};

/// `[[monitor]]`: a material point whose history goes to history.csv.
struct MonitorSpec {
  /// Unique, [A-Za-z0-9_]+ (a CSV column prefix).
  std::string name;
  /// Starting position (m); the monitor follows the material point that starts here.
  Point2 point = Point2::Zero();
  /// Line of this `[[monitor]]` header in the case file.
  int line = 0;
};

/// `[[bolt]]`: a rock bolt between two points, or along each gmsh curve of a Physical Curve
/// (docs/case-file.md, "[[bolt]]"; io/bolt_table.cpp reads it, io/scene_bolts.cpp places it).
struct BoltSpec {
  /// Unique, [A-Za-z0-9_]+ (the history.csv column `NAME.force`); default "bolt1", "bolt2"...
  /// in the order of the file. A curve of several gmsh curves makes NAME_1, NAME_2...
  std::string name;
  /// `from` and `to` (m), or the Physical Curve `curve` whose ends they are.
  std::optional<Point2> from;
  std::optional<Point2> to;
  std::string curve;
  BoltKind kind = BoltKind::end_anchored;
  /// `stiffness` (N/m, the whole bolt's axial stiffness) or `young` (Pa) x `area` (m^2):
  /// exactly one is given; axial_rigidity() makes EA of them.
  std::optional<double> stiffness;
  double young = 0.0;
  double area = 0.0;
  /// N, tension positive; |pretension| below the yield and rupture forces.
  double pretension = 0.0;
  /// N, > 0; infinity when absent.
  double yield_force = std::numeric_limits<double>::infinity();
  double rupture_force = std::numeric_limits<double>::infinity();
  /// Yielding over elastic stiffness, in [0, 1).
  double hardening = 0.0;
  /// Line of this `[[bolt]]` header in the case file.
  int line = 0;
  /// The `[[stage]]` it is installed with (a `[[stage.bolt]]`), 0: from the start.
  int stage = 0;

  /// EA (N) of a bolt of length @p length: young x area, or stiffness x length.
  [[nodiscard]] double axial_rigidity(double length) const {
    return stiffness ? *stiffness * length : young * area;
  }
};

/// `[[stage]]`: a part of the run with its own steps, analysis kind, excavation, and loads,
/// supports and bolts that start with it (docs/case-file.md, "[[stage]]").
struct StageSpec {
  /// Unique, [A-Za-z0-9_]+ (history.csv's `stage` column, summary.json's `stage`).
  std::string name;
  /// Time steps of the stage, 1..1e8.
  int steps = 0;
  /// `kind`; empty: `[analysis] kind`.
  std::optional<AnalysisKind> kind;
  /// `excavate`: Physical Surfaces whose material the stage removes, their tractions on the
  /// rest released over its steps.
  std::vector<std::string> excavate;
  /// `reset_displacement`: monitors, blocks.csv and the step files count displacements from
  /// the stage's start.
  bool reset_displacement = false;
  /// Line of this `[[stage]]` header in the case file.
  int line = 0;
};

/// `[in_situ]`: an initial stress growing with depth below a ground surface, given to every
/// material: sigma(y) = stress + gradient (surface - y), or with k0 syy = -unit_weight
/// (surface - y), sxx = k0 syy, sxy = 0 (docs/case-file.md, "[in_situ]").
struct InSituSpec {
  /// Line of the `[in_situ]` header in the case file.
  int line = 0;
  /// The y coordinate of the ground surface, m.
  double surface = 0.0;
  /// Horizontal over vertical stress, >= 0; empty: the components form.
  std::optional<double> k0;
  /// N/m^3, > 0 (k0 form only); empty: each material's density x |g| of the gravity loads.
  std::optional<double> unit_weight;
  /// Components form: sxx, syy, sxy at the surface (Pa) and their growth per metre of depth
  /// (Pa/m); tension positive.
  Eigen::Vector3d stress = Eigen::Vector3d::Zero();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

/// `[output]`.
struct OutputSpec {
  /// Output folder, resolved against the case file's folder.
  std::filesystem::path dir;
  /// Write the VTK files every this many steps, >= 1.
  int every = 1;
  /// Write a restart checkpoint every this many steps, >= 0; 0 = only when the run stops.
  int checkpoint_every = 0;
  /// `moved_threshold`: summary.json's `moved_blocks` lists the blocks whose centroid moved
  /// farther than this, >= 0, m; absent: no `moved_blocks` key.
  std::optional<double> moved_threshold;
};

/// The whole case file, every default applied (see docs/case-file.md).
struct CaseSpec {
  /// The case file as given to the reader, for messages ("case.toml:12: ...").
  std::filesystem::path file;
  /// The geometry (.geo or .msh), resolved against the case file's folder.
  std::filesystem::path geometry;
  /// Line of the `geometry` key, for messages about the geometry file.
  int geometry_line = 0;
  /// `geometry_time_limit`: the longest wall time (s) reading a .geo may take, > 0
  /// (GeometryReadOptions::time_limit).
  double geometry_time_limit = 60.0;
  std::string title;
  CoverMeshSpec cover_mesh;
  /// In the order of the case file.
  std::vector<MaterialSpec> materials;
  /// In the order of the case file.
  std::vector<JointSpec> joints;
  /// In the order of the case file.
  std::vector<JointSetSpec> joint_sets;
  /// Properties of every contact that is not on a named joint.
  JointProperties contact;
  /// Line of `[contact]`; 0 when the case has none.
  int contact_line = 0;
  std::vector<BoundarySpec> boundaries;
  std::vector<LoadSpec> loads;
  AnalysisSpec analysis;
  std::vector<MonitorSpec> monitors;
  /// In the order of the case file (those of `[[stage.bolt]]` after the others).
  std::vector<BoltSpec> bolts;
  /// In the order of the case file; empty: one stage of `[analysis] steps`.
  std::vector<StageSpec> stages;
  OutputSpec output;
  /// `[fos]`: the strength reduction of `nmm fos` (defaults when absent).
  FosSpec fos;
  /// `[in_situ]`, when the case has one (its field is in every MaterialSpec already).
  std::optional<InSituSpec> in_situ;
  /// Non-fatal remarks, each "file:line: what; why it may matter".
  std::vector<std::string> warnings;

  /// The material / joint called @p name, or nullptr.
  [[nodiscard]] const MaterialSpec* find_material(std::string_view name) const;
  [[nodiscard]] const JointSpec* find_joint(std::string_view name) const;
};

/// Reads and checks a case file; relative paths are resolved against its folder, and the
/// geometry file must exist.
/// @throws InputError "file:line:column: what is wrong; what to do" for the first problem.
[[nodiscard]] CaseSpec read_case_file(const std::filesystem::path& file);

/// As read_case_file() on @p text, with @p name_for_messages standing for the file (used in
/// messages and to resolve relative paths); does not look at the file system.
/// @throws InputError as read_case_file().
[[nodiscard]] CaseSpec parse_case_text(std::string_view text,
                                       const std::filesystem::path& name_for_messages);

} // namespace nmm
