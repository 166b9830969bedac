// SPDX-License-Identifier: MIT
#include "solver/time_stepper.hpp"

#include "mesh/error.hpp"
#include "solver/assembler.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/sparsity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

std::string point_text(const Point2& p) {
  std::ostringstream out;
  out.precision(6);
  out << '(' << p.x() << ", " << p.y() << ')';
  return out.str();
}

/// One element's (or spring's) unknowns in the reduced system: d_local = T z + t0.
struct Reduction {
  std::vector<int> reduced;  ///< reduced unknowns z, sorted
  Eigen::MatrixXd transform; ///< local x reduced.size(); empty when the identity
  Eigen::VectorXd constant;  ///< t0, empty when zero
};

Reduction reduce(const DofMap& map, const std::vector<int>& raw) {
  Reduction r;
  bool identity = true;
  std::vector<DofExpansion> expansions;
  expansions.reserve(raw.size());
  for (const int d : raw) {
    expansions.push_back(map.expansion(d));
    const DofExpansion& e = expansions.back();
    identity = identity && !map.is_slave(d);
    for (const auto& [j, c] : e.terms)
      r.reduced.push_back(j);
  }
  std::sort(r.reduced.begin(), r.reduced.end());
  r.reduced.erase(std::unique(r.reduced.begin(), r.reduced.end()), r.reduced.end());
  if (identity) {
    // Keep the local order: the reduced index of each local unknown, unsorted.
    r.reduced.clear();
    for (const int d : raw)
      r.reduced.push_back(map.reduced(d));
    return r;
  }
  r.transform = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(raw.size()),
                                      static_cast<Eigen::Index>(r.reduced.size()));
  r.constant = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(raw.size()));
  for (std::size_t i = 0; i < raw.size(); ++i) {
    r.constant(static_cast<Eigen::Index>(i)) = expansions[i].constant;
    for (const auto& [j, c] : expansions[i].terms) {
      const auto column =
          std::lower_bound(r.reduced.begin(), r.reduced.end(), j) - r.reduced.begin();
      r.transform(static_cast<Eigen::Index>(i), column) += c;
    }
  }
  return r;
}

} // namespace

struct TimeStepper::Impl {
  std::vector<LinearConstraint> dependencies; // order-1 fixes, chosen once
  CholmodSolver solver;
  SparsityPattern pattern;
  std::unique_ptr<Assembler> stiffness;
  /// Scalar consistent mass of every element (n x n, times density and thickness), kept
  /// from the assembly for the kinetic energy of the new velocities.
  std::vector<Eigen::MatrixXd> element_mass;
  std::vector<std::vector<int>> couplings; // reduced unknowns of each coupling, last pattern
  bool analysed = false;
};

TimeStepper::TimeStepper(Model& model, Scene scene, StepperOptions options)
    : model_(model), scene_(std::move(scene)), options_(options),
      velocity_(Eigen::VectorXd::Zero(model.n_dofs())), impl_(std::make_unique<Impl>()) {
  BoundingBox box;
  for (const ModelElement& e : model_.elements) {
    for (const Polygon& p : e.polygons) {
      for (const Point2& x : p.outer)
        box.extend(x);
    }
  }
  model_size_ = box.is_empty() ? 1.0 : std::max({box.size().x(), box.size().y(), 1e-300});
  // A dynamic run needs mass everywhere; a static one needs every body held.
  std::set<int> used_materials;
  for (const ModelElement& e : model_.elements)
    used_materials.insert(e.material);
  if (options_.integration == TimeIntegration::dynamic) {
    for (const int m : used_materials) {
      if (!(model_.materials[at(m)].density > 0.0)) {
        throw InputError("material \"" + model_.materials[at(m)].name +
                         "\" has no density, but a dynamic analysis needs the mass of every "
                         "body: give [materials." +
                         model_.materials[at(m)].name + "] density in kg/m³");
      }
    }
  } else {
    std::set<int> held;
    for (const SupportPoint& s : scene_.supports) {
      if (s.point.element >= 0)
        held.insert(model_.elements[at(s.point.element)].block);
    }
    for (int e = 0; e < model_.n_elements(); ++e) {
      const ModelElement& element = model_.elements[at(e)];
      if (held.count(element.block) == 0) {
        throw InputError(
            "the body of material \"" + model_.materials[at(element.material)].name +
            "\" containing " + point_text(element.polygons.front().outer.front()) +
            " can move freely: nothing holds it and a static analysis has no inertia to "
            "resist; add a [[boundary]] support on it, or use [analysis] kind = \"dynamic\"");
      }
    }
  }
  impl_->dependencies = model_.dependency_relations();
}

TimeStepper::~TimeStepper() = default;

const SolverCounters& TimeStepper::solver_counters() const { return impl_->solver.counters(); }

