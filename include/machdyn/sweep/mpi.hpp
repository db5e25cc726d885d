#pragma once
/// @file
/// MPI for sweeps across processes and nodes (`mpirun -np N machdyn sweep ...`). Built when CMake
/// finds MPI (option MACHDYN_MPI, default AUTO); MPI is initialized only when the process was
/// started by a launcher with more than one rank, so a plain `machdyn sweep` never touches it.

#include <memory>

namespace machdyn {

class DutyRanks;  // io/duty.hpp

/// Initializes MPI (MPI_THREAD_FUNNELED: only the main thread calls MPI) when started by mpirun
/// with more than one rank, and finalizes it on destruction. Throws std::runtime_error when
/// started under a multi-rank launcher but built without MPI (each rank would run the whole sweep).
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  /// True between MPI_Init and MPI_Finalize of a multi-rank run.
  static bool active();
  static int rank();  ///< 0 without MPI
  static int size();  ///< 1 without MPI
  /// Ranks on this node (for the default thread count), 1 without MPI.
  static int local_size();
  /// Ends every rank at once (after Ctrl-C on rank 0, whose journal is synced).
  [[noreturn]] static void abort(int code);
  /// Whether this build has MPI.
  static bool built();
};

/// A duty's ranks over MPI (io/duty.hpp's run_duty): the world of an active MpiSession.
std::unique_ptr<DutyRanks> mpi_duty_ranks();

/// The number of ranks the launcher announces in the environment (OpenMPI: OMPI_COMM_WORLD_SIZE;
/// MPICH, Slurm: PMI_SIZE), 1 if none.
int launcher_world_size();

}  // namespace machdyn
