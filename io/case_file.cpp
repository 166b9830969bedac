// SPDX-License-Identifier: MIT
#include "io/case_file.hpp"

#include "io/bolt_table.hpp"
#include "io/case_table.hpp"
#include "io/fos_table.hpp"
#include "io/in_situ_table.hpp"
#include "io/joint_set_table.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <utility>

namespace nmm {

double LoadSpec::factor_at(double time) const noexcept {
  if (time >= ramp_end)
    return 1.0;
  if (time <= ramp_start)
    return 0.0;
  return (time - ramp_start) / (ramp_end - ramp_start);
}

const MaterialSpec* CaseSpec::find_material(std::string_view name) const {
  const auto found = std::find_if(materials.begin(), materials.end(),
                                  [&](const MaterialSpec& m) { return m.name == name; });
  return found == materials.end() ? nullptr : &*found;
}

const JointSpec* CaseSpec::find_joint(std::string_view name) const {
  const auto found = std::find_if(joints.begin(), joints.end(),
                                  [&](const JointSpec& j) { return j.name == name; });
  return found == joints.end() ? nullptr : &*found;
}

namespace {

using namespace case_table;

// The schema: the keys each table accepts. Also used to say where a misplaced key belongs.
constexpr std::string_view top_level_keys[] = {"geometry",   "title",     "geometry_time_limit",
                                               "cover_mesh", "materials", "joints",
                                               "contact",    "boundary",  "load",
                                               "analysis",   "monitor",   "output",
                                               "joint_set",  "fos",       "in_situ",
                                               "bolt",       "stage"};
constexpr std::string_view cover_mesh_keys[] = {
    "kind",          "size", "order", "max_triangles", "min_cover_area_ratio", "curve_tolerance",
    "geometry_sizes"};
constexpr std::string_view material_keys[] = {"model",
                                              "density",
                                              "young",
                                              "poisson",
                                              "plane",
                                              "thickness",
                                              "initial_velocity",
                                              "initial_angular_velocity",
                                              "initial_stress",
                                              "exact_rotation"};
constexpr std::string_view joint_keys[] = {"friction_angle", "cohesion", "tensile_strength",
                                           "normal_stiffness", "shear_stiffness"};
constexpr std::string_view boundary_keys[] = {"curve", "point", "fix", "method"};
constexpr std::string_view load_keys[] = {
    "gravity",           "point", "force", "curve", "traction", "pressure", "water_level",
    "water_unit_weight", "ramp"};
constexpr std::string_view analysis_keys[] = {"kind",
                                              "steps",
                                              "time_step",
                                              "max_step_displacement",
                                              "penalty",
                                              "penalty_stiffness",
                                              "penetration_tolerance",
                                              "open_close_max",
                                              "solver",
                                              "pcg_tolerance",
                                              "pcg_mode_tolerance",
                                              "max_step_cuts",
                                              "end_time",
                                              "initial_equilibrium",
                                              "energy_tolerance",
                                              "energy_error_limit",
                                              "velocity_ratio"};
constexpr std::string_view monitor_keys[] = {"name", "point"};
constexpr std::string_view stage_keys[] = {
    "name", "steps", "kind", "excavate", "reset_displacement", "load", "boundary", "bolt"};
constexpr std::string_view output_keys[] = {"dir", "every", "checkpoint_every", "moved_threshold"};

constexpr TableKeys all_tables[] = {
    {top_level_name, top_level_keys},    {"[cover_mesh]", cover_mesh_keys},
    {"[materials.NAME]", material_keys}, {"[joints.NAME]", joint_keys},
    {"[contact]", joint_keys},           {"[[joint_set]]", joint_set_keys},
    {"[[boundary]]", boundary_keys},     {"[[load]]", load_keys},
    {"[analysis]", analysis_keys},       {"[[monitor]]", monitor_keys},
    {"[output]", output_keys},           {"[fos]", fos_keys},
    {"[in_situ]", in_situ_keys},         {"[[bolt]]", bolt_keys},
    {"[[stage]]", stage_keys},
};

constexpr std::string_view cover_mesh_kinds[] = {"regular", "gmsh"};
constexpr std::string_view material_models[] = {"nmm", "dda", "vem"};
constexpr std::string_view plane_conditions[] = {"strain", "stress"};
constexpr std::string_view fixed_components[] = {"x", "y", "xy"};
constexpr std::string_view boundary_methods[] = {"exact", "penalty"};
constexpr std::string_view analysis_kinds[] = {"dynamic", "static"};
constexpr std::string_view solver_kinds[] = {"cholmod", "pcg"};

std::filesystem::path resolve(const std::filesystem::path& case_file,
                              const std::filesystem::path& path) {
  return (case_file.parent_path() / path).lexically_normal();
}

CoverMeshSpec
read_cover_mesh(Context& context, const toml::table& root, const std::filesystem::path& geometry) {
  const toml::table* table = single_table(context, root, "cover_mesh");
  if (!table)
    context.fail({1, 1}, "the case file has no [cover_mesh] table; add one with at least "
                         "size = <triangle edge length in m>, e.g. [cover_mesh] size = 0.5");
  const TableView view(context, *table, "[cover_mesh]", cover_mesh_keys);
  CoverMeshSpec spec;
  spec.kind = static_cast<CoverMeshKind>(view.choice("kind", cover_mesh_kinds, 0));
  spec.size = view.required_number("size", "math mesh triangle edge length in m", "m", "0.5");
  if (!(spec.size > 0.0))
    view.fail_range("size", spec.size, "the triangle edge length must be > 0 (m)");
  spec.size_line = view.key_position("size").line;
  if (const toml::node* order = view.find("order");
      order && order->is_number() && order->value<double>() == 2.0)
    view.fail_at_value("order", "[cover_mesh] order = 2 is not yet supported; use order = 0 "
                                "(constant covers) or order = 1 (linear covers)");
  spec.order = view.small_integer_or("order", 0, 0, 1, "1");
  spec.max_triangles =
      view.integer("max_triangles", 1, std::numeric_limits<std::int64_t>::max(), "5e6")
          .value_or(spec.max_triangles);
  spec.min_cover_area_ratio = view.number_or("min_cover_area_ratio", spec.min_cover_area_ratio,
                                             "fraction of a math node's star", "1e-3");
  if (!(spec.min_cover_area_ratio >= 0.0 && spec.min_cover_area_ratio < 0.5))
    view.fail_range("min_cover_area_ratio", spec.min_cover_area_ratio,
                    "it must be >= 0 and < 0.5 (a fraction of the star of a math node)");
  spec.curve_tolerance = view.number_or("curve_tolerance", 0.0, "m", "0.01");
  if (!(spec.curve_tolerance >= 0.0))
    view.fail_range("curve_tolerance", spec.curve_tolerance, "it must be >= 0 (m; 0 = automatic)");
  const bool from_mesh = lower(geometry.extension().string()) == ".msh";
  if (from_mesh && spec.curve_tolerance > 0.0)
    view.fail_at_value("curve_tolerance",
                       "[cover_mesh] curve_tolerance cannot apply to the .msh geometry " +
                           quoted(geometry.filename()) +
                           ": its curves are its mesh's line elements, with no curve to sample "
                           "again; remove curve_tolerance (the mesh's curves are used as they "
                           "are), or give the .geo as geometry to sample its curves");
  spec.geometry_sizes = view.boolean_or("geometry_sizes", false);
  if (spec.geometry_sizes && (from_mesh || spec.kind != CoverMeshKind::gmsh))
    context.warn(view.key_position("geometry_sizes").line,
                 from_mesh ? "[cover_mesh] geometry_sizes has no effect with a .msh geometry, "
                             "whose own triangles are the cover mesh (graded as the .msh is)"
                           : "[cover_mesh] geometry_sizes has no effect on a regular cover mesh; "
                             "set kind = \"gmsh\" to grade the triangles by the .geo's sizes");
  return spec;
}

JointProperties read_joint_properties(const TableView& view) {
  JointProperties properties;
  properties.friction_angle_degrees = view.number_or("friction_angle", 0.0, "degrees", "30.0");
  if (!(properties.friction_angle_degrees >= 0.0 && properties.friction_angle_degrees < 90.0))
    view.fail_range("friction_angle", properties.friction_angle_degrees,
                    "the friction angle must be >= 0 and < 90 (degrees)");
  properties.cohesion = view.number_or("cohesion", 0.0, "Pa", "0.0");
  if (!(properties.cohesion >= 0.0))
    view.fail_range("cohesion", properties.cohesion, "the cohesion must be >= 0 (Pa)");
  properties.tensile_strength = view.number_or("tensile_strength", 0.0, "Pa", "0.0");
  if (!(properties.tensile_strength >= 0.0))
    view.fail_range("tensile_strength", properties.tensile_strength,
                    "the tensile strength must be >= 0 (Pa)");
  // A joint's own stiffness, instead of the penalty for its edge-to-edge contacts.
  for (const auto& [key, value] : {std::pair{"normal_stiffness", &properties.normal_stiffness},
                                   std::pair{"shear_stiffness", &properties.shear_stiffness}}) {
    if (const std::optional<double> given = view.number(key, "Pa/m", "1.0e10")) {
      if (!(*given > 0.0))
        view.fail_range(key, *given,
                        "a joint's stiffness must be > 0 (Pa/m); leave the key out for the "
                        "penalty springs of [analysis]");
      *value = *given;
    }
  }
  return properties;
}

// A material as read; whether a missing density is allowed is decided once [analysis] and
// the loads are known.
struct MaterialRead {
  MaterialSpec spec;
  Position position;
  bool has_density = false;
  bool has_thickness = false;
};

MaterialRead read_material(Context& context, const NamedTable& item) {
  const TableView view(context, *item.table, "[materials." + item.name + "]", material_keys);
  MaterialRead read;
  MaterialSpec& spec = read.spec;
  spec.name = item.name;
  spec.line = item.position.line;
  read.position = item.position;
  if (const toml::node* model = view.find("model");
      model && model->is_string() && lower(model->as_string()->get()) == "fem")
    view.fail_at_value("model", "[materials." + item.name + "] model = \"" +
                                    model->as_string()->get() +
                                    "\" is not a model of its own; FEM is model = \"nmm\" on a "
                                    "conforming mesh: set [cover_mesh] kind = \"gmsh\" and define "
                                    "no joints in this region");
  spec.model = static_cast<MaterialModel>(view.choice("model", material_models, 0));
  if (const std::optional<double> density = view.number("density", "kg/m^3", "2600.0")) {
    read.has_density = true;
    spec.density = *density;
    if (!(spec.density > 0.0))
      view.fail_range("density", spec.density, "the density must be > 0 (kg/m^3)");
  }
  spec.young = view.required_number("young", "Young's modulus in Pa", "Pa", "5.0e9");
  if (!(spec.young > 0.0))
    view.fail_range("young", spec.young, "Young's modulus must be > 0 (Pa)");
  spec.plane = static_cast<PlaneCondition>(view.choice("plane", plane_conditions, 0));
  spec.poisson = view.required_number("poisson", "Poisson's ratio", "dimensionless", "0.25");
  if (!(spec.poisson > -1.0 && spec.poisson < 0.5)) {
    const std::string requirement =
        spec.plane == PlaneCondition::strain
            ? "Poisson's ratio must be > -1 and < 0.5 in plane strain (0.5 is incompressible)"
            : "Poisson's ratio must be > -1 and < 0.5; plane stress would allow 0.5 in theory "
              "but nmm does not support incompressible materials, so use e.g. 0.499";
    view.fail_range("poisson", spec.poisson, requirement);
  }
  if (const std::optional<double> thickness = view.number("thickness", "m", "1.0")) {
    read.has_thickness = true;
    spec.thickness = *thickness;
    if (!(spec.thickness > 0.0))
      view.fail_range("thickness", spec.thickness, "the thickness must be > 0 (m)");
  }
  spec.initial_velocity =
      view.vector<2>("initial_velocity", "m/s", "[0.0, 0.0]").value_or(Eigen::Vector2d::Zero());
  spec.initial_angular_velocity = view.number_or("initial_angular_velocity", 0.0, "rad/s", "0.0");
  spec.initial_stress = view.vector<3>("initial_stress", "Pa: sxx, syy, sxy", "[0.0, 0.0, 0.0]")
                            .value_or(Eigen::Vector3d::Zero());
  spec.exact_rotation = view.boolean_or("exact_rotation", false);
  if (view.has("exact_rotation") && spec.model == MaterialModel::dda)
    view.fail_at_key("exact_rotation",
                     "[materials." + item.name +
                         "] exact_rotation is a choice of `nmm` and `vem` regions (DDA blocks "
                         "always turn by their rotation exactly); remove it");
  return read;
}

BoundarySpec read_boundary(Context& context, const toml::table& table) {
  const TableView view(context, table, "[[boundary]]", boundary_keys);
  BoundarySpec spec;
  spec.line = view.position().line;
  const bool has_curve = view.has("curve");
  const bool has_point = view.has("point");
  if (has_curve && has_point) {
    const std::string_view later =
        view.key_position("point") < view.key_position("curve") ? "curve" : "point";
    view.fail_at_key(later, "a [[boundary]] has both curve and point; give one of them and "
                            "write another [[boundary]] for the other");
  }
  if (!has_curve && !has_point)
    context.fail(view.position(), "a [[boundary]] needs curve = \"NAME\" (a Physical Curve) or "
                                  "point = \"NAME\" (a Physical Point); add one of them");
  spec.is_curve = has_curve;
  spec.target = has_curve ? *view.name_string("curve", "Physical Curve of the geometry")
                          : *view.name_string("point", "Physical Point of the geometry");
  if (!view.has("fix"))
    view.fail_missing("fix", "the fixed displacement components: \"x\", \"y\" or \"xy\"", "\"xy\"");
  const std::size_t fix = view.choice("fix", fixed_components, 2);
  spec.fix_x = fix != 1;
  spec.fix_y = fix != 0;
  spec.method = static_cast<SupportMethod>(view.choice("method", boundary_methods, 0));
  return spec;
}

LoadSpec read_load(Context& context, const toml::table& table) {
  const TableView view(context, table, "[[load]]", load_keys);
  LoadSpec spec;
  spec.line = view.position().line;
  // Exactly one of the three targets; report the second one written.
  std::vector<std::pair<Position, std::string_view>> forms;
  for (const std::string_view form : {"gravity", "point", "curve"})
    if (view.has(form))
      forms.emplace_back(view.key_position(form), form);
  std::sort(forms.begin(), forms.end());
  if (forms.empty())
    context.fail(view.position(),
                 "a [[load]] needs one of gravity = [gx, gy], point = \"P\" with force = [fx, "
                 "fy], or curve = \"C\" with traction = [tx, ty] or pressure = p; add one");
  if (forms.size() > 1)
    view.fail_at_key(forms[1].second, "a [[load]] has both " + std::string(forms[0].second) +
                                          " and " + std::string(forms[1].second) +
                                          "; write one [[load]] per load");
  const std::string_view form = forms.front().second;
  const auto forbid = [&](std::string_view key, std::string_view reason) {
    if (view.has(key))
      view.fail_at_key(key, "a [[load]] with " + std::string(form) + " takes no " +
                                std::string(key) + "; " + std::string(reason));
  };
  if (form == "gravity") {
    spec.kind = LoadKind::gravity;
    for (const std::string_view key :
         {"force", "traction", "pressure", "water_level", "water_unit_weight"})
      forbid(key, "a gravity load has only gravity = [gx, gy] and an optional ramp");
    spec.vector = *view.vector<2>("gravity", "m/s^2", "[0.0, -9.81]");
  } else if (form == "point") {
    spec.kind = LoadKind::point;
    for (const std::string_view key : {"traction", "pressure", "water_level", "water_unit_weight"})
      forbid(key, "a point load has force = [fx, fy] (N); traction and pressure act on a curve");
    spec.target = *view.name_string("point", "Physical Point of the geometry");
    const std::optional<Eigen::Vector2d> force = view.vector<2>("force", "N", "[1.0e4, 0.0]");
    if (!force)
      view.fail_missing("force", "the point force in N", "[1.0e4, 0.0]");
    spec.vector = *force;
  } else {
    forbid("force", "a curve load has traction = [tx, ty] or pressure = p (Pa); force acts at "
                    "a point");
    spec.target = *view.name_string("curve", "Physical Curve of the geometry");
    const bool has_traction = view.has("traction");
    const bool has_pressure = view.has("pressure");
    const bool has_water = view.has("water_level");
    if (has_traction && has_pressure)
      view.fail_at_key(view.key_position("pressure") < view.key_position("traction") ? "traction"
                                                                                     : "pressure",
                       "a curve [[load]] has both traction and pressure; write one [[load]] for "
                       "each");
    if (has_traction && has_water)
      view.fail_at_key("water_level", "a curve [[load]] has both traction and water_level; water "
                                      "pushes normal to the curve: write it as its own [[load]]");
    if (!has_traction && !has_pressure && !has_water)
      context.fail(view.position(), "a [[load]] on curve " + in_quotes(spec.target) +
                                        " needs traction = [tx, ty] (Pa), pressure = p (Pa, "
                                        "positive pushes into the material) or water_level = y "
                                        "(m, hydrostatic pressure below it); add one");
    if (view.has("water_unit_weight") && !has_water)
      view.fail_at_key("water_unit_weight",
                       "water_unit_weight goes with water_level (the water surface, m); add "
                       "water_level = y or remove water_unit_weight");
    if (has_traction) {
      spec.kind = LoadKind::traction;
      spec.vector = *view.vector<2>("traction", "Pa", "[0.0, -1.0e5]");
    } else {
      spec.kind = LoadKind::pressure;
      spec.pressure = view.number_or("pressure", 0.0, "Pa", "1.0e5");
      spec.water_level = view.number("water_level", "m", "15.0");
      spec.water_unit_weight = view.number_or("water_unit_weight", 9810.0, "N/m^3", "9810.0");
      if (!(spec.water_unit_weight > 0.0))
        view.fail_range("water_unit_weight", spec.water_unit_weight,
                        "the unit weight of water must be > 0 (N/m^3; 9810 for fresh water)");
    }
  }
  if (const std::optional<Eigen::Vector2d> ramp = view.vector<2>("ramp", "s", "[0.0, 1.0]")) {
    spec.ramp_start = (*ramp)[0];
    spec.ramp_end = (*ramp)[1];
    if (!(spec.ramp_start >= 0.0 && spec.ramp_end >= spec.ramp_start))
      view.fail_at_value("ramp", "[[load]] ramp = [" + format_number(spec.ramp_start) + ", " +
                                     format_number(spec.ramp_end) +
                                     "] is out of range; it must be [t0, t1] with 0 <= t0 <= t1 "
                                     "(s): zero before t0, full from t1");
  }
  return spec;
}

// Springs stiffer than this multiple of Young's modulus leave the element stiffness beside
// them below the last of double's 16 digits once the solver has eliminated them: the step
// matrix is singular in effect, and bodies that the springs hold look free.
constexpr double largest_penalty = 1e12;
constexpr const char* penalty_too_large =
    "springs more than 1e12 times the largest Young's modulus make the step system singular "
    "(next to them the elements' stiffness is below what double precision holds, so the "
    "bodies they hold look free); Shi uses 10 to 100, nmm's default is 40";

AnalysisSpec read_analysis(Context& context, const toml::table& root, bool staged) {
  const toml::table* table = single_table(context, root, "analysis");
  if (!table)
    context.fail({1, 1}, "the case file has no [analysis] table; add one with at least "
                         "steps = <number of time steps>, e.g. [analysis] steps = 1000");
  const TableView view(context, *table, "[analysis]", analysis_keys);
  AnalysisSpec spec;
  spec.kind = static_cast<AnalysisKind>(view.choice("kind", analysis_kinds, 0));
  const std::optional<std::int64_t> steps = view.integer("steps", 1, 100'000'000, "2000");
  if (staged && steps)
    view.fail_at_key("steps", "[analysis] steps cannot be given with [[stage]] tables: each "
                              "stage gives its own steps; remove it");
  if (!staged && !steps)
    view.fail_missing("steps", "the number of time steps, 1 to 1e8", "2000");
  spec.steps = static_cast<int>(steps.value_or(0)); // (staged: the stages' sum, later)
  spec.time_step_line = view.key_position("time_step").line;
  spec.time_step =
      view.time_step("time_step", "1.0e-3",
                     "the time step must be > 0 (s); write \"auto\" to let nmm choose it")
          .seconds;
  spec.max_step_displacement =
      view.number_or("max_step_displacement", 0.01, "fraction of the model size", "0.01");
  if (!(spec.max_step_displacement > 0.0 && spec.max_step_displacement <= 0.5))
    view.fail_range("max_step_displacement", spec.max_step_displacement,
                    "it must be > 0 and <= 0.5 (a fraction of the model size; Shi uses "
                    "0.001 to 0.01)");
  if (view.has("penalty") && view.has("penalty_stiffness"))
    view.fail_at_key(view.key_position("penalty") < view.key_position("penalty_stiffness")
                         ? "penalty_stiffness"
                         : "penalty",
                     "[analysis] has both penalty (a multiple of the largest Young's modulus) "
                     "and penalty_stiffness (N/m); keep one of them");
  spec.penalty = view.number_or("penalty", 40.0, "multiple of the largest Young's modulus", "40.0");
  if (!(spec.penalty > 0.0))
    view.fail_range("penalty", spec.penalty,
                    "it must be > 0 (a multiple of the largest Young's modulus; Shi uses 10 to "
                    "100)");
  if (spec.penalty > largest_penalty)
    view.fail_range("penalty", spec.penalty, penalty_too_large);
  spec.penalty_stiffness = view.number("penalty_stiffness", "N/m", "1.0e11");
  if (spec.penalty_stiffness && !(*spec.penalty_stiffness > 0.0))
    view.fail_range("penalty_stiffness", *spec.penalty_stiffness,
                    "the spring stiffness must be > 0 (N/m)");
  spec.penetration_tolerance = view.number("penetration_tolerance", "m", "1.0e-4");
  if (spec.penetration_tolerance && !(*spec.penetration_tolerance > 0.0))
    view.fail_range("penetration_tolerance", *spec.penetration_tolerance,
                    "it must be > 0 (m): the deepest penetration a contact may keep; remove "
                    "the line for the penalty springs alone");
  if (const auto given = view.integer("open_close_max", 1, 100, "20"))
    spec.open_close_max = static_cast<int>(*given);
  spec.solver = static_cast<LinearSolverKind>(view.choice("solver", solver_kinds, 0));
  spec.pcg_tolerance = view.number_or("pcg_tolerance", spec.pcg_tolerance, "a fraction", "1.0e-10");
  if (!(spec.pcg_tolerance >= 1e-15 && spec.pcg_tolerance <= 1e-3))
    view.fail_range("pcg_tolerance", spec.pcg_tolerance,
                    "it must be between 1e-15 and 1e-3: the residual of a conjugate-gradient "
                    "solve relative to its right-hand side");
  spec.pcg_mode_tolerance =
      view.number_or("pcg_mode_tolerance", spec.pcg_mode_tolerance, "a fraction", "1.0e-6");
  if (!(spec.pcg_mode_tolerance >= 1e-15 && spec.pcg_mode_tolerance <= 1e-3))
    view.fail_range("pcg_mode_tolerance", spec.pcg_mode_tolerance,
                    "it must be between 1e-15 and 1e-3: the residual of the conjugate-gradient "
                    "solves on which contacts' modes are decided, relative to their right-hand "
                    "side (at most pcg_tolerance: every solve to pcg_tolerance)");
  spec.max_step_cuts = view.small_integer_or("max_step_cuts", 10, 0, 50, "10");
  spec.energy_tolerance =
      view.number_or("energy_tolerance", spec.energy_tolerance, "a fraction", "0.05");
  if (!(spec.energy_tolerance > 0.0 && spec.energy_tolerance <= 1.0))
    view.fail_range("energy_tolerance", spec.energy_tolerance,
                    "it must be > 0 and <= 1: the residual of the energy balance over its "
                    "largest term above which a step warns");
  spec.velocity_ratio = view.number_or("velocity_ratio", 1.0, "a fraction", "0.98");
  if (!(spec.velocity_ratio > 0.0 && spec.velocity_ratio <= 1.0))
    view.fail_range("velocity_ratio", spec.velocity_ratio,
                    "it must be > 0 and <= 1: the fraction of the last step's velocities a "
                    "dynamic step starts from (Shi's k01; 1 carries them over)");
  spec.energy_error_limit = view.number("energy_error_limit", "a fraction", "0.5");
  if (spec.energy_error_limit && !(*spec.energy_error_limit >= spec.energy_tolerance))
    view.fail_range("energy_error_limit", *spec.energy_error_limit,
                    "it must be >= energy_tolerance (" + number_text(spec.energy_tolerance, 3) +
                        "): the residual of the energy balance over its largest term above "
                        "which the run stops; remove the line to stop only at ten times the "
                        "energy budget");
  spec.end_time = view.number("end_time", "s", "1.0");
  if (spec.end_time && !(*spec.end_time > 0.0))
    view.fail_range("end_time", *spec.end_time, "the end time must be > 0 (s)");
  spec.initial_equilibrium = view.boolean_or("initial_equilibrium", false);
  return spec;
}

MonitorSpec read_monitor(Context& context, const toml::table& table) {
  const TableView view(context, table, "[[monitor]]", monitor_keys);
  MonitorSpec spec;
  spec.line = view.position().line;
  const std::optional<std::string> name = view.string("name", "the monitor's name", "\"crest\"");
  if (!name)
    view.fail_missing("name", "a unique name of letters, digits and _", "\"crest\"");
  check_column_name(view, "name", *name);
  spec.name = *name;
  const std::optional<Eigen::Vector2d> point = view.vector<2>("point", "m", "[10.0, 5.0]");
  if (!point)
    view.fail_missing("point", "the starting position [x, y] in m", "[10.0, 5.0]");
  spec.point = *point;
  return spec;
}

/// One `[[stage]]` and the `[[stage.load]]`, `[[stage.boundary]]` and `[[stage.bolt]]`
/// under it (tagged with its index @p index) into @p spec.
StageSpec read_stage(Context& context, const toml::table& table, int index, CaseSpec& spec) {
  const TableView view(context, table, "[[stage]]", stage_keys);
  StageSpec stage;
  stage.line = view.position().line;
  const std::optional<std::string> name = view.string("name", "the stage's name", "\"excavate\"");
  if (!name)
    view.fail_missing("name", "a unique name of letters, digits and _", "\"excavate\"");
  check_column_name(view, "name", *name);
  stage.name = *name;
  const std::optional<std::int64_t> steps = view.integer("steps", 1, 100'000'000, "200");
  if (!steps)
    view.fail_missing("steps", "the number of time steps of the stage, 1 to 1e8", "200");
  stage.steps = static_cast<int>(*steps);
  if (view.has("kind"))
    stage.kind = static_cast<AnalysisKind>(view.choice("kind", analysis_kinds, 0));
  if (const toml::node* node = view.find("excavate")) {
    const toml::array* names = node->as_array();
    if (names == nullptr)
      view.fail_at_value("excavate", "[[stage]] excavate must be a list of Physical Surface "
                                     "names, e.g. excavate = [\"tunnel\"]");
    for (const toml::node& item : *names) {
      const auto* text = item.as_string();
      if (text == nullptr || text->get().empty())
        context.fail(position_of(item.source()),
                     "[[stage]] excavate must list Physical Surface names in double quotes, "
                     "e.g. excavate = [\"tunnel\"]");
      stage.excavate.push_back(text->get());
    }
  }
  stage.reset_displacement = view.boolean_or("reset_displacement", false);
  for (const toml::table* t : table_array(context, table, "boundary"))
    spec.boundaries.emplace_back(read_boundary(context, *t)).stage = index;
  for (const toml::table* t : table_array(context, table, "load"))
    spec.loads.emplace_back(read_load(context, *t)).stage = index;
  for (const toml::table* t : table_array(context, table, "bolt"))
    spec.bolts.emplace_back(read_bolt_table(context, *t, spec.bolts.size())).stage = index;
  return stage;
}

/// Every `[[stage]]`: names unique, the steps summed into [analysis] steps.
void read_stages(Context& context, const toml::table& root, CaseSpec& spec) {
  for (const toml::table* table : table_array(context, root, "stage")) {
    spec.stages.push_back(read_stage(context, *table, static_cast<int>(spec.stages.size()), spec));
    const StageSpec& stage = spec.stages.back();
    for (std::size_t j = 0; j + 1 < spec.stages.size(); ++j) {
      if (spec.stages[j].name == stage.name)
        context.fail({stage.line, 1}, "[[stage]] name " + in_quotes(stage.name) +
                                          " is already used by the [[stage]] at line " +
                                          std::to_string(spec.stages[j].line) +
                                          "; give each stage a unique name");
    }
  }
  std::int64_t total = 0;
  for (const StageSpec& stage : spec.stages)
    total += stage.steps;
  if (total > 100'000'000)
    context.fail({spec.stages.back().line, 1},
                 "the stages have " + std::to_string(total) +
                     " steps in all, more than 1e8; give fewer steps");
  if (!spec.stages.empty())
    spec.analysis.steps = static_cast<int>(total);
  check_bolt_names(context, spec.bolts);
}

OutputSpec read_output(Context& context, const toml::table& root, const std::string& file) {
  OutputSpec spec;
  spec.dir = resolve(file, "out");
  const toml::table* table = single_table(context, root, "output");
  if (!table)
    return spec;
  const TableView view(context, *table, "[output]", output_keys);
  if (const std::optional<std::string> dir = view.string("dir", "a folder", "\"out\"")) {
    if (dir->empty())
      view.fail_at_value("dir", "[output] dir is empty; give a folder, e.g. dir = \"out\"");
    spec.dir = resolve(file, *dir);
  }
  spec.every = view.small_integer_or("every", 1, 1, 100'000'000, "10");
  spec.checkpoint_every = view.small_integer_or("checkpoint_every", 0, 0, 100'000'000, "1000");
  spec.moved_threshold = view.number("moved_threshold", "m", "0.01");
  if (spec.moved_threshold && !(*spec.moved_threshold >= 0.0))
    view.fail_range("moved_threshold", *spec.moved_threshold,
                    "the displacement beyond which a block counts as moved must be >= 0 (m)");
  return spec;
}

bool has_geometry_extension(const std::filesystem::path& path) {
  const std::string extension = lower(path.extension().string());
  return extension == ".geo" || extension == ".msh";
}

// Checks that need more than one table, and the remarks that do not stop a run.
// Line of root[table][key], or 1 when absent (warnings about something left out).
int line_of(const toml::table& root, std::string_view table, std::string_view key) {
  if (const toml::node* node = root[table][key].node())
    return position_of(node->source()).line;
  if (const toml::node* node = root[table].node())
    return position_of(node->source()).line;
  return 1;
}

void check_whole_case(Context& context,
                      const toml::table& root,
                      CaseSpec& spec,
                      const std::vector<MaterialRead>& materials,
                      const std::vector<Position>& monitor_name_positions) {
  const LoadSpec* gravity = nullptr;
  for (const LoadSpec& load : spec.loads)
    if (load.kind == LoadKind::gravity && !gravity)
      gravity = &load;
  for (const MaterialRead& read : materials) {
    const MaterialSpec& material = read.spec;
    if (!read.has_density) {
      const bool dynamic_stage =
          std::any_of(spec.stages.begin(), spec.stages.end(),
                      [](const StageSpec& stage) { return stage.kind == AnalysisKind::dynamic; });
      if (spec.analysis.kind == AnalysisKind::dynamic && !dynamic_stage)
        context.fail(read.position,
                     "[materials." + material.name +
                         "] is missing density (kg/m^3), which a dynamic analysis needs; add "
                         "e.g. density = 2600.0, or set [analysis] kind = \"static\"");
      if (dynamic_stage)
        context.fail(read.position, "[materials." + material.name +
                                        "] is missing density (kg/m^3), which a [[stage]] of "
                                        "kind = \"dynamic\" needs; add e.g. density = 2600.0");
      if (gravity)
        context.fail(read.position,
                     "[materials." + material.name +
                         "] is missing density (kg/m^3), which the gravity [[load]] at line " +
                         std::to_string(gravity->line) + " needs; add e.g. density = 2600.0");
    }
    if (read.has_thickness && material.plane == PlaneCondition::strain)
      context.warn(material.line, "[materials." + material.name +
                                      "] thickness is ignored in plane strain (results are per "
                                      "metre of thickness); set plane = \"stress\" to use it");
    if (spec.analysis.kind == AnalysisKind::quasi_static &&
        (!material.initial_velocity.isZero() || material.initial_angular_velocity != 0.0))
      context.warn(material.line, "[materials." + material.name +
                                      "] has an initial velocity, which a static analysis "
                                      "discards (velocities are reset every step)");
  }

  for (std::size_t i = 0; i < spec.monitors.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (spec.monitors[i].name == spec.monitors[j].name)
        context.fail(monitor_name_positions[i], "monitor name " + in_quotes(spec.monitors[i].name) +
                                                    " is already used by the [[monitor]] at line " +
                                                    std::to_string(spec.monitors[j].line) +
                                                    "; give each monitor a unique name");

  const bool has_nmm =
      std::any_of(spec.materials.begin(), spec.materials.end(),
                  [](const MaterialSpec& m) { return m.model == MaterialModel::nmm; });
  if (spec.cover_mesh.order != 0 && !has_nmm)
    context.warn(line_of(root, "cover_mesh", "order"),
                 "[cover_mesh] order is used only by model = \"nmm\" materials and no "
                 "material has it; the order has no effect");

  for (std::size_t i = 0; i < spec.boundaries.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const BoundarySpec& a = spec.boundaries[j];
      const BoundarySpec& b = spec.boundaries[i];
      if (a.target == b.target && a.is_curve == b.is_curve)
        context.warn(b.line, std::string(b.is_curve ? "curve " : "point ") + in_quotes(b.target) +
                                 " is already fixed by the [[boundary]] at line " +
                                 std::to_string(a.line) + "; the fixed components are combined");
    }
  if (spec.analysis.kind == AnalysisKind::quasi_static && spec.boundaries.empty())
    context.warn(line_of(root, "analysis", "kind"),
                 "a static analysis with no [[boundary]]: unless contacts hold it, the "
                 "model can move as a rigid body and the solve fails; fix a curve or point");
  // Shi's contact springs (report 2.6, "g0"): stiff enough that penetrations stay far below
  // the blocks' elastic deformation, soft enough that the open-close iteration converges
  // and the equations keep their digits. The usual choice is 10 E to 100 E, 40 E by default;
  // a factor of 25 from 40 E either way is far from it.
  double largest_young = 0.0;
  for (const MaterialRead& read : materials)
    largest_young = std::max(largest_young, read.spec.young);
  const double penalty = spec.analysis.penalty_stiffness && largest_young > 0.0
                             ? *spec.analysis.penalty_stiffness / largest_young
                             : spec.analysis.penalty;
  if (spec.analysis.penalty_stiffness && penalty > largest_penalty) {
    const toml::node* node = root["analysis"]["penalty_stiffness"].node();
    context.fail(
        position_of(node->source()),
        "[analysis] penalty_stiffness = " + format_number(*spec.analysis.penalty_stiffness) +
            " N/m is " + number_text(penalty, 3) + " times the largest Young's modulus (" +
            number_text(largest_young, 3) + " Pa); " + penalty_too_large +
            "; use penalty = 40 instead");
  }
  if (penalty < 40.0 / 25.0 || penalty > 40.0 * 25.0) {
    const bool absolute = spec.analysis.penalty_stiffness.has_value();
    context.warn(line_of(root, "analysis", absolute ? "penalty_stiffness" : "penalty"),
                 "[analysis] " + std::string(absolute ? "penalty_stiffness" : "penalty") +
                     " makes the contact springs " + format_number(penalty) +
                     " times the largest Young's modulus, far from the usual 40 E (10 E to "
                     "100 E): " +
                     (penalty < 40.0 / 25.0
                          ? "contacts will penetrate by as much as the blocks deform"
                          : "the open-close iteration may not converge and the equations lose "
                            "digits") +
                     "; unless this is intended, use penalty = 40");
  }
  if (spec.analysis.end_time && spec.analysis.time_step &&
      *spec.analysis.time_step * spec.analysis.steps < *spec.analysis.end_time)
    context.warn(line_of(root, "analysis", "end_time"),
                 "[analysis] steps * time_step = " +
                     format_number(*spec.analysis.time_step * spec.analysis.steps) +
                     " s is before end_time = " + format_number(*spec.analysis.end_time) +
                     " s; the run stops after the last step");
}

CaseSpec read_case(Context& context, const toml::table& root, const std::string& file) {
  const TableView top(context, root, std::string(top_level_name), top_level_keys);
  CaseSpec spec;
  spec.file = file;

  const std::optional<std::string> geometry =
      top.name_string("geometry", "geometry file (.geo or .msh)");
  if (!geometry)
    context.fail({1, 1}, "the case file has no geometry key; add geometry = \"slope.geo\" "
                         "(a .geo or .msh file, relative to the case file) above the first "
                         "[table] header");
  if (!has_geometry_extension(*geometry))
    top.fail_at_value("geometry", "geometry = " + in_quotes(*geometry) +
                                      " is not a .geo or .msh file; give the gmsh geometry "
                                      "(.geo) or mesh (.msh) with the physical groups");
  spec.geometry = resolve(file, *geometry);
  spec.geometry_line = top.key_position("geometry").line;
  spec.title = top.string("title", "a title", "\"Slope with bedding joints\"").value_or("");
  spec.geometry_time_limit = top.number_or("geometry_time_limit", 60.0, "s", "600.0");
  if (!(spec.geometry_time_limit > 0.0))
    top.fail_range("geometry_time_limit", spec.geometry_time_limit,
                   "it must be > 0 (s): the longest time reading the .geo may take");

  spec.cover_mesh = read_cover_mesh(context, root, spec.geometry);

  std::vector<MaterialRead> materials;
  for (const NamedTable& item :
       named_tables(context, root, "materials", material_keys, "Physical Surface"))
    materials.push_back(read_material(context, item));
  if (materials.empty()) {
    const toml::node* node = root.get("materials");
    context.fail(node ? position_of(node->source()) : Position{1, 1},
                 "the case file has no material; add a [materials.NAME] table for each "
                 "Physical Surface NAME of the geometry, with at least young and poisson");
  }
  for (const MaterialRead& read : materials)
    spec.materials.push_back(read.spec);

  for (const NamedTable& item :
       named_tables(context, root, "joints", joint_keys, "Physical Curve")) {
    const TableView view(context, *item.table, "[joints." + item.name + "]", joint_keys);
    spec.joints.push_back({item.name, item.position.line, read_joint_properties(view)});
  }
  spec.joint_sets = read_joint_set_tables(context, root, file, spec.joints);
  if (const toml::table* table = single_table(context, root, "contact")) {
    const TableView view(context, *table, "[contact]", joint_keys);
    spec.contact = read_joint_properties(view);
    spec.contact_line = view.position().line;
  }

  for (const toml::table* table : table_array(context, root, "boundary"))
    spec.boundaries.push_back(read_boundary(context, *table));
  for (const toml::table* table : table_array(context, root, "load"))
    spec.loads.push_back(read_load(context, *table));

  spec.analysis = read_analysis(context, root, root.get("stage") != nullptr);

  std::vector<Position> monitor_name_positions;
  for (const toml::table* table : table_array(context, root, "monitor")) {
    spec.monitors.push_back(read_monitor(context, *table));
    monitor_name_positions.push_back(position_of(table->get("name")->source()));
  }

  spec.bolts = read_bolt_tables(context, root);
  read_stages(context, root, spec);

  spec.output = read_output(context, root, file);
  spec.fos = read_fos_table(context, root);

  check_whole_case(context, root, spec, materials, monitor_name_positions);
  read_in_situ(context, root, spec); // (after the materials' and loads' own checks)
  spec.warnings = context.take_warnings();
  return spec;
}

} // namespace

CaseSpec parse_case_text(std::string_view text, const std::filesystem::path& name_for_messages) {
  const std::string file = name_for_messages.string();
  Context context(file, all_tables);
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& error) {
    context.fail(position_of(error.source()),
                 "TOML syntax error: " + std::string(error.description()) +
                     "; correct the syntax (https://toml.io: key = value, strings in double "
                     "quotes, [table] headers)");
  }
  return read_case(context, root, file);
}

CaseSpec read_case_file(const std::filesystem::path& file) {
  std::error_code folder_error;
  if (std::filesystem::is_directory(file, folder_error))
    throw InputError(file.string(), 0, 0,
                     "is a folder, not a case file; give the case file (TOML) in it, e.g. " +
                         (file / "case.toml").string());
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file.string(), 0, 0, "cannot open the case file; check the path");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  CaseSpec spec = parse_case_text(buffer.str(), file);
  std::error_code error;
  if (!std::filesystem::is_regular_file(spec.geometry, error))
    throw InputError(file.string(), spec.geometry_line, 0,
                     "the geometry file " + spec.geometry.string() +
                         " does not exist; the path is relative to the case file's folder");
  return spec;
}

} // namespace nmm
