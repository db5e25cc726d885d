// `machdyn gears SPEC [--json] [-o DIR] [--set FIELD=VALUE ...]`: non-circular gear synthesis
// (paper 003 and any ratio law). A thin layer: read spec → compile → synthesize → teeth → write.
#include <filesystem>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"
#include "machdyn/gears/gear_model.hpp"
#include "machdyn/gears/synthesis.hpp"
#include "machdyn/gears/tooth_profile.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/gears_output.hpp"
#include "machdyn/io/yaml_reader.hpp"

namespace machdyn::cli {

namespace {
struct GearsOptions {
  std::string spec;
  bool json = false;
  bool plot = false;
  std::string out_dir;
  std::vector<std::string> sets;
};
}  // namespace

void register_gears(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<GearsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "gears", "Non-circular gear pair: sector table (paper 003, Table 1), pitch curves, teeth, speed uniformity");
  cmd->add_option("spec", opt->spec, "Gear spec file (YAML), e.g. examples/walking-drive-gears.yaml")->required();
  cmd->add_flag("--json", opt->json, "Print JSON {u, sectors: [{i, phi, dphi, rH, theta, dtheta, r}], ...} "
                                     "(rad, mm) instead of the table");
  cmd->add_option("-o,--out", opt->out_dir,
                  "Write sectors.csv, pitch_curves.svg (Fig. 1), ratio.svg (Fig. 2), teeth.svg, gears.dxf, "
                  "gears.json into this folder");
  cmd->add_flag("--plot", opt->plot,
                "Draw Fig. 1 and Fig. 2 with gnuplot: pitch_curves.svg/.png and ratio.svg/.png (axes, units, "
                "legend), into -o DIR (default out/SPEC)");
  cmd->add_option("--set", opt->sets, "Override a field: FIELD=VALUE (e.g. L=\"150 mm\", profile.basis=continuous); "
                                      "repeatable")
      ->allow_extra_args(false);
  cmd->callback([opt, &exit_code] {
    exit_code = guarded([&] {
      SpecNode root = read_yaml_file(opt->spec);
      for (const auto& s : opt->sets) apply_set(root, s);
      const gears::GearModel model = gears::compile_gears(root);
      const gears::GearSynthesis syn = gears::synthesize(model);
      const gears::ToothProfiles teeth = gears::generate_profiles(model, syn);
      const gears::SpeedUniformity speed = gears::speed_uniformity(model, syn);
      const io::GearReport report{model, syn, speed, teeth};
      std::vector<std::string> figures;
      if (opt->plot) {
        // The gnuplot figures replace the drawings pitch_curves.svg and ratio.svg.
        if (opt->out_dir.empty()) opt->out_dir = default_out_dir(opt->spec).string();
        figures = write_figures(opt->out_dir, {gears_pitch_figure(report), gears_ratio_figure(report)});
      }
      if (!opt->out_dir.empty()) {
        namespace fs = std::filesystem;
        const fs::path d(opt->out_dir);
        write_file_atomic((d / "sectors.csv").string(), io::gears_csv(report));
        write_file_atomic((d / "gears.json").string(), io::gears_json(report));
        if (!opt->plot) {
          write_file_atomic((d / "pitch_curves.svg").string(), io::gears_pitch_svg(report));
          write_file_atomic((d / "ratio.svg").string(), io::gears_ratio_svg(report));
        }
        write_file_atomic((d / "teeth.svg").string(), io::gears_teeth_svg(report));
        write_file_atomic((d / "gears.dxf").string(), io::gears_dxf(report));
      }
      std::cout << (opt->json ? io::gears_json(report) : io::gears_text(report));
      if (!figures.empty() && !opt->json)
        std::cout << "figures: " << opt->out_dir << "/{" << fmt::format("{}", fmt::join(figures, ",")) << "}\n";
      if (!teeth.undercut.empty())
        std::cerr << "machdyn: warning: " << teeth.undercut.size() << " tooth flanks are undercut\n";
      return 0;
    });
  });
}

}  // namespace machdyn::cli
