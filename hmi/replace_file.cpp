#include "hmi/replace_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace lcnc::hmi {

bool replace_file(const std::string& path, const std::function<void(std::ostream&)>& write,
                  std::string& error) {
  const std::string tmp = path + ".part";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) write(out);
    out.flush();
    if (!out) {
      error = "cannot write '" + tmp + "'";
      std::remove(tmp.c_str());
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = "cannot replace '" + path + "': " + std::strerror(errno);
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace lcnc::hmi
