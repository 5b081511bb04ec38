// Text from a user's file, quoted for a message: between single quotes,
// every byte that cannot be shown (control bytes, NUL, DEL) written as \xNN,
// so a message is never cut off or garbled by what it quotes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace lcnc {

// 'text', at most `max_shown` bytes of it (0: all) with "..." when cut.
[[nodiscard]] std::string quote(std::string_view text, std::size_t max_shown = 0);

}  // namespace lcnc
