#include "machdyn/elements/modes.hpp"

namespace machdyn {

const char* to_string(ContactMode m) {
  switch (m) {
    case ContactMode::stuck: return "stuck";
    case ContactMode::slip_pos: return "slip+";
    case ContactMode::slip_neg: return "slip-";
  }
  return "?";
}

const char* to_string(GapMode m) {
  switch (m) {
    case GapMode::open: return "open";
    case GapMode::closed_pos: return "closed+";
    case GapMode::closed_neg: return "closed-";
  }
  return "?";
}

}  // namespace machdyn
