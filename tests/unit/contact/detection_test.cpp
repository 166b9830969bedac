// SPDX-License-Identifier: MIT
#include "contact/detection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <vector>

namespace nmm {
namespace {

using std::numbers::pi;

/// Builds a boundary from loops given counter-clockwise (material on the left).
ContactBoundary boundary_of(const std::vector<std::vector<Point2>>& loops) {
  ContactBoundary b;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const int base = b.n_vertices();
    const int n = static_cast<int>(loops[l].size());
    for (int k = 0; k < n; ++k) {
      b.position.push_back(loops[l][static_cast<std::size_t>(k)]);
      b.next.push_back(base + (k + 1) % n);
      b.previous.push_back(base + (k + n - 1) % n);
      b.block.push_back(static_cast<int>(l));
    }
  }
  return b;
}

std::vector<Point2> square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

DetectionOptions options(double distance) {
  DetectionOptions o;
  o.distance = distance;
  o.penetration = 0.1 * distance;
  return o;
}

int count(const std::vector<ContactCandidate>& c, ContactKind kind) {
  int n = 0;
  for (const ContactCandidate& x : c)
    n += x.kind == kind;
  return n;
}

TEST(ContactBoundary, AnglesOfCornersStraightPointsAndCrackTips) {
  // A square, a straight point on its edge, and a slit (crack) ending at (0.5, 0.5).
  const ContactBoundary b = boundary_of(
      {{{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0.2, 0.5}, {0.5, 0.5}, {0.2, 0.5}}});
  EXPECT_NEAR(b.angle(0), pi / 2.0, 1e-14); // convex corner
  EXPECT_NEAR(b.angle(1), pi, 1e-14);       // straight
  EXPECT_NEAR(b.angle(6), 2.0 * pi, 1e-14); // crack tip: the slit turns back
  EXPECT_NEAR(b.outward_normal(0).y(), -1.0, 1e-14);
  EXPECT_TRUE(b.adjacent(0, 1));
  EXPECT_FALSE(b.adjacent(0, 2));
}

TEST(ContactDetection, FacingEdgesWithinTwiceTheStepDisplacementMakeAnEdgeContact) {
  // Two unit squares, one above the other with a 0.01 gap.
  const ContactBoundary b = boundary_of({square(0, 0, 1), square(0.3, 1.01, 1)});
  const auto near = detect_contacts(b, options(0.02), {});
  EXPECT_EQ(count(near, ContactKind::edge_edge), 1);
  EXPECT_EQ(count(near, ContactKind::vertex_edge), 0); // covered by the edge contact
  const auto far = detect_contacts(b, options(0.005), {});
  EXPECT_TRUE(far.empty());
}

TEST(ContactDetection, CornerAgainstAnEdgeIsAnAngleToEdgeContact) {
  // A square standing on its corner 0.005 above a base.
  const double h = std::sqrt(0.5);
  const ContactBoundary b = boundary_of(
      {square(-2, -1, 4), {{0, 3.005}, {h, 3.005 + h}, {0, 3.005 + 2 * h}, {-h, 3.005 + h}}});
  // (the base's top edge runs from (2, 3) to (-2, 3))
  const auto contacts = detect_contacts(b, options(0.02), {});
  ASSERT_EQ(contacts.size(), 1U);
  EXPECT_EQ(contacts[0].kind, ContactKind::vertex_edge);
  EXPECT_EQ(contacts[0].slave, 4);  // the lowest corner of the tilted square
  EXPECT_EQ(contacts[0].master, 2); // the base's top edge (from (2, 3) to (-2, 3))
}

TEST(ContactDetection, AngleCriterionRejectsAWedgeThatWouldHaveToRotate) {
  // A corner whose wedge dips 10 degrees below the edge's line cannot touch it without a
  // rotation larger than Shi's 2 x 1.5 degrees; dipping 2 degrees it can (the control: the
  // same corner, so a detector that finds nothing at all fails).
  const auto wedge = [](double degrees) {
    const double a = degrees * pi / 180.0;
    return boundary_of(
        {square(-2, -1, 4), {{0, 3.001}, {std::cos(-a), 3.001 + std::sin(-a)}, {0.2, 3.5}}});
  };
  EXPECT_TRUE(detect_contacts(wedge(10.0), options(0.02), {}).empty());
  const auto contacts = detect_contacts(wedge(2.0), options(0.02), {});
  ASSERT_EQ(contacts.size(), 1U);
  EXPECT_EQ(contacts[0].slave, 4);  // the wedge's corner
  EXPECT_EQ(contacts[0].master, 2); // the base's top edge
}

TEST(ContactDetection, TwoConvexCornersTouchThroughOneEntranceLineWithAnAlternative) {
  // Two squares corner to corner along their diagonal: an angle-to-angle contact of two
  // convex angles, reduced to one angle-to-edge contact and its alternative (Shi 3.2 [1]).
  const ContactBoundary b = boundary_of({square(0, 0, 1), square(1.003, 1.004, 1)});
  const auto contacts = detect_contacts(b, options(0.02), {});
  ASSERT_EQ(contacts.size(), 1U);
  EXPECT_EQ(contacts[0].kind, ContactKind::vertex_edge);
  EXPECT_GE(contacts[0].alternative_master, 0);
}

TEST(ContactDetection, ConvexCornerIntoAReflexCornerHasTwoEntranceLines) {
  // An L-shaped base with a reflex (270 degree) corner at (1, 1), and the tip of a 60 degree
  // wedge sitting in it, its sides 15 degrees off the L's sides (so no edge faces an edge):
  // the tip enters through both entrance lines of the reflex angle (Shi 3.2), one contact
  // against each of its edges.
  const double c = 1.003;
  const double a = 15.0 * pi / 180.0;
  const double b60 = 75.0 * pi / 180.0;
  const ContactBoundary b = boundary_of({{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                                         {{c, c},
                                          {c + 0.5 * std::cos(a), c + 0.5 * std::sin(a)},
                                          {c + 0.5 * std::cos(b60), c + 0.5 * std::sin(b60)}}});
  const auto contacts = detect_contacts(b, options(0.02), {});
  ASSERT_EQ(contacts.size(), 2U);
  std::set<int> masters;
  for (const ContactCandidate& contact : contacts) {
    EXPECT_EQ(contact.kind, ContactKind::vertex_edge);
    EXPECT_EQ(contact.slave, 6); // the wedge's tip
    masters.insert(contact.master);
  }
  EXPECT_EQ(masters, (std::set<int>{2, 3})); // the two edges of the reflex corner
}

/// Where a joint (V-W) meets a free face that curves away from the rock (the crown of an
/// opening, reflex corners E1, E2, E3 along it), the corner V of the block on the joint's
/// other side, behind the lines of E1's edges W-E1 and E1-E2 by at least @p behind: the
/// block above has corners W (convex) and V, the triangle beside it V, P, W. Block "above"
/// is loop 0 (W = 0, E1 = 1, E2 = 2, E3 = 3, V = 6), the triangle loop 1 (V = 7).
ContactBoundary joint_at_a_curved_face(double behind) {
  const std::vector<Point2> face = {{0.0, 0.0}, {0.3, 0.06}, {1.0, 0.13}, {1.6, 0.13}};
  const Point2 joint = Point2(-0.08, 0.23).normalized(); // from W up to V
  double along = 0.0; // V = W + along joint, behind both lines of E1's edges
  for (std::size_t k = 0; k < 2; ++k) {
    const Point2 d = face[k + 1] - face[k];
    const Point2 normal = Point2(d.y(), -d.x()).normalized(); // out of the rock, down
    along = std::max(along, (-behind - normal.dot(face[0] - face[k])) / normal.dot(joint));
  }
  const Point2 v = face[0] + along * joint;
  return boundary_of({{face[0], face[1], face[2], face[3], {0.9, 1.0}, {-0.3, 1.0}, v},
                      {v, {-1.5, -0.4}, face[0]}});
}

TEST(ContactDetection, ACornerOnAJointBehindTheReflexCornersOfAFaceIsNoNewContact) {
  // V lies on the block above's joint face, 0.24 m behind the lines of the reflex corner E1
  // of its free face (within the contact distance of it; E2 and E3 are beyond): no new
  // angle contact of V against the face's edges (0, 1, 2), only the joint's own pair. Locked from
  // the start with its 0.24 m as the springs' zero, such a spring jacked a tunnel's crown once the
  // blocks moved. Just within the depth a new contact may start (0.9 x penetration) the
  // angle-to-angle contacts are made, just beyond it (1.1 x) not; closed in the last step, they are
  // kept at any depth.
  const auto against_face = [](const std::vector<ContactCandidate>& contacts) {
    std::vector<ContactCandidate> found;
    for (const ContactCandidate& c : contacts) {
      if (c.slave == 7 && c.kind == ContactKind::vertex_edge && c.master <= 2)
        found.push_back(c);
    }
    return found;
  };
  const DetectionOptions o = options(0.6); // penetration 0.06 m
  EXPECT_TRUE(against_face(detect_contacts(joint_at_a_curved_face(0.24), o, {})).empty());
  EXPECT_TRUE(
      against_face(detect_contacts(joint_at_a_curved_face(1.1 * o.penetration), o, {})).empty());
  const auto shallow =
      against_face(detect_contacts(joint_at_a_curved_face(0.9 * o.penetration), o, {}));
  ASSERT_FALSE(shallow.empty());
  // Closed in the last step: kept at 0.24 m (made where new contacts may start 0.3 m deep).
  DetectionOptions deep = o;
  deep.penetration = 0.3;
  std::vector<std::uint64_t> keep;
  for (const ContactCandidate& c :
       against_face(detect_contacts(joint_at_a_curved_face(0.24), deep, {})))
    keep.push_back(c.key());
  ASSERT_FALSE(keep.empty());
  EXPECT_EQ(against_face(detect_contacts(joint_at_a_curved_face(0.24), o, keep)).size(),
            keep.size());
}

TEST(ContactDetection, AThinBlockDoesNotTouchItselfAcrossItsThickness) {
  // A 0.001-thick plate: its top face is within the contact distance of its bottom face,
  // but on the material side of it (penetration 0.001 > the 0.0002 a new contact may have).
  const ContactBoundary b = boundary_of({{{0, 0}, {1, 0}, {1, 0.001}, {0, 0.001}}});
  EXPECT_TRUE(detect_contacts(b, options(0.002), {}).empty());
}

TEST(ContactDetection, TwoCornersOfOneBlockJoinedByAStraightSideAreNoContact) {
  // A 3 x 0.5 slab whose sides are split by straight points (where math edges cross them),
  // searched with a contact distance larger than its thickness (Shi's delta = 0.1 of a 3 m
  // model). Its corners (0, 0) and (0, 0.5) lie on one straight side: the direction from one
  // to the other runs along a ray of each one's material wedge, and they can only meet
  // through the slab. They were an angle-to-angle contact at 0.5 m penetration.
  const ContactBoundary slab = boundary_of(
      {{{0, 0}, {1.5, 0}, {3, 0}, {3, 0.25}, {3, 0.5}, {1.5, 0.5}, {0, 0.5}, {0, 0.25}}});
  EXPECT_TRUE(detect_contacts(slab, options(0.64), {}).empty());
  // Two slabs stacked with a 0.01 gap: the same corners of different blocks do meet (one
  // edge-to-edge contact between the facing sides covers them).
  const ContactBoundary stacked =
      boundary_of({{{0, 0}, {3, 0}, {3, 0.5}, {0, 0.5}}, {{0, 0.51}, {3, 0.51}, {3, 1}, {0, 1}}});
  EXPECT_EQ(count(detect_contacts(stacked, options(0.64), {}), ContactKind::edge_edge), 1);
}

TEST(ContactDetection, CornersAlongOneStraightJointBeyondASideAreNoAngleContact) {
  // Two blocks that meet only at the origin, where two joints cross (x = 0 and y = 0): A to
  // the lower right, B to the upper left. B's right face runs up the joint x = 0 to its corner
  // (0, 0.5), split at (0, 0.4) where a math edge crosses it. With a contact distance of 1.2
  // (examples/02_jointed_slope: 1.6 m against edges of 0.07 m) criteria [2] and [4] pair A's
  // corner at the origin with B's corner (0, 0.5): 0.5 apart, their wedges translated onto
  // each other touch along the joint without overlapping. But A's corner lies along B's
  // side (0, 0.5)-(0, 0.4), 0.4 beyond its far end, on the joint's line: a spring there held
  // it to a line it was not near (touching, so locked from the start). The only contact is
  // the angle-to-angle one of the two corners at the origin (one spring, with its
  // alternative line), not one for each edge leaving the origin either.
  const ContactBoundary b = boundary_of(
      {{{0, 0}, {0, -1}, {1, -1}, {1, 0}}, {{-1, 0}, {0, 0}, {0, 0.4}, {0, 0.5}, {-1, 0.5}}});
  const auto contacts = detect_contacts(b, options(1.2), {});
  ASSERT_EQ(contacts.size(), 1U);
  EXPECT_EQ(contacts[0].kind, ContactKind::vertex_edge);
  EXPECT_GE(contacts[0].alternative_master, 0);
  for (const int v : {contacts[0].slave, contacts[0].alternative_slave})
    EXPECT_LT(b.position[static_cast<std::size_t>(v)].norm(), 1e-15); // a corner at the origin
}

TEST(ContactDetection, FourCornersWhereTwoJointsCrossMakeTwoAngleContacts) {
  // Four blocks around the point where two straight joints cross (at 20 and 110 degrees, away
  // from the origin, so that the ends of the edges leaving the point are one point only to
  // rounding), each side split where a math edge would cross it. Neighbours touch along
  // their faces (edge-to-edge contacts); the opposite corners, two pairs, touch at the
  // point: one angle-to-angle contact each. A corner against an edge that leaves the point
  // (its parameter 1e-16 from the end) is that same contact: counted as an angle-to-edge
  // contact too, it gave two corners four springs whose friction changed each other's normal
  // force from solve to solve (examples/02_jointed_slope, the crossings of the bedding and
  // the cross joints).
  const Point2 o(46.1081, 19.218);
  const double a = 20.0 * pi / 180.0;
  const Point2 u(std::cos(a), std::sin(a));
  const Point2 v(-std::sin(a), std::cos(a));
  auto at = [&](double s, double t) { return Point2(o + s * u + t * v); };
  // Each block: the crossing point, then out along one joint, around, back along the other
  // (counter-clockwise), its two sides split at 0.45 and 0.3.
  const ContactBoundary b =
      boundary_of({{at(0, 0), at(0.45, 0), at(1, 0), at(1, 1), at(0, 1), at(0, 0.3)},
                   {at(0, 0), at(0, 0.45), at(0, 1), at(-1, 1), at(-1, 0), at(-0.3, 0)},
                   {at(0, 0), at(-0.45, 0), at(-1, 0), at(-1, -1), at(0, -1), at(0, -0.3)},
                   {at(0, 0), at(0, -0.45), at(0, -1), at(1, -1), at(1, 0), at(0.3, 0)}});
  const auto contacts = detect_contacts(b, options(1.2), {});
  EXPECT_EQ(count(contacts, ContactKind::vertex_edge), 2);
  for (const ContactCandidate& c : contacts) {
    if (c.kind == ContactKind::vertex_edge) {
      EXPECT_GE(c.alternative_master, 0) << "an angle-to-angle contact, not a corner on an edge";
    }
  }
}

TEST(ContactDetection, TheTwoFacesOfACrackAreInContact) {
  // A slit loop (a crack inside a body, its faces split in three): out along the crack and
  // back. The faces' middle pieces touch; the pieces at each tip share the tip vertex (in
  // NMM they lie in the tip's element, one displacement field, so they cannot interpenetrate).
  const ContactBoundary b = boundary_of({{{0, -2}, {3, -2}, {3, 2}, {0, 2}},
                                         {{1, 0}, {1.4, 0}, {1.7, 0}, {2, 0}, {1.7, 0}, {1.4, 0}}});
  const auto contacts = detect_contacts(b, options(0.02), {});
  ASSERT_EQ(count(contacts, ContactKind::edge_edge), 1);
  EXPECT_EQ(contacts[0].slave, 5);  // (1.4, 0) -> (1.7, 0)
  EXPECT_EQ(contacts[0].master, 8); // (1.7, 0) -> (1.4, 0)
}

TEST(ContactDetection, ClosedContactsAreKeptWhatEverTheirPenetration) {
  // Squares overlapping by 0.005: a new contact would be refused (0.005 > 0.1 x 0.02), but a
  // contact closed in the last step carries over.
  const ContactBoundary b = boundary_of({square(0, 0, 1), square(0.3, 0.995, 1)});
  EXPECT_TRUE(detect_contacts(b, options(0.02), {}).empty());
  ContactCandidate closed;
  closed.kind = ContactKind::edge_edge;
  closed.slave = 2;
  closed.master = 4;
  EXPECT_EQ(detect_contacts(b, options(0.02), {closed.key()}).size(), 1U);
}

TEST(ContactDetection, BroadPhaseFindsEveryPairOfAManyBlockRow) {
  // 200 squares in a row with 0.01 gaps: 199 edge contacts, found by the sweep.
  std::vector<std::vector<Point2>> loops;
  for (int i = 0; i < 200; ++i)
    loops.push_back(square(1.01 * i, 0, 1));
  DetectionStats stats;
  const auto contacts = detect_contacts(boundary_of(loops), options(0.02), {}, &stats);
  EXPECT_EQ(count(contacts, ContactKind::edge_edge), 199);
  EXPECT_LT(stats.edge_pairs, 200 * 8); // neighbours only, not all pairs
}

TEST(ContactDetection, BroadPhaseFindsEveryPairInAnyShapeAndAcrossLongEdges) {
  // A tall column of 300 squares (the shape a sweep along x handled worst), and a 10 x 10
  // grid of squares on a slab 110 m long whose top edge crosses many cells of the grid:
  // every facing pair is found (299; 2 x 10 x 9 + 10), and only neighbours are paired.
  std::vector<std::vector<Point2>> column;
  for (int i = 0; i < 300; ++i)
    column.push_back(square(0, 1.01 * i, 1));
  DetectionStats stats;
  auto contacts = detect_contacts(boundary_of(column), options(0.02), {}, &stats);
  EXPECT_EQ(count(contacts, ContactKind::edge_edge), 299);
  EXPECT_LT(stats.edge_pairs, 1200 * 8); // 1200 edges; all pairs would be 7.2e5

  std::vector<std::vector<Point2>> grid{{{-50, -1.01}, {60, -1.01}, {60, -0.01}, {-50, -0.01}}};
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j)
      grid.push_back(square(1.01 * i, 1.01 * j, 1));
  }
  DetectionStats grid_stats;
  contacts = detect_contacts(boundary_of(grid), options(0.02), {}, &grid_stats);
  EXPECT_EQ(count(contacts, ContactKind::edge_edge), 2 * 10 * 9 + 10);
  EXPECT_LT(grid_stats.edge_pairs, 404 * 8); // 404 edges; all pairs would be 8.2e4
}

} // namespace
} // namespace nmm
