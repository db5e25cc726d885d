#pragma once
/// @file
/// Writers for a synthesized non-circular gear pair: the Table 1 text and CSV, JSON, the drawings of
/// the paper's Fig. 1 (pitch curves with sector boundaries) and Fig. 2 (theoretical vs stepwise ratio)
/// as SVG, the tooth outlines as SVG, and a DXF (R12, LINE entities in layers) for CAD.
/// Units: angles in rad (and deg where the paper prints them), lengths in mm.

#include <string>

#include "machdyn/gears/gear_model.hpp"
#include "machdyn/gears/synthesis.hpp"
#include "machdyn/gears/tooth_profile.hpp"

namespace machdyn::io {

struct GearReport {
  const gears::GearModel& model;
  const gears::GearSynthesis& synthesis;
  const gears::SpeedUniformity& speed;
  const gears::ToothProfiles& teeth;
};

std::string gears_text(const GearReport& r);   ///< the table as the paper prints it + checks
std::string gears_json(const GearReport& r);   ///< {u, k, sectors:[{i, phi, dphi, rH, theta, dtheta, r}], ...}
std::string gears_csv(const GearReport& r);    ///< one row per sector, rad, deg, mm
std::string gears_pitch_svg(const GearReport& r);  ///< Fig. 1: both pitch curves, sector boundaries
std::string gears_ratio_svg(const GearReport& r);  ///< Fig. 2: i(φ) and the stepwise ratio
std::string gears_teeth_svg(const GearReport& r);  ///< tooth outlines of both gears in mesh position
std::string gears_dxf(const GearReport& r);        ///< pitch curves, sector arcs, teeth (mm)

}  // namespace machdyn::io
