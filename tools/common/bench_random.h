// Seeded draws for the benchmark instances, on top of the core's counter-based hash
// (src/counter_rng.h): every draw is a pure function of (seed, stream, counter), so instance i of
// seed s is the same on any machine, on any number of threads, and however many other instances
// are made. Streams are instance numbers; counters are small integers or stable hashes of a
// variable's name (so adding a variable never shifts the others). Uniforms use integer arithmetic
// and exact conversions only; normals use Box-Muller (glibc's log/cos/sqrt).
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

#include "base/counter_rng.h"

namespace mcon::tools {

// FNV-1a, for turning variable names into counters.
constexpr std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001B3ull;
  }
  return h;
}

class BenchRng {
 public:
  BenchRng(std::uint64_t seed, std::uint64_t stream) : seed_(seed), stream_(stream) {}

  std::uint64_t bits(std::uint64_t counter) const { return counter_hash(seed_, stream_, counter); }

  // Uniform in [0, 1) with 53 random bits.
  double uniform(std::uint64_t counter) const { return counter_uniform(seed_, stream_, counter); }
  double uniform(std::uint64_t counter, double lo, double hi) const { return lo + (hi - lo) * uniform(counter); }
  double uniform(std::string_view name, double lo = 0.0, double hi = 1.0) const {
    return uniform(stable_hash(name), lo, hi);
  }

  // Standard normal (Box-Muller) from two uniforms derived from the counter.
  double normal(std::uint64_t counter) const {
    const double u1 = 1.0 - uniform(splitmix64(counter ^ 0x6A09E667F3BCC909ull));  // (0, 1]: finite log
    const double u2 = uniform(splitmix64(counter ^ 0xBB67AE8584CAA73Bull));
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

  // A random 64-bit key for ordering (shuffles sort on it).
  std::uint64_t key(std::uint64_t counter) const { return bits(splitmix64(counter ^ 0xA54FF53A5F1D36F1ull)); }

 private:
  std::uint64_t seed_;
  std::uint64_t stream_;
};

}  // namespace mcon::tools
