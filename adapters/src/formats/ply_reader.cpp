// PLY → TriangleMesh (when there are faces) or PointCloud (when there are none), strictly: header errors name
// the line, ASCII data errors the line, binary data errors the byte offset.
//
// Header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", "element <name> <count>",
//   "property <type> <name>", "property list <count type> <item type> <name>", "comment ..."/"obj_info ...",
//   "end_header". Types: char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32,
//   float/float32, double/float64; a list's count type must be an integer type.
// Used: element "vertex" (required, at least one) with scalar x, y, z of any numeric type, and scalar
//   nx, ny, nz (all three or none; kept as the normals of a point cloud); element "face" with the list
//   "vertex_indices" (or "vertex_index") of an integer type. Faces with k > 3 corners become a fan of k − 2
//   triangles from the first corner (exact for convex polygons). "tristrips" are refused (reading the
//   vertices alone would be a silently wrong model). Every other element and property is read
//   (so its values are checked and the data stays in step) and ignored. A "face" element with 0 entries
//   makes a point cloud.
// ASCII data: one element entry per line, exactly the values the header declares (blank lines are skipped);
//   integer-typed values must be integers within the type's range, others finite decimal numbers.
// Binary data: exactly the bytes the header declares — too few or too many is an error at the byte offset.
// So a header that lies about a count shows up at the line or byte where the data stops matching it.
#include "formats/readers.h"
#include "formats/text_scanner.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::formats {
namespace {

using Triangle = TriangleMesh::Triangle;

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct TypeInfo {
  const char* name;
  const char* alias;
  Type type;
  std::size_t size;
  bool integer;
  long long lo, hi;
};

const TypeInfo kTypes[] = {
    {"char", "int8", Type::Int8, 1, true, -128, 127},
    {"uchar", "uint8", Type::UInt8, 1, true, 0, 255},
    {"short", "int16", Type::Int16, 2, true, -32768, 32767},
    {"ushort", "uint16", Type::UInt16, 2, true, 0, 65535},
    {"int", "int32", Type::Int32, 4, true, std::numeric_limits<std::int32_t>::min(),
     std::numeric_limits<std::int32_t>::max()},
    {"uint", "uint32", Type::UInt32, 4, true, 0, std::numeric_limits<std::uint32_t>::max()},
    {"float", "float32", Type::Float32, 4, false, 0, 0},
    {"double", "float64", Type::Float64, 8, false, 0, 0},
};

const TypeInfo* findType(std::string_view name) {
  for (const TypeInfo& t : kTypes)
    if (name == t.name || name == t.alias) return &t;
  return nullptr;
}

/// What a property is used for.
enum class Role { None, X, Y, Z, NX, NY, NZ, Indices };

struct Property {
  std::string name;
  bool list = false;
  const TypeInfo* countType = nullptr;  // lists only
  const TypeInfo* type = nullptr;       // the value (or list item) type
  std::size_t line = 0;                 // header line, for messages
  Role role = Role::None;
  std::string label, lengthLabel;  // "property 'x'", "the length of list 'vertex_indices'" (messages)
};

struct Element {
  std::string name;
  long long count = 0;
  std::size_t line = 0;
  std::vector<Property> properties;
};

enum class Encoding { Ascii, BinaryLittle, BinaryBig };

constexpr long long kMaxCount = std::numeric_limits<std::uint32_t>::max() - 1;

class PlyReader {
 public:
  PlyReader(const std::string& path, std::string_view data) : path_(path), data_(data), s_(path, data) {}

  std::shared_ptr<const Model> read() {
    readHeader();
    assignRoles();
    if (encoding_ == Encoding::Ascii)
      readAscii();
    else
      readBinary();
    if (isMesh_) return makeMesh(path_, std::move(vertices_), std::move(triangles_));
    return makeCloud(path_, std::move(vertices_), std::move(normals_));
  }

 private:
  // ------------------------------------------------------------------------------------------------ header

