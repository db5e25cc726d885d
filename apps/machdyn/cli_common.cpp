#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "commands.hpp"
#include "machdyn/common/diagnostics.hpp"

namespace machdyn::cli {

int guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.str() << '\n';
    return 2;
  } catch (const SolverError& e) {
    std::cerr << "machdyn: " << e.what() << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "machdyn: error: " << e.what() << '\n';
    return 1;
  }
}

void add_set_option(CLI::App& cmd, std::vector<std::string>& sets) {
  cmd.add_option("--set", sets,
                 "Override one field: NAME.FIELD=VALUE (e.g. c1.stiffness=3e4, "
                 "I1.inertia=\"1.7 kg*m^2\", simulation.t_end=2); repeatable")
      ->allow_extra_args(false);
}

void write_file_atomic(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  fs::path p(path);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  fs::path tmp = p;
  tmp += ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, p);
}

std::vector<std::string> write_figures(const std::filesystem::path& dir, const std::vector<plot::Figure>& figures) {
  std::vector<plot::Rendered> rendered;
  for (const auto& f : figures) rendered.push_back(plot::render(f));
  std::vector<std::string> names;
  for (std::size_t k = 0; k < figures.size(); ++k) {
    write_file_atomic((dir / (figures[k].id + ".svg")).string(), rendered[k].svg);
    write_file_atomic((dir / (figures[k].id + ".png")).string(), rendered[k].png);
    names.push_back(figures[k].id + ".svg");
    names.push_back(figures[k].id + ".png");
  }
  return names;
}

std::filesystem::path default_out_dir(const std::string& model_path) {
  return std::filesystem::path("out") / std::filesystem::path(model_path).stem();
}

}  // namespace machdyn::cli
