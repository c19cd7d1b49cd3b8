#include "session/counters.hpp"

#include <cstdlib>
#include <new>

#include "top/text.hpp"

namespace topdump {

std::string unpack_ident(std::uint32_t k) {
  char b[3] = {static_cast<char>(k & 0xFF), static_cast<char>((k >> 8) & 0xFF),
               static_cast<char>((k >> 16) & 0xFF)};
  return top::escape(std::string_view(b, 3));
}

void Counters::FreeDeleter::operator()(std::uint64_t* p) const noexcept { std::free(p); }

void Counters::allocate(Page& page) {
  auto* p = static_cast<std::uint64_t*>(std::calloc(kPage, sizeof(std::uint64_t)));
  if (!p) throw std::bad_alloc();
  page.reset(p);
}

void Counters::materialize(Stats& s) const {
  s.per_ident.clear();
  for (const auto& [k, v] : other_) s.per_ident[unpack_ident(k)] += v;
  for (std::size_t p = 0; p < pages_.size(); ++p)
    if (const auto& page = pages_[p])
      for (std::size_t i = 0; i < kPage; ++i)
        if (page[i]) s.per_ident[top::ident_of(p * kPage + i)] += page[i];
  s.per_code.clear();
  for (std::size_t i = 0; i < codes_.size(); ++i)
    if (codes_[i])
      s.per_code[std::string(top::to_string(static_cast<top::FindingCode>(i)))] += codes_[i];
  for (std::size_t i = 0; i < acodes_.size(); ++i)
    if (acodes_[i]) s.per_code[std::string(to_string(static_cast<ACode>(i)))] += acodes_[i];
}

Latency& LatencyTable::of(std::uint32_t key) {
  std::uint32_t& hint = hint_[(key * 0x9E3779B1u) >> 26];
  if (hint != 0 && keys_[hint - 1] == key) return values_[hint - 1];
  std::size_t i = 0;
  while (i < keys_.size() && keys_[i] != key) ++i;
  if (i == keys_.size()) {
    keys_.push_back(key);
    values_.emplace_back();
  }
  hint = static_cast<std::uint32_t>(i + 1);
  return values_[i];
}

void LatencyTable::materialize(std::map<std::string, Latency>& out) const {
  out.clear();
  for (std::size_t i = 0; i < keys_.size(); ++i) out[unpack_ident(keys_[i])] = values_[i];
}

}  // namespace topdump
