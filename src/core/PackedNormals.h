#pragma once
// Every sample's unit normal (Terrain::sample_normal), packed into 32 bits
// once per terrain, so that lighting the samples for a new sun direction is
// a dot product per sample, with no square root or division (SunLight.h).
//
// Packing: x and z as 11-bit two's complement, y (>= 0 on a height field) as
// 10-bit unsigned, all in steps of 1/kScale:
//     bits 0..10 x, bits 11..20 y, bits 21..31 z.
// Rounding each component to the nearest step moves N . L by at most
// (|Lx| + |Ly| + |Lz|) / (2 kScale) <= 0.00085 for a unit L: under a quarter
// of a color level at full sun.
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace overflight {

struct PackedNormals {
    static constexpr float kScale = 1023.0f;
    std::vector<std::uint32_t> packed; // row-major, one per sample

    // Packs a unit normal with y >= 0.
    static std::uint32_t pack(const glm::vec3& n);
    // The packed components times kScale.
    static float x_of(std::uint32_t p) { return float(std::int32_t(p << 21) >> 21); }
    static float y_of(std::uint32_t p) { return float((p >> 11) & 0x3ffu); }
    static float z_of(std::uint32_t p) { return float(std::int32_t(p) >> 21); }
    static glm::vec3 unpack(std::uint32_t p) { return glm::vec3(x_of(p), y_of(p), z_of(p)) / kScale; }
};

// Terrain::sample_normal of every sample of `terrain`, packed. Parallel over rows.
PackedNormals pack_normals(const Terrain& terrain);

} // namespace overflight
