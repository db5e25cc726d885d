// Names and load cases are checked like everything else in a model file: located errors, all at once.
#include <string>
#include <gtest/gtest.h>

#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

const std::string kBase = R"(bodies:
  I1: {inertia: 1}
  I2: {inertia: 2}
links:
  c1: {type: spring, between: [I1, I2], stiffness: 100}
loads:
  M: {type: constant, body: I1, value: 5}
)";

/// Every diagnostic of compiling `text`, one per line; "accepted" if it compiles.
std::string errors(const std::string& text) {
  try {
    compile_model(parse_yaml_string(text, "m.yaml"), "m.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

// Claim: a name is unique across all sections (`--set I2.FIELD` must find one element); the later
// use is reported at its key with the place of the first, e.g. a link named like a body and a
// contact named like a link (which used to have no line and column).
TEST(Names, UniqueAcrossSectionsWithBothPlaces) {
  const std::string e = errors(kBase + "  I2: {type: constant, body: I2, value: 1}\n"
                                       "contacts:\n  c1: {between: [I2, ground], static: 10, kinetic: 8}\n");
  EXPECT_NE(e.find("m.yaml:8:3: error: the name 'I2' (under 'loads') is already used under 'bodies' at m.yaml:3:3"),
            std::string::npos) << e;
  EXPECT_NE(e.find("m.yaml:10:3: error: the name 'c1' (under 'contacts') is already used under 'links' at m.yaml:5:3"),
            std::string::npos) << e;
}

// Claim: a name with '.' is refused at its key (`--set I3.piston.x` or a link end `I3.piston`
// could not reach it).
TEST(Names, NoDotInNames) {
  const std::string e = errors("bodies:\n  I3.piston: {inertia: 1}\n");
  EXPECT_NE(e.find("m.yaml:2:3: error: bodies name 'I3.piston' contains '.'"), std::string::npos) << e;
}

// Claim: a type that belongs in another section gets a hint naming that section, at the type.
TEST(Names, TypeOfAnotherSectionPointsThere) {
  std::string e = errors(kBase + "  T: {type: brake, body: I1, holding: 5}\n");
  EXPECT_NE(e.find("m.yaml:8:13: error: load 'T': type 'brake' is not a kind of loads; a brake goes under 'brakes:'"),
            std::string::npos) << e;
  e = errors("bodies:\n  I1: {inertia: 1}\nlinks:\n  k: {type: constant, between: [I1, ground]}\n");
  EXPECT_NE(e.find("a constant goes under 'loads:'"), std::string::npos) << e;
}

// Claim: every case of the file compiles whichever case runs: a case that overrides a field no
// element has, names an element that does not exist or removes one that does not exist is a
// located error for the base model too (simulate, modes and report all compile through here).
TEST(Cases, BrokenCasesAreLocatedErrorsOfTheBaseModel) {
  const std::string text = kBase + R"(cases:
  typo_field: {bodies: {I1: {velocty: 3}}}
  typo_element: {links: {c9: {stiffness: 5}}}
  typo_remove: {remove: [M2]}
  fine: {remove: [M], bodies: {I1: {velocity: 2}}}
)";
  const std::string e = errors(text);
  EXPECT_NE(e.find("m.yaml:9:30: error: case 'typo_field': body 'I1': unknown field 'velocty'"), std::string::npos) << e;
  EXPECT_NE(e.find("m.yaml:10:30: error: case 'typo_element': link 'c9': missing field 'type'"), std::string::npos) << e;
  EXPECT_NE(e.find("m.yaml:11:26: error: case 'typo_remove': cannot remove 'M2': no such element"), std::string::npos) << e;
  EXPECT_EQ(e.find("'fine'"), std::string::npos) << e;
  // Through the file reader and with the case applied, the same errors (the CLI's path).
  const std::string path = test::write_temp("cases.yaml", text);
  EXPECT_THROW(load_model(path), InputError);
  EXPECT_NO_THROW(load_model_case(path, {}, "fine"));
}

// Claim: link ends resolve through the hashed body index built by compile (the same answers as
// the linear search it replaces): in a chain of 5000 bodies each link joins its two neighbours.
// (Linear time is shown by bench/bench_read_scale.cpp, not by a timed test.)
TEST(Names, LargeModelsResolveNamesByIndex) {
  std::string text = "bodies:\n";
  const int n = 5000;
  for (int k = 0; k < n; ++k) text += "  b" + std::to_string(k) + ": {inertia: 1}\n";
  text += "links:\n";
  for (int k = 1; k < n; ++k)
    text += "  l" + std::to_string(k) + ": {type: spring, between: [b" + std::to_string(k - 1) + ", b" +
            std::to_string(k) + "], stiffness: 1}\n";
  const Model m = compile_model(parse_yaml_string(text, "chain.yaml"), "chain.yaml");
  EXPECT_EQ(m.body_index("b4999"), n - 1);
  for (int k = 1; k < n; ++k) {
    EXPECT_EQ(m.links[static_cast<size_t>(k - 1)].a, k - 1);
    EXPECT_EQ(m.links[static_cast<size_t>(k - 1)].b, k);
  }
  EXPECT_EQ(m.body_index("nope"), -2);
}

// Claim: the memory the output grid needs is checked at compile, before anything is reserved:
// 5 s at dt_out = 0.1 µs is 5·10^7 rows × 6 columns × 8 B = 2.4 GB > 2 GiB, a located error at
// dt_out (it used to pass the row limit and end in std::bad_alloc); half the rows (1.2 GB) compile.
TEST(Limits, OutputMemoryIsCheckedBeforeTheRun) {
  const std::string e = errors(kBase + "simulation:\n  t_end: 5 s\n  dt_out: 1e-7 s\n");
  EXPECT_NE(e.find("m.yaml:10:11: error: simulation: the output needs 5e+07 rows x 6 columns = 2.4 GB"),
            std::string::npos) << e;
  EXPECT_EQ(errors(kBase + "simulation:\n  t_end: 5 s\n  dt_out: 2e-7 s\n"), "accepted");
}

}  // namespace
}  // namespace machdyn
