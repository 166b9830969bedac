// SPDX-License-Identifier: MIT
// contact/contact_system.hpp — contact points, their springs and friction, the open-close
// decisions and the transfer of closed contacts to the next step (Shi 1997, chapters 3.3-3.6,
// 6.2-6.5 and 8.2; Mohr-Coulomb joints with cohesion and tensile strength).
#pragma once

#include "contact/contact_point.hpp"
#include "contact/detection.hpp"
#include "contact/joint_law.hpp"
#include "contact/key_set.hpp"
#include "contact/lift_off.hpp"
#include "manifold/model.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace nmm {

/// The boundary loops of @p model flattened for detection, loop after loop (vertex k of loop
/// l is the edge from it to the next vertex), with the block areas as meshed.
[[nodiscard]] ContactBoundary contact_boundary(const Model& model);

/// Settings of the contact system.
struct ContactOptions {
  /// Normal and shear spring stiffness of an angle-to-edge contact (Shi's p), N/m.
  double penalty = 0.0;
  /// Length over which one point spring's stiffness is spread for edge-to-edge contacts:
  /// they get penalty / spring_length per unit length, so an edge pair of that length is as
  /// stiff as one of Shi's point springs, m. The cover size is the natural choice.
  double spring_length = 1.0;
  /// Contact detection criteria (the distance is set every step from the step displacement).
  DetectionOptions detection;
  /// prepare_kinematics() splits its points (and pairs) among threads only when each thread
  /// gets at least this many: below, starting a thread costs more than it saves. The
  /// results are the same either way.
  std::size_t parallel_min_chunk = 2048;
  /// A contact that has switched between open and closed this many times within a step
  /// stays open for the rest of it; one that has switched between lock and slide this many
  /// times stays locked: the chatter rule (docs/formulation.md).
  int chatter_limit = 3;
  /// Friction is a load computed from the normal forces of the last iteration (so that the
  /// matrix stays symmetric); the iteration continues until the work of the friction change
  /// since then is below this fraction of the work of all friction in the step: Coulomb's
  /// law holds within the step, not one iteration late.
  double friction_tolerance = 1e-5;
  /// An edge-to-edge contact has springs only where the edges press on each other; the
  /// iteration continues until the force the springs would take where the edges newly press
  /// is below this fraction of all contact force ...
  double lift_off_tolerance = 1e-4;
  /// ... and the springs left where the edges no longer press pull with less than this
  /// fraction (tension adds to the normal force elsewhere, and so to friction).
  double tension_tolerance = 1e-6;
  /// A contact whose lift-off point went back settles: it then only gives up springs that
  /// pull. When the part it leaves out would take more force than the contact bears, its
  /// lift-off points search for the place between their last two (false position) for at
  /// most this many moves in a step, and then it settles for good (docs/formulation.md,
  /// "Lift-off").
  int lift_off_searches = 4;
  /// Augmented Lagrange (Lin, Amadei, Jung and Dwyer 1996; Simo and Laursen 1992): when a
  /// converged open-close iteration leaves a closed contact penetrating by more than this,
  /// every closed spring's zero moves by its penetration (its force so far becomes a
  /// multiplier carried as a load) and the step is solved again with the same matrix (until
  /// the modes change), until no contact penetrates by more: towards the contacts of the hard
  /// limit of the penalty, at the conditioning of a moderate one. 0: the penalty springs
  /// alone (Shi), m.
  double penetration_tolerance = 0.0;
  /// Most augmented-Lagrange passes in a step; a step still penetrating by more after them
  /// goes on as it is (its penetration is reported).
  int augment_max = 10;
};

/// What one open-close iteration found.
struct ModeUpdate {
  int changes = 0; ///< contacts whose mode or lift-off point changed (the matrix changes)
  /// Of the changes, closed edge-to-edge contacts whose springs only moved along their
  /// overlap (the lift-off point converging), not opening, closing, sticking or slipping.
  int moves = 0;
  /// Work of the change of the friction forces since they were applied, over the work of
  /// all friction in the step (0 when nothing slides).
  double friction_residual = 0.0;
  /// Largest shear over friction limit of the locks this update holds beyond their limit
  /// (the chatter rule at the limit of friction) by more than lift_off_tolerance of all
  /// contact force, 0 when every lock is within friction or beyond it by a negligible force.
  double lock_excess = 0.0;
  /// Work of the friction of the contacts this update holds sliding at their limit (the
  /// chatter rule in a dynamic step) along motions that turned back against it, J: what that
  /// friction feeds in where Coulomb's law would stick; 0 when none turned back by more than
  /// the rounding with a friction force above lift_off_tolerance of all contact force.
  double slide_feed = 0.0;
};

/// What the chatter rule holds at the limit of friction in a state of the contacts
/// (ModeUpdate::lock_excess and slide_feed of the update that made it).
struct FrictionHolds {
  double lock_excess = 0.0;
  double slide_feed = 0.0;
};