  void readHeader() {
    if (!s_.nextLine()) s_.fail("empty file (a PLY file starts with the line 'ply')");
    if (s_.token() != "ply" || !s_.atEndOfLine()) s_.fail("not a PLY file: the first line must be 'ply'");
    bool haveFormat = false;
    for (;;) {
      if (!s_.nextLine()) s_.fail("end of file in the header: the 'end_header' line is missing");
      const std::string_view key = s_.token();
      if (key.empty()) s_.fail("blank line in the PLY header");
      if (key == "comment" || key == "obj_info") continue;
      if (key == "end_header") {
        if (!s_.atEndOfLine()) s_.fail("'end_header' must be alone on its line");
        if (!haveFormat) s_.fail("the header has no 'format' line");
        break;
      }
      if (key == "format") {
        if (haveFormat) s_.fail("a second 'format' line");
        if (!elements_.empty()) s_.fail("'format' must come before the elements");
        const std::string_view enc = s_.token();
        if (enc == "ascii")
          encoding_ = Encoding::Ascii;
        else if (enc == "binary_little_endian")
          encoding_ = Encoding::BinaryLittle;
        else if (enc == "binary_big_endian")
          encoding_ = Encoding::BinaryBig;
        else
          s_.fail("unknown PLY format " + quoted(enc) + " (ascii, binary_little_endian or binary_big_endian)");
        const std::string_view version = s_.token();
        if (version != "1.0") s_.fail("unsupported PLY version " + quoted(version) + " (1.0 expected)");
        if (!s_.atEndOfLine()) s_.fail("unexpected text after the format version");
        haveFormat = true;
      } else if (key == "element") {
        Element e;
        e.name = std::string(s_.token());
        if (e.name.empty()) s_.fail("'element' needs a name and a count");
        for (const Element& other : elements_)
          if (other.name == e.name) s_.fail("a second element named " + quoted(e.name));
        const std::string_view count = s_.token();
        if (count.empty()) s_.fail("element " + quoted(e.name) + " needs a count");
        e.count = s_.integer(count, "count of element '" + e.name + "'", 0, kMaxCount);
        if (!s_.atEndOfLine()) s_.fail("unexpected text after the element count");
        e.line = s_.lineNumber();
        elements_.push_back(std::move(e));
      } else if (key == "property") {
        if (elements_.empty()) s_.fail("'property' before any 'element'");
        Property p;
        p.line = s_.lineNumber();
        std::string_view type = s_.token();
        if (type == "list") {
          p.list = true;
          const std::string_view countType = s_.token();
          p.countType = findType(countType);
          if (!p.countType) s_.fail("unknown list count type " + quoted(countType));
          if (!p.countType->integer)
            s_.fail("unsupported list count type " + quoted(countType) + " (must be an integer type)");
          type = s_.token();
        }
        p.type = findType(type);
        if (!p.type)
          s_.fail("unknown property type " + quoted(type) +
                  " (char, uchar, short, ushort, int, uint, float, double or their int8 ... float64 names)");
        p.name = std::string(s_.token());
        if (p.name.empty()) s_.fail("the property has no name");
        if (!s_.atEndOfLine()) s_.fail("unexpected text after the property name");
        for (const Property& other : elements_.back().properties)
          if (other.name == p.name) s_.fail("a second property named " + quoted(p.name));
        p.label = "property '" + p.name + "'";
        p.lengthLabel = "the length of list '" + p.name + "'";
        elements_.back().properties.push_back(std::move(p));
      } else {
        s_.fail("unexpected header line starting with " + quoted(key) +
                " (expected format, element, property, comment, obj_info or end_header; is 'end_header' missing?)");
      }
    }
    dataStart_ = s_.nextLineOffset();
    headerEnd_ = s_.lineNumber();
  }

