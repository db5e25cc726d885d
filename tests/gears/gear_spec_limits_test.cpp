// Gear spec files share the reader's and the expression parser's limits: runaway input is a located
// InputError with a short message, never a stack overflow.
#include <string>
#include <gtest/gtest.h>

#include "machdyn/gears/gear_model.hpp"
#include "machdyn/io/yaml_reader.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

std::string first_error(const std::string& text) {
  try {
    (void)gears::compile_gears(parse_yaml_string(text, "g.yaml"));
  } catch (const InputError& e) {
    return e.diagnostics().at(0).str();
  }
  return "accepted";
}

// Claim: a ratio expression nested 20 000 deep is an error at the field (bounded depth), and the
// message quotes only the start of the text.
TEST(GearSpecLimits, DeepRatioExpressionIsALocatedShortError) {
  std::string ratio(20000, '(');
  ratio += "phi";
  ratio.append(20000, ')');
  const std::string e = first_error("law: expression\nratio: \"" + ratio + "\"\nL: 90 mm\nz: 20\nzH: 40\n");
  EXPECT_NE(e.find("g.yaml:2:8: error: gears: field 'ratio'"), std::string::npos) << e.substr(0, 300);
  EXPECT_NE(e.find("nested deeper than 200"), std::string::npos) << e.substr(0, 300);
  EXPECT_LT(e.size(), 400u);
}

// Claim: a self-referential alias as the law (`law: &l [*l]`) is an error at the alias.
TEST(GearSpecLimits, SelfReferentialLawIsALocatedError) {
  const std::string e = first_error("law: &l [*l]\nL: 90 mm\n");
  EXPECT_NE(e.find("g.yaml:1:10: error:"), std::string::npos) << e;
  EXPECT_NE(e.find("self-reference"), std::string::npos) << e;
}

}  // namespace
}  // namespace machdyn