/// Counters for summary.json and benchmarks.
struct ContactCounters {
  long points = 0; ///< summed over steps
  long chatter_holds = 0;
  long bonds_broken = 0;
  DetectionStats detection;
};

/// All contacts of the model during a step.
class ContactSystem {
public:
  /// @param strength_of_edge  strength of every boundary edge's surface (its joint set's
  ///                          or the [contact] default), indexed by loop then edge.
  /// @param bonded_edge       whether an edge is a face of an intact joint
  ContactSystem(ContactOptions options,
                std::vector<std::vector<JointStrength>> strength_of_edge,
                std::vector<std::vector<bool>> bonded_edge);

  /// Whether the model can have any contact at all (two blocks, or a joint face): when not,
  /// the stepper skips detection entirely.
  [[nodiscard]] static bool can_touch(const Model& model);

  /// Detects the contacts of the step (Shi's criteria, distance = 2 x max step displacement)
  /// and carries the states of the contacts closed at the end of the last step.
  void begin_step(const Model& model, double max_step_displacement);

  [[nodiscard]] const std::vector<ContactPoint>& points() const noexcept { return points_; }
  [[nodiscard]] int n_points() const noexcept { return static_cast<int>(points_.size()); }
  /// Raw unknowns coupled by point i (slave and master elements, without repeats); the same
  /// for the whole step.
  [[nodiscard]] std::vector<int> point_dofs(const Model& model, int i) const;
  /// point_dofs(i) appended to @p out (no allocation of its own).
  void append_point_dofs(const Model& model, int i, std::vector<int>& out) const;

  /// Springs and friction loads of point i in its current mode, on point_dofs(i); the loads
  /// only when @p stiffness is null (an iteration that keeps the factor: friction changed).
  /// With @p upper, only the upper triangle of the springs' matrix (the rest is zero): what an
  /// Assembler reads.
  /// @return whether a friction load that follows the normal force was assembled (a bond's
  /// cohesion alone, a constant load, is none).
  bool contribution(const Model& model,
                    int i,
                    Eigen::MatrixXd* stiffness,
                    Eigen::VectorXd& load,
                    bool upper = false) const;

  /// After a solve with step displacement @p raw: new modes by Shi's mode table, new lift-off
  /// points and new friction loads.
  ModeUpdate update_modes(const Model& model, const Eigen::VectorXd& raw);
  /// Computes the kinematics of every contact point and of every gap sample of an
  /// edge-to-edge pair as they are (on worker_threads() threads when there are many): what
  /// point_dofs(), the springs and update_modes() would compute one by one, the same numbers.
  void prepare_kinematics(const Model& model) const;
  /// After a converged open-close iteration: when ContactOptions::penetration_tolerance is
  /// set and a closed contact penetrates by more (or pushes across a wider gap), moves every
  /// closed spring's zero by its penetration (ContactPoint::shift, an
  /// augmented-Lagrange update: the matrix stays, the loads change) and returns true: the
  /// step is to be solved again. False when nothing penetrates by more (or it is not set).
  /// The penetrations are those update_modes() measured after the solve @p raw. The converged
  /// contacts and @p raw are kept for back_to_converged() when they penetrate less than those
  /// kept before in this try of the step. When the last pass left the deepest contact no
  /// shallower than the kept state, the passes stop: the contacts and @p raw go back to that
  /// state and it returns false (the step ends there).
  bool augment(Eigen::VectorXd& raw);
  /// Back to the least penetrating converged state augment() kept (contacts and step
  /// displacement, into @p raw), when the iteration after a pass does not converge: the step
  /// keeps that solve, whose springs balanced the loads, instead of being cut. False (the
  /// step is to be cut) when no pass ran in this try of the step, or when that state
  /// penetrates by more than fallback_depth times the tolerance.
  bool back_to_converged(Eigen::VectorXd& raw);
  /// How far past the penetration tolerance a solve back_to_converged() returns to may be.
  static constexpr double fallback_depth = 2.0;

  /// Whether @p update ends the open-close iteration: no mode changed and friction agrees
  /// with the normal forces. When only the friction residual is left, the matrix is the same
  /// and the next solve can reuse its factor.
  [[nodiscard]] bool converged(const ModeUpdate& update) const noexcept {
    return update.changes == 0 && update.friction_residual <= options_.friction_tolerance;
  }

  /// Back to the contacts as begin_step() left them (modes, springs, anchors, broken bonds):
  /// a cut step starts its open-close iteration again from the state at the start of the
  /// step. What a failed try with the longer step reached (a pressed part shrunk to a sliver,
  /// a lock anchored by that step's motion) is no guide for the shorter one.
  void restart_step();

