#include "machdyn/elements/speed_drive.hpp"

namespace machdyn {

const char* to_string(LimitMode m) {
  switch (m) {
    case LimitMode::linear: return "linear";
    case LimitMode::limited_pos: return "limited+";
    case LimitMode::limited_neg: return "limited-";
  }
  return "?";
}

}  // namespace machdyn
