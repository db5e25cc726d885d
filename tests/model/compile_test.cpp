#include "machdyn/model/compile.hpp"

#include <gtest/gtest.h>

#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

const char* kGood = R"(name: two masses
bodies:
  A: {inertia: 2 kg*m^2}
  B: {type: translational, mass: 3 t, velocity: 2 m/s}
links:
  s: {type: spring-damper, between: [A, B], ratio: 10 rad/m, stiffness: 5 kN/m, damping: 2 N*s/m}
  g: {type: spring, between: [A, ground], stiffness: 1 kN*m/rad}
loads:
  M: {type: motor-kloss, body: A, breakdown_torque: 1 kN*m, breakdown_slip: 0.2, synchronous_speed: 1500 rpm}
  W: {type: table, body: B, points: [[0, 0], [1 s, 2 kN]]}
simulation: {t_end: 2 s, dt_out: 10 ms}
)";

// Claim: a valid file compiles with every value converted to SI and names resolved.
TEST(Compile, ConvertsUnitsAndResolvesNames) {
  const Model m = load_model(test::write_temp("good.yaml", kGood));
  ASSERT_EQ(m.dof(), 2);
  EXPECT_EQ(m.bodies[1].kind, BodyKind::translational);
  EXPECT_DOUBLE_EQ(m.bodies[1].inertia, 3000.0);
  EXPECT_DOUBLE_EQ(m.bodies[1].v0, 2.0);
  EXPECT_EQ(m.links[0].a, 0);
  EXPECT_EQ(m.links[0].b, 1);
  EXPECT_DOUBLE_EQ(m.links[0].ratio, 10.0);
  EXPECT_DOUBLE_EQ(m.links[0].c, 5000.0);
  EXPECT_EQ(m.links[1].b, kGround);
  EXPECT_DOUBLE_EQ(m.loads[0].omega0, 1500 * 2 * 3.14159265358979323846 / 60);
  EXPECT_DOUBLE_EQ(m.loads[1].signal.values()[1], 2000.0);
  EXPECT_DOUBLE_EQ(m.simulation.dt_out, 0.01);
}

// Claim: --set overrides a named element's field or a run setting, with the same validation.
TEST(Compile, SetOverridesFieldsWithValidation) {
  const auto path = test::write_temp("good2.yaml", kGood);
  const Model m = load_model(path, {"s.stiffness=3e4", "A.inertia=1.7 kg*m^2", "simulation.t_end=5"});
  EXPECT_DOUBLE_EQ(m.links[0].c, 3e4);
  EXPECT_DOUBLE_EQ(m.bodies[0].inertia, 1.7);
  EXPECT_DOUBLE_EQ(m.simulation.t_end, 5.0);
  try {
    load_model(path, {"A.inertia=3 N"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].where.file, "--set A.inertia");
    EXPECT_NE(e.diagnostics()[0].message.find("expected a moment of inertia"), std::string::npos);
  }
  EXPECT_THROW(load_model(path, {"nobody.inertia=3"}), InputError);
  EXPECT_THROW(load_model(path, {"no-equals-sign"}), InputError);
}

struct Broken {
  const char* what;
  const char* yaml;
  std::vector<std::string> expected;  // each "line:col: error: ...substring"
};

// The catalogue of broken files the issue names; every problem in a file must be reported.
const Broken kCatalogue[] = {
    {"unknown key", "bodies:\n  A: {inertia: 1, colour: red}\n", {"2:19: error: body 'A': unknown field 'colour'"}},
    {"missing field", "bodies:\n  A: {type: rotational}\n", {"2:6: error: body 'A': missing field 'inertia'"}},
    {"negative inertia", "bodies:\n  A: {inertia: -1 kg*m^2}\n", {"2:16: error: body 'A': field 'inertia' must be zero or positive"}},
    {"zero inertia", "bodies:\n  A: {inertia: 0}\n", {"2:16: error: body 'A': zero inertia; a massless body"}},
    {"unknown body in link",
     "bodies:\n  A: {inertia: 1}\nlinks:\n  c: {type: spring, between: [A, Z], stiffness: 1}\n",
     {"4:34: error: link 'c': unknown body 'Z'"}},
    {"wrong unit", "bodies:\n  A: {inertia: 1}\nlinks:\n  c: {type: spring, between: [A, ground], stiffness: 5 N}\n",
     {"4:54: error: link 'c': field 'stiffness': expected a torque"}},
    {"NaN", "bodies:\n  A: {inertia: .nan}\n", {"2:16: error: body 'A': field 'inertia': expected a finite number"}},
    {"no mass", "name: empty\nbodies: {}\n", {"2:9: error: the model has no body"}},
    {"no bodies section", "name: empty\n", {"error: the model has no body"}},
    {"a gear-synthesis spec", "law: walking\na: 60 mm\nb: 100 mm\n",
     {"1:1: error: this is a gear-synthesis spec ('law', no 'bodies'), not a model: run `machdyn gears`"}},
    {"not yaml", "bodies: [A, {\n", {"error: invalid YAML"}},
    {"unknown top-level key", "bodies:\n  A: {inertia: 1}\nbodys: {}\n", {"3:1: error: model: unknown field 'bodys'"}},
    {"self link", "bodies:\n  A: {inertia: 1}\nlinks:\n  c: {type: spring, between: [A, A], stiffness: 1}\n",
     {"error: link 'c': joins 'A' to itself"}},
    {"load on unknown body", "bodies:\n  A: {inertia: 1}\nloads:\n  M: {type: constant, body: Q, value: 1}\n",
     {"4:29: error: load 'M': unknown body 'Q'"}},
    {"bad integrator", "bodies:\n  A: {inertia: 1}\nsimulation: {integrator: euler}\n",
     {"error: simulation: field 'integrator' is 'euler'; expected one of: auto, dopri5, bdf"}},
    {"table times decrease", "bodies:\n  A: {inertia: 1}\nloads:\n  M: {type: table, body: A, points: [[1, 0], [0, 1]]}\n",
     {"error: load 'M': times must not decrease"}},
    {"several problems at once",
     "bodies:\n  A: {inertia: -1}\n  B: {mass: 2}\nlinks:\n  c: {type: spring, between: [A, X], stiffness: 1}\n",
     {"2:16: error: body 'A': field 'inertia' must be zero or positive", "3:6: error: body 'B': missing field 'inertia'",
      "3:7: error: body 'B': unknown field 'mass'", "5:34: error: link 'c': unknown body 'X'"}},
};

