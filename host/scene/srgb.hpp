#pragma once
// The sRGB transfer curve (IEC 61966-2-1, piecewise) between linear light and encoded values,
// and the 8-bit encoding `.png` files hold. The curve is evaluated in double precision; the
// 8-bit paths use tables built once from it that give exactly the curve's results (a render's
// PNG was a tenth of a one-shot run's CPU in `pow`).

#include <cstdint>

namespace acetate {

// Encoded [0, 1] to linear. Values an 8-bit file decodes to (k * (1/255), as OpenImageIO
// converts) come from a table of the curve's own results; any other value is computed.
float srgb_to_linear(float encoded);
// Linear to encoded, computed.
float linear_to_srgb(float linear);
// A straight (not premultiplied) linear value in [0, 1] to its 8-bit code: exactly
// lround(linear_to_srgb(linear) * 255), from a table of where each code starts.
uint8_t linear_to_srgb8(float linear);

}  // namespace acetate
