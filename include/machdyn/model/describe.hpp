#pragma once
/// @file
/// Every element of a compiled model in words, as the file wrote it, with units: a rope with its EA,
/// free length, falls and drum; a buffer with its characteristic; a brake with its application and
/// thermal model; an end stop with its position and restitution; a gearbox, ideal or lossy, with its
/// ratio and efficiencies. The model report (io/report.hpp) and Python show these texts.
/// Each kind's text is written once, next to that kind's compile code (the place issue 29's element
/// interface will take them from): ropes in model/compile_rope.cpp, buffers in compile_crane.cpp,
/// gaps, contacts, brakes, clutches, freewheels and stops in compile_hybrid.cpp, lossy gears in
/// compile_lossy.cpp, ideal gears in compile_rigid.cpp.

#include <string>
#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// An element's kind ("rope", "buffer", "brake", "end stop", ...) and its parameters in words.
struct ElementText {
  std::string name;
  std::string type;
  std::string definition;
};

/// A link: spring, damper, backlash, rope or buffer.
ElementText describe_link(const Model& m, const Link& l);
/// A friction contact, brake, clutch, freewheel or end stop (not a gear joint).
ElementText describe_contact(const Model& m, const FrictionContact& c);
/// The gearboxes: every ideal gear compile merged (its ratio where compile kept it) and every
/// lossy gear (ratio, efficiencies η_mf1/η_mf2, bearing friction, self-locking), in the file's order
/// of each kind.
std::vector<ElementText> describe_gears(const Model& m);

namespace detail {
// Each kind's text, defined beside its compile code (see the file comment).
std::string describe_rope(const Model& m, const Link& l);          // compile_rope.cpp
std::string describe_buffer(const Model& m, const Link& l);        // compile_crane.cpp
std::string describe_gap(const Model& m, const Link& l);           // compile_hybrid.cpp
ElementText describe_friction_element(const Model& m, const FrictionContact& c);  // compile_hybrid.cpp
ElementText describe_lossy_gear(const Model& m, const LossyGear& g);              // compile_lossy.cpp
std::vector<ElementText> describe_ideal_gears(const Model& m);                    // compile_rigid.cpp
/// A number for these texts: 6 significant digits.
std::string describe_number(double v);
}  // namespace detail

}  // namespace machdyn
