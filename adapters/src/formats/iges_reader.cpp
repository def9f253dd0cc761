// IGES → NurbsModel: every rational B-spline surface (entity 128) of the file, each moved by its
// transformation matrix (entity 124, chained ones applied in turn) when its directory entry points to one.
//
// Accepted: the fixed 80-column ASCII form. Column 73 says the section (S start, G global, D directory,
// P parameter, T terminate); lines of other sections are ignored where they are not needed. The global
// section's first two fields set the parameter and record delimiters ("1H," style Hollerith or empty for the
// defaults ',' and ';'). A directory entry is two lines of 8-column fields; its field 2 points to the entity's
// first P line (by sequence number), field 7 to a transformation matrix, and line 2 field 4 gives the P line
// count. Parameter data is columns 1–64 of those P lines; strings are Hollerith (nHtext), numbers may use D
// exponents. Entity 128: K1 K2 M1 M2 PROP1..5, knots, weights, control points, parameter range.
// Trimming is not modelled: a trimmed face (144 with 142, or a B-rep face 510 with its loop 508) is accepted
// only where its boundary, in the surface's parameter space (102 / 110 / 126 curves), traces the whole parameter
// rectangle, so that the face is the whole surface (a CAD kernel's closed torus or sphere); holes, a boundary
// inside the rectangle, a bounded surface (143) or a boundary given in model space only are refused with an
// error naming the entity. A parameter range narrower than the knot domain restricts the surface to it
// (NurbsSurface::restricted); one reaching outside it is an error.
// The model is a solid when its surfaces close up (NurbsModel's closedness test), an open surface otherwise.
// Every problem is an InputError "<path>:<line>: ..." (physical line of the file, from 1).
#include "formats/readers.h"
#include "formats/text_scanner.h"

#include "unidist/adapters/spec.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace unidist::formats {
namespace {

struct Token {
  std::string text;
  std::size_t line;  // physical line of its first character
};

struct DirectoryEntry {
  int type = 0, parameterStart = 0, transform = 0, parameterLines = 0;
  std::size_t line = 0;
};

class IgesParser {
 public:
  explicit IgesParser(std::string path) : path_(std::move(path)) {}

  std::shared_ptr<const Model> read() {
    const std::string text = readWholeFile(path_);
    splitSections(text);
    if (directory_.empty()) failAt(lastLine_, "no directory section (D lines): not an IGES file");
    readGlobal();
    readDirectory();
    checkTrimming();
    std::vector<NurbsSurface> surfaces;
    std::size_t firstLine = 0;
    for (const auto& [de, entry] : entries_) {
      if (entry.type != 128) continue;
      if (!firstLine) firstLine = entry.line;
      surfaces.push_back(surface(de, entry));
    }
    if (surfaces.empty()) failAt(lastLine_, "no rational B-spline surface (entity 128) in the file");
    try {
      try {
        return std::make_shared<const NurbsModel>(surfaces, true);
      } catch (const InputError& e) {
        if (std::string(e.what()).find("not closed") == std::string::npos) throw;
        return std::make_shared<const NurbsModel>(std::move(surfaces), false);
      }
    } catch (const InputError& e) {
      throw InputError(path_ + ":" + std::to_string(firstLine) + ": " + e.what());
    }
  }

 private:
  [[noreturn]] void failAt(std::size_t line, const std::string& what) const { failAtLine(path_, line, what); }

  void splitSections(const std::string& text) {
    LineScanner s(path_, text);
    while (s.nextLine()) {
      std::string line(s.line());
      lastLine_ = s.lineNumber();
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      if (line.size() < 73) failAt(s.lineNumber(), "line shorter than 73 columns (IGES lines are 80 columns, section letter in column 73)");
      const char section = line[72];
      const std::string data = line.substr(0, 72);
      switch (section) {
        case 'S': break;
        case 'G': global_.push_back({data, s.lineNumber()}); break;
        case 'D': directory_.push_back({data, s.lineNumber()}); break;
        case 'P': parameter_.push_back({data.substr(0, 64), s.lineNumber()}); break;
        case 'T': break;
        case 'F': case 'C': failAt(s.lineNumber(), "compressed or binary IGES is not supported (ASCII fixed format only)");
        default: failAt(s.lineNumber(), std::string("unknown section letter '") + section + "' in column 73");
      }
    }
  }

