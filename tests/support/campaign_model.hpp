#pragma once
// A campaign model against the reference simulator, as the campaign-defect tests check it.
#include <cstdint>
#include <string>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"
#include "support/models.hpp"

namespace machdyn::test {

/// Model `index` of `family` at `seed` (tests/reference/generator.hpp), run by the engine on ic with
/// the audit on and compared with the reference simulator (tests/reference/campaign.hpp: events and
/// states within the stated tolerances); the reference's own result into *out when given.
inline reference::Outcome against_reference(const std::string& family, std::uint64_t seed, std::uint64_t index,
                                            IntegratorChoice ic, reference::RefResult* out = nullptr) {
  const reference::RefModel m = reference::random_model(family, seed, index);
  const reference::RefResult rr = reference::simulate_reference(m);
  if (out) *out = rr;
  return reference::compare(m, integrator_word(ic), rr);
}

}  // namespace machdyn::test
