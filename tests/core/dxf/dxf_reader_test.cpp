// The DXF reader: every entity kind, blocks, units, mirrored OCS, and every
// kind of malformed file — a clear error with file and line, never a crash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"
#include "dxf/contour_chain.h"
#include "dxf/dxf_tolerances.h"
#include "dxf/spline_curve.h"

namespace lcnc::dxf {
namespace {

using test::dxf_data;
using test::read_ok;
constexpr double kPi = std::numbers::pi;

double total_length(const Drawing& d) {
  double l = 0;
  for (const Entity& e : d.entities) {
    for (const Edge& ed : e.edges) l += edge_length(ed);
  }
  return l;
}

// A closed periodic cubic SPLINE near a circle of radius r (mm): 8 control
// points on the circle, 3 repeated, uniform knots.
std::string periodic_cubic_spline(double r) {
  std::string sp = "0\nSPLINE\n8\n0\n70\n11\n71\n3\n72\n15\n73\n11\n74\n0\n";
  for (int k = 0; k < 15; ++k) sp += "40\n" + std::to_string(k) + "\n";
  for (int i = 0; i < 11; ++i) {
    const double a = 2.0 * kPi * (i % 8) / 8.0;
    sp += "10\n" + std::to_string(r * std::cos(a)) + "\n20\n" + std::to_string(r * std::sin(a)) + "\n";
  }
  return sp;
}

std::vector<Contour> contours_of(const Drawing& d) {
  Result<std::vector<Contour>> cs = chain_contours(d);
  EXPECT_TRUE(cs.ok()) << (cs.ok() ? "" : cs.error().to_string());
  return cs.ok() ? *cs : std::vector<Contour>{};
}

// Extent of a contour, sampled.
Eigen::AlignedBox2d bbox(const Contour& c) {
  Eigen::AlignedBox2d b;
  for (const Edge& e : c.edges) {
    const double l = edge_length(e);
    for (int k = 0; k <= 64; ++k) b.extend(edge_point(e, l * k / 64.0));
  }
  return b;
}

TEST(DxfReader, LinesChainIntoASquare) {
  const Drawing d = read_ok(dxf_data("line_square.dxf"));
  ASSERT_EQ(d.entities.size(), 4u);
  EXPECT_EQ(d.entities[0].kind, EntityKind::Line);
  EXPECT_EQ(d.entities[0].line, 19u);
  EXPECT_EQ(d.entities[0].layer, "CUT");
  const std::vector<Contour> cs = contours_of(d);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_NEAR(cs[0].length(), 40.0, 1e-12);
}

TEST(DxfReader, ArcsRunCounterClockwiseFromAngle1ToAngle2) {
  const Drawing d = read_ok(dxf_data("arc_slot.dxf"));
  ASSERT_EQ(d.entities.size(), 4u);
  const Entity& arc = d.entities[1];  // centre (20, 5), r 5, 270° → 90°
  ASSERT_EQ(arc.kind, EntityKind::Arc);
  EXPECT_NEAR(edge_length(arc.edges[0]), 5 * kPi, 1e-12);
  EXPECT_TRUE(arc.start().isApprox(Eigen::Vector2d(20, 0), 1e-12));
  // Counter-clockwise from the bottom passes the rightmost point.
  EXPECT_TRUE(edge_point(arc.edges[0], 2.5 * kPi).isApprox(Eigen::Vector2d(25, 5), 1e-12));
  EXPECT_NEAR(contours_of(d)[0].length(), 40 + 10 * kPi, 1e-9);
}

TEST(DxfReader, CircleIsAClosedContourByItself) {
  const Drawing d = read_ok(dxf_data("circle.dxf"));
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_TRUE(d.entities[0].closed);
  const std::vector<Contour> cs = contours_of(d);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_NEAR(cs[0].length(), 8 * kPi, 1e-12);
}

TEST(DxfReader, LwPolylineBulgesAreArcs) {
  // 40 × 20 rectangle with r 5 corners: 2·(30 + 10) straight + 2π·5.
  const Drawing d = read_ok(dxf_data("lwpolyline_bulge.dxf"));
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_EQ(d.entities[0].kind, EntityKind::LwPolyline);
  EXPECT_EQ(d.entities[0].edges.size(), 8u);
  EXPECT_NEAR(total_length(d), 80 + 10 * kPi, 1e-9);
  const Eigen::AlignedBox2d b = bbox(contours_of(d)[0]);
  EXPECT_NEAR(b.min().x(), 0, 1e-9);
  EXPECT_NEAR(b.max().x(), 40, 1e-9);
  EXPECT_NEAR(b.max().y(), 20, 1e-9);
}

TEST(DxfReader, PolylineWithVerticesAndABulge) {
  // (0,0) → (10,0) → bulge 1: a counter-clockwise half circle to (10,10) → (0,10) → close.
  const Drawing d = read_ok(dxf_data("polyline_vertex.dxf"));
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_EQ(d.entities[0].kind, EntityKind::Polyline);
  EXPECT_NEAR(total_length(d), 30 + 5 * kPi, 1e-9);
  EXPECT_NEAR(bbox(contours_of(d)[0]).max().x(), 15.0, 1e-9);  // bulges outwards
}

TEST(DxfReader, ClosedSplineIsSampledOnTheCurve) {
  const Drawing d = read_ok(dxf_data("spline_closed.dxf"));
  ASSERT_EQ(d.entities.size(), 1u);
  EXPECT_EQ(d.entities[0].kind, EntityKind::Spline);
  const std::vector<Contour> cs = contours_of(d);
  ASSERT_EQ(cs.size(), 1u);
  const Edge& e = cs[0].edges[0];
  ASSERT_EQ(e.kind, EdgeKind::Spline);
  // Symmetric control polygon: the curve is symmetric and inside it.
  const Eigen::AlignedBox2d b = bbox(cs[0]);
  EXPECT_NEAR(b.max().x(), -b.min().x(), 1e-6);
  EXPECT_LT(b.max().x(), 10.0);
  EXPECT_GT(b.max().x(), 5.0);
  // Equal arc lengths: the chords of 1000 equal steps are all equal (the
  // curve is smooth, so chord = arc to within curvature · step³).
  const double l = edge_length(e);
  double lo = 1e9, hi = 0;
  for (int k = 0; k < 1000; ++k) {
    const double c = (edge_point(e, l * (k + 1) / 1000) - edge_point(e, l * k / 1000)).norm();
    lo = std::min(lo, c);
    hi = std::max(hi, c);
  }
  EXPECT_LT(hi - lo, 1e-6 * l / 1000 + 1e-9);
}

// A rational quadratic with weights 1, √2/2, 1 is exactly a quarter circle:
// every point at radius R, the length πR/2, the point at s at angle s/R —
// which holds only if the table's rational point and derivative are right
// (its arc lengths integrate |C'|).
TEST(SplineCurve, ARationalQuarterCircleIsExactInPointsAndLength) {
  constexpr double R = 25.0;
  SplineData d;
  d.degree = 2;
  d.knots = {0, 0, 0, 1, 1, 1};
  d.control = {Vec2(R, 0), Vec2(R, R), Vec2(0, R)};
  d.weights = {1.0, std::sqrt(0.5), 1.0};
  std::string why;
  const auto c = SplineCurve::make(d, &why);
  ASSERT_TRUE(c) << why;
  EXPECT_NEAR(c->length(), kPi * R / 2, 1e-9);
  for (int k = 0; k <= 100; ++k) {
    const double s = c->length() * k / 100;
    const Vec2 q = c->at_length(s);
    EXPECT_NEAR(q.norm(), R, 1e-9) << "s " << s;
    EXPECT_NEAR(std::atan2(q.y(), q.x()), s / R, 1e-9) << "s " << s;
  }
}

TEST(DxfReader, InsertPlacesBlockArraysScaledAndRotated) {
  // Block SQ (base 1,1) inserted at (100, 0), scale 2, 90°, 3 columns × 2
  // rows spaced 20 / 30 along the rotated block axes.
  const Drawing d = read_ok(dxf_data("insert_array.dxf"));
  ASSERT_EQ(d.entities.size(), 6u);
  for (const Entity& e : d.entities) EXPECT_EQ(e.block, "SQ");
  // The block's base point (1,1) lands on the insertion point for copy (0,0).
  EXPECT_TRUE(d.entities[0].start().isApprox(Eigen::Vector2d(100, 0), 1e-9));
  // Column 1 is 20 along the rotated X axis: +20 in Y.
  EXPECT_TRUE(d.entities[1].start().isApprox(Eigen::Vector2d(100, 20), 1e-9));
  // Row 1 is 30 along the rotated Y axis: −30 in X.
  EXPECT_TRUE(d.entities[3].start().isApprox(Eigen::Vector2d(70, 0), 1e-9));
  // Lengths scale by 2 (5 + 3 + 3 straight, a half circle of r 2.5).
  const double one = 2 * (5 + 3 + 3 + 2.5 * kPi);
  EXPECT_NEAR(total_length(d), 6 * one, 1e-9);
  EXPECT_EQ(contours_of(d).size(), 6u);
}

TEST(DxfReader, NestedInsertsCompose) {
  const Drawing d = read_ok(dxf_data("insert_nested.dxf"));
  ASSERT_EQ(d.entities.size(), 2u);
  EXPECT_TRUE(d.entities[0].edges[0].center.isApprox(Eigen::Vector2d(5, 5)));
  EXPECT_TRUE(d.entities[1].edges[0].center.isApprox(Eigen::Vector2d(10, 5)));
}

TEST(DxfReader, InsunitsInchesAreConvertedToMm) {
  Result<ReadResult> r = read_dxf_file(dxf_data("units_inch.dxf"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->drawing.unit_mm, 25.4);
  EXPECT_EQ(r->drawing.units, "inch");
  EXPECT_NEAR(r->drawing.entities[0].edges[0].radius, 25.4, 1e-12);
  // The caller may override the drawing's units.
  ReadOptions mm;
  mm.unit_mm = 1.0;
  Result<ReadResult> r2 = read_dxf_file(dxf_data("units_inch.dxf"), mm);
  ASSERT_TRUE(r2.ok());
  EXPECT_NEAR(r2->drawing.entities[0].edges[0].radius, 1.0, 1e-12);
}

TEST(DxfReader, MirroredOcsArcIsMappedBackToXY) {
  // Extrusion (0, 0, −1), OCS centre (−10, 5), 90° → 270°: in the world the
  // right end cap of a slot, centre (10, 5), through (15, 5).
  const Drawing d = read_ok(dxf_data("mirrored_arc.dxf"));
  const Edge& arc = d.entities[1].edges[0];
  EXPECT_TRUE(arc.center.isApprox(Eigen::Vector2d(10, 5)));
  EXPECT_LT(arc.sweep_rad, 0.0);  // clockwise seen from +Z
  EXPECT_TRUE(edge_point(arc, 2.5 * kPi).isApprox(Eigen::Vector2d(15, 5), 1e-12));
  const std::vector<Contour> cs = contours_of(d);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_NEAR(cs[0].length(), 20 + 10 * kPi, 1e-9);
}

TEST(DxfReader, TextIsIgnoredAndNoted) {
  Result<ReadResult> r = read_dxf_file(dxf_data("text_ignored.dxf"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->drawing.entities.size(), 1u);
  bool noted = false;
  for (const std::string& n : r->notes) noted = noted || n == "ignored: 1 TEXT";
  EXPECT_TRUE(noted);
}

TEST(DxfReader, SamplePartHasEveryEntityKind) {
  const Drawing d = read_ok(test::sample_part());
  bool kinds[6] = {};
  for (const Entity& e : d.entities) kinds[static_cast<int>(e.kind)] = true;
  for (bool k : kinds) EXPECT_TRUE(k);
  EXPECT_EQ(contours_of(d).size(), 7u);
}

// --- malformed files: the code, the line, what was expected --------------

struct BadFile {
  const char* file;
  ErrorCode code;
  std::uint32_t line;
  const char* mentions;
};

class DxfReaderBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(DxfReaderBadFile, IsAnErrorWithFileAndLine) {
  const BadFile& b = GetParam();
  Result<ReadResult> r = read_dxf_file(dxf_data(b.file));
  ASSERT_FALSE(r.ok()) << b.file;
  EXPECT_EQ(r.error().code, b.code) << r.error().to_string();
  EXPECT_EQ(r.error().line, b.line) << r.error().to_string();
  EXPECT_EQ(r.error().file, dxf_data(b.file));
  EXPECT_MENTIONS(r.error(), b.mentions);
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, DxfReaderBadFile,
    ::testing::Values(
        BadFile{"bad_group_code.dxf", ErrorCode::DxfSyntax, 41, "found '2O' where a group code was expected"},
        BadFile{"bad_number.dxf", ErrorCode::DxfSyntax, 48, "expected a finite real number"},
        BadFile{"truncated.dxf", ErrorCode::DxfSyntax, 31, "truncated"},
        BadFile{"count_mismatch.dxf", ErrorCode::DxfSyntax, 23, "declares 5 vertices"},
        BadFile{"undefined_block.dxf", ErrorCode::DxfSyntax, 19, "'NOPE', which is not defined"},
        BadFile{"recursive_block.dxf", ErrorCode::DxfUnsupported, 35, "inside block 'LOOP' closes a loop"},
        BadFile{"ellipse.dxf", ErrorCode::DxfUnsupported, 19, "ELLIPSE is not supported"},
        BadFile{"not_dxf.dxf", ErrorCode::DxfSyntax, 1, "where a group code was expected"},
        BadFile{"empty.dxf", ErrorCode::DxfSyntax, 0, "empty file"}));

TEST(DxfReader, MissingFileIsFileNotFound) {
  Result<ReadResult> r = read_dxf_file(dxf_data("no_such_file.dxf"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::FileNotFound);
}

TEST(DxfReader, NoEofIsTruncated) {
  Result<ReadResult> r = read_dxf_text("0\nSECTION\n2\nENTITIES\n" + test::dxf_circle(0, 0, 1), "t.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "inside section ENTITIES");
}

TEST(DxfReader, SplineKnotCountMismatchIsAnError) {
  const std::string sp =
      "0\nSPLINE\n8\n0\n70\n8\n71\n3\n72\n5\n73\n4\n74\n0\n"
      "40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n"  // 5 knots, 4 control points of degree 3 need 8
      "10\n0\n20\n0\n10\n1\n20\n1\n10\n2\n20\n0\n10\n3\n20\n1\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(sp), "s.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfUnsupported);
  EXPECT_MENTIONS(r.error(), "5 knots for 4 control points of degree 3; expected 8");
}

// Found by fuzzing: a drawing whose $INSUNITS said miles made a closed
// spline of the sample part 24 km long; its arc-length table (a node per
// 0.1 µm of chord error) took minutes. A table past kSplineMaxNodes is
// refused, saying why, within a fraction of a second.
TEST(DxfReader, ASplineKilometresLongIsRefusedNotTabulatedForMinutes) {
  const std::string sp = periodic_cubic_spline(1e7);  // on a circle of 10 km
  const auto t0 = std::chrono::steady_clock::now();
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(sp), "km.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "are the drawing's units right?");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20));  // a hang, not a speed test
  // the fuzzer's own input reads to an answer
  std::ifstream in(std::string(LCNC_SOURCE_DIR) + "/tests/data/dxf_regress/spline_in_miles.dxf",
                   std::ios::binary);
  const std::string found((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(found.empty());
  (void)read_dxf_text(found, "miles.dxf");
}

// Found by fuzzing: blocks nested 16 deep, each inserting the next as an
// array, took minutes under the sanitizers — every copy placed (and its
// spline tabulated) before the depth was found too deep. The INSERTs' copies
// are now counted per block before anything is placed: refused at once,
// at the outermost INSERT, saying how many.
TEST(DxfReader, NestedArraysThatMultiplyIntoMillionsAreRefusedBeforeAnyIsPlaced) {
  std::string blocks;
  constexpr int kLevels = 12;  // B0 … B10 each insert the next 2 × 2: 4^11 = 4.2 million lines
  for (int b = 0; b < kLevels; ++b) {
    blocks +=
        "0\nBLOCK\n8\n0\n2\nB" + std::to_string(b) + "\n70\n0\n10\n0\n20\n0\n3\nB" + std::to_string(b) + "\n";
    if (b + 1 < kLevels) {
      blocks +=
          "0\nINSERT\n8\n0\n2\nB" + std::to_string(b + 1) + "\n10\n0\n20\n0\n70\n2\n71\n2\n44\n10\n45\n10\n";
    } else {
      blocks += test::dxf_line(0, 0, 1, 1);
    }
    blocks += "0\nENDBLK\n8\n0\n";
  }
  const std::string top = "0\nINSERT\n8\n0\n2\nB0\n10\n0\n20\n0\n";
  const auto t0 = std::chrono::steady_clock::now();
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(top, blocks), "nest.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfUnsupported);
  EXPECT_MENTIONS(r.error(), "the INSERTs place more than 1000000 entities");
  EXPECT_MENTIONS(r.error(), "block 'B0' 4.194e+06");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));  // no placing, not a speed test
  // fewer levels are a drawing (4^10 = 1,048,576 lines would still be over)
  std::string nine = blocks;
  const std::string b9 = "0\nINSERT\n8\n0\n2\nB9\n";
  ASSERT_NE(nine.find(b9), std::string::npos);
  nine.replace(nine.find(b9), b9.size(), "0\nINSERT\n8\n0\n2\nB11\n");  // B8 inserts the line: 9 arrays
  Result<ReadResult> ok = read_dxf_text(test::dxf_doc(top, nine), "nine.dxf");
  ASSERT_TRUE(ok.ok()) << ok.error().to_string();
  EXPECT_EQ(ok->drawing.entities.size(), 262144u);  // 4^9
  // the fuzzer's own input
  std::ifstream in(std::string(LCNC_SOURCE_DIR) + "/tests/fuzz/corpus/dxf/timeout_nested_arrays.dxf",
                   std::ios::binary);
  const std::string found((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(found.empty());
  const auto t1 = std::chrono::steady_clock::now();
  EXPECT_FALSE(read_dxf_text(found, "found.dxf").ok());
  EXPECT_LT(std::chrono::steady_clock::now() - t1, std::chrono::seconds(5));
}

// An array of a spline block tabulates every copy: the drawing's tables
// together are bounded too (kMaxDrawingSplineNodes), with a clear error.
TEST(DxfReader, AnArrayOfSplinesPastTheDrawingsTableBudgetIsRefused) {
  const std::string sp = periodic_cubic_spline(5000);  // near a circle of 5 m
  Result<ReadResult> one = read_dxf_text(test::dxf_doc(sp), "one.dxf");
  ASSERT_TRUE(one.ok()) << one.error().to_string();
  const std::string block = "0\nBLOCK\n8\n0\n2\nS\n70\n0\n10\n0\n20\n0\n3\nS\n" + sp + "0\nENDBLK\n8\n0\n";
  const std::string array = "0\nINSERT\n8\n0\n2\nS\n10\n0\n20\n0\n70\n40\n71\n40\n44\n20000\n45\n20000\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(array, block), "array.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfUnsupported);
  EXPECT_MENTIONS(r.error(), "the drawing's splines take at most 262144 pieces in all");
}

// Found by fuzzing: a value line longer than dxflib reads (1023 characters)
// left its reading loop running for ever; the scanner refuses it first.
TEST(DxfReader, ALineLongerThanTheReaderTakesIsAnErrorNotAHang) {
  const std::string c = "0\nCIRCLE\n8\n0\n10\n0." + std::string(1500, '4') + "\n20\n0\n40\n1\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(c), "long.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfSyntax);
  EXPECT_MENTIONS(r.error(), "a line of 1502 characters; expected at most 1023");
  EXPECT_GT(r.error().line, 0u);
  // the fuzzer's own input, from the corpus
  std::ifstream in(std::string(LCNC_SOURCE_DIR) + "/tests/fuzz/corpus/dxf/hang_long_line.dxf",
                   std::ios::binary);
  const std::string found((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(found.empty());
  EXPECT_FALSE(read_dxf_text(found, "hang.dxf").ok());
}

// A file read from a device without end (/dev/zero) stops at the first line
// longer than the scanner takes, on line 1, instead of reading until the
// memory runs out.
TEST(DxfReader, EndlessDeviceIsAnErrorNotAnEndlessRead) {
  const auto t0 = std::chrono::steady_clock::now();
  Result<ReadResult> r = read_dxf_file("/dev/zero");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfSyntax);
  EXPECT_EQ(r.error().line, 1u);
  EXPECT_MENTIONS(r.error(), "a line of more than 1023 characters");
  EXPECT_EQ(r.error().to_string().rfind("/dev/zero:1: error E601", 0), 0u) << r.error().to_string();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));
}

// Lines counted across read chunks name the right line.
TEST(DxfReader, OverlongLineInAFileNamesItsLine) {
  const std::string path = ::testing::TempDir() + "dxf_long_line.dxf";
  {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 40000; ++i) out << "999\ncomment\r\n";  // 80,000 lines, > one chunk
    out << std::string(5000, 'x') << "\n0\nEOF\n";
  }
  Result<ReadResult> r = read_dxf_file(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfSyntax);
  EXPECT_EQ(r.error().line, 80001u);
  std::remove(path.c_str());
}

// A regular file beyond the bound is refused before it is read (a sparse
// file: no disk space taken).
TEST(DxfReader, FileLargerThanTheBoundIsRefusedUpFront) {
  const std::string path = ::testing::TempDir() + "dxf_too_large.dxf";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(::ftruncate(::fileno(f), static_cast<off_t>(kMaxDxfFileBytes + 1)), 0);
  std::fclose(f);
  Result<ReadResult> r = read_dxf_file(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DxfUnsupported);
  EXPECT_MENTIONS(r.error(),
                  "a file of 134217729 bytes; expected a DXF file of at most 134217728 bytes (128 MiB)");
  std::remove(path.c_str());
}

TEST(DxfReader, ArcOfZeroRadiusIsAnError) {
  const std::string arc = "0\nARC\n8\n0\n10\n0\n20\n0\n40\n0\n50\n0\n51\n90\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(arc), "a.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "expected a radius > 0");
}

TEST(DxfReader, ArcInsertedWithUnequalScalesIsAnError) {
  const std::string blk = "0\nBLOCK\n2\nB\n10\n0\n20\n0\n" + test::dxf_circle(0, 0, 1) + "0\nENDBLK\n";
  const std::string ins = "0\nINSERT\n2\nB\n10\n0\n20\n0\n41\n2\n42\n1\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(ins, blk), "i.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "would be an ellipse");
}

TEST(DxfReader, EntityOutsideTheXYPlaneIsAnError) {
  const std::string c = "0\nCIRCLE\n8\n0\n10\n0\n20\n0\n40\n1\n210\n1\n220\n0\n230\n0\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(c), "c.dxf");
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "outside the XY plane");
}