  /// Tokens of a delimited stream: fields separated by delim_, ended by record_; Hollerith strings kept whole.
  std::vector<Token> tokens(const std::vector<Token>& lines, bool stopAtRecord, std::size_t& firstLine) const {
    std::string all;
    std::vector<std::size_t> lineOf;  // physical line of every character
    for (const Token& l : lines) {
      all += l.text;
      lineOf.insert(lineOf.end(), l.text.size(), l.line);
    }
    firstLine = lines.empty() ? lastLine_ : lines.front().line;
    std::vector<Token> out;
    std::size_t i = 0;
    std::string current;
    std::size_t currentLine = firstLine;
    bool inField = false;
    while (i < all.size()) {
      const char c = all[i];
      if (c == delim_ || c == record_) {
        out.push_back({trim(current), inField ? currentLine : lineOf[i]});
        current.clear();
        inField = false;
        ++i;
        if (c == record_ && stopAtRecord) return out;
        continue;
      }
      if (!inField) {
        currentLine = lineOf[i];
        inField = c != ' ';
      }
      // A Hollerith string: digits, 'H', then exactly that many characters (delimiters included).
      if (c >= '0' && c <= '9' && trim(current).empty()) {
        std::size_t j = i;
        while (j < all.size() && all[j] >= '0' && all[j] <= '9') ++j;
        if (j < all.size() && (all[j] == 'H' || all[j] == 'h')) {
          if (j - i > 6) failAt(lineOf[i], "Hollerith string length is not a sensible count");
          const std::size_t n = std::stoul(all.substr(i, j - i));
          if (j + 1 + n > all.size()) failAt(lineOf[i], "Hollerith string longer than the data that follows");
          current = all.substr(i, j + 1 + n - i);
          i = j + 1 + n;
          inField = true;
          continue;
        }
      }
      current += c;
      ++i;
    }
    if (stopAtRecord) failAt(lineOf.empty() ? firstLine : lineOf.back(), std::string("missing record delimiter '") + record_ + "'");
    if (!trim(current).empty()) out.push_back({trim(current), currentLine});
    return out;
  }

  static std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
  }

  void readGlobal() {
    // The first two fields define the delimiters themselves, so they are read by hand.
    std::string all;
    for (const Token& l : global_) all += l.text;
    const std::size_t line = global_.empty() ? lastLine_ : global_.front().line;
    std::size_t i = 0;
    auto delimiterField = [&](char fallback, char separator) -> char {
      while (i < all.size() && all[i] == ' ') ++i;
      if (i < all.size() && all[i] == separator) return fallback;  // empty field: the default
      if (i + 2 < all.size() && all[i] == '1' && (all[i + 1] == 'H' || all[i + 1] == 'h')) {
        const char d = all[i + 2];
        i += 3;
        return d;
      }
      failAt(line, "global section: a delimiter must be given as 1Hx or left empty");
    };
    if (all.empty()) return;  // defaults
    delim_ = delimiterField(',', ',');
    if (i >= all.size() || all[i] != delim_) failAt(line, "global section: parameter delimiter not followed by itself");
    ++i;
    record_ = delimiterField(';', delim_);
    if (delim_ == record_) failAt(line, "global section: parameter and record delimiters are the same");
  }

  int integerField(const std::string& line, int field, std::size_t where, const char* name) const {
    const std::string f = trim(line.substr(static_cast<std::size_t>(field) * 8, 8));
    if (f.empty()) return 0;
    long long v = 0;
    if (!parseInteger(f, v) || v < -1000000000LL || v > 1000000000LL)
      failAt(where, std::string("directory entry field ") + name + " is not an integer: " + quoted(f));
    return static_cast<int>(v);
  }

