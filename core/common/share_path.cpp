#include "common/share_path.h"

#include <cstdlib>
#include <filesystem>

namespace lcnc {
namespace {

// <exe>/../share/lasercnc when it exists, else the source tree's.
const std::string& default_share() {
  static const std::string dir = [] {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
      const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "lasercnc";
      if (std::filesystem::is_directory(installed / "machines", ec)) return installed.string();
    }
    return std::string(LCNC_SHARE_DIR);
  }();
  return dir;
}

}  // namespace

std::string share_path(std::string_view relative) {
  const char* share = std::getenv("LASERCNC_SHARE");
  std::string p = share != nullptr && *share != '\0' ? share : default_share();
  p += '/';
  p += relative;
  return p;
}

}  // namespace lcnc