  /// While set, closed contacts lock and never slide (the initial equilibrium: the shear
  /// springs take what friction could not); for the step begun last.
  void set_hold_shear(bool hold);
  /// While set, set_hold_shear(true) also ties every touching contact (of some length):
  /// bonded, with no limit to its tension, its springs along the whole overlap. The initial
  /// equilibrium of a body that only tension or a tipping motion resolves (a block hanging
  /// under a ceiling, a tall block that must topple) is then a solve of an elastic system
  /// instead of a mechanism (TimeStepper::equilibrate()).
  void set_tie(bool tie) noexcept { tie_ = tie; }
  /// After a solve with the contacts tied: a description of the first pair of blocks whose
  /// tied contacts pull on each other with more, net, than their bonds' tensile strength
  /// holds (tensile_strength times the length in contact; nothing without a bond), or
  /// empty. Such a pair is held together by nothing but that tension.
  [[nodiscard]] std::string untenable_tension(const Model& model) const;

  /// What the chatter rule holds at the limit of friction in the contacts as they are: those
  /// of the last update_modes(), or of the converged solve that augment() or
  /// back_to_converged() went back to; none after begin_step() or restart_step().
  [[nodiscard]] FrictionHolds holds() const noexcept { return holds_; }

  /// Whether a contact at the chatter limit of friction slides at its limit for the rest of
  /// the step begun last instead of being held locked beyond it (docs/formulation.md,
  /// "Chatter rule"): in a dynamic step (its velocities carry on), and in the static steps of
  /// a strength-reduction trial (StepperOptions::static_chatter_slides).
  void set_chatter_slides(bool slides);

  /// While set, the friction of a sliding contact is no load from the normal force of the
  /// last iteration: it is coupled to the normal force of the solve itself. contribution()
  /// leaves it out, friction_coupling() gives it as a term of rank one of the step matrix,
  /// and update_modes() measures its consistency against the springs' resultant
  /// (docs/formulation.md, "Coupled friction"). Off after begin_step().
  void set_coupled_friction(bool coupled) noexcept { coupled_friction_ = coupled; }

  /// The friction of one sliding contact coupled to its normal force. With the step
  /// displacement d on the unknowns point_dofs(point), the contact's normal force is
  /// N = -(c0 + a . d) (compressive positive) and its friction acts as the load
  /// coef (c0 + a . d) w = -sign tan(phi) N w: the matrix gains the unsymmetric term
  /// -coef w a^T and the load coef c0 w (Shi eq. 3.27-3.33 with N of the same solve).
  struct FrictionCoupling {
    int point = 0;     ///< the contact's first point
    double coef = 0.0; ///< slide sign x tan(friction angle)
    double c0 = 0.0;   ///< -N at d = 0, N
    Eigen::VectorXd w; ///< the points' shear directions, each by its share of the springs
    Eigen::VectorXd a; ///< the springs' normal directions times their stiffnesses
  };
  /// The coupled friction of every sliding contact with friction (empty unless
  /// set_coupled_friction(true)); a contact that just closed has it too: its normal force is
  /// that of the solve, not the penetration it reached while open.
  [[nodiscard]] std::vector<FrictionCoupling> friction_coupling(const Model& model) const;

  /// Stores the closed contacts (and their anchors, forces, bonds) for the next step; to be
  /// called with the step's final displacement, before the model moves.
  void end_step(const Model& model, const Eigen::VectorXd& raw);

  /// Writes what carries over to the next step (the closed contacts' states, broken bonds,
  /// counters) for a restart checkpoint; call between steps.
  void save_state(StateWriter& out) const;
  /// Reads what save_state() wrote; the next begin_step() continues from it.
  void load_state(StateReader& in);

