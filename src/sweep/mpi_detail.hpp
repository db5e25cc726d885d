#pragma once
// The few messages of a sweep (and of a duty: mpi_duty_ranks) under MPI (private to src/sweep).
// Without MPI in the build these are never called (MpiSession::active() is false).
#include <string>
#include <vector>

namespace machdyn::mpi_detail {

/// Rank 0's value of `v` on every rank.
void broadcast(int& v);
/// Rank 0's bytes on every rank (`bytes` must have the same size everywhere).
void broadcast(std::vector<char>& bytes);
/// Sends journal records (concatenated lines) to rank 0; an empty string says "this rank is done".
void send_rows(const std::string& records);
/// Rank 0: receives every message waiting now. Appends the records to `records` and returns the
/// number of "done" messages among them.
int poll_rows(std::string& records);
/// A duty's operations (io/duty.cpp): a rank's packed results to rank 0, and rank 0's blocking
/// receive of the results of rank `source`.
void send_to_root(const std::string& bytes);
std::string receive_from(int source);

}  // namespace machdyn::mpi_detail
