// Machine axes and poses. Units at every interface: mm for X Y Z, degrees for
// A B C (docs/design.md §4). A Pose holds all six; axes the machine lacks stay 0.
#pragma once

#include <array>
#include <cstdint>
#include <numbers>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace lcnc {

inline constexpr int kAxisCount = 6;

enum class Axis : std::uint8_t { X = 0, Y, Z, A, B, C };

inline constexpr std::array<Axis, kAxisCount> kAllAxes = {Axis::X, Axis::Y, Axis::Z,
                                                          Axis::A, Axis::B, Axis::C};
inline constexpr std::array<char, kAxisCount> kAxisLetters = {'X', 'Y', 'Z', 'A', 'B', 'C'};

[[nodiscard]] constexpr int index(Axis a) noexcept { return static_cast<int>(a); }
[[nodiscard]] constexpr char letter(Axis a) noexcept { return kAxisLetters[index(a)]; }
[[nodiscard]] constexpr bool is_rotary(Axis a) noexcept { return index(a) >= 3; }

// Radians per degree: the rotary axes are in degrees, the trigonometry in radians.
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

using Pose = Eigen::Matrix<double, kAxisCount, 1>;  // mm, mm, mm, deg, deg, deg
using Vec3 = Eigen::Vector3d;

[[nodiscard]] inline Vec3 linear_part(const Pose& p) { return p.head<3>(); }

}  // namespace lcnc
