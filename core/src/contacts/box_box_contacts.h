// Contact manifold of two boxes (internal): what manifoldContacts() uses for a box–box pair instead of the mesh
// feature search on the boxes' stand-ins and the patch fill.
#pragma once

#include "unidist/contacts.h"
#include "unidist/primitives.h"

#include <vector>

namespace unidist::contact {

/// Contacts of box a and box b within margin, deepest first, in unidist::Contact's conventions (pointB − pointA =
/// distance · normal, normal from A toward B; overlapping: distance < 0, normal the way B moves to separate).
///  * The separating-axis test over the 15 axes gives the minimum translation (overlap) or the largest axis gap
///    (apart); beyond the margin there is nothing to report.
///  * Along a face axis the other box's face most opposite to the reference face is clipped to the reference
///    face's side planes (Sutherland–Hodgman); each corner of the clipped polygon within the margin of the
///    reference plane is a contact, with its own distance along the face normal: on a face-on-face contact the
///    corners of the contact polygon, also for boxes apart (speculative contacts).
///  * Along an edge–edge axis (clearly shallower than every face axis): the one closest-point pair of the two edges.
///  * When no face axis realises the distance (boxes apart whose nearest features are a vertex and an edge, or two
///    parallel edges), the single exact closest pair (detail::boxBox, to `tolerance`).
///  * In the last two cases, when the best face axis lies within 0.05 rad of that pair's normal (a box resting on
///    another across an edge, nearly flat: the edges' crossing is deepest by a hair), the clipped polygon's corners
///    that are no deeper than the pair are added: a resting box keeps its whole patch, not one point.
/// The deepest contact is the exact signed distance; no contact is deeper. maxContacts > 0 reduces the set by
/// reduceContacts (the deepest, then the most spread); 0 keeps all (at most nine).
std::vector<Contact> boxBoxContacts(const Box& a, const Eigen::Isometry3d& X_WA, const Box& b,
                                    const Eigen::Isometry3d& X_WB, double margin, double tolerance, int maxContacts);

}  // namespace unidist::contact
