// SPDX-License-Identifier: MIT
// io/joint_sets.cpp — `[[joint_set]]` joints into the physical mesh (joint_sets.hpp).
#include "io/joint_sets.hpp"

#include "io/text.hpp"
#include "mesh/error.hpp"
#include "mesh/joint_set.hpp"

#include <string>
#include <vector>

namespace nmm {

void add_joint_sets(const CaseSpec& spec, PhysicalMesh& physical) {
  if (spec.joint_sets.empty())
    return;
  // The drawn joints: the [joints.NAME] that are Physical Curves of the geometry.
  std::vector<int> drawn;
  for (const JointSpec& joint : spec.joints)
    if (const int curve = physical.find_curve(joint.name); curve >= 0)
      drawn.push_back(curve);
  std::vector<JointSetParameters> sets;
  for (const JointSetSpec& set : spec.joint_sets) {
    JointSetParameters parameters = set.parameters;
    if (!set.region.empty()) {
      const int region = physical.find_region(set.region);
      if (region < 0)
        throw InputError(spec.file.string(), set.line, 0,
                         "[[joint_set]] region = " + in_quotes(set.region) +
                             " is not a Physical Surface of " + spec.geometry.filename().string() +
                             "; use one of: " + physical.region_names() +
                             ", or leave region out for all material");
      parameters.regions = {region};
    }
    sets.push_back(std::move(parameters));
  }
  const JointSetResult result = generate_joint_sets(physical, drawn, sets);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const std::string& name = spec.joint_sets[s].joint;
    if (result.joints[s].empty()) {
      physical.warnings.push_back(sets[s].where +
                                  " made no joint in the material: check angle, spacing, "
                                  "origin and region");
      continue;
    }
    int curve = physical.find_curve(name);
    if (curve < 0) {
      curve = static_cast<int>(physical.curves.size());
      physical.curves.push_back({name, {}});
    }
    auto& polylines = physical.curves[static_cast<std::size_t>(curve)].polylines;
    for (const JointSegment& joint : result.joints[s])
      polylines.push_back({joint.a, joint.b});
  }
  for (const std::string& note : result.notes)
    physical.warnings.push_back(note);
}

} // namespace nmm
