#include "machdyn/sweep/mpi.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <fmt/format.h>

#include "machdyn/io/duty.hpp"
#include "sweep/mpi_detail.hpp"

#ifdef MACHDYN_HAVE_MPI
#include <mpi.h>
#endif

namespace machdyn {
namespace {

bool g_active = false;
int g_rank = 0, g_size = 1;

int env_int(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : 0;
}

#ifdef MACHDYN_HAVE_MPI
constexpr int kTagRows = 7001;
constexpr int kTagDuty = 7002;
#endif

}  // namespace

int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (int n = env_int(name); n > 0) return n;
  return 1;
}

bool MpiSession::built() {
#ifdef MACHDYN_HAVE_MPI
  return true;
#else
  return false;
#endif
}

MpiSession::MpiSession() {
  if (launcher_world_size() <= 1) return;
#ifdef MACHDYN_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  g_active = true;
#else
  throw std::runtime_error(fmt::format("started by an MPI launcher with {} ranks, but this machdyn was built without "
                                       "MPI (each rank would run the whole sweep); install libopenmpi-dev and rebuild",
                                       launcher_world_size()));
#endif
}

MpiSession::~MpiSession() {
#ifdef MACHDYN_HAVE_MPI
  if (g_active) MPI_Finalize();
#endif
  g_active = false;
  g_rank = 0;
  g_size = 1;
}

bool MpiSession::active() { return g_active; }
int MpiSession::rank() { return g_rank; }
int MpiSession::size() { return g_size; }

int MpiSession::local_size() {
  if (!g_active) return 1;
  if (int n = env_int("OMPI_COMM_WORLD_LOCAL_SIZE"); n > 0) return n;
  if (int n = env_int("MPI_LOCALNRANKS"); n > 0) return n;
  return 1;
}

void MpiSession::abort(int code) {
#ifdef MACHDYN_HAVE_MPI
  if (g_active) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::_Exit(code);
}

namespace {
class MpiDutyRanks final : public DutyRanks {
 public:
  [[nodiscard]] int rank() const override { return MpiSession::rank(); }
  [[nodiscard]] int size() const override { return MpiSession::size(); }
  [[nodiscard]] int on_this_node() const override { return MpiSession::local_size(); }
  void send_to_root(const std::string& bytes) override { mpi_detail::send_to_root(bytes); }
  std::string receive_from(int rank) override { return mpi_detail::receive_from(rank); }
};
}  // namespace

std::unique_ptr<DutyRanks> mpi_duty_ranks() { return std::make_unique<MpiDutyRanks>(); }

namespace mpi_detail {

#ifdef MACHDYN_HAVE_MPI
void broadcast(int& v) { MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD); }

void broadcast(std::vector<char>& bytes) {
  MPI_Bcast(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR, 0, MPI_COMM_WORLD);
}

void send_rows(const std::string& records) {
  MPI_Send(records.data(), static_cast<int>(records.size()), MPI_CHAR, 0, kTagRows, MPI_COMM_WORLD);
}

int poll_rows(std::string& records) {
  int done = 0;
  for (;;) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagRows, MPI_COMM_WORLD, &flag, &st);
    if (!flag) return done;
    int count = 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    std::string buf(static_cast<size_t>(count), '\0');
    MPI_Recv(buf.data(), count, MPI_CHAR, st.MPI_SOURCE, kTagRows, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (count == 0) ++done;
    records += buf;
  }
}

void send_to_root(const std::string& bytes) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR, 0, kTagDuty, MPI_COMM_WORLD);
}

std::string receive_from(int source) {
  MPI_Status st;
  MPI_Probe(source, kTagDuty, MPI_COMM_WORLD, &st);
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  std::string buf(static_cast<size_t>(count), '\0');
  MPI_Recv(buf.data(), count, MPI_CHAR, source, kTagDuty, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return buf;
}
#else
void send_to_root(const std::string&) {}
std::string receive_from(int) { return {}; }
void broadcast(int&) {}
void broadcast(std::vector<char>&) {}
void send_rows(const std::string&) {}
int poll_rows(std::string&) { return 0; }
#endif

}  // namespace mpi_detail
}  // namespace machdyn
