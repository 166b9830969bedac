// SPDX-License-Identifier: MIT
// io/case_stages.cpp — CaseAnalysis's `[[stage]]`s (docs/case-file.md, "[[stage]]"): the
// supports, loads and bolts each stage starts, its kind and its excavation.
#include "io/case_names.hpp"
#include "io/case_runner.hpp"
#include "io/scene_bolts.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace nmm {

namespace {

using namespace case_names;

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// The ramp of @p load in a stage that starts at @p start (s): its times count from there.
Ramp ramp_of(const LoadSpec& load, double start) {
  return {start + load.ramp_start, start + load.ramp_end};
}

/// Places what a stage starts (its supports, loads and bolts) in the model as it is, each
/// checked against the material: outside it, or wholly in a region that stage or an earlier
/// one excavates, it is an error naming the case file's line.
class StagePlacer {
public:
  StagePlacer(const CaseSpec& spec,
              const PhysicalMesh& physical,
              const Model& model,
              double tolerance,
              int stage)
      : spec_(spec), physical_(physical), model_(model), tolerance_(tolerance), stage_(stage),
        removed_by_(physical.regions.size(), -1) {
    for (int k = 0; k <= stage && k < static_cast<int>(spec.stages.size()); ++k) {
      for (const std::string& name : spec.stages[at(k)].excavate) {
        const int region = physical.find_region(name);
        if (region >= 0 && removed_by_[at(region)] < 0)
          removed_by_[at(region)] = k;
      }
    }
  }

  void add_supports(Scene& scene) const {
    for (const BoundarySpec& b : spec_.boundaries) {
      if (b.stage != stage_)
        continue;
      if (b.is_curve) {
        const int curve = resolve_curve(spec_, physical_, model_, "[[boundary]]", b.target, b.line);
        const std::vector<SupportPoint> points = curve_support_points(
            model_, curve, b.fix_x, b.fix_y, b.method, "curve " + in_quotes(b.target));
        if (!points.empty() &&
            std::all_of(points.begin(), points.end(),
                        [&](const SupportPoint& p) { return removed_by(p.point.element) >= 0; }))
          refuse_if_removed(points.front().point.element, b.line,
                            "[[boundary]] curve " + in_quotes(b.target));
        scene.supports.insert(scene.supports.end(), points.begin(), points.end());
        continue;
      }
      const int group = resolve_point_group(spec_, physical_, "[[boundary]]", b.target, b.line);
      for (const Point2& x : physical_.points[at(group)].points) {
        SupportPoint support;
        support.point = {element_at(x, b.line, "[[boundary]] point " + in_quotes(b.target),
                                    "it cannot hold anything"),
                         x};
        support.fix_x = b.fix_x;
        support.fix_y = b.fix_y;
        support.method = b.method;
        support.origin = "point " + in_quotes(b.target);
        support.start = x;
        scene.supports.push_back(support);
      }
    }
  }

  /// The loads' ramps count from @p start_time (s).
  void add_loads(Scene& scene, double start_time) const {
    for (const LoadSpec& load : spec_.loads) {
      if (load.stage != stage_)
        continue;
      switch (load.kind) {
      case LoadKind::gravity:
        scene.body_loads.push_back({load.vector, ramp_of(load, start_time)});
        break;
      case LoadKind::point: {
        const int group = resolve_point_group(spec_, physical_, "[[load]]", load.target, load.line);
        for (const Point2& x : physical_.points[at(group)].points)
          scene.point_loads.push_back(
              {{element_at(x, load.line, "[[load]] point " + in_quotes(load.target),
                           "the force would act on nothing"),
                x},
               load.vector,
               ramp_of(load, start_time)});
        break;
      }
      case LoadKind::traction:
      case LoadKind::pressure:
        scene.curve_loads.push_back(curve_load(load, start_time));
        break;
      }
    }
  }

  void add_bolts(Scene& scene) const {
    scene.bolts = place_bolts(spec_, physical_, model_, tolerance_, stage_);
    for (const Bolt& bolt : scene.bolts) {
      const auto spec =
          std::find_if(spec_.bolts.begin(), spec_.bolts.end(), [&](const BoltSpec& b) {
            return b.stage == stage_ &&
                   (bolt.name == b.name || bolt.name.starts_with(b.name + "_"));
          });
      const int line = spec == spec_.bolts.end() ? 0 : spec->line;
      for (const MaterialPoint& end : {bolt.bars.front().a, bolt.bars.back().b})
        refuse_if_removed(end.element, line,
                          "[[bolt]] " + in_quotes(bolt.name) + ": its end " +
                              point_text(end.position));
    }
  }

private:
  /// The stage that excavates @p element's region, up to this one; -1: none.
  [[nodiscard]] int removed_by(int element) const {
    return removed_by_[at(model_.elements[at(element)].material)];
  }

  void refuse_if_removed(int element, int line, const std::string& what) const {
    const int k = removed_by(element);
    if (k < 0)
      return;
    fail(spec_, line,
         what + " lies in " +
             in_quotes(physical_.regions[at(model_.elements[at(element)].material)].name) +
             ", which [[stage]] " + in_quotes(spec_.stages[at(k)].name) +
             " excavates, so it would act on nothing; move it into the material that stays, "
             "or start it with an earlier stage");
  }

