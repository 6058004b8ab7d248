// Runs the tracer over batches on worker threads (and MPI ranks) and folds the batch tallies, in
// batch order within chunks and chunk order across them (channel_sums.hpp), into per-channel
// estimates with standard errors.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/parallel.hpp"
#include "bssrdf/process_group.hpp"
#include "channel_sums.hpp"
#include "tracer.hpp"

namespace bssrdf {

std::string_view to_string(BinSpacing spacing) { return spacing == BinSpacing::linear ? "linear" : "log"; }
std::string_view to_string(AbsorptionEstimator estimator) {
  return estimator == AbsorptionEstimator::analog ? "analog" : "implicit_capture";
}

void MonteCarloOptions::validate() const {
  if (photons < 1 || photons > 10'000'000'000)
    throw InvalidInput("photons", std::to_string(photons), "1 to 10000000000");
  if (batch_size < 1) throw InvalidInput("batch_size", std::to_string(batch_size), ">= 1");
  if (threads > 4096) throw InvalidInput("threads", std::to_string(threads), "0 (all cores) to 4096");
  if (bins < 2 || bins > 10'000'000) throw InvalidInput("bins", std::to_string(bins), "2 to 10000000");
  // Bins of at least 1e-9 mm, so R(r) = weight / bin area stays finite; lengths within 1e6 mm.
  if (!(r_max == 0 || (r_max >= 1e-9 * static_cast<double>(bins) && r_max <= 1e6)))
    throw InvalidInput("r_max", format_number(r_max), "1e-9 mm per bin to 1e6 mm (0: default)");
  if (!(r_min == 0 || (r_min >= 1e-9 && r_min <= 1e6)))
    throw InvalidInput("r_min", format_number(r_min), "1e-9 to 1e6 mm (0: default)");
  if (r_max > 0 && r_min > 0 && spacing == BinSpacing::log && !(r_min < r_max))
    throw InvalidInput("r_min", format_number(r_min), "< r_max = " + format_number(r_max));
  if (depth_bins > 10'000'000) throw InvalidInput("depth_bins", std::to_string(depth_bins), "0 to 10000000");
  if (!(z_max == 0 || (z_max >= 1e-9 * static_cast<double>(depth_bins) && z_max <= 1e6)))
    throw InvalidInput("z_max", format_number(z_max), "1e-9 mm per depth bin to 1e6 mm (0: default)");
  if (!(roulette_threshold >= 0) || !(roulette_threshold < 1))
    throw InvalidInput("roulette_threshold", format_number(roulette_threshold), "0 <= threshold < 1");
  if (!(roulette_survival > 0) || !(roulette_survival <= 1))
    throw InvalidInput("roulette_survival", format_number(roulette_survival), "0 < survival <= 1");
  if (max_interactions < 1) throw InvalidInput("max_interactions", std::to_string(max_interactions), ">= 1");
}

ChannelResult ChannelResult::per_entered_flux() const {
  ChannelResult out = *this;
  const double k = entered_scale();
  for (Estimate* e : {&out.diffuse_reflectance, &out.single_scattering_reflectance, &out.unscattered_reflectance,
                      &out.total_transmittance, &out.unscattered_transmittance, &out.absorbed}) {
    e->value *= k;
    e->standard_error *= k;
  }
  out.lost *= k;
  out.reflectance_beyond *= k;
  out.transmittance_beyond *= k;
  for (auto* v : {&out.reflectance, &out.reflectance_stderr, &out.transmittance, &out.transmittance_stderr,
                  &out.absorbed_by_depth, &out.absorbed_by_depth_stderr})
    for (double& x : *v) x *= k;
  return out;
}

namespace {

// The largest transport mean free path over the attenuating layers and channels (mm): light
// spreads as far as the most open layer lets it, and that is often a deep one (a thin, dense
// epidermis over dermis set the top layer's 10 ell at a radius holding only 85 % of the red).
double largest_transport_mfp(const LayerStack& stack) {
  const double ell = transport_mfp_range(stack).max;
  return ell > 0 ? ell : 1.0;
}

// Mean of N per-photon contributions and its standard error.
Estimate estimate(double sum, double sum_sq, double n) {
  Estimate e;
  e.value = sum / n;
  const double variance = n > 1 ? std::max(0.0, (sum_sq / n - e.value * e.value) / (n - 1)) : 0.0;
  e.standard_error = std::sqrt(variance);
  return e;
}

}  // namespace

MonteCarloResult run_monte_carlo(const LayerStack& stack, const MonteCarloOptions& options_in) {
  stack.validate();
  options_in.validate();
  MonteCarloResult result;
  result.stack = stack;
  MonteCarloOptions& options = result.options;
  options = options_in;
  options.progress = nullptr;
  options.group = nullptr;
  if (options.r_max <= 0) options.r_max = 10 * largest_transport_mfp(stack);
  if (options.r_min <= 0) options.r_min = options.r_max / 1000;
  if (options.spacing == BinSpacing::log && !(options.r_min < options.r_max))
    throw InvalidInput("r_min", format_number(options.r_min), "< r_max = " + format_number(options.r_max));
  if (options.depth_bins > 0 && options.z_max <= 0)
    options.z_max = stack.semi_infinite() ? 10 * largest_transport_mfp(stack) : stack.depth();

  const mc::RadialBinning binning(options.spacing, options.bins, options.r_min, options.r_max);
  result.bin_inner = binning.inner;
  result.bin_outer = binning.outer;
  result.bin_radius = binning.radius;
  const double dz = options.depth_bins > 0 ? options.z_max / static_cast<double>(options.depth_bins) : 0;
  for (std::size_t i = 0; i < options.depth_bins; ++i) {
    result.depth_inner.push_back(dz * static_cast<double>(i));
    result.depth_outer.push_back(i + 1 == options.depth_bins ? options.z_max : dz * static_cast<double>(i + 1));
  }

  mc::TraceSettings settings;
  settings.binning = &binning;
  settings.transmission_bins = !stack.semi_infinite();
  settings.depth_bins = options.depth_bins;
  settings.inv_depth_width = dz > 0 ? 1 / dz : 0;
  settings.absorption = options.absorption;
  settings.roulette_threshold = options.roulette_threshold;
  settings.roulette_survival = options.roulette_survival;
  settings.max_interactions = options.max_interactions;
  settings.record_reflected = options.record_reflected_photons;

  const std::size_t channels = stack.channels();
  std::vector<mc::ChannelGeometry> geometry;
  for (std::size_t c = 0; c < channels; ++c) geometry.push_back(mc::make_geometry(stack, c));

  const std::uint64_t batches_per_channel = (options.photons + options.batch_size - 1) / options.batch_size;
  const std::uint64_t chunks_per_channel = (batches_per_channel + mc::kBatchesPerChunk - 1) / mc::kBatchesPerChunk;
  const std::uint64_t total_chunks = chunks_per_channel * channels;
  const std::uint64_t total_photons = options.photons * channels;
  ProcessGroup* group = options_in.group && options_in.group->size() > 1 ? options_in.group : nullptr;
  const std::uint64_t ranks = group ? static_cast<std::uint64_t>(group->size()) : 1;
  const std::uint64_t rank = group ? static_cast<std::uint64_t>(group->rank()) : 0;
  result.ranks = static_cast<int>(ranks);

  // This rank's batches (global index channel * batches_per_channel + batch), chunk by chunk.
  struct Work {
    std::uint64_t chunk, channel, batch;
  };
  std::vector<Work> work;
  for (std::uint64_t chunk = rank; chunk < total_chunks; chunk += ranks) {
    const std::uint64_t channel = chunk / chunks_per_channel,
                        first = (chunk % chunks_per_channel) * mc::kBatchesPerChunk;
    for (std::uint64_t b = first; b < std::min(batches_per_channel, first + mc::kBatchesPerChunk); ++b)
      work.push_back({chunk, channel, b});
  }
  result.threads = worker_count(work.size(), options.threads);

  std::vector<mc::ChannelSums> sums(channels);
  std::vector<mc::ChunkSums> finished;  // this rank's chunks, kept for rank 0 when distributed
  mc::ChunkSums current{work.empty() ? 0 : work[0].chunk, {}};
  const auto finish_chunk = [&] {
    if (group)
      finished.push_back(std::move(current));
    else
      sums[current.chunk / chunks_per_channel].add(current.sums);
  };
  std::mutex fold_mutex;
  std::map<std::size_t, mc::BatchTally> pending;  // finished, waiting for earlier batches
  std::size_t next_fold = 0;
  std::uint64_t photons_done = 0;

  const auto start = std::chrono::steady_clock::now();
  parallel_for(work.size(), options.threads, [&](std::size_t index) {
    const Work& w = work[index];
    const std::uint64_t count = std::min(options.batch_size, options.photons - w.batch * options.batch_size);
    mc::BatchTally tally;
    tally.reset(binning.bins, settings.transmission_bins, settings.depth_bins);
    mc::Rng rng(options.seed, w.channel, w.batch);
    mc::trace_batch(geometry[w.channel], settings, rng, count, tally);
    std::lock_guard<std::mutex> lock(fold_mutex);
    pending.emplace(index, std::move(tally));
    // Fold in batch order only: floating-point sums then never depend on the thread count.
    while (!pending.empty() && pending.begin()->first == next_fold) {
      if (work[next_fold].chunk != current.chunk) {
        finish_chunk();
        current = {work[next_fold].chunk, {}};
      }
      current.sums.add(pending.begin()->second);
      pending.erase(pending.begin());
      ++next_fold;
    }
    photons_done += count;
    // Rank 0 speaks for all: the ranks progress at about the same pace.
    if (options_in.progress && rank == 0)
      options_in.progress(std::min(total_photons, photons_done * ranks), total_photons);
  });
  if (!work.empty()) finish_chunk();
  if (group) {
    // Rank 0 folds every rank's chunks in chunk order: the one-process fold, whatever the ranks.
    const std::vector<std::string> parts = group->gather(mc::serialize(finished));
    finished.clear();
    if (rank != 0) {
      result.gathered = false;
    } else {
      std::vector<mc::ChunkSums> all;
      for (const std::string& part : parts)
        for (auto& c : mc::deserialize(part)) all.push_back(std::move(c));
      std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.chunk < b.chunk; });
      BSSRDF_CHECK(all.size() == total_chunks);
      for (const auto& c : all) sums[c.chunk / chunks_per_channel].add(c.sums);
    }
    result.communication_bytes = group->bytes_moved();
    result.communication_seconds = group->seconds_communicating();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.photons_per_second = result.seconds > 0 ? static_cast<double>(total_photons) / result.seconds : 0;
  if (!result.gathered) return result;

  for (std::size_t c = 0; c < channels; ++c) {
    const mc::ChannelSums& s = sums[c];
    const double n = static_cast<double>(s.photons);
    ChannelResult ch;
    ch.name = stack.channel_names[c];
    ch.specular_reflectance = geometry[c].specular;
    ch.diffuse_reflectance = estimate(s.sum[mc::kR], s.sum_sq[mc::kR], n);
    ch.single_scattering_reflectance = estimate(s.sum[mc::kRSingle], s.sum_sq[mc::kRSingle], n);
    ch.unscattered_reflectance = estimate(s.sum[mc::kRUnscattered], s.sum_sq[mc::kRUnscattered], n);
    ch.total_transmittance = estimate(s.sum[mc::kT], s.sum_sq[mc::kT], n);
    ch.unscattered_transmittance = estimate(s.sum[mc::kTUnscattered], s.sum_sq[mc::kTUnscattered], n);
    ch.absorbed = estimate(s.sum[mc::kAbsorbed], s.sum_sq[mc::kAbsorbed], n);
    ch.lost = s.lost / n;
    ch.reflectance_beyond = s.r_beyond / n;
    ch.transmittance_beyond = s.t_beyond / n;
    ch.interactions = s.interactions;
    ch.reflected_photons = s.reflected;
    const auto radial = [&](const std::vector<double>& sum, const std::vector<double>& sum_sq,
                            std::vector<double>& value, std::vector<double>& error) {
      for (std::size_t i = 0; i < sum.size(); ++i) {
        const double area =
            std::numbers::pi * (binning.outer[i] * binning.outer[i] - binning.inner[i] * binning.inner[i]);
        const Estimate e = estimate(sum[i], sum_sq[i], n);
        value.push_back(e.value / area);
        error.push_back(e.standard_error / area);
      }
    };
    radial(s.r_sum, s.r_sq, ch.reflectance, ch.reflectance_stderr);
    radial(s.t_sum, s.t_sq, ch.transmittance, ch.transmittance_stderr);
    // Absorption by depth: one photon deposits in many bins, so the error comes from the spread
    // of the per-batch means (batch-means estimator; batches are independent and identically
    // distributed apart from the size of the last one).
    const double batches = static_cast<double>(s.batches);
    for (std::size_t i = 0; i < s.a_sum.size(); ++i) {
      const double mean = s.a_sum[i] / n;
      ch.absorbed_by_depth.push_back(mean / dz);
      const double spread = s.batches > 1 ? std::max(0.0, (s.a_batch_sq[i] - n * mean * mean) / (batches - 1)) : NAN;
      ch.absorbed_by_depth_stderr.push_back(std::sqrt(spread / n) / dz);
    }
    result.channels.push_back(std::move(ch));
  }
  return result;
}

}  // namespace bssrdf
