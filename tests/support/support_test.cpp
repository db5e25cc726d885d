// Implementation of the test helpers (the file name puts it into the test executable).
#include "support/support.hpp"

#include "machdyn/io/plot.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/common/diagnostics.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

namespace machdyn::test {

std::filesystem::path temp_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("machdyn-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    static struct Cleanup {
      std::filesystem::path p;
      ~Cleanup() {
        std::error_code ec;
        std::filesystem::remove_all(p, ec);
      }
    } cleanup{d};
    return d;
  }();
  return dir;
}

std::string write_temp(const std::string& name, const std::string& text) {
  auto p = temp_dir() / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p.string();
}

CliResult run_cli(const std::string& args, const std::filesystem::path& cwd) {
  static int counter = 0;
  const auto base = temp_dir() / ("cli-" + std::to_string(++counter));
  const std::string cmd = "cd '" + cwd.string() + "' && '" + std::string(MACHDYN_CLI) + "' " + args + " >'" +
                          base.string() + ".out' 2>'" + base.string() + ".err' </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(base.string() + ".out");
  r.err = slurp(base.string() + ".err");
  return r;
}

std::string example(const std::string& name) { return std::string(MACHDYN_SOURCE_DIR) + "/examples/" + name; }

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

bool have_gnuplot() {
  try {
    plot::find_gnuplot();  // $MACHDYN_GNUPLOT or gnuplot on PATH, as the library looks for it
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

const char* const kCrankSliderBody = R"Y(
  crank:
    type: crank-slider
    crank_radius: 40 mm
    rod_length: 160 mm
    rod_mass: 1.2 kg
    rod_com: 80 mm
    rod_inertia: 0.00256 kg*m^2
    piston_mass: 1.6 kg
    crank_inertia: 0.08 kg*m^2
)Y";

Model model_text(const std::string& yaml, const std::string& file) {
  return compile_model(parse_yaml_string(yaml, file), file);
}

std::string compile_errors(const std::string& yaml, const std::string& file) {
  try {
    model_text(yaml, file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::size_t column(const SimulationResult& r, const std::string& name) {
  for (std::size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c] == name) return c;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

const std::vector<double>& series(const SimulationResult& r, const std::string& name) {
  static const std::vector<double> none;
  for (std::size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c] == name) return r.columns[c];
  ADD_FAILURE() << "no column " << name;
  return none;
}

double at(const SimulationResult& r, const std::string& name, double t, double tol) {
  const auto& ts = series(r, "t_s");
  const auto& v = series(r, name);
  for (std::size_t i = 0; i < ts.size() && i < v.size(); ++i)
    if (std::abs(ts[i] - t) <= tol) return v[i];
  ADD_FAILURE() << "no output row of " << name << " at t = " << t;
  return std::nan("");
}

std::string sci(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2e", x);
  return b;
}

double first_positive(const std::function<double(double)>& f, double a, double b) {
  const double h = 1e-4;
  for (double x0 = a; x0 < b; x0 += h) {
    const double x1 = std::min(b, x0 + h);
    if (f(x1) > 0) {
      double lo = x0, hi = x1;
      while (hi - lo > 1e-15) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > 0 ? hi : lo) = mid;
      }
      return hi;
    }
  }
  return b;
}

}  // namespace machdyn::test