// Claim: a machine (position-dependent inertia) combines with a brake, a friction contact and a
// link with a gap to its output point: the model compiles as a hybrid one (no rejection any more).
TEST(Compile, MachineWithBrakeContactAndGapLinkCompiles) {
  const Model m = load_model(test::write_temp(
      "machine-brake.yaml",
      "bodies:\n  A: {type: inertia-expression, inertia: \"0.5 + 0.1*sin(q)^2\"}\n"
      "  C: {type: crank-slider, crank_radius: 40 mm, rod_length: 160 mm, crank_inertia: 0.08}\n"
      "  S: {type: translational, mass: 2 kg}\n"
      "links:\n  r: {type: spring, between: [C.piston, S], stiffness: 1e5 N/m, gap: 1 mm}\n"
      "contacts:\n  k: {between: [A, C], static: 5, kinetic: 4}\n"
      "brakes:\n  B: {body: A, holding: 10}\n"));
  EXPECT_TRUE(m.is_hybrid());
  ASSERT_EQ(m.dof(), 3);
  EXPECT_NE(m.bodies[0].machine, nullptr);
  EXPECT_TRUE(m.links[0].a_point);
  EXPECT_TRUE(m.links[0].has_gap);
  EXPECT_EQ(m.contacts.size(), 2u);
}

// Claim: each broken file gives InputError with file:line:col and what was expected — all problems.
TEST(Compile, CatalogueOfBrokenFilesReportsEveryProblemWithItsPlace) {
  int k = 0;
  for (const auto& b : kCatalogue) {
    const std::string path = test::write_temp("broken-" + std::to_string(k++) + ".yaml", b.yaml);
    try {
      load_model(path);
      ADD_FAILURE() << b.what << ": no error";
    } catch (const InputError& e) {
      std::string all = e.what();
      for (const auto& want : b.expected) EXPECT_NE(all.find(want), std::string::npos) << b.what << ":\n" << all;
      EXPECT_EQ(e.diagnostics().size(), b.expected.size()) << b.what << ":\n" << all;
      EXPECT_EQ(all.rfind(path, 0), 0u) << b.what << ": message must start with the file name:\n" << all;
    }
  }
}

// Claim: initial conditions default to rest with unstressed links: every position and velocity is
// 0, and the link load the run reports is 0 at t = 0 and stays 0 (no load acts, so nothing moves).
// The same file with A turned by 0.3 rad starts with the load c·(0.3/i − 0) = 0.1 N·m, so the
// column checked is the link load.
TEST(Compile, DefaultsToRestWithUnstressedLinks) {
  const std::string text = "bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\n"
                           "links:\n  c: {type: spring, between: [A, B], ratio: 3, stiffness: 1}\n"
                           "simulation: {t_end: 0.5}\n";
  const Model m = load_model(test::write_temp("rest.yaml", text));
  for (const auto& b : m.bodies) {
    EXPECT_EQ(b.q0, 0.0);
    EXPECT_EQ(b.v0, 0.0);
  }
  const SimulationResult r = simulate(m);
  const auto& load = r.columns[test::column(r, "c.load_N_m")];
  ASSERT_FALSE(load.empty());
  for (double F : load) EXPECT_EQ(F, 0.0);
  EXPECT_EQ(r.links[0].max, 0.0);
  EXPECT_EQ(r.links[0].min, 0.0);

  const Model turned = load_model(test::write_temp(
      "turned.yaml", "bodies:\n  A: {inertia: 1, position: 0.3}\n" + text.substr(text.find("  B:"))));
  const SimulationResult rt = simulate(turned);
  EXPECT_NEAR(rt.columns[test::column(rt, "c.load_N_m")][0], 0.1, 1e-14);
}

}  // namespace
}  // namespace machdyn
