#pragma once
/// @file
/// The discrete states (modes) of the switching elements. Between two events every element is in
/// one definite mode and its law is smooth there (elements/link.hpp, elements/contact.hpp).

namespace machdyn {

/// A friction contact or brake: stuck (sliding velocity u ≡ 0) or sliding in a definite direction.
enum class ContactMode : int { slip_neg = -1, stuck = 0, slip_pos = 1 };
/// A link with a gap: open (no load) or closed on its positive or negative flank.
enum class GapMode : int { closed_neg = -1, open = 0, closed_pos = 1 };

const char* to_string(ContactMode m);
const char* to_string(GapMode m);

}  // namespace machdyn
