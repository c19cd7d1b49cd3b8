#include "sim/faults.hpp"

#include <charconv>
#include <cstdlib>

namespace topsim {
namespace {

bool parse_prob(std::string_view v, double& out) {
  if (v.empty()) return false;
  std::string s(v);
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && out >= 0 && out <= 1;
}

bool is_hex_upper(char c) noexcept { return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'F'); }

}  // namespace

bool FaultConfig::any() const noexcept {
  return drop > 0 || delay_ms > 0 || duplicate > 0 || bad_checksum > 0 || header_case > 0 ||
         no_swap || lying_length > 0 || tmp_quirk || split || garbage > 0 || !hang_on.empty() ||
         crash_on || hang_class || slow_on || answer_corrupt;
}

const std::vector<std::string_view>& fault_names() {
  static const std::vector<std::string_view> names = {
      "drop",         "delay",     "duplicate", "bad-checksum",  "header-case", "no-swap",
      "lying-length", "tmp-quirk", "split",     "garbage",       "hang-on",     "crash-on",
      "hang-s",       "slow-on",   "slow-ms",   "answer-corrupt"};
  return names;
}

std::optional<FaultConfig> parse_faults(std::string_view spec, std::string& error) {
  FaultConfig cfg;
  while (!spec.empty()) {
    const std::size_t comma = spec.find(',');
    std::string_view item = spec.substr(0, comma);
    spec = comma == std::string_view::npos ? std::string_view{} : spec.substr(comma + 1);
    if (item.empty()) continue;
    const std::size_t eq = item.find('=');
    const std::string_view name = item.substr(0, eq);
    const bool has_value = eq != std::string_view::npos;
    const std::string_view value = has_value ? item.substr(eq + 1) : std::string_view{};
    auto bad = [&](std::string_view why) {
      error = "fault '" + std::string(item) + "': " + std::string(why);
      return std::nullopt;
    };
    double* prob = name == "drop"           ? &cfg.drop
                   : name == "duplicate"    ? &cfg.duplicate
                   : name == "bad-checksum" ? &cfg.bad_checksum
                   : name == "header-case"  ? &cfg.header_case
                   : name == "lying-length" ? &cfg.lying_length
                   : name == "garbage"      ? &cfg.garbage
                                            : nullptr;
    if (prob) {
      // A bare name means always.
      if (!has_value) {
        *prob = 1;
        continue;
      }
      if (!parse_prob(value, *prob)) return bad("P must be a number from 0 to 1");
    } else if (name == "delay") {
      unsigned ms = 0;
      auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), ms);
      if (!has_value || ec != std::errc{} || p != value.data() + value.size() || ms > 600000)
        return bad("delay needs milliseconds, 0-600000");
      cfg.delay_ms = ms;
    } else if (name == "no-swap" || name == "tmp-quirk" || name == "split") {
      if (has_value) return bad("takes no value");
      (name == "no-swap" ? cfg.no_swap : name == "tmp-quirk" ? cfg.tmp_quirk : cfg.split) = true;
    } else if (name == "hang-on") {
      if (value.size() == 3) {
        cfg.hang_on = std::string(value);
        continue;
      }
      auto c = parse_input_class(value);
      if (!c) return bad("hang-on needs a three-character identifier or ident:ID, len:N, byte:HH");
      cfg.hang_class = *c;
    } else if (name == "crash-on" || name == "slow-on") {
      auto c = parse_input_class(value);
      if (!c) return bad("needs ident:ID, len:N or byte:HH");
      (name == "crash-on" ? cfg.crash_on : cfg.slow_on) = *c;
    } else if (name == "hang-s" || name == "slow-ms") {
      unsigned n = 0;
      auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (!has_value || ec != std::errc{} || p != value.data() + value.size() || n > 600000)
        return bad("needs a whole number, 0-600000");
      (name == "hang-s" ? cfg.hang_s : cfg.slow_ms) = n;
    } else if (name == "answer-corrupt") {
      if (has_value) return bad("takes no value");
      cfg.answer_corrupt = true;
    } else {
      return bad(
          "unknown fault (known: drop delay duplicate bad-checksum "
          "header-case no-swap lying-length tmp-quirk split garbage hang-on crash-on hang-s "
          "slow-on slow-ms answer-corrupt)");
    }
  }
  return cfg;
}

FaultInjector::FaultInjector(FaultConfig cfg, std::uint64_t seed)
    : cfg_(std::move(cfg)), rng_(seed) {}

bool FaultInjector::chance(double p) {
  if (p <= 0) return false;
  if (p >= 1) return true;
  return std::uniform_real_distribution<double>(0, 1)(rng_) < p;
}

bool FaultInjector::on_request(const top::Frame& request) {
  if (hung_) return false;
  if (!cfg_.hang_on.empty() && request.ident_view() == cfg_.hang_on) {
    hung_ = true;
    return false;
  }
  return true;
}

void FaultInjector::apply(const std::string& frame, bool stream_link, std::vector<Emission>& out) {
  if (hung() || chance(cfg_.drop)) return;
  std::string f = frame;
  const bool plain = f.size() >= top::prefix_size + 2 && f[0] == '#' &&
                     (f[1] == 't' || f[1] == 'T') && (f[2] == 'p' || f[2] == 'P');
  if (plain && chance(cfg_.lying_length)) {
    // Declare one data byte fewer (or more for empty data), then checksum
    // the bytes as sent: the C12 "#tpDU3rVER010502" shape.
    if ((f[1] == 't' && f[2] == 'p') || (f[1] == 'T' && f[2] == 'P')) {
      const std::size_t data_len = f.size() - top::prefix_size - 2;
      if (data_len >= 2 && data_len <= 15) {
        const std::size_t lie = data_len - 1;
        f[5] = "0123456789ABCDEF"[lie];
        f.resize(f.size() - 2);
        f = top::with_checksum(f);
      }
    }
  }
  if (plain && chance(cfg_.header_case)) {
    // Flip the header's case after the checksum was computed.
    if (f[1] == 'T' && f[2] == 'P')
      f[1] = 't', f[2] = 'p';
    else if (f[1] == 't' && f[2] == 'p')
      f[1] = 'T', f[2] = 'P';
  }
  if (chance(cfg_.bad_checksum) && f.size() >= 2 && is_hex_upper(f[f.size() - 1])) {
    char& c = f[f.size() - 1];
    c = c == '0' ? '1' : '0';
  }
  if (chance(cfg_.garbage)) f.insert(0, "\x01\xFFzz%");
  std::uint64_t delay = std::uint64_t{cfg_.delay_ms} * 1000;
  if (slow_until_ > now_us_) delay += slow_until_ - now_us_;
  const int copies = chance(cfg_.duplicate) ? 2 : 1;
  for (int i = 0; i < copies; ++i) {
    const std::uint64_t d = delay + static_cast<std::uint64_t>(i) * 1000;
    if (cfg_.split && stream_link && f.size() > 1) {
      const std::size_t cut = f.size() / 2;
      out.push_back(Emission{f.substr(0, cut), d});
      out.push_back(Emission{f.substr(cut), d + 2000});
    } else {
      out.push_back(Emission{f, d});
    }
  }
}

}  // namespace topsim
