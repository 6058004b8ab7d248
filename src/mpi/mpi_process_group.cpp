// The MPI implementation of ProcessGroup (Open MPI, MPICH): point-to-point messages to rank 0 in
// rank order, errors returned instead of aborting so that a rank that cannot deliver is named. Built as
// the plugin libbssrdf-mpi.so, which launched_process_group.cpp opens under mpirun or srun only.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bssrdf/process_group.hpp"

namespace bssrdf {
namespace {

constexpr std::uint64_t kPiece = 1u << 30;  // MPI counts are int: messages go in pieces of 1 GiB

class MpiProcessGroup final : public ProcessGroup {
 public:
  MpiProcessGroup() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);  // only the main thread calls MPI
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
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

}  // namespace bssrdf

// The plugin's one entry point: the launch's group, MPI initialised on the first call (finalised at exit).
extern "C" __attribute__((visibility("default"))) bssrdf::ProcessGroup* bssrdf_mpi_process_group() {
  static bssrdf::MpiProcessGroup group;
  return &group;
}
