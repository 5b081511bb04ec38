#include "common/quote.h"

namespace lcnc {

std::string quote(std::string_view text, std::size_t max_shown) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const bool cut = max_shown > 0 && text.size() > max_shown;
  if (cut) text = text.substr(0, max_shown);
  std::string q;
  q.reserve(text.size() + 5);
  q += '\'';
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7F) {
      q += "\\x";
      q += kHex[c >> 4];
      q += kHex[c & 0xF];
    } else {
      q += ch;
    }
  }
  if (cut) q += "...";
  q += '\'';
  return q;
}

}  // namespace lcnc
