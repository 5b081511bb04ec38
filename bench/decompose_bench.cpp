// Main + auxiliary axes decomposition (docs/design.md §5.7):
//  1. throughput — contour points per second through chaining,
//     discretization, crossing checks and the decomposition (sync and seed
//     modes), on the sample part at 0.01 mm and at 1 µm (goal ≥ 1,000,000
//     points/s);
//  2. main-axis peak acceleration against a main-axes-only machine cutting
//     the same part at the same constant contour speed (goal ≥ 5× lower).
//     The main-axes-only machine's peak is the beam's own path acceleration
//     (the effective acceleration: vk² / r at the tightest bend).
//
//   build/bench/decompose_bench [--part FILE.dxf] [--runs N] [--csv DIR] [--png DIR]
//
// The comparison adds share/examples/star_decompose.dxf (sharp corners).
// --csv DIR writes the kinematics tables and SVG pictures of the 6 m/min
// cases (both parts, sync and seed); --png DIR also runs bench/plot_decompose.py on them
// and says plainly when it cannot (no python3 or matplotlib). Results go to
// BENCHMARKS.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "decompose/decompose_svg.h"
#include "decompose/part_decomposition.h"
#include "dxf/dxf_reader.h"

namespace {

using namespace lcnc;
using decompose::kG_mm_s2;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Peak {
  double a_main = 0, a_eff = 0, aux = 0, tau_max = 0, time_s = 0;
};

Peak peak_of(const decompose::PartResult& r) {
  Peak p;
  for (const decompose::ContourResult& c : r.contours) {
    p.a_main = std::max(p.a_main, c.peaks.a_main);
    p.a_eff = std::max(p.a_eff, c.peaks.a_eff);
    p.aux = std::max(p.aux, c.peaks.aux_excursion);
    p.tau_max = std::max(p.tau_max, c.tau_s);
    p.time_s += c.peaks.duration_s;
  }
  return p;
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  return static_cast<bool>(f);
}

}  // namespace

