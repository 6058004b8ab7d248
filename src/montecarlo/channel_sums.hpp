// Internal to the Monte Carlo solver: running sums of one channel over folded photon batches, and
// the chunk, the unit of work the batches are grouped into. A chunk is kBatchesPerChunk consecutive
// batches of one channel; its batches are folded in batch order into the chunk's sums, and the
// chunks' sums into the channel's in chunk order. That order depends on neither the thread count
// nor the number of MPI ranks, so one process and N ranks (each tracing the chunks c with
// c % N == rank) give bitwise identical results; rank 0 receives the other ranks' chunk sums as bytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tracer.hpp"

namespace bssrdf::mc {

// 64 batches (262144 photons at the default batch size): runs of up to that many photons per channel
// fold exactly as a plain batch-order fold; a 10^10-photon run moves ~40000 chunks (~5 kB each at 100 bins).
constexpr std::uint64_t kBatchesPerChunk = 64;

struct ChannelSums {
  std::uint64_t photons = 0, interactions = 0, batches = 0;
  double sum[kTotals] = {}, sum_sq[kTotals] = {};
  double lost = 0, r_beyond = 0, t_beyond = 0;
  std::vector<double> r_sum, r_sq, t_sum, t_sq, a_sum, a_batch_sq;
  std::vector<ReflectedPhoton> reflected;

  void add(const BatchTally& t);      // one batch
  void add(const ChannelSums& more);  // a later chunk's sums
};

// Chunk sums tagged with their global chunk index, as bytes for the trip to rank 0 (same machine
// architecture on every rank, as MPI clusters are).
struct ChunkSums {
  std::uint64_t chunk = 0;
  ChannelSums sums;
};
std::string serialize(const std::vector<ChunkSums>& chunks);
std::vector<ChunkSums> deserialize(std::string_view bytes);  // throws std::runtime_error when malformed

}  // namespace bssrdf::mc
