#pragma once

// The common plane (c-p) between two convex blocks: the plane that lies
// between them and is as far as possible from the nearest vertex of either
// block (for overlapping blocks: as little as possible overlapped by the most
// deeply buried vertex). It gives the contact normal, the gap (or overlap) and
// the contact type from vertex-to-plane tests only, at a cost linear in the
// number of vertices (eqs. 4 and 14 of the theory manual).
//
// Everything here works on flat vertex arrays (pointer + count) so that it can
// run directly on the model's block storage; nothing allocates.

#include <talus/geometry/plane.h>

#include <limits>

namespace talus
{

/// How two blocks touch, from the number of vertices of each block that touch
/// the common plane (Table 1 of the theory manual). The names are symmetric:
/// vertex_face means one block touches with a vertex and the other with a
/// face, whichever is which.
enum class ContactType
{
  vertex_face,
  edge_edge,
  edge_face,
  face_face,
  vertex_edge,
  vertex_vertex,
  none
};

/// Contact type from the number of vertices of block A and of block B that
/// touch the common plane: 1 = vertex, 2 = edge, 3 or more = face; 0 on either
/// side = none.
ContactType classify_contact(unsigned int n_a, unsigned int n_b);

/// Name of a contact type, e.g. "edge-face".
const char* to_string(ContactType type);

/// The common plane of one contact: the plane {x : normal . (x - reference) = 0}.
struct CommonPlane
{
  /// Unit normal pointing from block A towards block B.
  Vec3 normal = Vec3::UnitZ();
  /// Reference point C: the point the plane rotates about and, for touching
  /// blocks, where the contact force acts.
  Vec3 reference = Vec3::Zero();

  Plane plane() const { return Plane(normal, normal.dot(reference)); }
};

struct CommonPlaneSettings
{
  /// First perturbation angle of a new contact (eq. 10 with k = tan(angle)).
  double k_max_degrees = 5.0;
  /// Smallest perturbation angle: the resolution of the hill-climb.
  double k_min_degrees = 0.01;
  /// Contact tolerance (CTOL, a length): as soon as the gap exceeds it the
  /// search stops and the result says the contact is to be deleted. Infinite
  /// by default (never stop early).
  double contact_tolerance = std::numeric_limits<double>::infinity();
  /// A vertex V counts as touching when it lies within
  ///   touch_tolerance + tan(k_min) |V - V_near|
  /// of its block's nearest level to the plane (or beyond the plane, for
  /// overlapping blocks), V_near being the block's nearest vertex. The second
  /// term covers the angular resolution of the hill-climb. A length.
  double touch_tolerance = 1e-9;
  /// Safety cap on perturbation rounds.
  unsigned int max_iterations = 1000;
  /// After the hill-climb, solve for the exact normal of the touching
  /// features (face normal, edge-cross-edge, ...) and keep it when it does
  /// not lower the gap. This is an addition to the manual's scheme: it removes
  /// the O(k_min) error of the hill-climb in the normal and the gap.
  bool polish = true;
};

struct CommonPlaneResult
{
  /// d_B - d_A: the distance between the blocks measured along the normal;
  /// negative = overlap (eqs. 6-7).
  double gap = 0.0;
  /// False when the gap exceeded the contact tolerance: delete the contact.
  /// Then the search stopped at once: the gap and plane are those of that
  /// moment, the counts are zero and the type is none.
  bool within_tolerance = true;
  /// Perturbation rounds (each tries four normals, eq. 10) plus steps along
  /// a ridge (one normal each).
  unsigned int iterations = 0;
  /// Normals whose gap was evaluated by a scan of both vertex sets (the unit
  /// of cost of eq. 14), counting scans cut short because they could no
  /// longer win. The scans that collect touching vertices for the exact
  /// solve, the ridge steps and the final classification come on top.
  unsigned int evaluations = 0;
  /// Vertices of A and of B that touch the plane (see touch_tolerance); for
  /// blocks apart by a small gap these are the vertices facing each other.
  unsigned int n_touching_a = 0;
  unsigned int n_touching_b = 0;
  /// classify_contact(n_touching_a, n_touching_b).
  ContactType type = ContactType::none;
  /// True when the final normal came from the exact solve for the touching
  /// features (see CommonPlaneSettings::polish).
  bool polished = false;
};

/// Initial guess of a new contact (eq. 5): reference point midway between the
/// centroids, normal from A's centroid to B's. If the centroids coincide the
/// normal is +z.
CommonPlane initial_common_plane(const Vec3& centroid_a, const Vec3& centroid_b);

/// Moves `cp` to the plane that maximises the gap between blocks A and B
/// (vertices `va[0..na)` and `vb[0..nb)`, both convex, na, nb > 0; requires
/// 0 < k_min <= k_max). `cp` is the result of initial_common_plane() for a
/// new contact, or the plane of the last update for an existing one.
/// - Rotation: the perturbation hill-climb of eq. 10, from k_max for a new
///   contact; an existing contact first gets the exact solve (below) and the
///   four k_min perturbations, and climbs from k_max only if they help. Two
///   additions to the manual's scheme keep the climb from stalling on a
///   sharp ridge of the gap function and make the answer exact: a step along
///   the ridge before k is halved, and the exact normal of the touching
///   features at the end (CommonPlaneSettings::polish).
/// - Translation to the mid-plane along the normal (eqs. 6-8).
/// - For blocks apart (gap > 0) the reference point goes midway between the
///   nearest vertices (eq. 9). Where a block has several equally near
///   vertices, the feature of lower dimension decides: a vertex or edge
///   facing a face gives its own centre, two crossing edges the midpoint of
///   their closest points, otherwise the mean of both sides; the point is
///   then put on the mid-plane. For touching blocks the reference point only
///   moves along the normal (its tangential position belongs to the
///   mechanics, eqs. 11-13).
/// For blocks apart the maximum is unique and found to round-off. For
/// overlapping blocks the overlap can have several local minima; the one
/// nearest the starting plane is found (tests/contact/common_plane_06).
CommonPlaneResult update_common_plane(CommonPlane& cp, const Vec3* va, unsigned int na,
                                      const Vec3* vb, unsigned int nb,
                                      const CommonPlaneSettings& settings, bool new_contact);

} // namespace talus
