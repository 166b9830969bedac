// SPDX-License-Identifier: MIT
// io/step_output.hpp — the manifold elements of a running analysis as one VTK data set per
// output step (`step_NNNNNN.vtu`; DESIGN.md "Output", docs/output.md lists every array).
#pragma once

#include "contact/contact_system.hpp"
#include "io/vtk_writer.hpp"
#include "manifold/bolt.hpp"
#include "manifold/model.hpp"

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

namespace nmm {

/// Principal stresses of a plane stress state (sxx, syy, sxy), Pa, s1 >= s2, and the unit
/// direction of s1 (angle 0.5 atan2(2 sxy, sxx - syy) from x; (1, 0) for an isotropic
/// state, where every direction is principal).
struct PrincipalStress {
  double s1 = 0.0;
  double s2 = 0.0;
  Point2 direction = Point2::UnitX();
};

[[nodiscard]] PrincipalStress principal_stress(const Eigen::Vector3d& stress);

/// The angle of @p principal's s1 direction from the x axis, degrees, in (-90, 90]
/// (counter-clockwise positive): the step files' cell array `principal_angle`.
[[nodiscard]] double principal_angle(const PrincipalStress& principal);

/// The name of a contact state in the contact files: "open", "sliding", "locked" (the
/// `state_name` of each point, and the `state_legend` "0 open", "1 sliding", "2 locked").
[[nodiscard]] const char* contact_state_name(ContactMode mode);

/// The names of the parts of an output step in `case.pvd`, by part number: "elements" (the
/// step file), "contacts" and "boundaries" (PvdSeries's `part_names`).
[[nodiscard]] std::vector<std::string> step_part_names();

/// Area centroid of all polygons of @p element (holes subtracted); the mean vertex when the
/// element has no area.
[[nodiscard]] Point2 element_centroid(const ModelElement& element);

/// Every vertex of every element polygon in the order make_step_data() writes its points:
/// element by element, polygon by polygon, the outer loop, then each hole. Kept at step 0,
/// it is the reference for the `displacement` array (the model moves vertices, never adds
/// or removes them).
[[nodiscard]] std::vector<Point2> step_points(const Model& model);

/// The model's elements at their current position as a polygon mesh for write_vtu(): one
/// cell per element polygon, each with its own points (as `mesh.vtu`); excavated elements
/// (ModelElement::excavated) are left out, so the opening shows.
/// - point data `displacement` (m, 3 components x, y, z = 0): current minus
///   @p initial_points; `velocity` (m/s, 3 components x, y, z): the element's velocity field at
///   the point.
/// - cell data `stress` (Pa; components sxx, syy, sxy, at the element's centroid),
///   `principal_stresses` (Pa; s1 >= s2), `principal_direction` (unit vector of s1, x, y,
///   z = 0), `principal_angle` (degrees, principal_angle()), `element`, `material`, `block`,
///   `kind` (ElementKind; Int32).
/// - field data `TimeValue` (s).
/// @param initial_points  step_points() of the model at step 0.
/// @param velocity        raw velocity of every unknown (TimeStepper::velocity()).
[[nodiscard]] PolygonMeshData make_step_data(const Model& model,
                                             std::span<const Point2> initial_points,
                                             const Eigen::VectorXd& velocity,
                                             double time);

/// `step_NNNNNN.vtu`: the step number with at least 6 digits.
[[nodiscard]] std::string step_file_name(long step);

/// The contact points of the last step as a point cloud for write_vtp_points(), at their
/// current position (the slave material point): point data `normal_force` and
/// `shear_force` (N per metre of thickness; compressive normal force positive, shear along
/// the master edge), `state` (Int32: 0 open, 1 slide, 2 lock), `state_name` (the same as
/// text: contact_state_name()), `gap` (m, negative:
/// penetration), `normal` (unit outward normal of the master edge, 3 components), `bonded`
/// (Int32: 1 for an intact joint), `length` (the point's tributary length, m), `pressure`
/// (compressive normal stress, Pa: an angle's spring force over its length; for the points of
/// edge-to-edge contacts the force of the closed points on the same slave edge over their
/// summed lengths; 0 when open); field data `TimeValue` (s) and `state_legend` (text, one
/// line per state: "0 open", "1 sliding", "2 locked").
[[nodiscard]] PointCloudData
make_contact_data(const ContactSystem& contact, const Model& model, double time);

/// `contacts_NNNNNN.vtp`: the step number with at least 6 digits.
[[nodiscard]] std::string contact_file_name(long step);

/// The joints and free boundaries of every block at their current position as polylines
/// for write_vtp_lines() (make_boundary_data() of Model::loops): both faces of an opening or
/// sliding joint are drawn, each moving with its own block. Cell data `block`, `joint`
/// (named curve, -1 on a free boundary), `loop`; field data `TimeValue` (s). With @p bolts,
/// a line per bolt bar after the loops (block, joint and loop -1 on them) and the cell data
/// `bolt` (index in history.csv's order, -1 on the loops), `axial_force` (N, tension
/// positive) and `bolt_state` (0 elastic, 1 yielding, 2 ruptured; -1 on the loops); field
/// data `bolt_names` ("0 B1", ...) and `bolt_state_legend`.
[[nodiscard]] PolylineData
make_boundary_step_data(const Model& model, std::span<const Bolt> bolts, double time);

/// `boundary_NNNNNN.vtp`: the step number with at least 6 digits.
[[nodiscard]] std::string boundary_file_name(long step);

} // namespace nmm
