// Text → core objects: numbers, primitive specs and poses as written on the `unidist` command line
// (syntax in docs/query-contract.md, "Primitive specs" and "Pose"). Every function either returns a valid
// object or throws InputError with a one-line message naming the problem; nothing is silently repaired
// except the documented normalisation of a pose's quaternion.
#pragma once

#include "unidist/model.h"
#include "unidist/types.h"

#include <memory>
#include <string>
#include <string_view>

namespace unidist {

/// One finite number in C/JSON decimal syntax: [+-] digits [. digits] [(e|E) [+-] digits] (".5" and "5." are
/// accepted as in C). Rejects the empty string, spaces, hex, "inf", "nan", trailing junk and values that
/// overflow a double; values that underflow become the nearest double (possibly 0). `what` names the field in
/// the error message, e.g. "sphere: r".
double parseNumber(std::string_view text, std::string_view what);

/// True when text has the shape of a primitive spec, "name:..." with an alphabetic name; loadModel treats
/// everything else as a file path. Says nothing about validity (parsePrimitiveSpec decides that).
bool looksLikePrimitiveSpec(std::string_view text);

/// Builds the primitive of a spec `name:key=value,...`: sphere:r · box:hx,hy,hz · capsule:r,h · cylinder:r,h ·
/// cone:r,h · torus:R,r (0 < r < R) · plane:nx,ny,nz,d (n ≠ 0). Keys are case-sensitive, in any order, each
/// exactly once, no spaces. Sizes must be > 0. Errors read e.g. "sphere: missing key 'r'",
/// "box: duplicate key 'hx'", "unknown primitive 'pyramid'", "capsule: h must be > 0 (got -1)".
std::shared_ptr<const Model> parsePrimitiveSpec(const std::string& spec);

/// Parses a pose "tx ty tz qw qx qy qz" (seven numbers separated by white space): world = R(q)·local + t.
/// q is normalised silently; a zero quaternion, a count other than seven, NaN/Inf or junk throw InputError.
/// `what` starts every error message (the command line passes the option name, e.g. "--pose-a").
Eigen::Isometry3d parsePose(const std::string& text, std::string_view what = "pose");

}  // namespace unidist
