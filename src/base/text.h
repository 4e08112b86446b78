// Strings that come from files and callers (entry names, tags, field names...): what may be
// stored, and how to show one safely in a message or on a terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace mcon {

// Offset of the first byte that is not part of well-formed UTF-8 (RFC 3629: no overlong forms,
// no surrogates, nothing above U+10FFFF), or std::string_view::npos if there is none.
std::size_t invalid_utf8_offset(std::string_view text);

// Why `text` cannot be stored as a name, or "" if it can. Stored strings are well-formed UTF-8
// without NUL bytes: a NUL would end the string for every C caller (two field names differing
// only after one would look identical) and invalid UTF-8 breaks the bindings' decoders.
// E.g. "contains a NUL byte at offset 3", "is not valid UTF-8 (byte 0xff at offset 5)".
std::string text_problem(std::string_view text);

// `text` safe to print: control characters (C0, DEL and C1, which terminals interpret) become
// \n, \r, \t or \xNN (C1 as \u0080..\u009f), bytes that are not well-formed UTF-8 become \xNN and
// a backslash is doubled, so the result is unambiguous. Everything else is kept as it is.
std::string printable_text(std::string_view text);

// `value` in the shortest form that reads back to the same double ("1e-12", "0.3"): for
// messages, where std::to_string would print 1e-12 as "0.000000".
std::string number_text(double value);

}  // namespace mcon
