#pragma once
// The models file's friendly units and the SI the structs hold. The loader and
// the writer share these exact functions, so the writer can pick the decimal
// that the loader turns back into the very same double.

#include <numbers>

namespace p3at::verifier::models_detail {

inline double degrees_to_radians(double deg) { return deg * (std::numbers::pi / 180.0); }
inline double radians_to_degrees(double rad) { return rad * (180.0 / std::numbers::pi); }
inline double ms_to_s(double ms) { return ms / 1000.0; }
inline double s_to_ms(double s) { return s * 1000.0; }
/// A standard deviation per sqrt(unit) is held as the variance per unit.
inline double sd_to_var(double sd) { return sd * sd; }
/// A delay's standard deviation in ms, held as a variance in s^2.
inline double sd_ms_to_var_s(double sd_ms) { return sd_to_var(ms_to_s(sd_ms)); }

}  // namespace p3at::verifier::models_detail