  /// Closed contact points now.
  [[nodiscard]] int n_closed() const;
  /// Closed contact points sliding now (ContactMode::slide).
  [[nodiscard]] int n_sliding() const;
  /// The block of boundary edge @p edge (a ContactPoint's slave_edge or master), as
  /// begin_step() numbered the boundary; -1 for an edge it does not have.
  [[nodiscard]] int edge_block(int edge) const noexcept {
    return edge >= 0 && edge < boundary_.n_vertices()
               ? boundary_.block[static_cast<std::size_t>(edge)]
               : -1;
  }
  /// Largest penetration of the springs of a closed contact after the last solve (offset -
  /// gap: an angle contact found already penetrating counts from its offset), m.
  [[nodiscard]] double max_penetration() const;
  /// The springs' energy in the step of displacement @p raw (raw unknowns), J: at its start and
  /// end, and what the springs lost or made in it (docs/formulation.md, "Energy balance").
  struct SpringWork {
    double start = 0.0; ///< energy of the springs at the start of the step
    double end = 0.0;   ///< after the last solve
    double lost = 0.0;  ///< dissipated by the time integration and by springs that let go
    double made = 0.0;  ///< made by springs that started stretched while open
  };
  /// Of the points' springs in the modes begin_step() gave them and in their modes now: p g^2 / 2
  /// of every closed normal spring and p s^2 / 2 of every locked shear spring, p the point's
  /// stiffness (for edge-to-edge pairs the Gauss point's share of the integrated springs),
  /// g and s its gap and shear displacement. Call before end_step().
  [[nodiscard]] SpringWork spring_work(const Model& model, const Eigen::VectorXd& raw) const;
  /// Work of friction in the step of displacement @p raw (raw unknowns): |S| times the
  /// slip of every sliding contact point, J. Call before end_step().
  [[nodiscard]] double friction_dissipation(const Model& model, const Eigen::VectorXd& raw) const;
  [[nodiscard]] const ContactCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const ContactOptions& options() const noexcept { return options_; }
  /// Where a point is now, in the model's current geometry (after the step's move), and the
  /// outward unit normal of its master edge there.
  struct Place {
    Point2 position = Point2::Zero(); ///< the slave material point
    Point2 normal = Point2::Zero();
  };
  /// The Place of every point, for output.
  [[nodiscard]] std::vector<Place> current_places(const Model& model) const;
  /// A force on a material point, N (per metre of thickness in plane strain).
  struct PointForce {
    MaterialPoint point;
    Point2 force = Point2::Zero();
  };
  /// The forces with which the last step's contacts between material just excavated
  /// (ModelElement::excavated, set since that step) and material left press and pull on the
  /// material left, each at its material point where it acts (the slave point, or its
  /// projection on the master edge), in the model's current geometry: what the excavation
  /// takes off the rest at those contacts, for a stage to release over its steps.
  [[nodiscard]] std::vector<PointForce> forces_of_excavated(const Model& model) const;
  /// A description of point i for messages ("vertex (x, y) against edge (x1, y1)-(x2, y2)").
  [[nodiscard]] std::string describe(int i) const;
  /// The point of the contact that changed last in the open-close iteration (for the message
  /// of a step that does not converge), or 0.
  [[nodiscard]] int last_changed() const noexcept { return last_changed_; }

private:
  /// The linearised kinematics of one contact point (Shi 3.4-3.5; eq. 3.12-3.16, 3.21-3.24):
  /// normal gap g = g0 + hn . d and shear displacement s = s0 + hs . d on the coupled
  /// unknowns.
  struct Kinematics {
    std::vector<int> dofs;
    Eigen::VectorXd hn;
    Eigen::VectorXd hs;
    double g0 = 0.0;
    double s0 = 0.0;

    [[nodiscard]] double gap(const Eigen::VectorXd& raw) const {
      double g = g0;
      for (std::size_t j = 0; j < dofs.size(); ++j)
        g += hn(static_cast<Eigen::Index>(j)) * raw(dofs[j]);
      return g;
    }
    [[nodiscard]] double tangential(const Eigen::VectorXd& raw) const {
      double s = 0.0;
      for (std::size_t j = 0; j < dofs.size(); ++j)
        s += hs(static_cast<Eigen::Index>(j)) * raw(dofs[j]);
      return s;
    }
  };
  /// Kinematics of a point, kept with what they were computed from: a point's are used by
  /// its springs, its mode decision, its lift-off gaps and the transfer, several times per
  /// open-close iteration, and change only when the point moves (lift-off) or re-anchors.
  struct CachedKinematics {
    std::uint64_t stamp = 0; ///< kinematics_stamp_ of the step they are of (0: none)
    int slave_edge = -1;
    int master = -1;
    Point2 slave = Point2::Zero();
    double anchor = 0.0;
    double offset = 0.0;
    double shift = 0.0;
    Kinematics kinematics;
  };
  /// A contact: one angle point, or the Gauss points of one edge-to-edge pair, deciding
  /// their mode together.
  struct Group {
    std::uint64_t key = 0;
    bool edge = false;
    int first = 0; ///< first point
    int count = 0; ///< points
    /// Edge-to-edge: the overlap with the master on the slave edge (parameters u), the part
    /// of it with springs (where the edges press on each other), and the projections of the
    /// slave edge's ends on the master from its first vertex.
    double lo = 0.0;
    double hi = 1.0;
    double from = 0.0;
    double to = 1.0;
    double t_first = 0.0;
    double t_next = 0.0;
    /// The two ends of the part with springs as the lift-off iteration moves them.
    LiftOffEnd from_end;
    LiftOffEnd to_end;
    /// The contact made its first move back (it then only gives up springs that pull) ...
    bool settled = false;
    /// ... unless the part it leaves out would take more than its whole normal force: then
    /// its ends search (LiftOffEnd), for ContactOptions::lift_off_searches moves at most.
    bool searching = false;
    int searches = 0;
    /// The shear springs' pre-shear of an in-situ angle contact (in_situ_traction()), m: its
    /// point's anchor sits this far behind its slave point along the master when the contact
    /// locks new (an edge pair's points each take the traction at their own place:
    /// edge_preload()).
    double in_situ_shear = 0.0;
    /// The in-situ pre-compression (ContactPoint::shift) at the two ends of an edge pair's
    /// overlap (lo, hi), and an angle contact's (both the same), m: whether it touches.
    std::array<double, 2> in_situ_shift{};
    /// Ends the search (its brackets hold for this overlap and these springs only).
    void stop_search() noexcept {
      searching = false;
      from_end.bracketed = false;
      to_end.bracketed = false;
    }
  };
  /// State of a closed contact carried to the next step.
  struct Carried {
    int slave = -1;
    int master = -1;
    ContactMode mode = ContactMode::open;
    int slide_sign = 0;
    double normal = 0.0; ///< resultant normal force
    double offset = 0.0; ///< ContactPoint::offset of an angle contact
    /// (u, anchor) of every point, the anchors of a locked pair as a function of the slave
    /// material point: carried_anchors_[first_anchor ... first_anchor + n_anchors).
    int first_anchor = 0;
    int n_anchors = 0;
  };
  /// The state carried under @p key, or null.
  [[nodiscard]] const Carried* carried_at(std::uint64_t key) const;
  /// The anchors of a carried state.
  [[nodiscard]] std::span<const std::pair<double, double>> anchors_of(const Carried& state) const;
  /// Stores @p state with @p anchors under @p key (replacing what a key carried already).
  void carry(std::uint64_t key, Carried state, std::span<const std::pair<double, double>> anchors);
  /// Forgets every carried state (keeping the storage).
  void clear_carried();
  /// A carried contact by one of its edges.
  struct ByEdge {
    int edge;
    std::uint64_t key;
    const Carried* state;
  };
  /// The carried contacts sorted by slave edge and by master edge, and for one edge by
  /// decreasing key.
  struct CarriedByEdge {
    std::vector<ByEdge> slave;
    std::vector<ByEdge> master;
  };
  /// CarriedByEdge of the carried contacts @p keep (their keys, increasing).
  [[nodiscard]] CarriedByEdge carried_by_edge(const std::vector<std::uint64_t>& keep) const;
  /// The carried state of the contact @p key of @p slave against @p master (an edge pair if
  /// @p edge): its own, or one the contact takes over (Shi 3.3), or null; *identical tells
  /// whether its anchors and offset refer to this pair.
  [[nodiscard]] const Carried* carried_state(const CarriedByEdge& carried,
                                             std::uint64_t key,
                                             int slave,
                                             int master,
                                             bool edge,
                                             bool* identical) const;

