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
  double repeat = 1.0;          ///< whole number ≥ 0 (from per_hour × design life when that is given)
  double per_hour = -1.0;       ///< operations per hour of design life; < 0: `repeat` was given
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
  double design_life_h = 0.0;  ///< design life in hours (0: not given); with per_hour counts
  /// Rated loads P_max of k_m per link (name, value in the load's unit); a link not listed takes the
  /// largest |P| of the duty.
  std::vector<std::pair<std::string, double>> rated;
  std::vector<Location> rated_locs;
};

/// Reads a duty file; `cases` are the model's load case names (to check the operations'). Throws
/// InputError with every problem at its file:line:col.
DutySpec read_duty(const std::string& path, const std::vector<std::string>& cases);

/// One link's counts over the duty and its figures.
struct DutyLink {
  std::string link;
  std::string unit;                   ///< the load's SI unit, "N" or "N*m"
  std::vector<RainflowCycle> cycles;  ///< merged; counts multiplied by the repetitions
  StressHistory history;              ///< N_t, Δ̂, k, ν, s
  double equivalent_range = 0.0;      ///< Δ_eq for N_t cycles, exponent m
  double damage = 0.0;                ///< Miner, with the spec's S–N curve (0 without)
  // ISO 4301-1 / FEM 1.001 (analysis/duty_classes.hpp), over the running time of the whole duty:
  double k_m = 0.0;        ///< Σ n_i ∫|P|³dt / (P_max³ Σ n_i T_i)
  double p_max = 0.0;      ///< the rated load given, else the largest |P| of the duty
  bool rated = false;      ///< p_max is the rated load of the duty file
  int spectrum_class = 0;  ///< L1…L4
  int group = 0;           ///< M1…M8 (with the duty's class of utilization)
  int stress_class = 0;    ///< EN 13001's S0…S9 of s (10: above S9), analysis/duty_classes.hpp
};

struct DutyResult {
  DutySpec spec;
  std::vector<DutyLink> links;
  std::vector<double> op_seconds;  ///< each operation's running time T_i (its counted window), s
  double running_hours = 0.0;      ///< Σ n_i T_i, h: the total running time of the duty
  int utilization_class = 0;       ///< T0…T9 of running_hours
};

/// The processes a duty's operations are spread over (R ranks; rank 0 merges): the messages, not
/// their carrier — MPI's is sweep/mpi.hpp's `mpi_duty_ranks`, the layer above.
class DutyRanks {
 public:
  virtual ~DutyRanks() = default;
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  [[nodiscard]] virtual int on_this_node() const = 0;       ///< ranks sharing this node's cores
  virtual void send_to_root(const std::string& bytes) = 0;  ///< a rank ≠ 0: its operations' results
  virtual std::string receive_from(int rank) = 0;           ///< rank 0: rank `rank`'s results
};

/// Reads the duty file and runs it on the model file (with `sets` overrides), every operation once,
/// on `jobs` threads (0: all cores; the result is the same for any number). With `ranks` (R > 1),
/// rank r runs the operations i ≡ r (mod R) on its share of the node's cores and rank 0 merges them
/// all in the duty's order, as one process would; the other ranks return a result without links.
/// Every model is compiled before any runs, so bad input stops first. InputError for bad input,
/// SolverError for a failed run (the first operation's in the duty's order when several fail).
DutyResult run_duty(const std::string& model_path, const std::string& duty_path, const std::vector<std::string>& sets,
                    int jobs = 0, DutyRanks* ranks = nullptr);

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
