// Number and vector formatting shared by the subcommands. Every number is printed with 17 significant digits
// ("%.17g": it reads back as the same double); a non-finite value is JSON null (human output: "inf"/"-inf"/"nan").
#pragma once

#include <Eigen/Core>

#include <string>

namespace unidist::cli {

/// %.17g for finite values, "null" otherwise.
std::string jsonNumber(double v);
/// [x,y,z] with jsonNumber entries.
std::string jsonVector(const Eigen::Vector3d& v);
/// A JSON string literal (quoted and escaped).
std::string jsonString(const std::string& s);

/// %.17g, also for non-finite values ("inf", "-inf", "nan").
std::string textNumber(double v);
/// "x y z" with textNumber entries.
std::string textVector(const Eigen::Vector3d& v);

}  // namespace unidist::cli
