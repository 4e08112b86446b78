#include "base/text.h"

#include <charconv>

namespace mcon {
namespace {

// Length of the well-formed UTF-8 sequence starting at text[i], or 0 if there is none there
// (the Unicode standard's table of well-formed byte sequences).
std::size_t sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xbf;  // range of the second byte
  if (b >= 0xc2 && b <= 0xdf) {
    length = 2;
  } else if (b >= 0xe0 && b <= 0xef) {
    length = 3;
    if (b == 0xe0) low = 0xa0;   // overlong below U+0800
    if (b == 0xed) high = 0x9f;  // surrogates U+D800..U+DFFF
  } else if (b >= 0xf0 && b <= 0xf4) {
    length = 4;
    if (b == 0xf0) low = 0x90;   // overlong below U+10000
    if (b == 0xf4) high = 0x8f;  // above U+10FFFF
  } else {
    return 0;
  }
  if (text.size() - i < length) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
  return length;
}

// Two lowercase hex digits.
std::string hex(unsigned char c) {
  static const char digits[] = "0123456789abcdef";
  return {digits[c >> 4], digits[c & 15]};
}

}  // namespace

std::size_t invalid_utf8_offset(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

std::string text_problem(std::string_view text) {
  const std::size_t nul = text.find('\0');
  if (nul != std::string_view::npos) return "contains a NUL byte at offset " + std::to_string(nul);
  const std::size_t bad = invalid_utf8_offset(text);
  if (bad == std::string_view::npos) return "";
  return "is not valid UTF-8 (byte 0x" + hex(static_cast<unsigned char>(text[bad])) + " at offset " +
         std::to_string(bad) + ")";
}

std::string printable_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = sequence_length(text, i);
    if (n == 0) {
      out += "\\x" + hex(c);
      ++i;
    } else if (n == 2 && c == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) {
      out += "\\u00" + hex(static_cast<unsigned char>(text[i + 1]));  // U+0080..U+009F
      i += 2;
    } else if (n > 1) {
      out.append(text, i, n);
      i += n;
    } else if (c == '\\') {
      out += "\\\\";
      ++i;
    } else if (c == '\n' || c == '\r' || c == '\t') {
      out += c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t";
      ++i;
    } else if (c < 0x20 || c == 0x7f) {
      out += "\\x" + hex(c);
      ++i;
    } else {
      out += static_cast<char>(c);
      ++i;
    }
  }
  return out;
}

std::string number_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace mcon
