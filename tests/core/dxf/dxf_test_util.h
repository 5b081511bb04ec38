// Shared helpers of the DXF and decomposition tests: test drawings by name
// (tests/data/dxf/, share/examples/) and small DXF texts built in code.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "dxf/dxf_reader.h"
#include "support/expect_mentions.h"

namespace lcnc::test {

inline std::string dxf_data(const std::string& name) {
  return std::string(LCNC_SOURCE_DIR) + "/tests/data/dxf/" + name;
}
inline std::string sample_part() {
  return std::string(LCNC_SOURCE_DIR) + "/share/examples/plate_decompose.dxf";
}

// Reads a drawing that must be valid.
inline dxf::Drawing read_ok(const std::string& path) {
  Result<dxf::ReadResult> r = dxf::read_dxf_file(path);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  return r.ok() ? r->drawing : dxf::Drawing{};
}

// A minimal DXF around an ENTITIES body of "code\nvalue\n" pairs.
inline std::string dxf_doc(const std::string& entities, const std::string& blocks = {}) {
  std::string s = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n";
  if (!blocks.empty()) s += "0\nSECTION\n2\nBLOCKS\n" + blocks + "0\nENDSEC\n";
  return s + "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n";
}
inline std::string dxf_line(double x1, double y1, double x2, double y2) {
  return "0\nLINE\n8\n0\n10\n" + std::to_string(x1) + "\n20\n" + std::to_string(y1) + "\n11\n" +
         std::to_string(x2) + "\n21\n" + std::to_string(y2) + "\n";
}
inline std::string dxf_circle(double cx, double cy, double r) {
  return "0\nCIRCLE\n8\n0\n10\n" + std::to_string(cx) + "\n20\n" + std::to_string(cy) + "\n40\n" +
         std::to_string(r) + "\n";
}
// A closed LWPOLYLINE through the points (no bulges).
inline std::string dxf_lwpoly(std::initializer_list<std::pair<double, double>> pts) {
  std::string s = "0\nLWPOLYLINE\n8\n0\n90\n" + std::to_string(pts.size()) + "\n70\n1\n";
  for (const auto& [x, y] : pts) s += "10\n" + std::to_string(x) + "\n20\n" + std::to_string(y) + "\n";
  return s;
}

}  // namespace lcnc::test
