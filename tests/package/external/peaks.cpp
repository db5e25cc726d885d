// Loads a model file, simulates it and prints each link's maximum load with 17 digits, one per
// line as "NAME MAX": the test compares them with the installed CLI's summary.json.
#include <cstdio>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const machdyn::Model m = machdyn::load_model(argv[1]);
  const machdyn::SimulationResult r = machdyn::simulate(m);
  for (std::size_t l = 0; l < m.links.size(); ++l) std::printf("%s %.17g\n", m.links[l].name.c_str(), r.links[l].max);
  return 0;
}
