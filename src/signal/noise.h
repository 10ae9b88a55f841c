// Portable pseudo-random numbers for synthetic data: the same seed gives the same noise with any C++ standard library.
//
// The engine is std::mt19937_64, whose output sequence the C++ standard fixes. Everything after it is ours, because
// the standard fixes neither std::uniform_real_distribution nor std::normal_distribution:
//   uniform  u = ((x >> 11) + 0.5) 2^-53, in the open interval (0, 1);
//   Gaussian by the Box-Muller transform on two uniforms: g1 = r cos(2 pi u2), g2 = r sin(2 pi u2), r = sqrt(-2 ln u1)
//            (both used, in that order).
// Seeds are mixed with SplitMix64 (core/hash.h) so that nearby seeds (1, 2, 3, ...) give unrelated streams.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hash.h"

namespace beamid::signal {

// `count` independent standard normal deviates from `seed`.
std::vector<double> gaussian_deviates(std::uint64_t seed, std::size_t count);

// Root mean square of a signal (0 for an empty one).
double rms(const std::vector<double>& signal);

// z_i = y_i + level * rms(y) * g_i: white Gaussian noise whose standard deviation is `level` times the clean signal's
// RMS (level 0 returns y unchanged).
std::vector<double> add_noise(const std::vector<double>& clean, double level, std::uint64_t seed);

}  // namespace beamid::signal
