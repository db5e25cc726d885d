#pragma once
/// @file
/// The figures of a duty (docs/duty.md): per counted link the cumulative spectrum (exceedance
/// diagram) of its merged rainflow cycles with the spectrum classes' limits drawn in, and the
/// range–mean matrix as a heat map; and the duty's section of `machdyn report --duty`.
///
///   exceedance   H(Δ) = Σ n_i over the cycles with Δ_i ≥ Δ: the cycles whose range reaches Δ, drawn
///                as a staircase of Δ against log₁₀ H;
///   class limits the constant-range spectrum of N_t cycles that has the spectrum factor k_lim
///                (k = Σ n_i (Δ_i/Δ̂)^m / N_t) lies at Δ̂ k_lim^(1/m): a spectrum whose equivalent
///                range Δ_eq (for N_t cycles) lies below that line has k ≤ k_lim. Drawn for the
///                limits of L1…L3 (0.125, 0.25, 0.5) with the duty's exponent m; with m = 3 at
///                0.500, 0.630, 0.794 Δ̂.

#include <string>
#include <vector>

#include "machdyn/io/duty.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/io/report.hpp"

namespace machdyn {

/// The exceedance diagram of one link (id "duty_exceedance_LINK"); `m` the exponent of k.
plot::Figure duty_exceedance_figure(const DutyLink& l, double m);

/// The staircase of the exceedance diagram: ranges in decreasing order and the cumulative count of
/// cycles whose range is at least each (equal ranges merged).
struct Exceedance {
  std::vector<double> range, cycles;
};
Exceedance exceedance(const std::vector<RainflowCycle>& cycles);

/// The heat map's data: one row "range_lo range_hi mean_lo mean_hi count" per non-empty cell of the
/// range–mean matrix (analysis/rainflow.hpp, `bins` × `bins` over the link's own extent).
std::string duty_heat_map_data(const DutyLink& l, int bins = 32);

/// The heat map of one link drawn by gnuplot (SVG + PNG, the sizes and fonts of io/plot.hpp), counts
/// on a logarithmic colour scale. Throws std::runtime_error without gnuplot.
plot::Rendered render_duty_heat_map(const DutyLink& l, int bins = 32);

/// The duty's section of the report: the table per link (cycles, Δ̂, Δ_eq, s, k_m, L, M, damage),
/// the running time and its class, the operations, and each link's exceedance diagram.
report::Section duty_report_section(const DutyResult& r);

}  // namespace machdyn
