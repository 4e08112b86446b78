// A cursor over an in-memory text buffer for the mesh readers: numbers are parsed in place with
// std::from_chars (no iostreams, no locale, never reads past the buffer), and every error names
// the file and the line ("file:12: message") so a user can find the bad spot.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

#include "base/error.h"

namespace mcon::io {

class TextCursor {
 public:
  TextCursor(std::string_view text, const std::string& file_name, std::size_t start = 0, int line = 1)
      : text_(text), pos_(start), line_(line), file_name_(file_name) {}

  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  // A number or index must end at one of these (or at the end of the buffer).
  static bool is_delimiter(char c) { return is_blank(c) || c == '\n' || c == '#'; }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  void advance() { ++pos_; }
  int line() const { return line_; }
  std::size_t position() const { return pos_; }

  // Returns to an earlier position on the current line (a one-token look-ahead).
  void rewind_on_line(std::size_t position) { pos_ = position; }

  // Skips spaces and tabs (and '\r') but stays on the line.
  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
  }
  // True at '\n', at a '#' comment or at the end, after skipping blanks.
  bool at_line_end() {
    skip_blanks();
    return at_end() || text_[pos_] == '\n' || text_[pos_] == '#';
  }
  // Moves past the next '\n' (the rest of the line is ignored).
  void next_line() {
    if (pos_ >= text_.size()) return;
    const void* nl = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
    if (!nl) {
      pos_ = text_.size();
      return;
    }
    pos_ = static_cast<std::size_t>(static_cast<const char*>(nl) - text_.data()) + 1;
    ++line_;
  }
  // Skips whitespace including newlines (counting lines), and '#' comments when asked.
  void skip_space(bool hash_comments) {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++pos_;
        ++line_;
      } else if (is_blank(c)) {
        ++pos_;
      } else if (hash_comments && c == '#') {
        next_line();
      } else {
        break;
      }
    }
  }
  // The run of non-blank characters at the cursor (empty at a line end).
  std::string_view word() {
    skip_blanks();
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_blank(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    return text_.substr(begin, pos_ - begin);
  }

  // Parses a number at the cursor (after blanks on the same line); false if there is none or it
  // is not followed by a delimiter. A leading '+' is accepted (from_chars alone rejects it).
  bool read_double(double& value) {
    skip_blanks();
    const std::size_t saved = pos_;
    if (pos_ < text_.size() && text_[pos_] == '+') ++pos_;
    const char* end = text_.data() + text_.size();
    const auto [ptr, ec] = std::from_chars(text_.data() + pos_, end, value);
    if (ec != std::errc() || (ptr != end && !is_delimiter(*ptr))) {
      pos_ = saved;
      return false;
    }
    pos_ = static_cast<std::size_t>(ptr - text_.data());
    return true;
  }
  // Parses an integer; `also_stop_at` is an extra allowed terminator (OBJ's '/').
  bool read_integer(long long& value, char also_stop_at = '\0') {
    skip_blanks();
    const std::size_t saved = pos_;
    if (pos_ < text_.size() && text_[pos_] == '+') ++pos_;
    const char* end = text_.data() + text_.size();
    const auto [ptr, ec] = std::from_chars(text_.data() + pos_, end, value);
    if (ec != std::errc() ||
        (ptr != end && !is_delimiter(*ptr) && !(also_stop_at != '\0' && *ptr == also_stop_at))) {
      pos_ = saved;
      return false;
    }
    pos_ = static_cast<std::size_t>(ptr - text_.data());
    return true;
  }

  // Garbage bytes shown as '?' and long tokens cut, so messages stay readable.
  static std::string printable(std::string_view token) {
    std::string out(token.substr(0, 32));
    for (char& c : out)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return out;
  }

  [[noreturn]] void error(const std::string& message) const {
    fail(MCON_ERROR_IO, file_name_ + ":" + std::to_string(line_) + ": " + message);
  }
  // The token at the cursor, quoted and shortened, for error messages.
  std::string quote_here() const {
    std::size_t end = pos_;
    while (end < text_.size() && end - pos_ < 32 && !is_blank(text_[end]) && text_[end] != '\n') ++end;
    if (pos_ >= text_.size()) return "end of file";
    return "'" + printable(text_.substr(pos_, end - pos_)) + "'";
  }

 private:
  std::string_view text_;
  std::size_t pos_;
  int line_;
  const std::string& file_name_;
};

}  // namespace mcon::io