  /// Workspaces of kinematics(): where each unknown sits, the columns and the interpolation
  /// of one point, the terms before they are cut to the unknowns used.
  struct KinematicsWork {
    std::vector<Eigen::Index> local;
    std::vector<int> columns;
    PointInterpolation t;
    PointInterpolation t_master;
    std::vector<int> master_columns;
    std::vector<double> hn;
    std::vector<double> hs;
  };
  /// The kinematics of @p p into @p k (its storage reused: a slot's are computed many times
  /// a step), with the workspace @p work.
  void
  kinematics(const Model& model, const ContactPoint& p, Kinematics& k, KinematicsWork& work) const;
  struct Term;
  struct PointTerms;
  /// The terms of kinematics() summed into @p k when the two elements' unknowns are apart
  /// (each element's follow in the order of their interpolations' columns) ...
  static void kinematics_apart(const PointTerms& terms, Kinematics& k, KinematicsWork& work);
  /// ... and when they may share unknowns (each looked up where it is first used).
  static void kinematics_shared(const PointTerms& terms, Kinematics& k, KinematicsWork& work);
  /// cached_kinematics() of slot @p slot with the workspace @p work.
  const Kinematics& cached_kinematics(const Model& model,
                                      const ContactPoint& p,
                                      std::size_t slot,
                                      KinematicsWork& work) const;
  /// The kinematics of gap sample @p sample of edge group @p g (0 at lo, 1 in the middle,
  /// 2 at hi) through its cache slot, with the multiplier interpolated from @p shifts
  /// (shifts_of(g), taken once for the group's samples), with the workspace @p work.
  const Kinematics& sample_kinematics(const Model& model,
                                      const Group& g,
                                      int sample,
                                      const std::vector<std::pair<double, double>>& shifts,
                                      KinematicsWork& work) const;
  /// kinematics(model, p) through slot @p slot of the cache (slots: the points, then three
  /// gap samples per group); the same numbers, computed again only when p's slave point,
  /// edges, anchor, offset or shift differ from the slot's.
  [[nodiscard]] const Kinematics&
  cached_kinematics(const Model& model, const ContactPoint& p, std::size_t slot) const;
  /// The shape of @p element at the start of the step (built by begin_step() for the
  /// elements of every contact point's edges).
  [[nodiscard]] const ElementShape& shape(int element) const;
  /// Normal gap at gap sample @p sample of edge group @p g (sample_kinematics()) after the
  /// step displacement @p raw.
  [[nodiscard]] double gap_at(const Model& model,
                              const Group& g,
                              int sample,
                              const std::vector<std::pair<double, double>>& shifts,
                              const Eigen::VectorXd& raw) const;
  /// Places the Gauss points of edge group g on [from, to], anchored where the slave points
  /// project on the master, shifted by the shear offsets @p offsets interpolated at their u
  /// (offset_at()) when given.
  void
  place(Group& g, double from, double to, const std::vector<std::pair<double, double>>* offsets);
  /// What update_modes() found of an edge-to-edge contact whose springs may move to where
  /// its edges press (docs/formulation.md, "Lift-off").
  struct LiftOff {
    int group = 0;
    OverlapPart part;
    bool just_closed = false;
    double pulling = 0.0; ///< force of the springs on parts that no longer press (tension)
    double pushing = 0.0; ///< force the springs would take on parts that now press
    /// force of the springs over the whole overlap stretched by the rounding
    double spring_noise = 0.0;
    double bearing = 0.0; ///< the pair's normal force (its springs that push)
  };
  /// The part of group @p l.group that is to have springs, or none when they stay: the
  /// pressed part, or the next place of a search, or the pressed part within the springs'
  /// (a settled contact), by the forces of @p l against all contact force @p total_normal.
  [[nodiscard]] OverlapPart lift_off_part(const LiftOff& l, double total_normal);
  /// Moves the springs of the group of @p l to @p part (anchors, multipliers and normal
  /// forces going with them), counted in @p update.
  void move_springs(const LiftOff& l, const OverlapPart& part, ModeUpdate& update);
  /// (u, ContactPoint::shift) of the points of group g; empty when every shift is 0 (no
  /// augmented-Lagrange pass: nothing allocated).
  [[nodiscard]] std::vector<std::pair<double, double>> shifts_of(const Group& g) const;
  /// The key under which broken_ marks the interface between the blocks of edges @p slave
  /// and @p master broken (its highest bit set: no contact key has it).
  [[nodiscard]] std::uint64_t interface_key(int slave, int master) const;
  /// Whether the edge-to-edge contact of edges @p face and @p other is bonded: both faces of
  /// an intact joint, its bond and that of their interface unbroken.
  [[nodiscard]] bool bonded_face(int face, int other) const;
  /// Breaks the bonds of every interface (a pair of blocks) whose bonded contacts all slide
  /// with the step displacement @p raw or pull open beyond their tensile strength: it has
  /// yielded all along (docs/formulation.md, "Joint strength"). Marks the open ones in
  /// opened_.
  void break_yielded_interfaces(const Model& model, const Eigen::VectorXd& raw);
  /// Anchor parameter on the master of the projection of slave point @p x.
  [[nodiscard]] double projection(int master, const Point2& x) const;
  /// The gap (less the point's offset and shift) and the shear displacement from its anchor
  /// of @p p in the geometry of the step's start: Kinematics::g0 and Kinematics::s0.
  [[nodiscard]] std::pair<double, double> start_gap_and_shear(const ContactPoint& p) const;

