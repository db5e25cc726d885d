#pragma once
/// @file
/// How finely a signal must be looked at for an event function that reads it to be judged by
/// sampling (EventSystem::sampling_step): the longest time over which s, between its breakpoints,
/// cannot rise and fall back (or fall and rise back) unseen at the two ends of the interval.
///   constant, step, ramp, table, pulse   +∞ (linear between breakpoints: monotone there)
///   sine                                 T/8 = 2π/(8ω): a quarter of a half-wave, so an excursion
///                                        of s beyond a level lasting longer than T/8 is seen
///   expression                           (t1 − t0)/4096, the resolution of Signal::crossings
///   sum                                  the smallest of its terms'
/// In s over (t0, t1). A sampling step says nothing of excursions shorter than itself.

#include "machdyn/model/signal.hpp"

namespace machdyn {

struct Model;

[[nodiscard]] double sampling_step(const Signal& s, double t0, double t1);

/// The smallest sampling step of a model's signals over (0, t_end), those Model::breakpoints reads:
/// loads (an expression load in t, q, v as an expression), brake and clutch applications, prescribed
/// motions; a drive whose law has events (its signals are its element's own) as an expression.
[[nodiscard]] double sampling_step(const Model& m, double t_end);

}  // namespace machdyn
