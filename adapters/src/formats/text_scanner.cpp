// The shared strict tokenizers of the file readers (see text_scanner.h) and the two model builders every
// reader ends with (readers.h).
#include "formats/text_scanner.h"

#include "formats/readers.h"
#include "unidist/adapters/spec.h"
#include "unidist/point_cloud.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <system_error>

namespace unidist::formats {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// True when every byte is printable ASCII (so the text can go into a message unchanged).
bool printable(std::string_view s) {
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) return false;
  return true;
}

}  // namespace

std::string readWholeFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    const int err = errno;
    throw InputError(path + ": cannot open (" + std::strerror(err) + ")");
  }
  std::string data;
  if (std::fseek(f, 0, SEEK_END) == 0) {
    const long size = std::ftell(f);
    if (size > 0) data.reserve(static_cast<std::size_t>(size));
    std::rewind(f);
  }
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) data.append(buffer, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw InputError(path + ": read error");
  return data;
}

namespace {

/// [+-]digits, at least one digit.
bool integerSyntax(std::string_view token) {
  const std::size_t i = !token.empty() && (token[0] == '+' || token[0] == '-') ? 1 : 0;
  if (i == token.size()) return false;
  for (std::size_t k = i; k < token.size(); ++k)
    if (!isDigit(token[k])) return false;
  return true;
}

}  // namespace

bool parseInteger(std::string_view token, long long& value) {
  if (!integerSyntax(token)) return false;
  const std::string_view body = token[0] == '+' ? token.substr(1) : token;  // from_chars takes no '+'
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  return ec == std::errc() && end == body.data() + body.size();
}

std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c < 0x20 || c >= 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

void failAtLine(const std::string& path, std::size_t line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what);
}

void failAtByte(const std::string& path, std::size_t offset, const std::string& what) {
  throw InputError(path + ": byte " + std::to_string(offset) + ": " + what);
}

// ---------------------------------------------------------------------------------------------- LineScanner

LineScanner::LineScanner(const std::string& path, std::string_view text) : path_(path), text_(text) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") begin_ = 3;
  next_ = begin_;
}

bool LineScanner::nextLine() {
  if (next_ >= text_.size()) {
    current_ = {};
    cursor_ = 0;
    return false;
  }
  const std::size_t start = next_;
  std::size_t end = start;
  const std::size_t n = text_.size();
  const char* p = text_.data();
  while (end < n && p[end] != '\n' && p[end] != '\r') ++end;
  current_ = text_.substr(start, end - start);
  next_ = end;
  if (next_ < n) next_ += (p[next_] == '\r' && next_ + 1 < n && p[next_ + 1] == '\n') ? 2 : 1;
  cursor_ = 0;
  pendingComma_ = false;
  ++line_;
  return true;
}

void LineScanner::stripComment(char marker) {
  const std::size_t at = current_.find(marker, cursor_);
  if (at != std::string_view::npos) current_ = current_.substr(0, at);
}

std::string_view LineScanner::token() {
  const std::size_t n = current_.size();
  while (cursor_ < n && isBlank(current_[cursor_])) ++cursor_;
  const std::size_t start = cursor_;
  while (cursor_ < n && !isBlank(current_[cursor_])) ++cursor_;
  return current_.substr(start, cursor_ - start);
}

std::string_view LineScanner::field() {
  const std::size_t n = current_.size();
  while (cursor_ < n && isBlank(current_[cursor_])) ++cursor_;
  if (cursor_ == n) {
    if (pendingComma_) fail("a ',' ends the line (a value is missing after it)");
    return {};
  }
  if (current_[cursor_] == ',') fail("empty value: ',' with no value before it");
  const std::size_t start = cursor_;
  while (cursor_ < n && !isBlank(current_[cursor_]) && current_[cursor_] != ',') ++cursor_;
  const std::string_view value = current_.substr(start, cursor_ - start);
  while (cursor_ < n && isBlank(current_[cursor_])) ++cursor_;
  pendingComma_ = cursor_ < n && current_[cursor_] == ',';
  if (pendingComma_) ++cursor_;
  return value;
}

bool LineScanner::atEndOfLine() {
  while (cursor_ < current_.size() && isBlank(current_[cursor_])) ++cursor_;
  return cursor_ == current_.size();
}

std::string_view LineScanner::rest() {
  atEndOfLine();
  std::string_view r = current_.substr(cursor_);
  while (!r.empty() && isBlank(r.back())) r.remove_suffix(1);
  cursor_ = current_.size();
  return r;
}

double LineScanner::number(std::string_view token, const std::string& what) const {
  try {
    return parseNumber(token, what);
  } catch (const InputError& e) {
    // parseNumber quotes the whole token; keep messages one short printable line.
    if (printable(token) && token.size() <= 60) fail(e.what());
    fail(what + ": " + quoted(token) + " is not a number");
  }
}

long long LineScanner::integer(std::string_view token, const std::string& what, long long lo, long long hi) const {
  if (token.empty()) fail(what + ": missing (expected an integer)");
  long long value = 0;
  if (!integerSyntax(token)) fail(what + ": " + quoted(token) + " is not an integer");
  if (parseInteger(token, value) && value >= lo && value <= hi) return value;
  fail(what + ": " + quoted(token) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

double LineScanner::nextNumber(const std::string& what) {
  const std::string_view t = token();
  if (t.empty()) fail("expected " + what + ", found the end of the line");
  return number(t, what);
}

// -------------------------------------------------------------------------------------------- model builders

std::shared_ptr<const Model> makeMesh(const std::string& path, std::vector<Eigen::Vector3d> vertices,
                                      std::vector<TriangleMesh::Triangle> triangles) {
  try {
    return std::make_shared<const TriangleMesh>(std::move(vertices), std::move(triangles));
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

std::shared_ptr<const Model> makeCloud(const std::string& path, std::vector<Eigen::Vector3d> points,
                                       std::vector<Eigen::Vector3d> normals) {
  try {
    return std::make_shared<const PointCloud>(std::move(points), std::move(normals));
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace unidist::formats