  /// The element holding point @p x of @p what (a Physical Point's), checked.
  [[nodiscard]] int element_at(const Point2& x,
                               int line,
                               const std::string& what,
                               const std::string& consequence) const {
    const int element = model_.find_element(x, tolerance_);
    if (element < 0)
      fail(spec_, line,
           what + ": the point " + point_text(x) + " of " + geometry_name(spec_) +
               " lies outside the material, so " + consequence +
               "; move it onto or into a Physical Surface");
    refuse_if_removed(element, line, what + " at " + point_text(x));
    return element;
  }

  [[nodiscard]] CurveLoad curve_load(const LoadSpec& load, double start_time) const {
    CurveLoad curve_load;
    curve_load.curve = resolve_curve(spec_, physical_, model_, "[[load]]", load.target, load.line);
    curve_load.is_pressure = load.kind == LoadKind::pressure;
    curve_load.traction = load.vector;
    curve_load.pressure = load.pressure;
    curve_load.ramp = ramp_of(load, start_time);
    if (load.water_level) {
      // Hydrostatic: gamma (level - y) below the water surface, at the current position.
      const double level = *load.water_level;
      const double gamma = load.water_unit_weight;
      curve_load.pressure_at = [level, gamma](const Point2& x) {
        return gamma * std::max(0.0, level - x.y());
      };
    }
    return curve_load;
  }

  const CaseSpec& spec_;
  const PhysicalMesh& physical_;
  const Model& model_;
  double tolerance_;
  int stage_;
  std::vector<int> removed_by_; ///< per region: the stage excavating it, -1: none
};

} // namespace

Scene CaseAnalysis::stage_scene(int stage, double start_time) const {
  const StagePlacer placer(spec_, geometry_.physical, model_, 1e-9 * model_size_, stage);
  Scene scene;
  placer.add_supports(scene);
  placer.add_loads(scene, start_time);
  placer.add_bolts(scene);
  return scene;
}

void CaseAnalysis::refuse_bad_excavations() {
  const PhysicalMesh& physical = geometry_.physical;
  std::set<int> removed;
  for (const StageSpec& stage : spec_.stages) {
    for (const std::string& name : stage.excavate) {
      const int region = physical.find_region(name);
      if (region < 0)
        fail(spec_, stage.line,
             unknown_name(spec_, physical,
                          "[[stage]] " + in_quotes(stage.name) + " excavate " + in_quotes(name),
                          name, "Physical Surface", physical.regions, physical.region_names(),
                          "name the Physical Surface of the material to remove"));
      if (!removed.insert(region).second)
        fail(spec_, stage.line,
             "[[stage]] " + in_quotes(stage.name) + " excavates " + in_quotes(name) +
                 ", which an earlier stage (or this one) excavates already; remove it here");
    }
  }
  if (removed.empty())
    return;
  for (const StageSpec& stage : spec_.stages) {
    if (!stage.excavate.empty() && stage.steps > 1 && spec_.cover_mesh.order == 1 &&
        spec_.cover_mesh.kind == CoverMeshKind::regular)
      warnings_.push_back(
          spec_.file.filename().string() + ":" + std::to_string(stage.line) + ": [[stage]] " +
          in_quotes(stage.name) + " releases its excavation over " + std::to_string(stage.steps) +
          " steps on order-1 covers of a regular math mesh, whose triangles the opening's "
          "outline cuts; such a release is not verified yet (an opening's crown stress came out "
          "twice Kirsch's over 3 steps, right in 1): give the excavating stage steps = 1 and "
          "the later steps to a stage of their own, or use [cover_mesh] kind = \"gmsh\"");
  }
  for (const ModelElement& element : model_.elements) {
    if (removed.count(element.material) == 0)
      return;
  }
  fail(spec_, spec_.stages.back().line,
       "the stages excavate all the material of " + geometry_name(spec_) +
           ", so nothing would be left to compute; excavate only the openings");
}

void CaseAnalysis::begin_stage(int stage) {
  const StageSpec& spec = spec_.stages[at(stage)];
  const AnalysisKind kind = spec.kind.value_or(spec_.analysis.kind);
  stepper_->set_integration(kind == AnalysisKind::dynamic ? TimeIntegration::dynamic
                                                          : TimeIntegration::static_reset);
  if (stage > 0)
    stepper_->add_to_scene(stage_scene(stage, stepper_->time()));
  releasing_.clear();
  for (const std::string& name : spec.excavate) {
    const int region = geometry_.physical.find_region(name);
    NMM_ASSERT(region >= 0, "the excavated regions were checked against the geometry");
    for (int e = 0; e < model_.n_elements(); ++e) {
      const ModelElement& element = model_.elements[at(e)];
      if (element.material == region && !element.excavated)
        releasing_.push_back(e);
    }
  }
  if (!releasing_.empty()) {
    model_.excavate(releasing_, spec_.cover_mesh.min_cover_area_ratio);
    stepper_->material_removed();
  }
}

void CaseAnalysis::set_release(double left) {
  if (releasing_.empty())
    return;
  for (const int e : releasing_)
    model_.elements[at(e)].release = left;
  stepper_->set_contact_release(left);
}

void CaseAnalysis::reset_monitor_starts() {
  for (std::size_t k = 0; k < monitor_starts_.size(); ++k)
    monitor_starts_[k] = stepper_->scene().monitors[k].position;
}

} // namespace nmm
