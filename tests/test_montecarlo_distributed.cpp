// Distributed Monte Carlo without MPI: ranks played by threads of this process through an
// in-memory ProcessGroup. Any number of ranks gives the one-process result bitwise, and the chunk
// sums survive their byte form. (tests/mpi/mpi_runs.sh checks the same under mpirun.)
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "../src/montecarlo/channel_sums.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/process_group.hpp"

namespace bssrdf {
namespace {

// Ranks as threads: gather hands every rank's bytes to rank 0 once all have arrived.
class SharedMemory {
 public:
  explicit SharedMemory(int size) : parts_(static_cast<std::size_t>(size)) {}
  std::vector<std::string> gather(int rank, const std::string& bytes) {
    std::unique_lock lock(mutex_);
    parts_[static_cast<std::size_t>(rank)] = bytes;
    if (++arrived_ == static_cast<int>(parts_.size())) done_.notify_all();
    done_.wait(lock, [&] { return arrived_ == static_cast<int>(parts_.size()); });
    return rank == 0 ? parts_ : std::vector<std::string>{};
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  std::vector<std::string> parts_;
  int arrived_ = 0;
};

class ThreadRank final : public ProcessGroup {
 public:
  ThreadRank(SharedMemory& memory, int rank, int size) : memory_(memory), rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::vector<std::string> gather(const std::string& bytes) override {
    bytes_ += bytes.size();
    return memory_.gather(rank_, bytes);
  }
  bool any(bool) override { throw std::logic_error("not used by run_monte_carlo"); }
  std::uint64_t bytes_moved() const override { return bytes_; }
  double seconds_communicating() const override { return 0; }

 private:
  SharedMemory& memory_;
  int rank_, size_;
  std::uint64_t bytes_ = 0;
};

MonteCarloResult run_on_ranks(const LayerStack& stack, MonteCarloOptions options, int ranks) {
  SharedMemory memory(ranks);
  std::vector<MonteCarloResult> results(static_cast<std::size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      ThreadRank group(memory, r, ranks);
      MonteCarloOptions o = options;
      o.group = &group;
      results[static_cast<std::size_t>(r)] = run_monte_carlo(stack, o);
    });
  for (auto& t : threads) t.join();
  for (int r = 1; r < ranks; ++r) {
    EXPECT_FALSE(results[static_cast<std::size_t>(r)].gathered);
    EXPECT_TRUE(results[static_cast<std::size_t>(r)].channels.empty());
  }
  return results[0];
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const MonteCarloResult& a, const MonteCarloResult& b) {
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    const auto &x = a.channels[c], &y = b.channels[c];
    for (auto [p, q] : {std::pair{x.diffuse_reflectance, y.diffuse_reflectance},
                        {x.total_transmittance, y.total_transmittance},
                        {x.absorbed, y.absorbed},
                        {x.single_scattering_reflectance, y.single_scattering_reflectance}}) {
      EXPECT_TRUE(same_bits(p.value, q.value)) << p.value << " vs " << q.value;
      EXPECT_TRUE(same_bits(p.standard_error, q.standard_error));
    }
    EXPECT_EQ(x.interactions, y.interactions);
    for (auto [u, v] : {std::pair{&x.reflectance, &y.reflectance},
                        {&x.reflectance_stderr, &y.reflectance_stderr},
                        {&x.transmittance, &y.transmittance},
                        {&x.absorbed_by_depth, &y.absorbed_by_depth},
                        {&x.absorbed_by_depth_stderr, &y.absorbed_by_depth_stderr}}) {
      ASSERT_EQ(u->size(), v->size());
      for (std::size_t i = 0; i < u->size(); ++i) EXPECT_TRUE(same_bits((*u)[i], (*v)[i])) << i;
    }
  }
}

TEST(MonteCarloDistributed, AnyNumberOfRanksGivesTheOneProcessResultBitwise) {
  // Two channels and a slab: 300 batches of 256 photons = 5 chunks per channel, 10 in all.
  const Medium medium{{"a", "b"}, {0.05, 0.3}, {4.0, 6.0}, {0.8, 0.5}, 1.4, {}};
  const LayerStack stack = LayerStack::slab(medium, 2.0);
  MonteCarloOptions options;
  options.photons = 300 * 256;
  options.batch_size = 256;
  options.bins = 20;
  options.depth_bins = 8;
  options.threads = 2;
  const MonteCarloResult one = run_monte_carlo(stack, options);
  EXPECT_EQ(one.ranks, 1);
  for (int ranks : {2, 3, 7, 13}) {  // 13 > 10 chunks: some ranks trace nothing
    SCOPED_TRACE(ranks);
    const MonteCarloResult many = run_on_ranks(stack, options, ranks);
    EXPECT_EQ(many.ranks, ranks);
    EXPECT_GT(many.communication_bytes, 0u);
    expect_identical(one, many);
  }
}

TEST(MonteCarloDistributed, RecordedPhotonsArriveInBatchOrder) {
  const LayerStack stack = LayerStack::half_space(Medium::single_channel(0.1, 0.9, 0.3, 1.3));
  MonteCarloOptions options;
  options.photons = 130 * 64;  // 3 chunks of 64 batches
  options.batch_size = 64;
  options.bins = 2;
  options.record_reflected_photons = true;
  const auto one = run_monte_carlo(stack, options);
  const auto three = run_on_ranks(stack, options, 3);
  const auto& a = one.channels[0].reflected_photons;
  const auto& b = three.channels[0].reflected_photons;
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(same_bits(a[i].radius, b[i].radius));
    EXPECT_EQ(a[i].scatterings, b[i].scatterings);
  }
}

TEST(MonteCarloDistributed, ChunkSumsSurviveTheirByteForm) {
  mc::ChunkSums c;
  c.chunk = 42;
  c.sums.photons = 7;
  c.sums.sum[mc::kT] = 0.25;
  c.sums.r_sum = {1, 2, 3};
  c.sums.a_batch_sq = {0.5};
  c.sums.reflected = {{1.5, 3, 0.25f}};
  const std::string bytes = mc::serialize({c, c});
  const auto back = mc::deserialize(bytes);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].chunk, 42u);
  EXPECT_EQ(back[1].sums.photons, 7u);
  EXPECT_EQ(back[1].sums.sum[mc::kT], 0.25);
  EXPECT_EQ(back[1].sums.r_sum, c.sums.r_sum);
  EXPECT_EQ(back[1].sums.reflected[0].scatterings, 3u);
  EXPECT_EQ(mc::serialize(back), bytes);
  EXPECT_THROW(mc::deserialize(std::string_view(bytes).substr(0, bytes.size() - 1)), std::runtime_error);
  EXPECT_THROW(mc::deserialize(bytes + "x"), std::runtime_error);
}

}  // namespace
}  // namespace bssrdf
