/// \file
/// The impulse chapter's friction figures: Fig. 5.2 (damping against Newtonian friction along a
/// chain) and Coulomb friction on an incline, against time and against the incline's angle.
#pragma once

#include <string>

namespace boxsim {

/// fig5_2_damping_vs_friction.dat into `dir`.
void figFig5_2DampingVsFriction(const std::string& dir);
/// s7_friction_incline.dat into `dir`.
void figS7FrictionIncline(const std::string& dir);
/// s7_friction_incline_sweep.dat into `dir`.
void figS7FrictionInclineSweep(const std::string& dir);

}  // namespace boxsim
