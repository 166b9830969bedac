// SPDX-License-Identifier: MIT
#include "io/case_names.hpp"

#include "mesh/error.hpp"

namespace nmm::case_names {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

} // namespace

void fail(const CaseSpec& spec, int line, const std::string& message) {
  throw InputError(spec.file.string(), line, 0, message);
}

std::string geometry_name(const CaseSpec& spec) { return spec.geometry.filename().string(); }

std::string group_kind(const PhysicalMesh& physical, const std::string& name) {
  if (physical.find_region(name) >= 0)
    return "a Physical Surface";
  if (physical.find_curve(name) >= 0)
    return "a Physical Curve";
  if (physical.find_point(name) >= 0)
    return "a Physical Point";
  return {};
}

int resolve_curve(const CaseSpec& spec,
                  const PhysicalMesh& physical,
                  const Model& model,
                  const std::string& entry,
                  const std::string& name,
                  int line) {
  const int curve = physical.find_curve(name);
  if (curve < 0) {
    fail(spec, line,
         unknown_name(spec, physical, entry + " curve " + in_quotes(name), name, "Physical Curve",
                      physical.curves, physical.curve_names(),
                      physical.find_point(name) >= 0 ? "write point = " + in_quotes(name)
                                                     : "name a Physical Curve"));
  }
  if (model.curve_pieces[at(curve)].empty()) {
    fail(spec, line,
         entry + " curve " + in_quotes(name) + " of " + geometry_name(spec) +
             " does not touch the material, so it would act on nothing; move the curve onto "
             "the material's boundary or into it, or name another curve");
  }
  return curve;
}

int resolve_point_group(const CaseSpec& spec,
                        const PhysicalMesh& physical,
                        const std::string& entry,
                        const std::string& name,
                        int line) {
  const int group = physical.find_point(name);
  if (group < 0) {
    fail(spec, line,
         unknown_name(spec, physical, entry + " point " + in_quotes(name), name, "Physical Point",
                      physical.points, physical.point_names(),
                      physical.find_curve(name) >= 0 ? "write curve = " + in_quotes(name)
                                                     : "name a Physical Point"));
  }
  return group;
}

} // namespace nmm::case_names
