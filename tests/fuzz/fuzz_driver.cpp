// The fuzz targets without libFuzzer (any compiler): every file of the
// target's corpus, then N inputs mutated from them (byte flips, inserts,
// deletions, splices of two corpus files, runs of interesting bytes) by a
// seeded generator — not coverage-guided, a smoke that CI runs under
// ASan+UBSan; the long, guided runs use libFuzzer (RELIABILITY.md).
//
//   fuzz_driver TARGET [--mutations N] [--seed S] CORPUS (file or folder)...
//
// Exit 0 when every input returned; a crash or a sanitizer report ends it
// otherwise, and the input that did it stays in fuzz-<target>-last.bin (to
// be added to tests/fuzz/corpus/<target>/ once fixed).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_targets.h"

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string mutate(const std::vector<std::string>& corpus, std::mt19937_64& rng) {
  const auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  std::string s = corpus[pick(corpus.size())];
  const int edits = 1 + static_cast<int>(rng() % 8);
  static const char interesting[] = {'\0', '\n', '\r', ' ', ',',    '.',    '-', '+', 'e', 'E',
                                     '9',  '0',  '=',  '"', '[',    ']',    '{', '}', '#', ';',
                                     '(',  ')',  '$',  '*', '\xff', '\x80', 'G', 'X'};
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 6) {
      case 0:  // flip a bit
        if (!s.empty()) s[pick(s.size())] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:  // insert an interesting byte
        s.insert(s.begin() + static_cast<std::ptrdiff_t>(pick(s.size() + 1)),
                 interesting[pick(sizeof interesting)]);
        break;
      case 2: {  // delete a run
        if (s.empty()) break;
        const std::size_t at = pick(s.size());
        s.erase(at, 1 + pick(16));
        break;
      }
      case 3: {  // duplicate a run (long lines, repeated sections)
        if (s.empty()) break;
        const std::size_t at = pick(s.size()), n = 1 + pick(64);
        const std::string run = s.substr(at, n);
        for (int k = 0, times = 1 + static_cast<int>(pick(50)); k < times; ++k) s.insert(at, run);
        break;
      }
      case 4: {  // splice another corpus file in
        const std::string& o = corpus[pick(corpus.size())];
        if (o.empty()) break;
        const std::size_t from = pick(o.size());
        s.insert(pick(s.size() + 1), o.substr(from, 1 + pick(256)));
        break;
      }
      default: {  // overwrite a digit run with an extreme number
        static const char* numbers[] = {"1e308", "-1e308", "nan",       "inf", "99999999999999999999",
                                        "-0",    "1e-320", "0x7fffffff"};
        const std::string n = numbers[pick(std::size(numbers))];
        s.insert(pick(s.size() + 1), n);
        break;
      }
    }
  }
  if (s.size() > (1u << 20)) s.resize(1u << 20);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: fuzz_driver TARGET [--mutations N] [--seed S] CORPUS...\n");
    return 2;
  }
  const lcnc::fuzz::Target* t = lcnc::fuzz::find_target(argv[1]);
  if (t == nullptr) {
    std::fprintf(stderr, "fuzz_driver: no target '%s'\n", argv[1]);
    return 2;
  }
  long mutations = 10000;
  std::uint64_t seed = 1;
  std::vector<std::string> corpus;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--mutations" || a == "--seed") && i + 1 < argc) {
      if (a == "--mutations") {
        mutations = std::atol(argv[++i]);
      } else {
        seed = std::strtoull(argv[++i], nullptr, 10);
      }
      continue;
    }
    const std::filesystem::path p(a);
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::directory_iterator(p))
        if (e.is_regular_file()) corpus.push_back(slurp(e.path()));
    } else if (std::filesystem::is_regular_file(p)) {
      corpus.push_back(slurp(p));
    } else {
      std::fprintf(stderr, "fuzz_driver: no corpus '%s'\n", a.c_str());
      return 2;
    }
  }
  if (corpus.empty()) corpus.emplace_back();
  std::mt19937_64 rng(seed);
  const std::string keep = std::string("fuzz-") + t->name + "-last.bin";
  const auto run = [&](const std::string& input) {
    std::ofstream(keep, std::ios::binary | std::ios::trunc) << input;  // left behind by a crash
    t->run(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  };
  for (const std::string& c : corpus) run(c);
  for (long n = 0; n < mutations; ++n) run(mutate(corpus, rng));
  std::remove(keep.c_str());
  std::printf("fuzz %s: %zu corpus inputs and %ld mutations, every one returned\n", t->name, corpus.size(),
              mutations);
  return 0;
}