int TimeStepper::n_unknowns() const { return impl_->pattern.n_dofs(); }

void TimeStepper::set_rigid_velocities(const std::vector<Point2>& block_velocity,
                                       const std::vector<double>& block_angular_velocity) {
  // Centre of each block: area-weighted element centroids.
  std::vector<Point2> centre(model_.blocks.size(), Point2::Zero());
  std::vector<double> weight(model_.blocks.size(), 0.0);
  for (const ModelElement& e : model_.elements) {
    for (const Polygon& p : e.polygons) {
      const double a = area(p);
      Point2 c = Point2::Zero();
      for (const Point2& x : p.outer)
        c += x / static_cast<double>(p.outer.size());
      centre[at(e.block)] += a * c;
      weight[at(e.block)] += a;
    }
  }
  for (std::size_t b = 0; b < centre.size(); ++b) {
    if (weight[b] > 0.0)
      centre[b] /= weight[b];
  }
  velocity_.setZero();
  for (int c = 0; c < model_.n_covers(); ++c) {
    const ModelCover& cover = model_.covers[at(c)];
    const Point2 v0 = block_velocity[at(cover.block)];
    const double omega = block_angular_velocity[at(cover.block)];
    const Point2 r = cover.position - centre[at(cover.block)];
    velocity_(model_.dof(c, 0)) = v0.x() - omega * r.y();
    velocity_(model_.dof(c, 1)) = v0.y() + omega * r.x();
    if (model_.order > 0) {
      velocity_(model_.dof(c, 3)) = omega * model_.scale;  // dv/dx L
      velocity_(model_.dof(c, 4)) = -omega * model_.scale; // du/dy L
    }
  }
}

Point2 TimeStepper::velocity_at(int element, const Point2& x) const {
  return model_.displacement(element, x, velocity_);
}

