#pragma once
/// @file
/// A sweep plan: the base model spec, the varied fields and the list of runs, each run a set of
/// `--set NAME.FIELD=VALUE` overrides on the base. Built and checked once, before any run, so a
/// wrong element name or unit is reported at once (InputError, exit 2) and not as a failed run.
///
/// Run order (the table's row order and the meaning of the run index):
///   grid:   full factorial; the FIRST --vary varies slowest, the LAST fastest (nested loops in the
///           order written). Run count = n1·n2·…·nd.
///   random: --samples points, uniform on each range (or log-uniform for `:log`), seeded.
///   lhs:    --samples points of a Latin hypercube, seeded (sweep/sampling.hpp).
/// With model cases (see SweepRequest::cases) the case is the outermost factor: runs
/// [c·P, (c+1)·P) are case c over the same P points. A run's spec is built as `simulate --case`
/// builds it: the model file, its case, the --set overrides, then the run's varied values.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/sweep/sampling.hpp"

namespace machdyn {

enum class SweepMethod { grid, random, lhs };

/// Puts the named case of a model into its spec. The model files' `cases:` (model/cases.hpp) use
/// machdyn::apply_case; tests may supply their own. Throws InputError for an unknown case.
using CaseApplier = std::function<void(SpecNode& spec, const std::string& case_name)>;

/// What a user asks for (the command line fills it).
struct SweepRequest {
  std::string model_path;
  /// The model's YAML text; when not empty it is used instead of reading `model_path`, which then
  /// only names the source in messages (the Python module's models from a string).
  std::string model_text;
  std::vector<std::string> sets;  ///< `NAME.FIELD=VALUE`, applied to the base before any --vary
  std::vector<std::string> vary;  ///< `NAME.FIELD=SPEC`, in order
  SweepMethod method = SweepMethod::grid;
  int samples = 0;                ///< random, lhs: number of points (> 0)
  std::uint64_t seed = 1;         ///< random, lhs
  std::vector<std::string> cases; ///< model cases to run every point for (empty: the model as is)
  CaseApplier apply_case;         ///< required when `cases` is not empty
};

struct VaryAxis {
  std::string target;  ///< `NAME.FIELD`, also the table column
  SampleSpec spec;
};

struct SweepRun {
  long index = 0;                  ///< 0-based; the table's `run` column and row order
  int case_index = -1;             ///< into SweepPlan::cases, -1 without cases
  std::vector<AxisValue> values;   ///< one per axis
};

struct SweepPlan {
  SweepRequest request;
  SpecNode base;                   ///< the model file with the --set overrides
  Model base_model;                ///< base compiled (for column names)
  /// With cases, per case c (request.cases order): the file, case c, the --set overrides ...
  std::vector<SpecNode> case_bases;
  std::vector<Model> case_models;  ///< ... and compiled (the table's columns are their union)
  std::vector<VaryAxis> axes;
  std::vector<SweepRun> runs;
  std::string fingerprint;         ///< 16 hex digits over model text, options and run list
  std::string description;         ///< e.g. "grid 5 × 4 = 20 runs"
};

/// Parses and checks the request and lists the runs. Throws InputError when the model (with --set)
/// does not compile, a --vary has bad syntax or names an unknown element or field, a value's unit
/// does not fit the field, every value of an axis is rejected by the compiler, or the options do
/// not fit the method (grid needs `a:b:n` or a list; random and lhs need --samples and `a:b` or a
/// list). A value that only some runs reject (a negative stiffness in a list) is not an input
/// error: those runs fail alone with status `error`.
SweepPlan make_sweep_plan(const SweepRequest& request);

/// The spec of one run: base (with cases: the file, its case, --set), then `target=text` for each axis.
SpecNode run_spec(const SweepPlan& plan, const SweepRun& run);

/// The models whose summary columns make the table: base_model, or one per case (a case may add
/// or remove elements, e.g. a brake).
std::vector<const Model*> column_models(const SweepPlan& plan);

}  // namespace machdyn