int main(int argc, char** argv) {
  std::string part = std::string(LCNC_SHARE_DIR) + "/examples/plate_decompose.dxf";
  int runs = 5;
  std::string csv_dir, png_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 < argc && a == "--part")
      part = argv[++i];
    else if (i + 1 < argc && a == "--runs")
      runs = std::max(1, std::atoi(argv[++i]));
    else if (i + 1 < argc && a == "--csv")
      csv_dir = argv[++i];
    else if (i + 1 < argc && a == "--png")
      png_dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: decompose_bench [--part FILE.dxf] [--runs N] [--csv DIR] [--png DIR]\n");
      return 2;
    }
  }
  if (!png_dir.empty() && csv_dir.empty()) csv_dir = png_dir;

  Result<dxf::ReadResult> read = dxf::read_dxf_file(part);
  if (!read) {
    std::fprintf(stderr, "%s\n", read.error().to_string().c_str());
    return 1;
  }
  const dxf::Drawing& drawing = read->drawing;
  // A part with sharp corners, where the paper's smoothing acts.
  Result<dxf::ReadResult> read_star =
      dxf::read_dxf_file(std::string(LCNC_SHARE_DIR) + "/examples/star_decompose.dxf");
  if (!read_star) {
    std::fprintf(stderr, "%s\n", read_star.error().to_string().c_str());
    return 1;
  }
  const dxf::Drawing& star = read_star->drawing;

  // --- 1. throughput ---------------------------------------------------------
  std::printf("throughput: %s, %d runs each, median\n", part.c_str(), runs);
  std::printf("%-7s %-5s %10s %12s %12s %14s %14s\n", "step", "mode", "points", "prepare s", "decompose s",
              "prepare pts/s", "end-to-end pts/s");
  for (const double step : {0.01, 0.001}) {
    for (const decompose::Mode mode : {decompose::Mode::Sync, decompose::Mode::Seed}) {
      decompose::Options opt;
      opt.mode = mode;
      opt.speed_mm_s = 100.0;
      std::vector<double> t_prep, t_dec;
      std::size_t points = 0;
      for (int r = 0; r < runs; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        Result<decompose::PreparedPart> prep = decompose::prepare_part(drawing, step);
        t_prep.push_back(seconds_since(t0));
        if (!prep) {
          std::fprintf(stderr, "%s\n", prep.error().to_string().c_str());
          return 1;
        }
        const auto t1 = std::chrono::steady_clock::now();
        Result<decompose::PartResult> res = decompose::decompose_prepared(*prep, opt);
        t_dec.push_back(seconds_since(t1));
        if (!res) {
          std::fprintf(stderr, "%s\n", res.error().to_string().c_str());
          return 1;
        }
        points = res->points;
      }
      const double p = median(t_prep), d = median(t_dec);
      std::printf("%-7.3f %-5s %10zu %12.4f %12.4f %14.0f %14.0f\n", step,
                  mode == decompose::Mode::Sync ? "sync" : "seed", points, p, d,
                  static_cast<double>(points) / p, static_cast<double>(points) / (p + d));
    }
  }

  // --- 2. main axes against a main-axes-only machine --------------------------
  std::printf(
      "\nmain-axis peak acceleration vs a main-axes-only machine (same part, same "
      "constant contour speed; sync mode, limits 0.5 g, aux 300 m/min, field +-5 mm, "
      "step 0.01 mm)\n");
  std::printf("%-6s %-10s %14s %14s %8s %10s %9s %10s\n", "part", "speed", "main-only a", "main axes a",
              "ratio", "aux max", "tau max", "time s");
  struct Case {
    const char* name;
    const dxf::Drawing* d;
    double m_min;
  };
  const Case cases[] = {{"plate", &drawing, 3.0},
                        {"plate", &drawing, 6.0},
                        {"plate", &drawing, 10.0},
                        {"plate", &drawing, 15.0},
                        {"star", &star, 6.0}};
  for (const Case& k : cases) {
    decompose::Options opt;
    opt.speed_mm_s = k.m_min * 1000.0 / 60.0;
    Result<decompose::PartResult> res = decompose::decompose_part(*k.d, 0.01, opt);
    if (!res) {
      std::printf("%-6s %4.1f m/min %s\n", k.name, k.m_min, res.error().to_string().c_str());
      continue;
    }
    const Peak p = peak_of(*res);
    std::printf("%-6s %4.1f m/min %8.0f mm/s2 %8.0f mm/s2 %7.1fx %7.3f mm %7.3f s %10.4f\n", k.name, k.m_min,
                p.a_eff, p.a_main, p.a_eff / p.a_main, p.aux, p.tau_max, p.time_s);
  }

  // --- pictures ----------------------------------------------------------------
  if (!csv_dir.empty()) {
    struct Pic {
      const char* name;
      const dxf::Drawing* d;
      decompose::Mode mode;
    };
    const Pic pics[] = {{"plate", &drawing, decompose::Mode::Sync},
                        {"plate", &drawing, decompose::Mode::Seed},
                        {"star", &star, decompose::Mode::Sync},
                        {"star", &star, decompose::Mode::Seed}};
    for (const Pic& k : pics) {
      decompose::Options opt;
      opt.mode = k.mode;
      opt.speed_mm_s = 100.0;
      Result<decompose::PartResult> res = decompose::decompose_part(*k.d, 0.01, opt);
      if (!res) continue;
      const std::string tag = std::string(k.name) + (k.mode == decompose::Mode::Sync ? "_sync" : "_seed");
      const std::string base = csv_dir + "/decompose_" + tag;
      std::ofstream csv(base + ".csv", std::ios::binary);
      std::vector<const decompose::KinematicsTable*> tables;
      for (const decompose::ContourResult& c : res->contours) tables.push_back(&c.table);
      decompose::write_csv(csv, tables);
      csv.close();
      const std::string title = std::string(k.name) + ", " +
                                (k.mode == decompose::Mode::Sync ? "sync" : "seed") +
                                " mode, 6 m/min, step 0.01 mm";
      const bool ok = static_cast<bool>(csv) &&
                      write_text(base + "_paths.svg", decompose::paths_svg(*res, opt, title)) &&
                      write_text(base + "_accel.svg", decompose::accel_svg(*res, opt, title));
      std::printf("\n%s: %s.csv, %s_paths.svg, %s_accel.svg\n", ok ? "wrote" : "could not write",
                  base.c_str(), base.c_str(), base.c_str());
      if (png_dir.empty()) continue;
      const std::string script = std::string(LCNC_SHARE_DIR) + "/../bench/plot_decompose.py";
      const std::string png = png_dir + "/decompose_" + tag + ".png";
      const std::string cmd =
          "python3 '" + script + "' '" + base + ".csv' '" + png + "' --title '" + title + "'";
      std::fflush(stdout);
      const int rc = std::system(cmd.c_str());
      if (rc == 0) {
        std::printf("picture: %s\n", png.c_str());
      } else {
        std::printf(
            "no PNG (plot_decompose.py exit status %d: python3 or matplotlib "
            "missing?); the CSV and SVG pictures above are written\n",
            rc);
      }
    }
  }
  return 0;
}