  /// Finds the vertex coordinates, normals and face indices, and checks their types.
  void assignRoles() {
    const Element* vertex = nullptr;
    for (Element& e : elements_) {
      // Entries without values carry nothing, and a binary count of them costs time but no bytes.
      if (e.properties.empty() && e.count > 0)
        failAtLine(path_, e.line, "element '" + e.name + "' has entries but no properties");
      // Ignoring strips would turn a mesh into a point cloud without a word.
      if (e.name == "tristrips" && e.count > 0)
        failAtLine(path_, e.line, "triangle strips ('tristrips') are not supported; write faces");
      if (e.name == "vertex") {
        vertex = &e;
        for (Property& p : e.properties) {
          const std::pair<const char*, Role> roles[] = {{"x", Role::X},   {"y", Role::Y},   {"z", Role::Z},
                                                        {"nx", Role::NX}, {"ny", Role::NY}, {"nz", Role::NZ}};
          for (const auto& [name, role] : roles)
            if (p.name == name) {
              if (p.list) failAtLine(path_, p.line, "vertex property '" + p.name + "' is a list; it must be a number");
              p.role = role;
            }
        }
      } else if (e.name == "face") {
        for (Property& p : e.properties)
          if (p.name == "vertex_indices" || p.name == "vertex_index") {
            if (faceIndices_) failAtLine(path_, p.line, "the face element has both vertex_indices and vertex_index");
            if (!p.list)
              failAtLine(path_, p.line,
                         "face property '" + p.name + "' must be a list (property list uchar int " + p.name + ")");
            if (!p.type->integer)
              failAtLine(path_, p.line,
                         "face property '" + p.name + "' has item type '" + p.type->name +
                             "'; vertex indices must be an integer type");
            p.role = Role::Indices;
            faceIndices_ = &p;
          }
        if (!faceIndices_) failAtLine(path_, e.line, "the face element has no 'vertex_indices' list");
        faceCount_ = e.count;
      }
    }
    if (!vertex) failAtLine(path_, headerEnd_, "the header declares no 'vertex' element");
    bool has[7] = {};
    for (const Property& p : vertex->properties) has[static_cast<int>(p.role)] = true;
    for (const auto& [role, name] : {std::pair{Role::X, "x"}, {Role::Y, "y"}, {Role::Z, "z"}})
      if (!has[static_cast<int>(role)])
        failAtLine(path_, vertex->line, std::string("the vertex element has no '") + name + "' property");
    const int normals =
        has[static_cast<int>(Role::NX)] + has[static_cast<int>(Role::NY)] + has[static_cast<int>(Role::NZ)];
    if (normals != 0 && normals != 3)
      failAtLine(path_, vertex->line, "the vertex element has only some of nx, ny, nz (all three or none)");
    if (vertex->count == 0) failAtLine(path_, vertex->line, "the vertex element has 0 entries");
    vertexCount_ = vertex->count;
    isMesh_ = faceCount_ > 0;
    wantNormals_ = !isMesh_ && normals == 3;
  }

  // ---------------------------------------------------------------------------------------------- data

  /// Reserves for `count` entries, but never more than the data could hold (a lying header must not make
  /// us allocate gigabytes before the data runs out).
  template <class V>
  void reserveAtMost(V& v, long long count, std::size_t minBytesEach) {
    const std::size_t left = data_.size() - std::min(data_.size(), dataStart_);
    v.reserve(std::min<std::size_t>(static_cast<std::size_t>(count), left / std::max<std::size_t>(1, minBytesEach)));
  }

  void prepare(const Element& e, std::size_t minBytesEach) {
    if (e.name == "vertex") {
      reserveAtMost(vertices_, e.count, minBytesEach);
      if (wantNormals_) reserveAtMost(normals_, e.count, minBytesEach);
    } else if (e.name == "face" && isMesh_) {
      reserveAtMost(triangles_, e.count, minBytesEach);
    }
  }

  /// One vertex entry's values, indexed by Role, into the vertex (and normal) lists.
  void storeVertex(const double (&v)[7]) {
    vertices_.emplace_back(v[1], v[2], v[3]);
    if (wantNormals_) normals_.emplace_back(v[4], v[5], v[6]);
  }

