// Pull-style streams of segments: each stage asks the previous one for its
// next item (a program's reader, the tool-tip expander, the planner, the
// deviation meter's own reading of the program).
#pragma once

#include <cstdint>
#include <functional>

#include "path/segment.h"

namespace lcnc {

enum class SourceStatus : std::uint8_t { Item, End, Error };

using SegmentSource = std::function<SourceStatus(Segment&)>;

}  // namespace lcnc
