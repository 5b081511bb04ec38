// The fuzz targets by name (tests/fuzz/fuzz_targets.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace lcnc::fuzz {

struct Target {
  const char* name;
  int (*run)(const std::uint8_t* data, std::size_t size);
};

[[nodiscard]] const Target* find_target(std::string_view name);

}  // namespace lcnc::fuzz