StepReport TimeStepper::step(double until) {
  const bool dynamic = options_.integration == TimeIntegration::dynamic;
  // Static analysis without contact: one solve with the stiffness alone per step.
  const bool with_mass = dynamic;
  const double limit = options_.max_step_displacement * model_size_;

  double dt = 0.0;
  if (options_.time_step) {
    dt = *options_.time_step;
  } else if (!dynamic) {
    dt = 1.0;
  } else {
    // Shi 8.5: G dt² + V dt - D = 0 with G the largest load per mass, V the largest
    // velocity, D the allowed step displacement.
    double g = 0.0;
    for (const BodyLoad& load : scene_.body_loads)
      g = std::max(g, load.acceleration.norm() * load.ramp.at(time_));
    double mass = 0.0;
    for (int e = 0; e < model_.n_elements(); ++e)
      mass += model_.material_of(e).density * model_.elements[at(e)].area *
              model_.material_of(e).thickness_factor();
    for (const PointLoad& load : scene_.point_loads)
      g = std::max(g, load.force.norm() / std::max(mass, 1e-300));
    double v = 0.0;
    for (int c = 0; c < model_.n_covers(); ++c)
      v = std::max(v, Point2(velocity_(model_.dof(c, 0)), velocity_(model_.dof(c, 1))).norm());
    if (g > 0.0)
      dt = (-v + std::sqrt(v * v + 4.0 * g * limit)) / (2.0 * g);
    else if (v > 0.0)
      dt = limit / v;
    else
      dt = std::sqrt(2.0 * limit / 9.81);
  }
  dt = std::min(dt, std::max(until - time_, 1e-300));

  StepReport report;
  Eigen::VectorXd raw;
  for (int cut = 0;; ++cut) {
    const double t1 = time_ + dt;
    // Constraints and the reduction of every element.
    std::vector<LinearConstraint> constraints = model_.extension_relations();
    constraints.insert(constraints.end(), impl_->dependencies.begin(), impl_->dependencies.end());
    const std::vector<LinearConstraint> supports = support_constraints(model_, scene_.supports, t1);
    constraints.insert(constraints.end(), supports.begin(), supports.end());
    const DofMap map(model_.n_dofs(), constraints);

    std::vector<std::vector<int>> element_raw(model_.elements.size());
    std::vector<Reduction> reductions;
    reductions.reserve(model_.elements.size() + scene_.supports.size());
    for (int e = 0; e < model_.n_elements(); ++e) {
      element_raw[at(e)] = model_.element_dofs(e);
      reductions.push_back(reduce(map, element_raw[at(e)]));
    }
    std::vector<int> spring_of; // support index of each extra coupling
    for (std::size_t s = 0; s < scene_.supports.size(); ++s) {
      const SupportPoint& support = scene_.supports[s];
      if (support.method == SupportMethod::penalty && support.point.element >= 0) {
        reductions.push_back(reductions[at(support.point.element)]);
        spring_of.push_back(static_cast<int>(s));
      }
    }

    // The sparsity pattern: rebuilt only when the couplings changed.
    bool rebuilt = false;
    if (!impl_->stiffness || impl_->pattern.n_dofs() != map.n_reduced() ||
        impl_->couplings.size() != reductions.size() ||
        !std::equal(reductions.begin(), reductions.end(), impl_->couplings.begin(),
                    [](const Reduction& r, const std::vector<int>& c) { return r.reduced == c; })) {
      SparsityBuilder builder(map.n_reduced());
      impl_->couplings.clear();
      for (const Reduction& r : reductions) {
        builder.add(r.reduced);
        impl_->couplings.push_back(r.reduced);
      }
      impl_->pattern = builder.build();
      impl_->stiffness = std::make_unique<Assembler>(impl_->pattern);
      for (const auto& c : impl_->couplings)
        (void)impl_->stiffness->plan(c);
      ++counters_.pattern_builds;
      rebuilt = true;
    }
    Assembler& a = *impl_->stiffness;
    a.zero();

    // Loads of the end of the step (point and curve loads here, body forces and initial
    // stresses per element below).
    Eigen::VectorXd f = Eigen::VectorXd::Zero(model_.n_dofs());
    for (const PointLoad& load : scene_.point_loads)
      add_point_load(model_, load, t1, f);
    for (const CurveLoad& load : scene_.curve_loads)
      add_curve_load(model_, load, t1, f);

    // One pass over the elements: one set of moments gives stiffness, mass, inertia load,
    // body forces and the initial-stress load.
    Eigen::VectorXd rhs_correction = Eigen::VectorXd::Zero(map.n_reduced());
    const double inertia = with_mass ? 2.0 / (dt * dt) : 0.0;
    impl_->element_mass.resize(model_.elements.size());
    for (int e = 0; e < model_.n_elements(); ++e) {
      const ModelElement& element = model_.elements[at(e)];
      const ElasticMaterial& material = model_.material_of(e);
      const NmmShape shape = model_.shape(e);
      const NmmElementIntegrals integrals(shape, element.polygons);
      const std::vector<int>& dofs = element_raw[at(e)];
      Eigen::MatrixXd local =
          integrals.stiffness(elasticity_matrix(material), material.thickness_factor());
      const Eigen::VectorXd load = element_load(model_, e, integrals, scene_.body_loads, t1);
      for (std::size_t i = 0; i < dofs.size(); ++i)
        f(dofs[i]) += load(static_cast<Eigen::Index>(i));
      if (with_mass) {
        const Eigen::MatrixXd mass = integrals.mass(material.density * material.thickness_factor());
        local += inertia * mass;
        // Inertia load 2 M v0 / dt (Shi eq. 2.23); velocities are zero in static steps.
        Eigen::VectorXd v(shape.n_dofs());
        for (int i = 0; i < shape.n_dofs(); ++i)
          v(i) = velocity_(dofs[at(i)]);
        const Eigen::VectorXd inertia_load = (2.0 / dt) * (mass * v);
        for (int i = 0; i < shape.n_dofs(); ++i)
          f(dofs[at(i)]) += inertia_load(i);
        // The scalar part (u-u block) is all the kinetic energy needs.
        Eigen::MatrixXd scalar(shape.n_shapes(), shape.n_shapes());
        for (int i = 0; i < shape.n_shapes(); ++i)
          for (int j = 0; j < shape.n_shapes(); ++j)
            scalar(i, j) = mass(2 * i, 2 * j);
        impl_->element_mass[at(e)] = std::move(scalar);
      }
      const Reduction& r = reductions[at(e)];
      if (r.transform.size() == 0) {
        a.add(e, local);
      } else {
        a.add(e, r.transform.transpose() * local * r.transform);
        if (r.constant.size() > 0 && !r.constant.isZero()) {
          const Eigen::VectorXd correction = r.transform.transpose() * (local * r.constant);
          for (std::size_t j = 0; j < r.reduced.size(); ++j)
            rhs_correction(r.reduced[j]) -= correction(static_cast<Eigen::Index>(j));
        }
      }
    }
    for (std::size_t s = 0; s < spring_of.size(); ++s) {
      const SupportPoint& support = scene_.supports[at(spring_of[s])];
      const Eigen::MatrixXd spring = support_spring(model_, support, options_.spring_stiffness);
      const Eigen::VectorXd pull =
          support_spring_load(model_, support, options_.spring_stiffness, t1);
      const std::vector<int>& spring_dofs = element_raw[at(support.point.element)];
      for (std::size_t i = 0; i < spring_dofs.size(); ++i)
        f(spring_dofs[i]) += pull(static_cast<Eigen::Index>(i));
      const Reduction& r = reductions[model_.elements.size() + s];
      const int plan = static_cast<int>(model_.elements.size() + s);
      if (r.transform.size() == 0)
        a.add(plan, spring);
      else
        a.add(plan, r.transform.transpose() * spring * r.transform);
    }
    const Eigen::VectorXd rhs = map.restrict(f) + rhs_correction;

    // Solve.
    if (rebuilt || !impl_->analysed) {
      if (impl_->solver.analyze(a.matrix()) != SolveStatus::ok)
        throw NumericalError("the symbolic analysis of the step matrix failed");
      impl_->analysed = true;
    }
    const SolveStatus factor = impl_->solver.factorize(a.matrix());
    if (factor != SolveStatus::ok) {
      // Name the body whose unknowns made the matrix singular.
      const long column = impl_->solver.failed_column();
      std::ostringstream message;
      message << "the step matrix is singular (" << to_string(factor) << ")";
      if (column >= 0) {
        for (int d = 0; d < model_.n_dofs(); ++d) {
          if (map.reduced(d) == column) {
            const ModelCover& cover = model_.covers[at(d / model_.dofs_per_cover())];
            int material = -1;
            for (const ModelElement& e : model_.elements) {
              if (e.block == cover.block)
                material = e.material;
            }
            message << " at the unknowns of the cover near " << point_text(cover.position)
                    << (material >= 0
                            ? " (material \"" + model_.materials[at(material)].name + "\")"
                            : std::string())
                    << ": this body can move freely in " << ((d % 2) == 0 ? "x" : "y")
                    << "; hold it with a [[boundary]] support (static analysis) or give it "
                       "mass (dynamic analysis)";
            break;
          }
        }
      }
      throw NumericalError(message.str());
    }
    Eigen::VectorXd reduced;
    if (impl_->solver.solve(rhs, reduced) != SolveStatus::ok)
      throw NumericalError("the solve of the step system failed");
    raw = map.expand(reduced);
    if (!raw.allFinite())
      throw NumericalError("the step displacement is not finite");

    double largest = 0.0;
    for (int c = 0; c < model_.n_covers(); ++c)
      largest = std::max(largest, Point2(raw(model_.dof(c, 0)), raw(model_.dof(c, 1))).norm());
    report.max_displacement = largest;
    if (largest > limit && dynamic) {
      if (!options_.time_step && cut < options_.max_step_cuts) {
        dt *= std::max(0.1, 0.9 * limit / largest);
        ++report.step_cuts;
        ++counters_.step_cuts;
        continue;
      }
      if (options_.time_step && warnings_.empty()) {
        std::ostringstream w;
        w << "step " << step_ + 1 << " moved " << largest << " m, more than max_step_displacement ("
          << limit << " m): the fixed time step is too large for Shi's small-step "
          << "assumption; consider time_step = \"auto\"";
        warnings_.push_back(w.str());
      }
    }
    break;
  }

  // Commit: velocities (Shi eq. 2.18-2.19: v1 = 2 d / dt - v0), stresses, geometry.
  if (options_.integration == TimeIntegration::dynamic)
    velocity_ = (2.0 / dt) * raw - velocity_;
  else
    velocity_.setZero();
  model_.accumulate_stress(raw);
  ++counters_.stress_updates;
  std::vector<MaterialPoint> points;
  for (const SupportPoint& s : scene_.supports)
    points.push_back(s.point);
  for (const PointLoad& l : scene_.point_loads)
    points.push_back(l.point);
  for (const MaterialPoint& p : scene_.monitors)
    points.push_back(p);
  model_.move(raw, points);
  std::size_t k = 0;
  for (SupportPoint& s : scene_.supports)
    s.point = points[k++];
  for (PointLoad& l : scene_.point_loads)
    l.point = points[k++];
  for (MaterialPoint& p : scene_.monitors)
    p = points[k++];

  time_ += dt;
  ++step_;
  ++counters_.steps;
  report.step = step_;
  report.time = time_;
  report.dt = dt;
  report.open_close_iterations = 1;
  // Kinetic energy 1/2 v^T M v of the new velocities with the step's element masses.
  double kinetic = 0.0;
  if (options_.integration == TimeIntegration::dynamic) {
    for (int e = 0; e < model_.n_elements(); ++e) {
      const Eigen::MatrixXd& mass = impl_->element_mass[at(e)];
      const std::vector<int> dofs = model_.element_dofs(e);
      const Eigen::Index n = mass.rows();
      Eigen::VectorXd u(n);
      Eigen::VectorXd v(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        u(i) = velocity_(dofs[at(static_cast<int>(2 * i))]);
        v(i) = velocity_(dofs[at(static_cast<int>(2 * i + 1))]);
      }
      kinetic += 0.5 * (u.dot(mass * u) + v.dot(mass * v));
    }
  }
  report.kinetic_energy = kinetic;
  return report;
}

} // namespace nmm
