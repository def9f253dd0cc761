// Contact regions for Bullet's 4-point manifolds: a non-convex pair touching in separate places gets one
// manifold per place. Internal.
#pragma once

#include "unidist/contacts.h"

#include <vector>

namespace unidist::bullet {

/// Splits contacts (deepest first) into groups of at most 4: while a group is larger, it is cut at the widest
/// gap between its points along the axis of its largest extent — so a box resting on a floor stays one group and
/// a dumbbell's two ends become two. At most maxGroups groups (the deepest contacts are kept first); each group
/// deepest first, groups ordered by their deepest contact.
std::vector<std::vector<Contact>> contactRegions(const std::vector<Contact>& deepestFirst, int maxGroups);

}  // namespace unidist::bullet