  // begin_step(), in parts.
  /// The boundary at the start of the step, and each edge's element, strength and bond.
  void set_up_boundary(const Model& model);
  /// The traction of the initial stress across the contact of slave edge @p slave (and, for
  /// an angle, the vertex's other edge @p slave_other) on @p master: (normal, compressive
  /// positive; shear, the stretch of the shear springs along the master's direction times
  /// their stiffness per unit length: t.sigma0 n), Pa. Zero unless every slave edge and the master
  /// are faces of one joint curve: the joints the initial stress acts across (docs/formulation.md,
  /// "In-situ stress").
  [[nodiscard]] Point2
  in_situ_traction(int slave, int slave_other, int master, const Point2& x) const;
  /// The initial stress of edge @p edge's material at @p x (zero for an edge of no element).
  [[nodiscard]] Eigen::Vector3d initial_stress_at(int edge, const Point2& x) const;
  /// An edge pair's spring @p p at its slave point: its in-situ pre-compression
  /// (ContactPoint::shift; a tensile one only when @p bonded) and pre-shear (the shear
  /// springs' stretch, m) for the traction there.
  [[nodiscard]] std::pair<double, double> edge_preload(const ContactPoint& p, bool bonded) const;
  /// Puts the spring of angle-to-angle candidate @p c on the entrance line with the smaller
  /// passing distance (Shi 3.2 [1]): @p p's slave and master.
  void choose_entrance_line(const ContactCandidate& c, ContactPoint& p) const;
  /// Adds the contact of candidate @p c (none for an angle pair made already, in
  /// @p angle_pairs, or an edge pair that only touches at an end), with its state carried
  /// or new; @p g0 and @p offsets are workspaces.
  void add_contact(const ContactCandidate& c,
                   const CarriedByEdge& carried,
                   KeySet& angle_pairs,
                   std::vector<double>& g0,
                   std::vector<std::pair<double, double>>& offsets);
  /// Adds the point of angle contact @p c, made from @p p, to group @p g, and its gap at the
  /// start of the step to @p g0.
  void
  add_angle_point(const ContactCandidate& c, Group& g, ContactPoint& p, std::vector<double>& g0);
  /// Adds the Gauss points of edge pair @p c, made from @p p, to group @p g with its overlap,
  /// and the gaps at the overlap's ends to @p g0; false (nothing added) when the overlap only
  /// touches.
  bool
  add_edge_points(const ContactCandidate& c, Group& g, ContactPoint& p, std::vector<double>& g0);
  /// The state of group @p g at the start of the step (Shi 3.3): broken bonds, the mode,
  /// anchors and offset carried or new, the springs placed and the normal force shared.
  void start_contact(Group& g,
                     const ContactPoint& p,
                     const CarriedByEdge& carried,
                     const std::vector<double>& g0,
                     std::vector<std::pair<double, double>>& offsets);
  /// The shapes of the elements of every contact point's edges.
  void set_up_shapes(const Model& model);
  /// Ties the touching contacts (set_tie()), keeping each point's own bond strength in
  /// tie_capacity_.
  void tie_touching();

