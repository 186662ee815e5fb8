// The deferred technique's attribute encodings (DOOM: The Dark Ages, "Deferred Attribute
// Interpolation"): CPU mirror of renderer/techniques/deferred/include/deferred_attributes.glsl,
// bit for bit (tests/test_deferred.cpp runs both).
//
// Barycentric derivatives, RGBA16UI: ddx(b), ddx(c), ddy(b), ddy(c), each a binary16 of the
// derivative clamped to ]-2, 2[ (to the largest half below 2, 1.9990234375). A half whose
// magnitude is below 2 never sets bit 14 (the top exponent bit), so that bit carries a flag:
// channel 0 front facing, 1 the world normal's z sign, 2 the tangent's z sign, 3 the bitangent
// sign (handedness). A NaN derivative packs as 0 (the NaN guard of the passes that read it).
//
// Tangent frame, RGBA16F: world normal x, y and world tangent x, y; each z is rebuilt from the
// sign flag as sqrt(max(0, 1 - x^2 - y^2)). Precision: x, y carry 11 significant bits, so z is
// coarse where it is small (a normal 0.6 degrees off the xy plane comes back ~1.5 degrees off);
// that is the seed's format and its cost. The writer rounds x, y to binary16 itself (ties to
// even) before the store, since a device's float-to-half store may truncate: a y of 0.99999994
// truncated to 0.99951 rebuilds z as 0.031, a 1.8 degree tilt. The probable cause of an H100
// reading a sunlit floor 0.05 % too bright in deferred (not re-checked there after the change).
#pragma once
#include <cstdint>

namespace gib::codecs {

inline constexpr float kBaryDerivMax = 1.9990234375f;  // largest binary16 below 2
inline constexpr uint16_t kBaryDerivFlagBit = 0x4000u;

uint16_t pack_bary_deriv(float derivative, bool flag);
float unpack_bary_deriv(uint16_t packed);
bool bary_deriv_flag(uint16_t packed);

// z of a unit vector from its x, y and the sign flag (true: negative).
float unit_z_from_xy(float x, float y, bool negative);

}  // namespace gib::codecs
