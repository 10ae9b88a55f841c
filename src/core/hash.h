// Stable 64-bit identities and seeds: what study ids, store checks and the noise streams are built from. Neither is
// cryptographic; both are fixed functions, so an id or a seed is the same on every machine and compiler.
#pragma once

#include <cstdint>
#include <string_view>

namespace beamid::core {

// SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijection of 64-bit words with good avalanche.
std::uint64_t mix64(std::uint64_t x);
// FNV-1a 64-bit hash of bytes (a stable identity for canonical text; not cryptographic).
std::uint64_t fnv1a64(std::string_view text);
// Seed for a named sub-stream of a parent seed: mix64(parent ^ fnv1a64(name)).
std::uint64_t derive_seed(std::uint64_t parent, std::string_view name);

}  // namespace beamid::core
