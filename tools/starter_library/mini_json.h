// A minimal JSON reader for the starter library's text sources (entries.json): objects, arrays,
// strings (with the standard escapes, \u for the Basic Multilingual Plane), numbers, true, false,
// null. The generator uses only the SDK's C API, so it does not link the tools' JSON layer.
// Errors throw std::runtime_error naming the byte offset.
#pragma once

#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace starter {

struct JsonValue {
  enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<JsonValue> array;
  std::vector<std::pair<std::string, JsonValue>> object;

  const JsonValue* find(const std::string& key) const {
    for (const auto& m : object)
      if (m.first == key) return &m.second;
    return nullptr;
  }
  const JsonValue& at(const std::string& key) const {
    const JsonValue* v = find(key);
    if (v == nullptr) throw std::runtime_error("missing key \"" + key + "\"");
    return *v;
  }
  double num(const std::string& key) const {
    const JsonValue& v = at(key);
    if (v.kind != Number) throw std::runtime_error("\"" + key + "\" is not a number");
    return v.number;
  }
  double num_or(const std::string& key, double fallback) const {
    const JsonValue* v = find(key);
    return (v != nullptr && v->kind == Number) ? v->number : fallback;
  }
  std::string str(const std::string& key) const {
    const JsonValue& v = at(key);
    if (v.kind != String) throw std::runtime_error("\"" + key + "\" is not a string");
    return v.string;
  }
  std::string str_or(const std::string& key, const std::string& fallback) const {
    const JsonValue* v = find(key);
    return (v != nullptr && v->kind == String) ? v->string : fallback;
  }
};

class JsonParser {
 public:
  explicit JsonParser(const std::string& text) : s_(text) {}
  JsonValue parse() {
    JsonValue v = value();
    ws();
    if (i_ != s_.size()) fail("trailing characters");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(i_));
  }
  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
  }
  bool eat(char c) {
    ws();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  void literal(const char* word) {
    for (const char* p = word; *p; ++p, ++i_)
      if (i_ >= s_.size() || s_[i_] != *p) fail(std::string("expected ") + word);
  }
  static void utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  std::string string_body() {
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated escape");
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          if (i_ + 4 > s_.size()) fail("short \\u escape");
          const std::string hex = s_.substr(i_, 4);
          char* end = nullptr;
          const unsigned long cp = std::strtoul(hex.c_str(), &end, 16);
          if (end != hex.c_str() + 4 || (cp >= 0xD800 && cp <= 0xDFFF)) fail("bad \\u escape");
          utf8(out, static_cast<unsigned>(cp));
          i_ += 4;
          break;
        }
        default: fail("bad escape");
      }
    }
  }
  JsonValue value() {
    ws();
    if (i_ >= s_.size()) fail("unexpected end");
    JsonValue v;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      v.kind = JsonValue::Object;
      if (eat('}')) return v;
      do {
        expect('"');
        std::string key = string_body();
        if (v.find(key) != nullptr) fail("duplicate key \"" + key + "\"");
        expect(':');
        v.object.emplace_back(std::move(key), value());
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      ++i_;
      v.kind = JsonValue::Array;
      if (eat(']')) return v;
      do v.array.push_back(value());
      while (eat(','));
      expect(']');
    } else if (c == '"') {
      ++i_;
      v.kind = JsonValue::String;
      v.string = string_body();
    } else if (c == 't') {
      literal("true");
      v.kind = JsonValue::Bool;
      v.boolean = true;
    } else if (c == 'f') {
      literal("false");
      v.kind = JsonValue::Bool;
    } else if (c == 'n') {
      literal("null");
    } else {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      v.kind = JsonValue::Number;
      v.number = std::strtod(begin, &end);
      if (end == begin) fail("unexpected character");
      i_ += static_cast<std::size_t>(end - begin);
    }
    return v;
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

}  // namespace starter
