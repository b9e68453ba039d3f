#pragma once
/// \file printable.h
/// Quoting input text in messages: a message must stay one readable line
/// whatever bytes the input holds.

#include <string>
#include <string_view>

namespace knitforge {

/// `text` for a one-line message: at most `max_chars` characters, printable
/// ASCII as is, every other byte (control bytes, non-ASCII) as `\xHH`; a
/// longer text is cut with "... (N bytes)".
inline std::string printable(std::string_view text, size_t max_chars = 80) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  size_t i = 0;
  for (; i < text.size() && out.size() < max_chars; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 15]);
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace knitforge