TEST(DxfReader, PaperSpaceIsIgnored) {
  const std::string ps = "0\nCIRCLE\n8\n0\n67\n1\n10\n0\n20\n0\n40\n1\n";
  Result<ReadResult> r = read_dxf_text(test::dxf_doc(ps + test::dxf_circle(5, 5, 1)), "p.dxf");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->drawing.entities.size(), 1u);
}

// Property: any damage to a valid file reads as a drawing or as an error —
// never a crash, hang or exception. Fixed seed; LCNC_FUZZ_N scales it.
TEST(DxfReader, DamagedFilesNeverCrash) {
  std::ifstream f(test::sample_part());
  std::stringstream ss;
  ss << f.rdbuf();
  std::vector<std::string> lines;
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  const char* env = std::getenv("LCNC_FUZZ_N");
  const int n = env ? std::atoi(env) : 1000;
  std::mt19937 rng(20261122);
  const char* junk[] = {"",    "x",      "-1", "1e400", "nan",        "999999999",  "0",      "SECTION",
                        "EOF", "ENDSEC", "-5", "1071",  "2147483648", "LWPOLYLINE", "SPLINE", "BLOCK"};
  int errors = 0;
  for (int it = 0; it < n; ++it) {
    std::vector<std::string> m = lines;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !m.empty(); ++e) {
      const std::size_t at = rng() % m.size();
      switch (rng() % 4) {
        case 0: m.erase(m.begin() + static_cast<long>(at)); break;
        case 1: m[at] = junk[rng() % std::size(junk)]; break;
        case 2: m.resize(at); break;
        default: m.insert(m.begin() + static_cast<long>(at), junk[rng() % std::size(junk)]);
      }
    }
    std::string text;
    for (const std::string& l : m) text += l + "\n";
    Result<ReadResult> r = read_dxf_text(text, "fuzz.dxf");
    if (!r.ok()) {
      ++errors;
      EXPECT_FALSE(r.error().message.empty());
    }
  }
  EXPECT_GT(errors, n / 2);  // most damage is caught
}

}  // namespace
}  // namespace lcnc::dxf
