// Strict decimal number parsing for specs, poses and command-line values. std::from_chars does the
// conversion (correctly rounded, locale-independent); the grammar is checked first because from_chars alone
// accepts "inf", "nan" and stops silently at the "x" of "0x1p3".
#include "unidist/adapters/spec.h"

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

namespace unidist {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

[[noreturn]] void notANumber(std::string_view text, std::string_view what) {
  throw InputError(std::string(what) + ": '" + std::string(text) + "' is not a number");
}

}  // namespace

double parseNumber(std::string_view text, std::string_view what) {
  if (text.empty()) throw InputError(std::string(what) + ": empty value (expected a number)");
  const std::size_t n = text.size();
  std::size_t i = 0;
  const bool negative = text[0] == '-';
  if (text[0] == '+' || text[0] == '-') ++i;

  // Decimal magnitude of the first non-zero digit (its power of ten before the exponent), to tell an
  // underflow from an overflow when from_chars reports "out of range".
  long long firstPower = 0;
  bool nonZero = false;
  std::size_t intDigits = 0, fracDigits = 0;
  while (i < n && isDigit(text[i])) {
    if (nonZero) ++firstPower;
    else if (text[i] != '0') nonZero = true;
    ++intDigits;
    ++i;
  }
  if (i < n && text[i] == '.') {
    ++i;
    while (i < n && isDigit(text[i])) {
      ++fracDigits;
      if (!nonZero) {
        --firstPower;
        if (text[i] != '0') nonZero = true;
      }
      ++i;
    }
  }
  if (intDigits + fracDigits == 0) notANumber(text, what);
  long long exponent = 0;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool expNegative = false;
    if (i < n && (text[i] == '+' || text[i] == '-')) expNegative = text[i++] == '-';
    std::size_t expDigits = 0;
    while (i < n && isDigit(text[i])) {
      if (exponent < 1000000000LL) exponent = 10 * exponent + (text[i] - '0');  // saturates: far out of range anyway
      ++expDigits;
      ++i;
    }
    if (expDigits == 0) notANumber(text, what);
    if (expNegative) exponent = -exponent;
  }
  if (i != n) notANumber(text, what);

  // from_chars takes no leading '+'.
  const std::string_view body = text[0] == '+' ? text.substr(1) : text;
  double value = 0;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (ec == std::errc::result_out_of_range) {
    if (nonZero && firstPower + exponent < 0) return negative ? -0.0 : 0.0;  // below the smallest subnormal
    throw InputError(std::string(what) + ": '" + std::string(text) + "' is out of range for a double");
  }
  if (ec != std::errc() || end != body.data() + body.size()) notANumber(text, what);
  if (!std::isfinite(value)) notANumber(text, what);  // cannot happen after the grammar check; kept as a guard
  return value;
}

}  // namespace unidist
