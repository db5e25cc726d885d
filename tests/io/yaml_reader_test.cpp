// The YAML reader's limits: hostile files (alias bombs, self-references, deep nesting) end in a
// located InputError instead of exhausting memory or the stack, and a large table stays lean.
#include "machdyn/io/yaml_reader.hpp"

#include <string>
#include <fmt/format.h>
#include <gtest/gtest.h>

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// The first diagnostic of the InputError `text` raises, as "file:line:col: error: message".
std::string first_error(const std::string& text) {
  try {
    parse_yaml_string(text, "bad.yaml");
  } catch (const InputError& e) {
    return e.diagnostics().at(0).str();
  }
  return "accepted";
}

// Claim: a self-referential alias (`&x [*x]`, 20 bytes that crashed the old reader) is an error at
// the alias, in any field, including a gear law.
TEST(YamlReader, SelfReferentialAliasIsALocatedError) {
  const std::string e = first_error("description: &x [*x]\n");
  EXPECT_NE(e.find("bad.yaml:1:18: error:"), std::string::npos) << e;
  EXPECT_NE(e.find("self-reference"), std::string::npos) << e;
  EXPECT_NE(first_error("law: &l {a: [1, *l]}\n").find("self-reference"), std::string::npos);
}

// Claim: a "billion laughs" file (each anchor lists the previous one ten times: 10^9 values from
// 300 bytes) stops at the alias budget with a located error, before memory is exhausted.
TEST(YamlReader, AliasBombStopsAtTheBudget) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k <= 9; ++k) {
    text += fmt::format("a{0}: &a{0} [", k);
    for (int j = 0; j < 10; ++j) text += fmt::format("{}*a{}", j ? ", " : "", k - 1);
    text += "]\n";
  }
  const std::string e = first_error(text);
  EXPECT_NE(e.find("bad.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("aliases expand to more than"), std::string::npos) << e;
}

// Claim: ordinary aliases still expand to a copy of the anchored value.
TEST(YamlReader, AliasesExpandToCopies) {
  const SpecNode root = parse_yaml_string("a: &v {m: 2 kg}\nb: *v\n", "ok.yaml");
  ASSERT_NE(root.find("b"), nullptr);
  ASSERT_NE(root.find("b")->find("m"), nullptr);
  EXPECT_EQ(root.find("b")->find("m")->scalar, "2 kg");
}

// Claim: nesting deeper than kSpecMaxDepth (flow or block style, 100 000 deep) is a located error
// saying what was expected, not a stack overflow or "bad file"; kSpecMaxDepth levels still read.
TEST(YamlReader, DeepNestingIsALocatedErrorSayingWhatWasExpected) {
  std::string deep = "x: ";
  deep.append(100000, '[').append(100000, ']');
  const std::string e = first_error(deep);
  EXPECT_NE(e.find("bad.yaml:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("nested deeper than 64 levels; expected a value"), std::string::npos) << e;
  std::string block;
  for (std::size_t k = 0; k < 200; ++k) block.append(k, ' ').append("k:\n");
  EXPECT_NE(first_error(block).find("nested deeper than"), std::string::npos);
  const std::size_t ok = kSpecMaxDepth - 1;  // the root map plus ok - 1 lists
  std::string fits = "x: ";
  fits.append(ok - 1, '[').append(ok - 1, ']');
  EXPECT_NO_THROW(parse_yaml_string(fits, "ok.yaml"));
}

// Claim: duplicate keys and non-scalar keys are still reported, all at once, at their keys.
TEST(YamlReader, DuplicateAndComplexKeysAreReportedTogether) {
  try {
    parse_yaml_string("a: 1\nb: 2\na: 3\n[x]: 4\n", "dup.yaml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 2u);
    EXPECT_EQ(e.diagnostics()[0].str(), "dup.yaml:3:1: error: duplicate key 'a'");
    EXPECT_EQ(e.diagnostics()[1].str(), "dup.yaml:4:1: error: expected a plain name as a key");
  }
}

// Claim: values keep their line and column, and a value in a map its key's place too.
TEST(YamlReader, KeepsLineAndColumnOfValuesAndKeys) {
  const SpecNode root = parse_yaml_string("bodies:\n  I1: {inertia: 2 kg*m^2}\n", "loc.yaml");
  const SpecNode* v = root.find("bodies")->find("I1")->find("inertia");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->loc.str(), "loc.yaml:2:17");
  EXPECT_EQ(v->key_loc.str(), "loc.yaml:2:8");
}

// Claim: a spec node stays small (the 10^6-point table of the issue took 2.27 GB, 0.7-2 kB per value):
// the source name is shared, not copied into each node.
TEST(YamlReader, SpecNodesAreLean) {
  EXPECT_LE(sizeof(SpecNode), 144u);
  std::string name(200, 'p');
  name += ".yaml";
  const SpecNode root = parse_yaml_string("t: [[0, 1], [1, 2]]\n", name);
  const SpecNode& a = root.find("t")->items[0].items[0];
  const SpecNode& b = root.find("t")->items[1].items[1];
  EXPECT_EQ(a.loc.file.get(), b.loc.file.get());
}

// Claim: an empty file is a null value placed at its line 1, column 1 (so "expected a gear spec"
// or "expected a model" about it is located).
TEST(YamlReader, EmptyFileIsPlacedAtItsStart) {
  const SpecNode root = parse_yaml_string("", "empty.yaml");
  EXPECT_EQ(root.kind, SpecNode::Kind::Null);
  EXPECT_EQ(root.loc.str(), "empty.yaml:1:1");
}

}  // namespace
}  // namespace machdyn

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: `--set NAME.A.B=V` descends into nested maps: it sets one field of a nested map and keeps
// its siblings, creates a missing map on the way, and refuses to descend into a plain value.
TEST(ApplySet, DottedPathsReachNestedMaps) {
  SpecNode root = parse_yaml_string(R"(
crane: {release: {mass: 4 t, kind: rapid}}
brakes: {B: {body: w, holding: 10, thermal: {heat_capacity: 50}}}
simulation: {t_end: 1}
)", "set.yaml");
  apply_set(root, "crane.release.time=2.5 s");
  const SpecNode* rel = root.find("crane")->find("release");
  ASSERT_NE(rel, nullptr);
  ASSERT_NE(rel->find("time"), nullptr);
  EXPECT_EQ(rel->find("time")->scalar, "2.5 s");
  ASSERT_NE(rel->find("mass"), nullptr);  // the sibling stays
  EXPECT_EQ(rel->find("mass")->scalar, "4 t");
  apply_set(root, "B.thermal.conductance=2 W/K");  // an element's nested map
  EXPECT_EQ(root.find("brakes")->find("B")->find("thermal")->find("conductance")->scalar, "2 W/K");
  EXPECT_EQ(root.find("brakes")->find("B")->find("thermal")->find("heat_capacity")->scalar, "50");
  apply_set(root, "simulation.settings.x=1");  // a missing nested map is created
  EXPECT_EQ(root.find("simulation")->find("settings")->find("x")->scalar, "1");
  EXPECT_EQ(root.find("simulation")->find("t_end")->scalar, "1");
  try {
    apply_set(root, "B.holding.x=1");
    FAIL() << "descended into a plain value";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'holding' is not a map"), std::string::npos) << e.what();
  }
  EXPECT_THROW(apply_set(root, "crane..time=1"), InputError);
}

}  // namespace
}  // namespace machdyn
