/// \file
/// Averages of unit quaternions and the angle between two orientations: the orientation half
/// of the box filter (\thesis{§5.5}) and of the envelope filter's test.
///
/// q and −q are the same orientation, so a plain mean of quaternions depends on which sign each
/// sample happens to carry: two nearly equal orientations of opposite sign average to nearly
/// zero. Both averages here first put every sample in the hemisphere of a reference quaternion
/// (the window's centre), which makes the result independent of the signs of the input.
#pragma once

#include <cstddef>
#include <string>

#include "boxsim/core/enum_names.hpp"
#include "boxsim/core/math.hpp"

namespace boxsim {

/// How a window of orientations is averaged.
enum class OrientationAverage {
  /// Every quaternion sign-aligned with the reference (q·ref ≥ 0), the four components averaged,
  /// the result normalised. For orientations within a few degrees of each other (a window of
  /// chatter) it agrees with the Markley average to second order in the spread.
  SignAlignedMean,
  /// The unit eigenvector of M = Σ qᵢ qᵢᵀ (4×4) with the largest eigenvalue: the orientation
  /// that minimises the summed squared chordal distance to the samples (F. L. Markley,
  /// Y. Cheng, J. L. Crassidis, Y. Oshman, "Averaging Quaternions", J. Guidance, Control, and
  /// Dynamics 30(4), 2007, eq. 13), signed to agree with the reference. Sign-independent by
  /// construction; costs a 4×4 symmetric eigenproblem per window.
  Markley,
};

/// The name of an average as headers and the command line spell it: "sign_aligned_mean",
/// "markley".
std::string orientationAverageName(OrientationAverage average);

/// The names of the averages.
inline constexpr EnumNames<OrientationAverage, 2> kOrientationAverageNames{{
    {OrientationAverage::SignAlignedMean, "sign_aligned_mean"},
    {OrientationAverage::Markley, "markley"},
}};

/// Parses orientationAverageName()'s output; throws std::invalid_argument naming the unknown
/// text and the known names.
OrientationAverage parseOrientationAverage(const std::string& name);

/// The average of the unit quaternions q[0], ..., q[n-1] by `method`, returned as a unit
/// quaternion in the hemisphere of `reference` (w·w' + x·x' + y·y' + z·z' ≥ 0). A single
/// sample (n = 1) is returned as it is, negated if it lies in the other hemisphere.
/// \param q          n unit quaternions (any signs)
/// \param n          the number of samples, ≥ 1
/// \param reference  a unit quaternion: the sign convention (the window's centre sample)
/// \throws std::invalid_argument when n is 0.
Quat averageOrientations(const Quat* q, std::size_t n, const Quat& reference,
                         OrientationAverage method);

/// The angle of the rotation that takes orientation a to orientation b, rad, in [0, π]; the
/// same for q and −q. Computed as 2 atan2(|vec(a⁻¹b)|, |w(a⁻¹b)|), accurate for small angles,
/// where 2 acos(|a·b|) loses half its digits.
double rotationAngle(const Quat& a, const Quat& b);

/// The rotation vector (axis × angle, rad, world frame, angle in [0, π]) of the rotation
/// b a⁻¹ that takes orientation a to orientation b.
Vec3 rotationVector(const Quat& a, const Quat& b);

}  // namespace boxsim