  // update_modes(), in parts.
  /// Gap, shear and step motion of one point after a solve.
  struct Measure {
    double gap = 0.0;
    double shear = 0.0;
    double ds = 0.0;
  };
  /// What one contact's mode decision is made from: the resultants of its points' springs
  /// (stiffness-weighted gap and motion), its bonds' cohesion and tension, friction, its
  /// shear limit, and for an edge pair where its edges press.
  struct Resultants {
    double stiffness = 0.0;
    double normal = 0.0; ///< resultant, compressive positive
    double shear = 0.0;  ///< resultant of the shear springs (lock)
    double motion = 0.0; ///< stiffness-weighted tangential step motion
    double gap = 0.0;    ///< stiffness-weighted gap
    double cohesion = 0.0;
    double tension = 0.0;
    double friction = 0.0;     ///< JointLaw::friction_coefficient()
    double noise = 0.0;        ///< force of the springs stretched by the rounding
    OverlapPart pressed;       ///< edge pair: where the edges now press
    double deepest = 0.0;      ///< deepest penetration
    double pulling = 0.0;      ///< force of the springs on parts that no longer press
    double pushing = 0.0;      ///< force the springs would take on the parts that now press
    double spring_noise = 0.0; ///< force of the pair's springs stretched by the rounding
    bool tie = false;          ///< every gap sample within the rounding
    double bearing = 0.0;      ///< the normal force the contact bears
    double limit = 0.0;        ///< shear limit on it
  };
  /// A contact's mode before and after a decision, its sliding direction, and whether its
  /// friction was coupled in the solve.
  struct ModeStep {
    ContactMode before = ContactMode::open;
    ContactMode after = ContactMode::open;
    int sign = 0;
    bool coupled = false;
  };
  /// Work of friction in the step (ModeUpdate::friction_residual): of its change since it
  /// was applied, and of all of it.
  struct FrictionWork {
    double change = 0.0;
    double total = 0.0;
  };
  /// Gap, shear and step motion of every point of group @p g after the solve @p raw, into
  /// @p measure (and each point's gap).
  void measure_points(const Model& model,
                      const Group& g,
                      const Eigen::VectorXd& raw,
                      std::vector<Measure>& measure);
  /// The Resultants of group @p g from @p measure.
  [[nodiscard]] Resultants resultants(const Model& model,
                                      const Group& g,
                                      const Eigen::VectorXd& raw,
                                      const std::vector<Measure>& measure) const;
  /// The part of @p r on what the contact bears and, for an edge pair, where its edges press
  /// after the solve @p raw, and its shear limit.
  void pressing(const Model& model,
                const Group& g,
                const Eigen::VectorXd& raw,
                const std::vector<Measure>& measure,
                Resultants& r) const;
  /// The new mode of group @p g by Shi's table (8.2) and the chatter rule.
  [[nodiscard]] ModeStep decide_mode(const Group& g, const Resultants& r);
  /// The mode of a closed contact that stays closed, led by @p lead: a lock that slips, a
  /// slide that sticks or turns, or the chatter rule holding either at the limit of friction.
  [[nodiscard]] ModeStep closed_mode(const ContactPoint& lead, const Resultants& r);
  /// Sets the mode of @p step on the points of @p g (anchoring a contact that closes at its
  /// entrance position), counting flips and slips.
  void set_modes(const Model& model,
                 const Group& g,
                 const std::vector<Measure>& measure,
                 const ModeStep& step);
  /// The normal and shear forces of the points of @p g in their new mode, and the work of
  /// its friction added to @p work_done.
  void set_forces(const Group& g,
                  const std::vector<Measure>& measure,
                  const Resultants& r,
                  const ModeStep& step,
                  FrictionWork& work_done);

