#pragma once
/// @file
/// A duty (docs/duty.md): a file of operations — load cases of a model, each with its repetitions —
/// read with every problem located (InputError), run (each operation once, its link loads counted
/// over their located turning points, analysis/load_history.hpp), the counts merged over the duty
/// with the residue rule (merge_parts, analysis/rainflow.hpp), and per link the fatigue figures
/// (analysis/fatigue.hpp). `machdyn duty` and `machdyn.duty` are thin layers over run_duty.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "machdyn/analysis/fatigue.hpp"
#include "machdyn/analysis/rainflow.hpp"
#include "machdyn/common/diagnostics.hpp"

namespace machdyn {

struct DutyOperation {
  std::string name, load_case;  ///< load_case empty: the model as it is
  double repeat = 1.0;          ///< whole number ≥ 0
};

/// What a duty file says (defaults as documented in docs/duty.md).
struct DutySpec {
  std::vector<DutyOperation> operations;
  std::vector<std::string> links;  ///< empty: all
  std::vector<Location> link_locs;
  RainflowResidue residue = RainflowResidue::half_cycles;
  double gate = 1e-6;  ///< fraction of each operation's load range
  double m = 3.0;      ///< exponent of Δ_eq and s
  double n_ref = 2e6;  ///< EN 13001's reference number of cycles
  bool has_curve = false;
  SNCurve curve;
};

/// Reads a duty file; `cases` are the model's load case names (to check the operations'). Throws
/// InputError with every problem at its file:line:col.
DutySpec read_duty(const std::string& path, const std::vector<std::string>& cases);

/// One link's counts over the duty and its figures.
struct DutyLink {
  std::string link;
  std::vector<RainflowCycle> cycles;  ///< merged; counts multiplied by the repetitions
  StressHistory history;              ///< N_t, Δ̂, k, ν, s
  double equivalent_range = 0.0;      ///< Δ_eq for N_t cycles, exponent m
  double damage = 0.0;                ///< Miner, with the spec's S–N curve (0 without)
};

struct DutyResult {
  DutySpec spec;
  std::vector<DutyLink> links;
};

/// Reads the duty file and runs it on the model file (with `sets` overrides), every operation once
/// (twice: its extremes set the gate). InputError for bad input, SolverError for a failed run.
DutyResult run_duty(const std::string& model_path, const std::string& duty_path, const std::vector<std::string>& sets);

/// duty.json's content and the terminal table.
nlohmann::json duty_json(const DutyResult& r);
std::string duty_table(const DutyResult& r);
/// duty_cycles.csv: link,range,mean,count,from,to (17 digits).
std::string duty_cycles_csv(const DutyResult& r);
/// duty_range_mean.csv (range–mean matrix, `bins` × `bins`) or duty_from_to.csv (from–to matrix):
/// one row per non-empty cell, link,ROW_lo,ROW_hi,COL_lo,COL_hi,count, the bins of
/// analysis/rainflow.hpp (RainflowMatrix) over each link's own extent.
std::string duty_matrix_csv(const DutyResult& r, bool from_to, int bins = 32);

}  // namespace machdyn
