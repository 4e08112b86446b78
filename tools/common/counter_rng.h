// Counter-based random numbers for the benchmark instances: every draw is a pure function of
// (seed, stream, counter), so instance i of seed s is the same on any machine, on any number of
// threads, and however many other instances are made. Streams are instance numbers; counters are
// small integers or stable hashes of a variable's name (so adding a variable never shifts others).
// Only integer arithmetic and exactly specified conversions are used for uniforms; normals use
// Box-Muller (std::log / std::cos / std::sqrt of glibc, which are deterministic per platform).
#pragma once

#include <cmath>
#include <cstdint>
#include <string_view>

namespace mcon::tools {

// SplitMix64's finalizer: a bijective 64-bit mixer with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// FNV-1a, for turning variable names into counters.
constexpr std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001B3ull;
  }
  return h;
}

class CounterRng {
 public:
  constexpr CounterRng(std::uint64_t seed, std::uint64_t stream)
      : key_(mix64(mix64(seed ^ 0x6A09E667F3BCC909ull) ^ mix64(stream ^ 0xBB67AE8584CAA73Bull))) {}

  constexpr std::uint64_t bits(std::uint64_t counter) const { return mix64(key_ ^ mix64(counter)); }

  // Uniform in [0, 1) with 53 random bits.
  constexpr double uniform(std::uint64_t counter) const {
    return static_cast<double>(bits(counter) >> 11) * (1.0 / 9007199254740992.0);
  }
  constexpr double uniform(std::uint64_t counter, double lo, double hi) const {
    return lo + (hi - lo) * uniform(counter);
  }
  double uniform(std::string_view name, double lo = 0.0, double hi = 1.0) const {
    return uniform(stable_hash(name), lo, hi);
  }

  // Standard normal (Box-Muller) from two uniforms derived from the counter.
  double normal(std::uint64_t counter) const {
    const double u1 = 1.0 - uniform(mix64(counter) * 2 + 1);  // (0, 1]: log is finite
    const double u2 = uniform(mix64(counter) * 2 + 2);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

  // A random 64-bit key for ordering (e.g. shuffles by sorting on it).
  constexpr std::uint64_t key(std::uint64_t counter) const { return bits(counter ^ 0xA54FF53A5F1D36F1ull); }

 private:
  std::uint64_t key_;
};

}  // namespace mcon::tools
