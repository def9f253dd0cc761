// .unurbs.json → NurbsModel, strictly. Every problem names the file and the JSON path of the offending value
// ("<path>: surfaces[0].knots_u[3]: ..."), or the byte offset for text that is not JSON at all.
//
// {"type": "nurbs", "solid": true|false,
//  "surfaces": [{"degree_u": p, "degree_v": q, "knots_u": [...], "knots_v": [...],
//                "control_points": [[[x, y, z, w], ...], ...]}]}
// control_points[i][j] has u-index i and v-index j; x, y, z are Euclidean (not weight-multiplied), w > 0.
// Every key is required and no other key is accepted; numbers must be finite; degrees are integers. What makes
// a surface valid (knot vector lengths, order, weights, net size) is checked by NurbsSurface, whose message gets
// the surface's JSON path in front; a "solid" model that is not closed is rejected by NurbsModel.
#include "formats/readers.h"
#include "formats/text_scanner.h"
#include "json_fields.h"

#include "unidist/nurbs.h"

namespace unidist::formats {
namespace {

using json = JsonFields::json;

class UnurbsParser : JsonFields {
 public:
  explicit UnurbsParser(const std::string& path) : JsonFields("", path) {}

  std::shared_ptr<const Model> read() {
    const std::string text = readWholeFile(what());
    json root;
    try {
      root = json::parse(text);
    } catch (const json::parse_error& e) {
      failAtByte(what(), e.byte > 0 ? e.byte - 1 : 0, std::string("not valid JSON (") + shortReason(e.what()) + ")");
    } catch (const json::exception& e) {  // e.g. a number too large for a double
      throw InputError(what() + ": not valid JSON (" + shortReason(e.what()) + ")");
    }
    const auto keys = {"type", "solid", "surfaces"};
    onlyKeys(root, "top level", keys, keys);
    const json& type = root["type"];
    if (!type.is_string() || type.get<std::string>() != "nurbs") fail("type", "must be the string \"nurbs\"");
    if (!root["solid"].is_boolean()) fail("solid", "must be true or false");
    const json& surfaces = root["surfaces"];
    if (!surfaces.is_array() || surfaces.empty()) fail("surfaces", "must be a non-empty array of surfaces");
    std::vector<NurbsSurface> out;
    for (std::size_t k = 0; k < surfaces.size(); ++k) out.push_back(surface(surfaces[k], "surfaces[" + std::to_string(k) + "]"));
    try {
      return std::make_shared<const NurbsModel>(std::move(out), root["solid"].get<bool>());
    } catch (const InputError& e) {
      throw InputError(what() + ": " + e.what());
    }
  }

 private:
  int degree(const json& v, const std::string& where) const {
    if (!v.is_number_integer()) fail(where, "must be an integer");
    const long long d = v.get<long long>();
    if (d < 1 || d > kMaxNurbsDegree) fail(where, "degree " + std::to_string(d) + " out of range (1.." + std::to_string(kMaxNurbsDegree) + ")");
    return static_cast<int>(d);
  }

  std::vector<double> knots(const json& v, const std::string& where) const {
    if (!v.is_array()) fail(where, "must be an array of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(number(v[i], where + "[" + std::to_string(i) + "]"));
    return out;
  }

  NurbsSurface surface(const json& s, const std::string& where) const {
    const auto keys = {"degree_u", "degree_v", "knots_u", "knots_v", "control_points"};
    onlyKeys(s, where, keys, keys);
    const int p = degree(s["degree_u"], where + ".degree_u"), q = degree(s["degree_v"], where + ".degree_v");
    const json& net = s["control_points"];
    const std::string netAt = where + ".control_points";
    if (!net.is_array() || net.empty()) fail(netAt, "must be a non-empty array of rows");
    std::vector<std::vector<Eigen::Vector4d>> points;
    for (std::size_t i = 0; i < net.size(); ++i) {
      const std::string rowAt = netAt + "[" + std::to_string(i) + "]";
      if (!net[i].is_array() || net[i].empty()) fail(rowAt, "must be a non-empty array of [x, y, z, w]");
      points.emplace_back();
      for (std::size_t j = 0; j < net[i].size(); ++j) {
        const std::string at = rowAt + "[" + std::to_string(j) + "]";
        const json& c = net[i][j];
        if (!c.is_array() || c.size() != 4) fail(at, "must be [x, y, z, w]");
        Eigen::Vector4d v;
        for (int k = 0; k < 4; ++k) v[k] = number(c[static_cast<std::size_t>(k)], at + "[" + std::to_string(k) + "]");
        if (!(v[3] > 0)) fail(at, "weight must be positive");
        points.back().push_back(v);
      }
    }
    std::vector<double> ku = knots(s["knots_u"], where + ".knots_u"), kv = knots(s["knots_v"], where + ".knots_v");
    try {
      return NurbsSurface(p, q, std::move(ku), std::move(kv), std::move(points));
    } catch (const InputError& e) {
      fail(where, e.what());
    }
  }
};

}  // namespace

std::shared_ptr<const Model> readUnurbs(const std::string& path) { return UnurbsParser(path).read(); }

}  // namespace unidist::formats
