// Merging and reducing contact lists. Internal.
#pragma once

#include "unidist/contacts.h"

#include <vector>

namespace unidist::contact {

/// Drops contacts whose two points both lie within eps of a deeper (or equal, earlier) contact's, then sorts
/// by distance (deepest first; ties by position, so the order is reproducible).
void mergeDuplicates(std::vector<Contact>& cs, double eps);

/// Keeps at most maxContacts (> 0): the deepest first, then repeatedly the one farthest from those kept
/// (spread over the contact region), reported deepest first.
void reduceContacts(std::vector<Contact>& cs, int maxContacts);

}  // namespace unidist::contact