  void readDirectory() {
    if (directory_.size() % 2 != 0) failAt(directory_.back().line, "odd number of directory lines (entries are two lines)");
    for (std::size_t k = 0; k < directory_.size(); k += 2) {
      const Token& a = directory_[k];
      const Token& b = directory_[k + 1];
      DirectoryEntry e;
      e.line = a.line;
      e.type = integerField(a.text, 0, a.line, "entity type");
      if (integerField(b.text, 0, b.line, "entity type") != e.type)
        failAt(b.line, "the two lines of a directory entry name different entity types");
      e.parameterStart = integerField(a.text, 1, a.line, "parameter data");
      e.transform = integerField(a.text, 6, a.line, "transformation matrix");
      e.parameterLines = integerField(b.text, 3, b.line, "parameter line count");
      entries_[static_cast<int>(k + 1)] = e;  // DE pointer = sequence number of the entry's first line
    }
  }

  /// The parameter tokens of an entity (its type first), from its P lines.
  std::vector<Token> parameters(const DirectoryEntry& e) const {
    if (e.parameterStart < 1 || static_cast<std::size_t>(e.parameterStart) > parameter_.size())
      failAt(e.line, "parameter data pointer " + std::to_string(e.parameterStart) + " is outside the P section (" +
                         std::to_string(parameter_.size()) + " lines)");
    const std::size_t first = static_cast<std::size_t>(e.parameterStart - 1);
    const std::size_t count = e.parameterLines > 0 ? static_cast<std::size_t>(e.parameterLines) : parameter_.size() - first;
    if (first + count > parameter_.size()) failAt(e.line, "parameter line count runs past the end of the P section");
    std::size_t firstLine = 0;
    std::vector<Token> t = tokens({parameter_.begin() + static_cast<long>(first), parameter_.begin() + static_cast<long>(first + count)}, true, firstLine);
    long long type = 0;
    if (t.empty() || !parseInteger(t.front().text, type) || type != e.type)
      failAt(firstLine, "parameter data does not start with the entity type " + std::to_string(e.type));
    return t;
  }

  double number(const Token& t, const std::string& what) const {
    std::string s = t.text;
    for (char& c : s)
      if (c == 'D' || c == 'd') c = 'e';
    if (!s.empty() && s.back() == '.') s += '0';  // IGES writes "1." for 1.0
    try {
      return parseNumber(s, what);
    } catch (const InputError& e) {
      failAt(t.line, e.what());
    }
  }

  int integer(const Token& t, const std::string& what) const {
    long long v = 0;
    if (!parseInteger(t.text, v) || v < 0 || v > 100000000) failAt(t.line, what + ": " + quoted(t.text) + " is not a valid count");
    return static_cast<int>(v);
  }