  void storeFace() {
    for (std::size_t k = 1; k + 1 < polygon_.size(); ++k)
      triangles_.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
  }

  std::string entryName(const Element& e, long long i) const {
    return e.name + " " + std::to_string(i) + " (of " + std::to_string(e.count) + ")";
  }

  void readAscii() {
    for (const Element& e : elements_) {
      prepare(e, 2 * std::max<std::size_t>(1, e.properties.size()));  // at least "0 " per value
      const bool isVertex = e.name == "vertex";
      for (long long i = 0; i < e.count; ++i) {
        do {
          if (!s_.nextLine())
            s_.fail("end of file after " + std::to_string(i) + " of the " + std::to_string(e.count) + " '" + e.name +
                    "' entries the header declares");
        } while (s_.atEndOfLine());
        double values[7] = {};
        for (const Property& p : e.properties) {
          if (p.list) {
            const long long n = s_.integer(asciiToken(e, i, p), p.lengthLabel, p.countType->lo, p.countType->hi);
            if (n < 0) s_.fail("list '" + p.name + "' has negative length " + std::to_string(n));
            if (p.role == Role::Indices) {
              if (n < 3)
                s_.fail("face " + std::to_string(i) + " has " + std::to_string(n) +
                        " vertices (at least 3; does the header match the data?)");
              polygon_.clear();
            }
            for (long long k = 0; k < n; ++k) {
              const std::string_view t = asciiToken(e, i, p);
              if (p.role == Role::Indices) {
                const long long index = s_.integer(t, p.label, p.type->lo, p.type->hi);
                if (index < 0 || index >= vertexCount_)
                  s_.fail("face " + std::to_string(i) + ": vertex index " + std::to_string(index) +
                          " is out of range (the header declares " + std::to_string(vertexCount_) + " vertices)");
                polygon_.push_back(static_cast<std::uint32_t>(index));
              } else {
                asciiValue(t, p);
              }
            }
            if (p.role == Role::Indices && isMesh_) storeFace();
          } else {
            values[static_cast<int>(p.role)] = asciiValue(asciiToken(e, i, p), p);
          }
        }
        if (!s_.atEndOfLine())
          s_.fail(entryName(e, i) + " has more values than its " + std::to_string(e.properties.size()) +
                  " properties (extra " + quoted(s_.token()) + "; does the header's count match the data?)");
        if (isVertex) storeVertex(values);
      }
    }
    while (s_.nextLine())
      if (!s_.atEndOfLine())
        s_.fail("data after the last entry the header declares (" + countsText() + "); the header's counts are wrong?");
  }

  std::string_view asciiToken(const Element& e, long long i, const Property& p) {
    const std::string_view t = s_.token();
    if (t.empty())
      s_.fail(entryName(e, i) + ": the line ends before property '" + p.name + "' (does the header match the data?)");
    return t;
  }

  double asciiValue(std::string_view t, const Property& p) {
    if (p.type->integer) return static_cast<double>(s_.integer(t, p.label, p.type->lo, p.type->hi));
    return s_.number(t, p.label);
  }

  static std::size_t minBytes(const Element& e) {
    std::size_t n = 0;
    for (const Property& p : e.properties) n += p.list ? p.countType->size : p.type->size;
    return n;
  }

  /// One binary value of type t as a double (integers are exact up to 2^53, so all PLY integer types).
  /// Running out of data is an error naming the entry and property (built only then: this is the hot loop).
  double binaryValue(ByteReader& r, const TypeInfo& t, const Element& e, long long i, const Property& p) const {
    if (r.remaining() < t.size)
      r.fail(r.offset(), "unexpected end of file in " + entryName(e, i) + ", property '" + p.name +
                             "' (the file is truncated or the header's counts are wrong)");
    switch (t.type) {
      case Type::Int8:
        return r.read<std::int8_t>("int8");
      case Type::UInt8:
        return r.read<std::uint8_t>("uint8");
      case Type::Int16:
        return r.read<std::int16_t>("int16");
      case Type::UInt16:
        return r.read<std::uint16_t>("uint16");
      case Type::Int32:
        return r.read<std::int32_t>("int32");
      case Type::UInt32:
        return r.read<std::uint32_t>("uint32");
      case Type::Float32:
        return r.read<float>("float32");
      case Type::Float64:
        return r.read<double>("float64");
    }
    return 0;
  }

