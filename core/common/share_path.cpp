#include "common/share_path.h"

#include <cstdlib>

namespace lcnc {

std::string share_path(std::string_view relative) {
  const char* share = std::getenv("LASERCNC_SHARE");
  std::string p = share != nullptr && *share != '\0' ? share : LCNC_SHARE_DIR;
  p += '/';
  p += relative;
  return p;
}

}  // namespace lcnc
