// machdyn_campaign: the random-model campaign of issue 27 — random small models run by the engine on
// dopri5 and bdf and compared with the brute-force reference simulator (tests/reference).
//   machdyn_campaign [--models N] [--seed S] [--families a,b,...] [--out DIR] [--no-shrink] [--verbose]
//                    [--shard I/N]   (only the models i with i % N == I)
//   machdyn_campaign [--seed S] --show FAMILY:INDEX   (one model: its file, both event lists, the outcome)
//   machdyn_campaign [--seed S] --converge FAMILY:INDEX   (a state mismatch with both tolerances tightened)
// Exit 0 when every run agrees, 1 when some fail (each written shrunk to DIR), 2 on bad arguments.
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"

int main(int argc, char** argv) {
  using namespace machdyn::reference;
  CampaignOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "machdyn_campaign: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (a == "--models") o.models = std::stol(value());
      else if (a == "--seed") o.seed = std::stoull(value());
      else if (a == "--out") o.out_dir = value();
      else if (a == "--no-shrink") o.shrink = false;
      else if (a == "--shard") {
        const std::string v = value();
        const size_t c = v.find('/');
        if (c == std::string::npos) throw std::invalid_argument(v);
        o.shard = std::stol(v.substr(0, c)), o.shards = std::stol(v.substr(c + 1));
        if (o.shards < 1 || o.shard < 0 || o.shard >= o.shards) throw std::invalid_argument(v);
      }
      else if (a == "--show") {
        const std::string v = value();
        const size_t c = v.find(':');
        if (c == std::string::npos) throw std::invalid_argument(v);
        show(v.substr(0, c), o.seed, std::stoull(v.substr(c + 1)));
        return 0;
      }
      else if (a == "--converge") {
        const std::string v = value();
        const size_t c = v.find(':');
        if (c == std::string::npos) throw std::invalid_argument(v);
        converge(v.substr(0, c), o.seed, std::stoull(v.substr(c + 1)));
        return 0;
      }
      else if (a == "--verbose") o.verbose = true;
      else if (a == "--families") {
        const std::string v = value();
        size_t p = 0;
        while (p <= v.size()) {
          const size_t q = v.find(',', p);
          const std::string f = v.substr(p, q == std::string::npos ? std::string::npos : q - p);
          if (!f.empty() && f != "all") {
            bool known = false;
            for (const auto& k : all_families()) known = known || k == f;
            if (!known) {
              std::fprintf(stderr, "machdyn_campaign: unknown family '%s' (known:", f.c_str());
              for (const auto& k : all_families()) std::fprintf(stderr, " %s", k.c_str());
              std::fprintf(stderr, ")\n");
              return 2;
            }
            o.families.push_back(f);
          }
          if (q == std::string::npos) break;
          p = q + 1;
        }
      } else {
        std::fprintf(stderr, "machdyn_campaign: unknown argument '%s'\n", a.c_str());
        return 2;
      }
    } catch (const std::exception&) {
      std::fprintf(stderr, "machdyn_campaign: bad value for %s\n", a.c_str());
      return 2;
    }
  }
  if (o.models < 0) {
    std::fprintf(stderr, "machdyn_campaign: --models must be >= 0\n");
    return 2;
  }
  return run_campaign(o) == 0 ? 0 : 1;
}
