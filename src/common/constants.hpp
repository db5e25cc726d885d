#pragma once
// Numerical constants the library's files share (private to src/). One definition each: the test
// build compiles several library files as one translation unit (cmake/Unity.cmake), where file-local
// copies of one constant would collide.
#include <limits>
#include <numbers>

namespace machdyn {

inline constexpr double kPi = std::numbers::pi;
/// One degree in radians.
inline constexpr double kDeg = kPi / 180.0;
/// The quiet NaN that marks "not defined" (a factor never reached, a missing value).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace machdyn
