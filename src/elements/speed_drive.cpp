#include "machdyn/elements/speed_drive.hpp"

namespace machdyn {

const char* to_string(LimitMode m) {
  switch (m) {
    case LimitMode::linear: return "linear";
    case LimitMode::limited_pos: return "limited+";
    case LimitMode::limited_neg: return "limited-";
    case LimitMode::on_limit_pos: return "on-limit+";
    case LimitMode::on_limit_neg: return "on-limit-";
  }
  return "?";
}

}  // namespace machdyn
