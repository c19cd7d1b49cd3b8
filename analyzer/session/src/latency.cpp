// Latency histograms and stream rates: the figures of topdump stats.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "session.hpp"
#include "session/analyzer.hpp"

namespace topdump {

// Latency: log buckets of 1% width from 1 us.

std::size_t Latency::bucket_exact(std::int64_t us) {
  if (us <= 1) return 0;
  return static_cast<std::size_t>(std::log(static_cast<double>(us)) / std::log(1.01)) + 1;
}

std::size_t Latency::bucket(std::int64_t us) {
  // A log per sample is a fair part of the per-frame cost, and so was a
  // 128 KiB table of the buckets below 65.536 ms (its lines missed the
  // cache). Below 256 us a small table; up to 65.536 ms the range of each
  // power of two is cut in 64 slices, each under 1.6% wide, so at most two
  // 1% buckets begin inside a slice: its first bucket and where the next two
  // begin. The same buckets as bucket_exact (tested for every value).
  struct Slice {
    std::uint16_t base;
    std::uint16_t t1, t2;  // offsets in the slice where base + 1 and base + 2 begin
  };
  struct Tables {
    std::array<std::uint16_t, 256> small{};
    std::array<std::array<Slice, 64>, 8> slices{};  // powers 2^8 .. 2^15
  };
  static const Tables kTables = [] {
    Tables t;
    for (std::int64_t x = 0; x < 256; ++x)
      t.small[static_cast<std::size_t>(x)] = static_cast<std::uint16_t>(bucket_exact(x));
    for (int k = 8; k < 16; ++k)
      for (std::int64_t j = 0; j < 64; ++j) {
        const std::int64_t width = std::int64_t{1} << (k - 6);
        const std::int64_t lo = (std::int64_t{1} << k) + j * width;
        Slice& s = t.slices[static_cast<std::size_t>(k - 8)][static_cast<std::size_t>(j)];
        const std::size_t base = bucket_exact(lo);
        s.base = static_cast<std::uint16_t>(base);
        // the first offset in [1, width) whose bucket is past b (width: none),
        // by bisection (the buckets rise with the value): a tenth of the
        // logarithms of a scan, at every start of topdump
        auto first_past = [&](std::size_t b) {
          std::int64_t a = 1, z = width;
          while (a < z) {
            const std::int64_t m = a + (z - a) / 2;
            if (bucket_exact(lo + m) > b)
              z = m;
            else
              a = m + 1;
          }
          return static_cast<std::uint16_t>(a);
        };
        s.t1 = first_past(base);
        s.t2 = first_past(base + 1);
      }
    return t;
  }();
  if (us < 256) return us <= 1 ? 0 : kTables.small[static_cast<std::size_t>(us)];
  if (us >= 65536) return bucket_exact(us);
  const auto x = static_cast<std::uint32_t>(us);
  const int k = 31 - std::countl_zero(x);  // 8 .. 15
  const std::uint32_t at = x - (std::uint32_t{1} << k);
  const std::uint32_t shift = static_cast<std::uint32_t>(k - 6);
  const Slice& s = kTables.slices[static_cast<std::size_t>(k - 8)][at >> shift];
  const std::uint32_t in = at & ((std::uint32_t{1} << shift) - 1);
  return std::size_t{s.base} + (in >= s.t1) + (in >= s.t2);
}
std::int64_t Latency::bucket_value(std::size_t b) {
  if (b == 0) return 1;
  return static_cast<std::int64_t>(std::llround(std::pow(1.01, static_cast<double>(b))));
}
void Latency::count_in_bucket(std::int64_t us) {
  std::size_t b = std::min<std::size_t>(bucket(us), 4000);
  if (buckets_.size() <= b) buckets_.resize(b + 1, 0);
  ++buckets_[b];
}
void Latency::add(std::int64_t us) {
  if (us < 0) us = 0;
  if (count_ < kExact) {
    if (count_ == 0) exact_.reserve(16);
    exact_.push_back(us);
  } else {
    // past kExact samples the quantiles come from the buckets: the exact
    // ones are counted in first
    if (count_ == kExact)
      for (std::int64_t e : exact_) count_in_bucket(e);
    count_in_bucket(us);
  }
  if (count_ == 0 || us < min_) min_ = us;
  if (count_ == 0 || us > max_) max_ = us;
  ++count_;
}
std::int64_t Latency::quantile(double q) const {
  if (count_ == 0) return 0;
  auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_)));
  if (rank == 0) rank = 1;
  if (count_ <= kExact) {
    std::vector<std::int64_t> v = exact_;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rank - 1), v.end());
    return v[rank - 1];
  }
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < buckets_.size(); ++b) {
    seen += buckets_[b];
    if (seen >= rank) return std::clamp(bucket_value(b), min_, max_);
  }
  return max_;
}

bool StreamStat::off_rate() const { return periodic && diag::off_rate(measured_hz(), asked_hz); }

double StreamStat::measured_hz() const { return diag::measured_hz(frames, first, last); }

}  // namespace topdump
