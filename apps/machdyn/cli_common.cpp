#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "commands.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/output_file.hpp"

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
  machdyn::write_file_atomic(std::filesystem::path(path), std::string_view(content));
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

std::filesystem::path output_dir(const std::string& model_path, const std::string& out_option,
                                 const std::string& load_case) {
  const std::filesystem::path out = out_option.empty() ? default_out_dir(model_path) : std::filesystem::path(out_option);
  return load_case.empty() ? out : out / load_case;
}

}  // namespace machdyn::cli
