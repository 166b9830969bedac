// SPDX-License-Identifier: MIT
// io/case_runner.hpp — from a case file to a running analysis and its outputs: the geometry
// read and every name of the case resolved against it, the math mesh, cover system, model,
// supports, loads and monitors, the time stepper, then the step loop writing the files of
// DESIGN.md "Contracts users see / Output". `nmm run`, `nmm check` and `nmm mesh` are thin
// layers over this header (io/cli.cpp).
#pragma once

#include "io/case_file.hpp"
#include "io/history.hpp"
#include "manifold/model.hpp"
#include "mesh/cover_system.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"
#include "solver/time_stepper.hpp"

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace nmm {

/// Receives one line about what is being done ("reading slope.geo", "cover system: ..."),
/// for the progress output of the command line. May be empty.
using PhaseCallback = std::function<void(std::string_view)>;

/// The geometry side of a case: all that `nmm mesh` needs.
struct CaseGeometry {
  PhysicalMesh physical;
  MathMesh math;
  CoverSystem covers;
  /// For each material region (PhysicalMesh::regions index), its CaseSpec::materials index.
  std::vector<int> region_material;
  /// PhysicalMesh::curves index of each `[joints.NAME]`, in CaseSpec::joints order.
  std::vector<int> joint_curves;
  /// Wall time of reading the geometry, making the math mesh and the cover system, s.
  double seconds_geometry = 0.0;
  double seconds_math_mesh = 0.0;
  double seconds_covers = 0.0;
};

/// Reads the geometry of @p spec (`read_physical_mesh` with `[cover_mesh] curve_tolerance`),
/// resolves the material and joint names, makes the math mesh (`[cover_mesh] kind`) and
/// builds the cover system. Looks only at `geometry`, `[cover_mesh]`, `[materials]` and
/// `[joints]`: the boundary, load and monitor names are not checked here.
/// @throws InputError "case.toml:LINE: ..." when a `[materials.X]` is not a Physical Surface
///         or a `[joints.X]` not a Physical Curve of the geometry (listing the names it
///         has), when a Physical Surface has no `[materials]` table, and whatever the gmsh
///         reader, the math mesh and the cover mesher throw.
[[nodiscard]] CaseGeometry build_case_geometry(const CaseSpec& spec,
                                               const PhaseCallback& on_phase = {});

/// A case ready to run: geometry, model, supports, loads, monitors and the time stepper,
/// every name of the case resolved. Neither copyable nor movable (the stepper holds the
/// model by reference).
class CaseAnalysis {
public:
  /// Builds everything; runs no step and writes no file.
  /// @throws InputError "case.toml:LINE: what; what to do" for every problem of the case
  ///         against the geometry: all of build_case_geometry(); a `dda` or `vem` block with fewer
  ///         than 3 vertices or no area; a `[[boundary]]` or
  ///         `[[load]]` target that is not a Physical Curve / Physical Point of the right kind or
  ///         that misses the material; a support point, point load or `[[monitor]]` outside the
  ///         material; a body that nothing holds in a static analysis (naming its material).
  /// @param strength_factor  every joint's and [contact]'s strength divided by it
  ///                         (reduced_strength(); `nmm fos`), > 0; 1: the case's own.
  explicit CaseAnalysis(CaseSpec spec,
                        const PhaseCallback& on_phase = {},
                        double strength_factor = 1.0);
  ~CaseAnalysis();
  CaseAnalysis(const CaseAnalysis&) = delete;
  CaseAnalysis& operator=(const CaseAnalysis&) = delete;
  CaseAnalysis(CaseAnalysis&&) = delete;
  CaseAnalysis& operator=(CaseAnalysis&&) = delete;

  [[nodiscard]] const CaseSpec& spec() const noexcept { return spec_; }
  [[nodiscard]] const CaseGeometry& geometry() const noexcept { return geometry_; }
  [[nodiscard]] const Model& model() const noexcept { return model_; }
  [[nodiscard]] TimeStepper& stepper() noexcept { return *stepper_; }
  [[nodiscard]] const TimeStepper& stepper() const noexcept { return *stepper_; }
  /// Where each monitor started (CaseSpec::monitors order), for total displacements.
  [[nodiscard]] const std::vector<Point2>& monitor_starts() const noexcept {
    return monitor_starts_;
  }
  /// The case file's warnings, then the geometry reader's and the cover mesher's (prefixed
  /// with the geometry file).
  /// The stepper's own warnings come later (TimeStepper::warnings()).
  [[nodiscard]] const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  /// Every bolt of the case, those of later stages included, in the order the stages add
  /// them to the scene (history.csv's columns).
  [[nodiscard]] const std::vector<std::string>& bolt_names() const noexcept { return bolt_names_; }
  /// The current values of every monitor (CaseSpec::monitors order).
  [[nodiscard]] std::vector<MonitorValues> monitor_values() const;
  /// `[analysis] initial_equilibrium`: TimeStepper::equilibrate(), then the monitors count
  /// their displacement from the settled state. Before the first step.
  void equilibrate();
  /// A restart: the monitors' starts of the interrupted run. @pre one per monitor.
  void restore_monitor_starts(std::vector<Point2> starts);
  /// The start of `[[stage]]` @p stage (CaseSpec::stages index): its analysis kind, its
  /// supports, loads and bolts (those of stage 0 are in the scene from the start), and its
  /// excavation, whose elements then release all of their loads and the forces of their
  /// contacts with the rest (set_release()).
  void begin_stage(int stage);
  /// The fraction of their loads and contact forces the elements the current stage excavates
  /// still apply, in [0, 1] (1 at its start, 0 by its last step).
  void set_release(double left);
  /// `reset_displacement`: the monitors count their displacement from where they are now.
  void reset_monitor_starts();

private:
  [[nodiscard]] std::unique_ptr<ContactSystem> make_contact_system(double penalty) const;
  /// The supports, loads and bolts that start with stage @p stage (0: with the run), those
  /// loads' ramps counted from @p start_time (s).
  [[nodiscard]] Scene stage_scene(int stage, double start_time) const;
  /// @throws InputError for a `[[stage]] excavate` that is no Physical Surface, that an
  ///         earlier stage excavates already, or stages that excavate all the material.
  ///         Warns of a release over several steps on order-1 covers of a regular mesh.
  void refuse_bad_excavations();
  /// Warnings about scales that the case file alone cannot judge (docs/case-file.md,
  /// "Checks across tables and warnings"): a fixed time step longer than Shi's for
  /// max_step_displacement, nmm blocks much smaller than the math triangles, a model so far
  /// from the origin (its material's bounding box @p box) that its coordinates lose digits.
  void add_scale_warnings(const BoundingBox& box, double model_size);
  /// A warning for every Physical Curve that runs through the inside of a block but is no
  /// joint, [[boundary]] or [[load]] of the case: a joint the case forgot does not cut.
  void add_unused_curve_warnings();

  CaseSpec spec_;
  double strength_factor_ = 1.0;
  CaseGeometry geometry_;
  Model model_;
  std::vector<Point2> monitor_starts_;
  std::vector<std::string> warnings_;
  double model_size_ = 1.0; ///< of the material's bounding box, m
  std::vector<std::string> bolt_names_;
  /// The elements the current stage excavates (set_release()).
  std::vector<int> releasing_;
  std::unique_ptr<TimeStepper> stepper_;
};

/// How run_case() ended when it returns normally (a failure throws).
enum class RunStatus { completed, interrupted };

/// Step cuts by reason (StepReport::cuts_open_close ...).
struct CutCounts {
  long open_close = 0;   ///< the open-close iteration did not converge
  long displacement = 0; ///< the step moved further than the step displacement limit
  long energy = 0;       ///< the energy check
  long not_finite = 0;   ///< a step displacement was not finite
  [[nodiscard]] long total() const noexcept {
    return open_close + displacement + energy + not_finite;
  }
  /// Adds the cuts of the step @p report.
  void add(const StepReport& report) noexcept {
    open_close += report.cuts_open_close;
    displacement += report.cuts_displacement;
    energy += report.cuts_energy;
    not_finite += report.cuts_not_finite;
  }
};

/// One completed step, for a progress display.
struct RunProgress {
  const StepReport* report = nullptr;
  /// `[analysis] steps`.
  long steps = 0;
  /// `[analysis] end_time`, or +infinity.
  double end_time = 0.0;
  /// Since run_case() started, s.
  double wall_seconds = 0.0;
  /// Step cuts so far (those before a restart included).
  long step_cuts = 0;
  /// The cuts of the steps since run_case() started, by reason (a restart does not know the
  /// reasons of the cuts before it: they are step_cuts - cuts.total()).
  CutCounts cuts;
  /// Simulated time and step when run_case() started (0, or the checkpoint's), s.
  double start_time = 0.0;
  long start_step = 0;
  /// The energy balance's part of the state line (ProgressPrinter), already formatted; empty:
  /// the state line has none. Left empty by run_case() until the run has an energy balance.
  std::string energy_balance;
};

/// Options of run_case().
struct RunOptions {
  /// Output folder; empty: `[output] dir` of the case. Created when missing.
  std::filesystem::path output_dir;
  /// When set and it becomes true (a signal handler sets it on Ctrl-C), the run stops after
  /// the current step, writes the last step, the .pvd and summary.json (status
  /// "interrupted") and returns RunStatus::interrupted.
  const std::atomic<bool>* stop = nullptr;
  /// Called after every step (for the progress line); may be empty.
  std::function<void(const RunProgress&)> on_step;
  /// Called with each warning that arises when the run starts, before its first step (a
  /// case file edited since the checkpoint of a restart), so that it is seen then and not
  /// only in the closing summary; may be empty. RunResult::warnings lists them too.
  std::function<void(const std::string&)> on_warning;
  /// Wall time already spent before run_case() (reading the case, building the model), s;
  /// counted in summary.json's wall_seconds.
  double seconds_before = 0.0;
  /// Continue the run whose output folder this is from its checkpoint.nmm (`nmm run CASE
  /// --restart DIR`): the steps after it are taken again, exactly as the interrupted run
  /// would have taken them; history.csv, case.pvd and the step files are continued.
  bool restart = false;
};

/// What run_case() did.
struct RunResult {
  RunStatus status = RunStatus::completed;
  long steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  long step_cuts = 0;
  /// Deepest penetration of a closed contact at the end of any step, m.
  double max_penetration = 0.0;
  /// Steps that ended with a contact held locked beyond its friction limit, and the largest
  /// shear over limit among them (StepperCounters).
  long locks_beyond_friction = 0;
  double max_lock_excess = 0.0;
  /// Steps that ended with a contact held sliding at its friction limit against a motion that
  /// turned back, and the work of that friction along those motions, J (StepperCounters).
  long slides_against_motion = 0;
  double slide_feed_work = 0.0;
  /// Linear solves, and of them by conjugate gradients ([analysis] solver = "pcg"): their
  /// iterations and the solves left to CHOLMOD (SolverCounters).
  long solves = 0;
  long cg_iterations = 0;
  long cg_fallbacks = 0;
  /// Work of the loads at the last step run (StepReport::load_work), J; 0 when none ran.
  double load_work = 0.0;
  std::filesystem::path output_dir;
  /// Number of step files written.
  long output_steps = 0;
  /// Every warning of the run (as in summary.json).
  std::vector<std::string> warnings;
};

/// Runs the analysis: `[analysis] steps` steps, stopping early at `[analysis] end_time`.
/// Writes into the output folder (docs/output.md): `step_NNNNNN.vtu` at step 0, every
/// `[output] every` steps and at the last step; `case.pvd`, rewritten after each of them;
/// `history.csv`, one row per step, flushed each row; `summary.json` with status "running"
/// at the start and the final status at the end; `checkpoint.nmm` every `[output]
/// checkpoint_every` steps and when the run stops (completed or interrupted; a failed
/// step leaves the last one). Step and contact files and the checkpoint of an earlier run
/// in the folder are removed first so that the folder holds one run, except with
/// RunOptions::restart, which continues them from the checkpoint's step.
/// @pre run_case() was not called on @p analysis before.
/// The folder is locked (output_lock_file_name) for the run.
/// @throws InputError naming the folder when it cannot be created or written, when another
///         run holds its lock, when a folder in it has the name of a file the run writes
///         (`checkpoint.nmm`, ...), or the checkpoint when a restart cannot continue from it
///         (read_checkpoint()).
/// @throws NumericalError (or anything else) when a step fails; the last completed step,
///         the .pvd and summary.json (status = the error message) are written first.
RunResult run_case(CaseAnalysis& analysis, const RunOptions& options);

/// What a run's contacts did that its user must know, as warnings with what to do (listed at
/// the end and in summary.json): locks the chatter rule held beyond Coulomb's law at the end
/// of a step (a static answer that calls standing what slides); penetration beyond a tenth of
/// the step displacement limit @p step_limit (max_step_displacement x model size, m: the
/// entrance theory assumes contacts that close within a step's small motion); more than one
/// step in ten cut (and more than ten).
[[nodiscard]] std::vector<std::string>
contact_warnings(const StepperCounters& counters, double max_penetration, double step_limit);

/// The file in the output folder that run_case() locks (flock) while it runs: a second run
/// into the same folder is refused. It stays in the folder and holds the last locker's
/// process id.
inline constexpr const char* output_lock_file_name = ".nmm.lock";

/// Creates @p dir (and its parents) when missing.
/// @throws InputError naming the folder when it cannot be created or is a file.
void create_output_dir(const std::filesystem::path& dir);

/// The output folder run_case() uses for @p options: options.output_dir or `[output] dir`.
[[nodiscard]] std::filesystem::path output_dir_of(const CaseSpec& spec, const RunOptions& options);

} // namespace nmm
