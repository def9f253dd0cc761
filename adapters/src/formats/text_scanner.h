// Strict tokenizers shared by the model file readers: a line scanner for the text formats (OBJ, ASCII STL,
// the PLY header and ASCII body, XYZ) and a byte reader for the binary ones (binary STL and PLY). Both work
// in place on the whole file held in memory (no per-line iostream), and both report a problem the one way the
// contract allows (docs/query-contract.md, "Bad input"): an InputError reading
//   "<path>:<line>: <what>"          for text, lines counted from 1;
//   "<path>: byte <offset>: <what>"  for binary data, offsets counted from 0 from the start of the file.
// Numbers are parsed by parseNumber (adapters/src/number.cpp): C/JSON decimal syntax only, finite, whole
// token — so "1.0abc", "0x1p3", "nan", "inf" and "1e999" are errors, not values.
#pragma once

#include "unidist/types.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

namespace unidist::formats {

/// The whole file as bytes. Throws InputError "<path>: cannot open (...)" / "<path>: read error".
std::string readWholeFile(const std::string& path);

/// Strict integer syntax [+-]digits that fits a long long; false otherwise (no exception: for hot loops that
/// build their error message only when needed).
bool parseInteger(std::string_view token, long long& value);

/// A token for an error message: quoted, at most 40 characters (then "..."), non-printable bytes as \xNN.
std::string quoted(std::string_view token);

[[noreturn]] void failAtLine(const std::string& path, std::size_t line, const std::string& what);
[[noreturn]] void failAtByte(const std::string& path, std::size_t offset, const std::string& what);

/// Line-by-line scanner over text. A line ends at "\n", "\r\n" or a lone "\r"; a UTF-8 byte-order mark at
/// the start of the text is skipped. Within a line, tokens are separated by blanks (space, tab, \v, \f).
class LineScanner {
 public:
  LineScanner(const std::string& path, std::string_view text);

  /// Advances to the next line; false (and lineNumber() stays at the last line) when the text is exhausted.
  bool nextLine();
  /// 1-based number of the current line (0 before the first nextLine()).
  std::size_t lineNumber() const { return line_; }
  /// The current line without its line ending.
  std::string_view line() const { return current_; }
  /// Byte offset in the text just past the current line's ending (where the next line, or binary data, starts).
  std::size_t nextLineOffset() const { return next_; }
  /// True when the text was empty (or held only a byte-order mark).
  bool emptyText() const { return begin_ >= text_.size(); }

  /// Drops the rest of the current line from the first `marker` on (a comment).
  void stripComment(char marker);
  /// The next blank-separated token of the current line; empty at the end of the line.
  std::string_view token();
  /// The next field of an XYZ-style line: fields are separated by blanks, or by one comma with optional
  /// blanks around it. Empty at the end of the line; an empty field ("1,,2", a leading or trailing comma)
  /// is an error naming the line.
  std::string_view field();
  /// True when only blanks remain on the current line.
  bool atEndOfLine();
  /// The unread rest of the current line, blanks at both ends trimmed.
  std::string_view rest();

  /// A finite decimal number (parseNumber's grammar); `what` names the value in the error message.
  double number(std::string_view token, const std::string& what) const;
  /// An integer [+-]digits in [lo, hi]; `what` names the value in the error message.
  long long integer(std::string_view token, const std::string& what, long long lo, long long hi) const;
  /// The next token as a number; a missing token is an error ("expected <what>").
  double nextNumber(const std::string& what);

  [[noreturn]] void fail(const std::string& what) const { failAtLine(path_, line_ == 0 ? 1 : line_, what); }
  const std::string& path() const { return path_; }

 private:
  const std::string& path_;
  std::string_view text_;
  std::size_t begin_ = 0;  // offset of the first line (after a byte-order mark)
  std::size_t next_ = 0;   // offset of the next line to read
  std::size_t line_ = 0;
  std::string_view current_;
  std::size_t cursor_ = 0;     // position in current_
  bool pendingComma_ = false;  // field(): a ',' was consumed after the last value
};

/// Reads fixed-size little- or big-endian scalars from binary data, reporting the byte offset of a value
/// that runs past the end of the data.
class ByteReader {
 public:
  ByteReader(const std::string& path, std::string_view data, std::size_t offset, bool bigEndian)
      : path_(path), data_(data), pos_(offset), bigEndian_(bigEndian) {}

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  bool bigEndian() const { return bigEndian_; }

  /// Reads a T (an arithmetic type of size 1, 2, 4 or 8) at the current offset and advances past it.
  /// `what` names the value when the data ends first.
  template <class T>
  T read(const char* what) {
    if (remaining() < sizeof(T))
      fail(pos_, std::string("unexpected end of file reading ") + what + " (" + std::to_string(sizeof(T)) +
                     " bytes needed, " + std::to_string(remaining()) + " left)");
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (bigEndian_ != kHostBigEndian)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  void skip(std::size_t n, const char* what) {
    if (remaining() < n) fail(pos_, std::string("unexpected end of file in ") + what);
    pos_ += n;
  }

  [[noreturn]] void fail(std::size_t offset, const std::string& what) const { failAtByte(path_, offset, what); }

 private:
#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__)
  static constexpr bool kHostBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
#else
  static constexpr bool kHostBigEndian = false;
#endif
  const std::string& path_;
  std::string_view data_;
  std::size_t pos_;
  bool bigEndian_;
};

}  // namespace unidist::formats
