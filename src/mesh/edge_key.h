// 64-bit keys of mesh edges for hash maps: directed (a -> b) and undirected ({a, b}).
#pragma once

#include <cstdint>
#include <utility>

namespace mcon {

inline std::uint64_t directed_edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return directed_edge_key(a, b);
}

}  // namespace mcon