  /// x -> R x + T of the entity-124 chain starting at directory pointer de.
  Eigen::Isometry3d transform(int de, std::size_t line) const {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    std::set<int> seen;
    while (de != 0) {
      if (!seen.insert(de).second) failAt(line, "transformation matrices point to each other in a cycle");
      const auto it = entries_.find(de);
      if (it == entries_.end() || it->second.type != 124)
        failAt(line, "transformation pointer " + std::to_string(de) + " does not name an entity 124");
      const std::vector<Token> t = parameters(it->second);
      if (t.size() < 13) failAt(t.back().line, "entity 124 needs 12 numbers");
      Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) M(r, c) = number(t[static_cast<std::size_t>(1 + 4 * r + c)], "entity 124 value");
      Eigen::Isometry3d step;
      step.matrix() = M;
      X = step * X;  // a matrix's own transformation pointer applies after it
      de = it->second.transform;
    }
    return X;
  }

  NurbsSurface surface(int de, const DirectoryEntry& e) const {
    const std::vector<Token> t = parameters(e);
    std::size_t at = 1;
    auto next = [&](const char* what) -> const Token& {
      if (at >= t.size()) failAt(t.back().line, std::string("entity 128 ends before ") + what);
      return t[at++];
    };
    const int k1 = integer(next("K1"), "K1"), k2 = integer(next("K2"), "K2");
    const int m1 = integer(next("M1"), "M1"), m2 = integer(next("M2"), "M2");
    for (int k = 0; k < 5; ++k) next("PROP1..5");
    const std::size_t line = t.front().line;
    if (m1 < 1 || m2 < 1) failAt(line, "degree below 1");
    const int nu = k1 + 1, nv = k2 + 1;
    std::vector<double> knotsU, knotsV;
    for (int i = 0; i < nu + m1 + 1; ++i) knotsU.push_back(number(next("the u knots"), "knot"));
    for (int i = 0; i < nv + m2 + 1; ++i) knotsV.push_back(number(next("the v knots"), "knot"));
    std::vector<double> weights;
    for (int i = 0; i < nu * nv; ++i) weights.push_back(number(next("the weights"), "weight"));
    const Eigen::Isometry3d X = transform(e.transform, e.line);
    std::vector<std::vector<Eigen::Vector4d>> net(static_cast<std::size_t>(nu), std::vector<Eigen::Vector4d>(static_cast<std::size_t>(nv)));
    for (int j = 0; j < nv; ++j)  // IGES order: the first index (u) varies fastest
      for (int i = 0; i < nu; ++i) {
        Eigen::Vector3d p;
        for (int c = 0; c < 3; ++c) p[c] = number(next("the control points"), "control point coordinate");
        p = X * p;
        net[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] << p, weights[static_cast<std::size_t>(j * nu + i)];
      }
    double range[4];
    for (double& r : range) r = number(next("the parameter range"), "parameter range");
    try {
      NurbsSurface s(m1, m2, std::move(knotsU), std::move(knotsV), std::move(net));
      // The range selects the part of the surface the entity stands for: the whole knot domain (to a CAD
      // system's rounding, 1e-9 of its extent) or less of it.
      const double su = 1e-9 * (std::abs(s.uMax()) + std::abs(s.uMin()) + 1), sv = 1e-9 * (std::abs(s.vMax()) + std::abs(s.vMin()) + 1);
      const auto snap = [](double x, double end, double slack) { return std::abs(x - end) <= slack ? end : x; };
      const double u0 = snap(range[0], s.uMin(), su), u1 = snap(range[1], s.uMax(), su);
      const double v0 = snap(range[2], s.vMin(), sv), v1 = snap(range[3], s.vMax(), sv);
      if (u0 == s.uMin() && u1 == s.uMax() && v0 == s.vMin() && v1 == s.vMax()) return s;
      return s.restricted(u0, u1, v0, v1);
    } catch (const InputError& err) {
      failAt(line, "entity 128 (directory entry " + std::to_string(de) + "): " + err.what());
    }
  }

  // --- Trimming: accepted only where it keeps the whole surface (a face bounded by its parameter rectangle, as a
  // CAD kernel writes a closed torus or sphere); any other trim is refused, since the untrimmed surface would be
  // a silently wrong model.

  const DirectoryEntry& entryAt(int de, std::size_t line, const char* what) const {
    const auto it = entries_.find(de);
    if (it == entries_.end()) failAt(line, std::string(what) + " pointer " + std::to_string(de) + " names no directory entry");
    return it->second;
  }

  int pointer(const std::vector<Token>& t, std::size_t k, const char* what) const {
    if (k >= t.size()) failAt(t.back().line, std::string("entity ") + t.front().text + " ends before " + what);
    return integer(t[k], what);
  }

  /// The parameter rectangle [u0, u1] x [v0, v1] of the entity 128 at de (its range fields, the last four).
  std::array<double, 4> rectangleOf(int de, std::size_t line) const {
    const DirectoryEntry& e = entryAt(de, line, "surface");
    if (e.type != 128)
      failAt(line, "a trimmed surface is entity " + std::to_string(e.type) + ", not a rational B-spline surface (128)");
    const std::vector<Token> t = parameters(e);
    const int k1 = pointer(t, 1, "K1"), k2 = pointer(t, 2, "K2"), m1 = pointer(t, 3, "M1"), m2 = pointer(t, 4, "M2");
    const auto count = [](int k) { return static_cast<std::size_t>(k); };
    const std::size_t rangeAt = 10 + count(k1 + m1 + 2) + count(k2 + m2 + 2) + 4 * count(k1 + 1) * count(k2 + 1);
    if (rangeAt + 4 > t.size()) failAt(t.back().line, "entity 128 ends before the parameter range");
    std::array<double, 4> r{};
    for (std::size_t k = 0; k < 4; ++k) r[k] = number(t[rangeAt + k], "parameter range");
    return r;
  }

  /// The point of the entity 126 (rational B-spline curve) tokens t at parameter x, by de Boor.
  Eigen::Vector2d curvePoint(const std::vector<Token>& t, double x) const {
    const int k = pointer(t, 1, "K"), m = pointer(t, 2, "M");
    if (m < 1 || m > 30) failAt(t.front().line, "entity 126 degree outside 1..30");
    const std::size_t knotsAt = 7, weightsAt = knotsAt + static_cast<std::size_t>(k + m + 2),
                      pointsAt = weightsAt + static_cast<std::size_t>(k + 1);
    if (pointsAt + 3 * static_cast<std::size_t>(k + 1) > t.size()) failAt(t.back().line, "entity 126 ends before its control points");
    std::vector<double> knots;
    for (int i = 0; i < k + m + 2; ++i) knots.push_back(number(t[knotsAt + static_cast<std::size_t>(i)], "knot"));
    int span = m;
    while (span < k && x >= knots[static_cast<std::size_t>(span + 1)]) ++span;
    std::vector<Eigen::Vector3d> d;  // homogeneous (w·u, w·v, w)
    for (int i = span - m; i <= span; ++i) {
      const double w = number(t[weightsAt + static_cast<std::size_t>(i)], "weight");
      const std::size_t at = pointsAt + 3 * static_cast<std::size_t>(i);
      d.emplace_back(w * number(t[at], "control point"), w * number(t[at + 1], "control point"), w);
    }
    for (int r = 1; r <= m; ++r)
      for (int j = m; j >= r; --j) {
        const double a = knots[static_cast<std::size_t>(span - m + j)], b = knots[static_cast<std::size_t>(span + 1 + j - r)];
        const double alpha = b > a ? (x - a) / (b - a) : 0;
        d[static_cast<std::size_t>(j)] = (1 - alpha) * d[static_cast<std::size_t>(j - 1)] + alpha * d[static_cast<std::size_t>(j)];
      }
    return d[static_cast<std::size_t>(m)].head<2>() / d[static_cast<std::size_t>(m)][2];
  }

  /// A piece of a parameter-space boundary lying on one edge of the rectangle: the edge (0: u = u0, 1: u = u1,
  /// 2: v = v0, 3: v = v1) and the interval of it the piece covers; pieces are followed through composites (102).
  struct EdgePiece {
    int edge;
    double from, to;
  };
  void edgePieces(int de, const std::array<double, 4>& r, std::size_t line, std::vector<EdgePiece>& out, int depth = 0) const {
    // Composites pointing into each other would otherwise be followed without end.
    if (depth > 8 || out.size() > 100000) failAt(line, "composite curves nest too deep or repeat");
    const DirectoryEntry& e = entryAt(de, line, "boundary curve");
    const std::vector<Token> t = parameters(e);
    std::vector<Eigen::Vector2d> points;  // the piece lies in their hull
    Eigen::Vector2d a, b;                 // its ends
    if (e.type == 102) {
      const int n = pointer(t, 1, "N");
      for (int k = 0; k < n; ++k) edgePieces(pointer(t, 2 + static_cast<std::size_t>(k), "piece"), r, line, out, depth + 1);
      return;
    } else if (e.type == 110) {
      if (t.size() < 7) failAt(t.back().line, "entity 110 needs 6 numbers");
      a = {number(t[1], "line"), number(t[2], "line")};
      b = {number(t[4], "line"), number(t[5], "line")};
      points = {a, b};
    } else if (e.type == 126) {
      const int k = pointer(t, 1, "K"), m = pointer(t, 2, "M");
      const std::size_t pointsAt = 7 + static_cast<std::size_t>(k + m + 2) + static_cast<std::size_t>(k + 1);
      const std::size_t rangeAt = pointsAt + 3 * static_cast<std::size_t>(k + 1);
      if (rangeAt + 2 > t.size()) failAt(t.back().line, "entity 126 ends before its parameter range");
      for (int i = 0; i <= k; ++i) {
        const std::size_t at = pointsAt + 3 * static_cast<std::size_t>(i);
        points.emplace_back(number(t[at], "control point"), number(t[at + 1], "control point"));
      }
      a = curvePoint(t, number(t[rangeAt], "curve range"));
      b = curvePoint(t, number(t[rangeAt + 1], "curve range"));
    } else {
      failAt(line, "a trimming boundary is entity " + std::to_string(e.type) +
                       " (read: 102, 110, 126 in parameter space): trimmed surfaces are not read");
    }
    const double slack = 1e-7 * std::max(r[1] - r[0], r[3] - r[2]);
    for (int edge = 0; edge < 4; ++edge) {
      const int axis = edge < 2 ? 0 : 1;
      const double at = r[static_cast<std::size_t>(edge)];
      if (std::all_of(points.begin(), points.end(), [&](const Eigen::Vector2d& p) { return std::abs(p[axis] - at) <= slack; })) {
        out.push_back({edge, std::min(a[1 - axis], b[1 - axis]), std::max(a[1 - axis], b[1 - axis])});
        return;
      }
    }
    out.push_back({-1, 0, 0});  // inside the rectangle: a real trim
  }

  /// Do the boundary curves trace the whole rectangle of the surface at surfaceDe (every edge covered)?
  bool wholeRectangle(int surfaceDe, const std::vector<int>& curves, std::size_t line) const {
    const std::array<double, 4> r = rectangleOf(surfaceDe, line);
    std::vector<EdgePiece> pieces;
    for (int c : curves) edgePieces(c, r, line, pieces);
    const double slack = 1e-7 * std::max(r[1] - r[0], r[3] - r[2]);
    for (int edge = 0; edge < 4; ++edge) {
      const int axis = edge < 2 ? 1 : 0;  // the coordinate along the edge
      std::vector<std::pair<double, double>> covered;
      for (const EdgePiece& p : pieces) {
        if (p.edge < 0) return false;
        if (p.edge == edge) covered.emplace_back(p.from, p.to);
      }
      std::sort(covered.begin(), covered.end());
      double reached = r[static_cast<std::size_t>(2 * axis)];
      for (const auto& [from, to] : covered) {
        if (from > reached + slack) return false;
        reached = std::max(reached, to);
      }
      if (reached < r[static_cast<std::size_t>(2 * axis + 1)] - slack && !collapsed(surfaceDe, edge, line)) return false;
    }
    return true;
  }

  /// Does the edge of the surface at de collapse to a point (a sphere's pole, which a boundary leaves out)?
  /// Sampled densely along it: an edge curve that is not a point moves between samples.
  bool collapsed(int de, int edge, std::size_t line) const {
    const NurbsSurface s = surface(de, entryAt(de, line, "surface"));
    const auto at = [&](double x) {
      return edge < 2 ? s.evaluate(edge == 0 ? s.uMin() : s.uMax(), s.vMin() + x * (s.vMax() - s.vMin()))
                      : s.evaluate(s.uMin() + x * (s.uMax() - s.uMin()), edge == 2 ? s.vMin() : s.vMax());
    };
    const Eigen::Vector3d first = at(0);
    double reach = 0, spread = 0;
    for (int k = 0; k <= 64; ++k) {
      const Eigen::Vector3d p = at(k / 64.0), q = s.evaluate(s.uMin() + (s.uMax() - s.uMin()) * k / 64.0, s.vMin() + (s.vMax() - s.vMin()) * k / 64.0);
      spread = std::max(spread, (p - first).norm());
      reach = std::max(reach, (q - first).norm());
    }
    return spread <= 1e-9 * std::max(reach, 1e-300);
  }

  void checkTrimming() const {
    for (const auto& [de, e] : entries_) {
      const auto refuse = [&](const std::string& why) {
        failAt(e.line, "entity " + std::to_string(e.type) + " (directory entry " + std::to_string(de) + ") " + why +
                           ": trimmed surfaces are not read (the untrimmed surface would be a wrong model)");
      };
      if (e.type == 143) refuse("bounds a surface by curves");
      if (e.type == 144) {  // PTS N1 N2 PTO PTI...
        const std::vector<Token> t = parameters(e);
        const int surfaceDe = pointer(t, 1, "PTS"), n1 = pointer(t, 2, "N1"), n2 = pointer(t, 3, "N2");
        if (n2 > 0) refuse("cuts " + std::to_string(n2) + " hole(s) into its surface");
        if (n1 == 0) continue;  // the outer boundary is the surface's own
        const DirectoryEntry& outer = entryAt(pointer(t, 4, "PTO"), e.line, "outer boundary");
        if (outer.type != 142) refuse("has an outer boundary that is not a curve on a surface (142)");
        const std::vector<Token> c = parameters(outer);  // CRTN SPTR BPTR CPTR PREF
        const int inParameters = pointer(c, 3, "BPTR");
        if (inParameters == 0) refuse("gives its boundary in model space only");
        if (!wholeRectangle(surfaceDe, {inParameters}, e.line)) refuse("keeps part of its surface");
      }
      if (e.type == 510) {  // SURF N OF LOOP1..N
        const std::vector<Token> t = parameters(e);
        const int surfaceDe = pointer(t, 1, "SURF"), loops = pointer(t, 2, "N");
        if (loops != 1) refuse("has " + std::to_string(loops) + " loops (holes)");
        const DirectoryEntry& loop = entryAt(pointer(t, 4, "LOOP"), e.line, "loop");
        if (loop.type != 508) refuse("has a loop that is not entity 508");
        const std::vector<Token> l = parameters(loop);  // N, then per edge TYPE EDGE NDX OF K (ISOP CURV) x K
        const int edges = pointer(l, 1, "N");
        std::vector<int> curves;
        std::size_t at = 2;
        for (int k = 0; k < edges; ++k) {
          const int count = pointer(l, at + 4, "K");
          if (count == 0) refuse("has an edge without a parameter-space curve");
          for (int c = 0; c < count; ++c) curves.push_back(pointer(l, at + 6 + 2 * static_cast<std::size_t>(c), "CURV"));
          at += 5 + 2 * static_cast<std::size_t>(count);
        }
        if (!wholeRectangle(surfaceDe, curves, e.line)) refuse("keeps part of its surface");
      }
    }
  }

  std::string path_;
  std::vector<Token> global_, directory_, parameter_;
  std::map<int, DirectoryEntry> entries_;
  char delim_ = ',', record_ = ';';
  std::size_t lastLine_ = 1;
};

}  // namespace

std::shared_ptr<const Model> readIges(const std::string& path) { return IgesParser(path).read(); }

}  // namespace unidist::formats
