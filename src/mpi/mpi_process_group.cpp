// The MPI implementation of ProcessGroup (Open MPI, MPICH): point-to-point messages to rank 0 in
// rank order, errors returned instead of aborting so that a rank that cannot deliver is named.
#include <mpi.h>
#include <unistd.h>

#include <fcntl.h>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "launched_process_group.hpp"

namespace bssrdf {
namespace {

// This process's rank as the launcher announces it (Open MPI's mpirun; PMIx or PMI as srun and
// MPICH's hydra set them), or -1 when no launcher started it.
int announced_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return -1;
}

int announced_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return 0;  // unknown (PMIx announces no size): assume several
}

void silence() {
  const int null = ::open("/dev/null", O_WRONLY);
  if (null < 0) return;
  ::dup2(null, STDOUT_FILENO);
  ::dup2(null, STDERR_FILENO);
  ::close(null);
}

extern "C" void on_terminate(int) {
  static const char message[] =
      "bssrdf: error: MPI run stopped by the launcher (a rank died or was killed); no output written\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(3);
}

constexpr std::uint64_t kPiece = 1u << 30;  // MPI counts are int: messages go in pieces of 1 GiB

class MpiProcessGroup final : public ProcessGroup {
 public:
  MpiProcessGroup() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);  // only the main thread calls MPI
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (rank_ != 0)
      silence();
    else if (size_ > 1)
      std::signal(SIGTERM, on_terminate);  // again, in case MPI_Init replaced it
  }
  ~MpiProcessGroup() override { MPI_Finalize(); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::string> gather(const std::string& bytes) override {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> all;
    if (rank_ == 0) {
      all.push_back(bytes);
      for (int from = 1; from < size_; ++from) {
        std::uint64_t length = 0;
        check(MPI_Recv(&length, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), from);
        std::string received(length, '\0');
        for (std::uint64_t at = 0; at < length; at += kPiece)
          check(MPI_Recv(received.data() + at, static_cast<int>(std::min(kPiece, length - at)), MPI_BYTE, from, 1,
                         MPI_COMM_WORLD, MPI_STATUS_IGNORE),
                from);
        bytes_ += length + sizeof length;
        all.push_back(std::move(received));
      }
    } else {
      std::uint64_t length = bytes.size();
      check(MPI_Send(&length, 1, MPI_UINT64_T, 0, 0, MPI_COMM_WORLD), 0);
      for (std::uint64_t at = 0; at < length; at += kPiece)
        check(MPI_Send(bytes.data() + at, static_cast<int>(std::min(kPiece, length - at)), MPI_BYTE, 0, 1,
                       MPI_COMM_WORLD),
              0);
      bytes_ += length + sizeof length;
    }
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return all;
  }

  bool any(bool value) override {
    int local = value ? 1 : 0, global = 0;
    check(MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD), -1);
    return global != 0;
  }

  std::uint64_t bytes_moved() const override { return bytes_; }
  double seconds_communicating() const override { return seconds_; }

 private:
  static void check(int code, int peer) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw std::runtime_error("MPI: " + (peer >= 0 ? "exchange with rank " + std::to_string(peer) + " failed: " : "") +
                             std::string(text, static_cast<std::size_t>(length)));
  }

  int rank_ = 0, size_ = 1;
  std::uint64_t bytes_ = 0;
  double seconds_ = 0;
};

}  // namespace

void prepare_launched_process() {
  const int rank = announced_rank();
  if (rank > 0) silence();
  // From the start: a rank that dies before or during MPI_Init stops rank 0 there too.
  if (rank == 0 && announced_size() != 1) std::signal(SIGTERM, on_terminate);
}

ProcessGroup* launched_process_group() {
  if (announced_rank() < 0) return nullptr;
  static MpiProcessGroup group;  // MPI_Finalize at exit
  return &group;
}

}  // namespace bssrdf