  void readBinary() {
    ByteReader r(path_, data_, dataStart_, encoding_ == Encoding::BinaryBig);
    const char* const roleName[] = {"", "x", "y", "z", "nx", "ny", "nz", ""};
    for (const Element& e : elements_) {
      prepare(e, minBytes(e));
      const bool isVertex = e.name == "vertex";
      for (long long i = 0; i < e.count; ++i) {
        double values[7] = {};
        for (const Property& p : e.properties) {
          if (p.list) {
            const std::size_t at = r.offset();
            const double n = binaryValue(r, *p.countType, e, i, p);
            if (n < 0) r.fail(at, "list '" + p.name + "' of " + entryName(e, i) + " has negative length");
            if (n * static_cast<double>(p.type->size) > static_cast<double>(r.remaining()))
              r.fail(at, "list '" + p.name + "' of " + entryName(e, i) + " has " +
                             std::to_string(static_cast<long long>(n)) + " items, more than the " +
                             std::to_string(r.remaining()) +
                             " bytes left hold (the file is truncated or the header's counts are wrong)");
            if (p.role == Role::Indices) {
              if (n < 3)
                r.fail(at, "face " + std::to_string(i) + " has " + std::to_string(static_cast<long long>(n)) +
                               " vertices (at least 3; does the header match the data?)");
              polygon_.clear();
            }
            for (long long k = 0; k < static_cast<long long>(n); ++k) {
              const std::size_t itemAt = r.offset();
              const double v = binaryValue(r, *p.type, e, i, p);
              if (p.role == Role::Indices) {
                if (v < 0 || v >= static_cast<double>(vertexCount_))
                  r.fail(itemAt,
                         "face " + std::to_string(i) + ": vertex index " + std::to_string(static_cast<long long>(v)) +
                             " is out of range (the header declares " + std::to_string(vertexCount_) + " vertices)");
                polygon_.push_back(static_cast<std::uint32_t>(v));
              }
            }
            if (p.role == Role::Indices && isMesh_) storeFace();
          } else {
            const std::size_t at = r.offset();
            const double v = binaryValue(r, *p.type, e, i, p);
            if (p.role != Role::None && !std::isfinite(v))
              r.fail(at, entryName(e, i) + ": " + roleName[static_cast<int>(p.role)] + " is " +
                             (std::isnan(v) ? "NaN" : "infinite"));
            values[static_cast<int>(p.role)] = v;
          }
        }
        if (isVertex) storeVertex(values);
      }
    }
    if (r.remaining() != 0)
      r.fail(r.offset(), std::to_string(r.remaining()) + " bytes after the last entry the header declares (" +
                             countsText() + "); the header's counts are wrong?");
  }

  std::string countsText() const {
    std::string t;
    for (const Element& e : elements_) t += (t.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
    return t;
  }

  const std::string& path_;
  std::string_view data_;
  LineScanner s_;
  Encoding encoding_ = Encoding::Ascii;
  std::vector<Element> elements_;
  std::size_t dataStart_ = 0, headerEnd_ = 0;
  const Property* faceIndices_ = nullptr;
  long long vertexCount_ = 0, faceCount_ = 0;
  bool isMesh_ = false, wantNormals_ = false;
  std::vector<Eigen::Vector3d> vertices_, normals_;
  std::vector<Triangle> triangles_;
  std::vector<std::uint32_t> polygon_;
};

}  // namespace

std::shared_ptr<const Model> readPly(const std::string& path) {
  const std::string data = readWholeFile(path);
  return PlyReader(path, data).read();
}

}  // namespace unidist::formats
