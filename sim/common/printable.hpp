// Messages quote what they read, and what they read may be any bytes: a damaged file's
// garbage must not reach a terminal or a log as invalid UTF-8 or control characters.
#pragma once

#include <string>

namespace bimloc::sim {

// `text` with every byte that is not part of valid UTF-8, and every control character but
// newline and tab, written as \xNN. Valid UTF-8 (a room named "Küche") is kept as it is.
std::string printable(const std::string& text);

// Whether `text` is valid UTF-8 (RFC 3629), control characters allowed.
bool isValidUtf8(const std::string& text);

}  // namespace bimloc::sim