  ContactOptions options_;
  /// The joints' strength: every decision on it (MohrCoulombJoint; shared, never changed).
  std::shared_ptr<const JointLaw> law_;
  ContactBoundary boundary_;
  std::vector<int> edge_element_;
  std::vector<JointStrength> edge_strength_;
  std::vector<char> edge_bonded_;
  /// Per boundary edge: the joint curve it is a face of (BoundaryEdge::joint) and its
  /// element's material (-1: none), whose initial stress the joint's springs carry.
  std::vector<int> edge_joint_;
  std::vector<int> edge_material_;
  /// 1 for an edge of an excavated element (ModelElement::excavated): no contact on it.
  std::vector<char> edge_excavated_;
  /// The model's materials (their initial stress fields), as of the step's start.
  std::vector<ElasticMaterial> materials_;
  /// Shapes of the elements the contact points' edges belong to, built once per step (the
  /// geometry stays put through a step; a VEM block's shape computes its projector), and
  /// each element's index into them (-1: none).
  std::vector<ElementShape> shapes_;
  std::vector<int> shape_of_element_;
  int gauss_ = 2;
  std::vector<Group> groups_;
  std::vector<ContactPoint> points_;
  /// cached_kinematics() slots, made invalid by begin_step() (the geometry moved; their
  /// storage is kept for the next step's).
  mutable std::vector<CachedKinematics> kinematics_cache_;
  std::uint64_t kinematics_stamp_ = 0; ///< of this step's kinematics_cache_ (1, 2, ...)
  /// Workspaces of kinematics() on this thread, and on each thread of prepare_kinematics().
  mutable KinematicsWork work_;
  mutable std::vector<KinematicsWork> works_;
  /// Closed contacts of the last step: their states and keys in the order end_step() stored
  /// them, where each key's state is, and the anchors of all of them (flat: a step of 10,004
  /// DDA blocks carries 60,000 contacts, and a hash map's node and anchor vector per contact
  /// would be a sizeable part of the step).
  std::vector<Carried> carried_;
  std::vector<std::uint64_t> carried_keys_;
  KeyIndex carried_index_;
  std::vector<std::pair<double, double>> carried_anchors_;
  /// Broken bonds, by contact key (a broken joint never heals).
  std::unordered_map<std::uint64_t, bool> broken_;
  /// Bonded contacts open at the end of the last step (yielded in tension), by contact key:
  /// they start the next step open.
  std::unordered_map<std::uint64_t, bool> opened_;
  /// What an open-close iteration changes: the state begin_step() left, for restart_step(),
  /// and the least penetrating converged one an augmented-Lagrange pass started from, for
  /// augment() and back_to_converged().
  struct State {
    std::vector<Group> groups;
    std::vector<ContactPoint> points;
    std::unordered_map<std::uint64_t, bool> broken;
    long bonds_broken = 0;
    FrictionHolds holds;
  };
  void save(State& state) const;
  void restore(const State& state);
  /// The contacts and @p raw back to converged_ (which is then no longer this try's).
  void back_to_kept(Eigen::VectorXd& raw);
  State start_;
  State converged_;
  Eigen::VectorXd converged_raw_;
  bool has_converged_ = false; ///< converged_ is this try's (a pass ran since the step began)
  double converged_penetration_ = 0.0; ///< max_penetration() of converged_, m
  int last_changed_ = 0;
  bool hold_shear_ = false;
  bool tie_ = false;
  /// Per point, after a tie: the tension its own bond holds (JointLaw::bond_tension()), N;
  /// -1 for a point not tied.
  std::vector<double> tie_capacity_;
  double held_open_penetration_ = 0.0; ///< deepest a contact held open may penetrate, m
  /// update_modes(): (shear - limit, shear / limit) of each lock held beyond its friction
  /// limit (kept for its storage)
  std::vector<std::pair<double, double>> held_beyond_;
  /// update_modes(): (friction force, motion against it) of each contact held sliding at the
  /// chatter limit whose motion turned back.
  std::vector<std::pair<double, double>> held_against_;
  FrictionHolds holds_; ///< holds()
  bool chatter_slides_ = false;
  bool coupled_friction_ = false; ///< set_coupled_friction()
  /// The normal spring stiffness per unit length of an edge-to-edge contact of @p strength
  /// (its points get it times their length), N/m per m: the joint's own normal_stiffness,
  /// else penalty / spring_length.
  [[nodiscard]] double edge_stiffness(const JointStrength& strength) const noexcept {
    return strength.normal_stiffness > 0.0 ? strength.normal_stiffness
                                           : options_.penalty / options_.spring_length;
  }
  /// Shear over normal stiffness of such a contact: 1 without a joint's own stiffness.
  [[nodiscard]] double edge_shear_ratio(const JointStrength& strength) const noexcept {
    if (!(strength.normal_stiffness > 0.0) && !(strength.shear_stiffness > 0.0))
      return 1.0;
    const double shear = strength.shear_stiffness > 0.0 ? strength.shear_stiffness
                                                        : options_.penalty / options_.spring_length;
    return shear / edge_stiffness(strength);
  }
  /// The stiffness of group @p g's springs: the sum over its points, in order (the shares
  /// of its normal force and friction are by it).
  [[nodiscard]] double group_stiffness(const Group& g) const;
  /// Whether point @p p's friction is coupled in the solve (set_coupled_friction()).
  [[nodiscard]] bool friction_coupled(const ContactPoint& p) const noexcept {
    return coupled_friction_ && p.mode == ContactMode::slide && law_->has_pure_friction(p);
  }
  /// Rounding of the coordinates of the step, m: gaps and motions within it change no mode.
  double rounding_ = 0.0;
  ContactCounters counters_;
};

} // namespace nmm
