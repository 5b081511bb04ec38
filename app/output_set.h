// The outputs of one CLI command, each through the one door for output
// files (common/output_file.h).
#pragma once

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "common/output_file.h"

namespace lcnc::app {

// The outputs of one command: each written to its temporary file as it is
// made, all renamed over their targets by commit_all() once the command has
// done its work; a refused or failed command leaves every target as it was.
class OutputSet {
 public:
  explicit OutputSet(std::vector<std::string> inputs) : inputs_(std::move(inputs)) {}
  // Opens `path`, `fill` writes it; false (and the message printed) when it
  // cannot be opened.
  template <typename Fill>
  bool add(const std::string& path, Fill fill) {
    Result<OutputFile> f = OutputFile::open(path, inputs_);
    if (!f) {
      std::fprintf(stderr, "%s\n", f.error().to_string().c_str());
      return false;
    }
    fill(*f);
    files_.push_back(std::move(f).value());
    return true;
  }
  bool commit_all() {
    for (OutputFile& f : files_) {
      if (Status s = f.commit(); !s) {
        std::fprintf(stderr, "%s\n", s.error().to_string().c_str());
        return false;
      }
    }
    return true;
  }

 private:
  std::vector<std::string> inputs_;
  std::vector<OutputFile> files_;
};

}  // namespace lcnc::app
