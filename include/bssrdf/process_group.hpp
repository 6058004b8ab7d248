// A group of cooperating processes sharing one Monte Carlo run: the MPI ranks of `mpirun -np N` or
// `srun`. The library knows only this interface (run_monte_carlo hands each rank its share of the
// photon batches and gathers the tallies on rank 0); the MPI implementation lives in the optional
// bssrdf_mpi library, so a build without MPI changes nothing and one process is the case N = 1.
//
//   options.group = launched_process_group();   // bssrdf_mpi (launched_process_group.hpp); null: one process
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bssrdf {

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Collective: rank 0 receives every rank's bytes in rank order (its own first); the others get {}.
  // Throws std::runtime_error naming the rank when one cannot deliver.
  virtual std::vector<std::string> gather(const std::string& bytes) = 0;
  // Collective: true on every rank when any rank passes true.
  virtual bool any(bool value) = 0;
  // Communication so far on this rank: bytes sent or received by gather and the seconds spent in it
  // (waiting for slower ranks included).
  virtual std::uint64_t bytes_moved() const = 0;
  virtual double seconds_communicating() const = 0;
};

}  // namespace bssrdf
