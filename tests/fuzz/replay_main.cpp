// Replays fuzz inputs through a target's LLVMFuzzerTestOneInput without libFuzzer, so the normal
// (g++) build and the ASan build keep every past finding fixed: `fuzz_replay_T DIR_OR_FILE...`.
// `--random N` then runs N inputs of seeded random bytes (the same every run): a fuzz-style
// campaign where libFuzzer cannot go (the browser build, in Node).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

std::vector<std::filesystem::path> inputs(int argc, char** argv, size_t& random) {
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--random" && i + 1 < argc) {
      char* end = nullptr;
      random = std::strtoul(argv[++i], &end, 10);
      if (*end) std::fprintf(stderr, "fuzz replay: --random wants a count, not '%s'\n", argv[i]), std::exit(2);
      continue;
    }
    std::filesystem::path p = argv[i];
    if (!std::filesystem::is_directory(p)) {
      files.push_back(p);
      continue;
    }
    for (const auto& e : std::filesystem::directory_iterator(p))
      if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  size_t random = 0;
  std::vector<std::filesystem::path> files = inputs(argc, argv, random);
  if (files.empty() && !random) {
    std::fprintf(stderr, "fuzz replay: no inputs in the given paths\n");
    return 1;
  }
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "fuzz replay: cannot read %s\n", f.c_str());
      return 1;
    }
    std::ostringstream bytes;
    bytes << in.rdbuf();
    std::string data = bytes.str();
    std::fprintf(stderr, "replaying %s (%zu bytes)\n", f.c_str(), data.size());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(data.data()), data.size());
  }
  std::mt19937_64 gen(20261207);
  for (size_t k = 0; k < random; ++k) {
    std::string data(16 + gen() % 2048, '\0');
    for (char& c : data) c = static_cast<char>(gen());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(data.data()), data.size());
  }
  std::printf("fuzz replay: %zu inputs and %zu random ones, no finding\n", files.size(), random);
  return 0;
}
