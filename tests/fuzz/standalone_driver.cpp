// Runs a fuzz target without libFuzzer: every file of the seed corpus, then deterministic
// random inputs and mutations of the seeds (ITERATIONS of them, 20000 unless a second argument
// says). A crash, sanitizer report or hang fails the test.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  std::vector<std::vector<std::uint8_t>> seeds;
  if (argc > 1 && std::filesystem::is_directory(argv[1])) {
    for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
      std::ifstream file(entry.path(), std::ios::binary);
      seeds.emplace_back(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    }
  }
  for (const auto& seed : seeds) LLVMFuzzerTestOneInput(seed.data(), seed.size());

  std::mt19937_64 rng(12345);
  const int iterations = argc > 2 ? std::atoi(argv[2]) : 20000;
  std::vector<std::uint8_t> input;
  for (int i = 0; i < iterations; ++i) {
    if (!seeds.empty() && (i & 1)) {
      input = seeds[rng() % seeds.size()];
      // Flip, truncate or extend: the mutations that break length and field checks.
      const int edits = 1 + int(rng() % 4);
      for (int e = 0; e < edits && !input.empty(); ++e) input[rng() % input.size()] ^= std::uint8_t(1u << (rng() % 8));
      if (rng() % 3 == 0) input.resize(rng() % (input.size() + 1));
      if (rng() % 5 == 0) input.resize(input.size() + rng() % 64, std::uint8_t(rng()));
    } else {
      input.resize(rng() % 512);
      for (auto& b : input) b = std::uint8_t(rng());
    }
    LLVMFuzzerTestOneInput(input.data(), input.size());
  }
  std::printf("fuzz: %zu seeds and %d generated inputs, no crash\n", seeds.size(), iterations);
  return 0;
}
