// Folding batch and chunk sums, and their byte form for distributed runs.
#include "channel_sums.hpp"

#include <cstring>
#include <stdexcept>

namespace bssrdf::mc {
namespace {

void accumulate(std::vector<double>& into, const std::vector<double>& from) {
  if (into.empty()) into.assign(from.size(), 0.0);
  for (std::size_t i = 0; i < from.size(); ++i) into[i] += from[i];
}

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  template <class T>
  void put(const std::vector<T>& values) {
    put(static_cast<std::uint64_t>(values.size()));
    if (values.empty()) return;
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  void get(T& value) {
    need(sizeof value);
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
  }
  template <class T>
  void get(std::vector<T>& values) {
    std::uint64_t n = 0;
    get(n);
    if (n > (bytes_.size() - at_) / sizeof(T)) throw std::runtime_error("Monte Carlo chunk sums: truncated");
    values.resize(n);
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not be given
    std::memcpy(values.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw std::runtime_error("Monte Carlo chunk sums: truncated");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

void ChannelSums::add(const BatchTally& t) {
  reflected.insert(reflected.end(), t.reflected.begin(), t.reflected.end());
  photons += t.photons;
  interactions += t.interactions;
  ++batches;
  for (int i = 0; i < kTotals; ++i) {
    sum[i] += t.sum[i];
    sum_sq[i] += t.sum_sq[i];
  }
  lost += t.lost;
  r_beyond += t.r_beyond;
  t_beyond += t.t_beyond;
  accumulate(r_sum, t.r_sum);
  accumulate(r_sq, t.r_sq);
  accumulate(t_sum, t.t_sum);
  accumulate(t_sq, t.t_sq);
  accumulate(a_sum, t.a_sum);
  if (a_batch_sq.empty()) a_batch_sq.assign(t.a_sum.size(), 0.0);
  const double n = static_cast<double>(t.photons);
  for (std::size_t i = 0; i < t.a_sum.size(); ++i) a_batch_sq[i] += t.a_sum[i] * t.a_sum[i] / n;
}

void ChannelSums::add(const ChannelSums& more) {
  reflected.insert(reflected.end(), more.reflected.begin(), more.reflected.end());
  photons += more.photons;
  interactions += more.interactions;
  batches += more.batches;
  for (int i = 0; i < kTotals; ++i) {
    sum[i] += more.sum[i];
    sum_sq[i] += more.sum_sq[i];
  }
  lost += more.lost;
  r_beyond += more.r_beyond;
  t_beyond += more.t_beyond;
  for (auto [into, from] : {std::pair{&r_sum, &more.r_sum},
                            {&r_sq, &more.r_sq},
                            {&t_sum, &more.t_sum},
                            {&t_sq, &more.t_sq},
                            {&a_sum, &more.a_sum},
                            {&a_batch_sq, &more.a_batch_sq}})
    accumulate(*into, *from);
}

std::string serialize(const std::vector<ChunkSums>& chunks) {
  Writer w;
  w.put(static_cast<std::uint64_t>(chunks.size()));
  for (const auto& [chunk, s] : chunks) {
    w.put(chunk);
    w.put(s.photons);
    w.put(s.interactions);
    w.put(s.batches);
    w.put(s.sum);
    w.put(s.sum_sq);
    w.put(s.lost);
    w.put(s.r_beyond);
    w.put(s.t_beyond);
    for (const auto* v : {&s.r_sum, &s.r_sq, &s.t_sum, &s.t_sq, &s.a_sum, &s.a_batch_sq}) w.put(*v);
    w.put(s.reflected);
  }
  return w.take();
}

std::vector<ChunkSums> deserialize(std::string_view bytes) {
  Reader r(bytes);
  std::uint64_t n = 0;
  r.get(n);
  std::vector<ChunkSums> chunks;
  for (std::uint64_t k = 0; k < n; ++k) {
    ChunkSums c;
    ChannelSums& s = c.sums;
    r.get(c.chunk);
    r.get(s.photons);
    r.get(s.interactions);
    r.get(s.batches);
    r.get(s.sum);
    r.get(s.sum_sq);
    r.get(s.lost);
    r.get(s.r_beyond);
    r.get(s.t_beyond);
    for (auto* v : {&s.r_sum, &s.r_sq, &s.t_sum, &s.t_sq, &s.a_sum, &s.a_batch_sq}) r.get(*v);
    r.get(s.reflected);
    chunks.push_back(std::move(c));
  }
  if (!r.done()) throw std::runtime_error("Monte Carlo chunk sums: trailing bytes");
  return chunks;
}

}  // namespace bssrdf::mc
