// Helpers the decomposition tests share.
#pragma once

#include <string>

#include "common/result.h"
#include "core/dxf/dxf_test_util.h"
#include "decompose/part_decomposition.h"

namespace lcnc::decompose {

// The drawing in `file` (DXF text) decomposed with `o`, discretized at `step` mm.
inline Result<PartResult> decompose_file(const std::string& file, const Options& o, double step = 0.01) {
  return decompose_part(test::read_ok(file), step, o);
}

}  // namespace lcnc::decompose
