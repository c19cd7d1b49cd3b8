#include "sim/faults.hpp"

#include <charconv>
#include <cstdlib>

#include "device_faults.hpp"

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

// `frame` built again through BuildSpec with a lying length (one data char
// fewer declared, the checksum right for the bytes sent: the C12
// "#tpDU3rVER010502" shape) and/or its header's case flipped after the
// checksum (#TP sent, summed as #tp: the SkyDroid errata). Only a #TP/#tp
// frame with a good checksum changes; a lie needs a one-digit length and
// 2 to 15 data chars.
std::string malformed(const std::string& frame, bool lie, bool flip) {
  const top::ParseResult r = top::parse_exact(frame);
  const top::Frame& f = r.frame;
  if (r.status != top::ParseStatus::frame || !f.checksum_ok ||
      (f.header != top::Header::fixed && f.header != top::Header::variable))
    return frame;
  top::BuildSpec spec{.header = f.header,
                      .src = f.src,
                      .dst = f.dst,
                      .control = f.control,
                      .ident = f.ident_view(),
                      .data = f.data(),
                      // "#tpDU16wTMP...": the two-digit TMP form keeps its length.
                      .two_digit_length = f.data_offset > top::prefix_size};
  lie = lie && !spec.two_digit_length && spec.data.size() >= 2 &&
        spec.data.size() <= top::max_data_hex;
  if (!lie && !flip) return frame;
  if (lie) spec.declared_length = static_cast<std::uint32_t>(spec.data.size() - 1);
  if (flip) {
    spec.checksum_header = f.header;
    spec.header = f.header == top::Header::fixed ? top::Header::variable : top::Header::fixed;
  }
  return top::build_frame(spec);
}

}  // namespace

bool FaultConfig::any() const noexcept {
  return drop > 0 || delay_ms > 0 || duplicate > 0 || bad_checksum > 0 || header_case > 0 ||
         no_swap || lying_length > 0 || tmp_quirk || split || garbage > 0 || !hang_on.empty() ||
         !ignore.empty() || crash_on || hang_class || slow_on || answer_corrupt || !late.empty() ||
         checksum_case > 0 || reboot_us > 0 || device.any();
}

const std::vector<std::string_view>& fault_names() {
  static const std::vector<std::string_view> names = {
      "drop", "delay", "duplicate", "bad-checksum", "header-case", "no-swap", "lying-length",
      "tmp-quirk", "split", "garbage", "hang-on", "crash-on", "hang-s", "slow-on", "slow-ms",
      "answer-corrupt", "ignore", "late", "checksum-case", "reboot",
      // the device faults (device_faults.cpp)
      "stall", "no-stream", "ignore-motion", "invert", "placeholder-identity", "refuse-tracking",
      "clock", "stop", "ere", "range-form"};
  return names;
}

std::string_view fault_usage() noexcept {
  return "faults: drop=P,delay=MS,duplicate=P,bad-checksum=P,header-case=P,no-swap,"
         "lying-length=P,tmp-quirk,split,garbage=P,hang-on=IDENT,ignore=CLASS[+CLASS] (no "
         "answer to those requests, e.g. ignore=VER+AWB); firmware faults (SIGHUP "
         "restarts the device): crash-on=CLASS,hang-on=CLASS,hang-s=S,slow-on=CLASS,"
         "slow-ms=MS,answer-corrupt, CLASS = ident:ID|len:N|byte:HH; device faults (each "
         "shows a diagnosis of topdump): stall=IDENT@T+S (the push IDENT stops T s after its "
         "switch-on, for S s), no-stream=IDENT (the switch is answered, no push comes), "
         "ignore-motion=IDENT[+IDENT] (echoed, nothing moves), invert=yaw|pitch|roll[:angle|:rate] "
         "(the axis moves opposite to the command), placeholder-identity (VER/MOD/VSN/PA2 "
         "answer 000000000, 0.0.0), refuse-tracking (TRC state 4), clock=month-early (TIM/UTC "
         "answered one month early), stop=IDENT@T (the stream switched off T s after its "
         "start, until switched on again), ere=IDENT (ERE to IDENT), range-form=short (LRF "
         "unpadded); for topconf drive: late=IDENT@MS (frames of IDENT MS later), "
         "checksum-case=P (lowercase checksum), reboot=S (power cycle after S s)";
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
    double* prob = name == "drop"            ? &cfg.drop
                   : name == "duplicate"     ? &cfg.duplicate
                   : name == "bad-checksum"  ? &cfg.bad_checksum
                   : name == "header-case"   ? &cfg.header_case
                   : name == "lying-length"  ? &cfg.lying_length
                   : name == "garbage"       ? &cfg.garbage
                   : name == "checksum-case" ? &cfg.checksum_case
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
    } else if (name == "ignore") {
      // CLASS+CLASS...: several classes in one item (a comma ends the item)
      for (std::size_t start = 0;;) {
        const std::size_t plus = value.find('+', start);
        auto c = parse_input_class(value.substr(
            start, plus == std::string_view::npos ? std::string_view::npos : plus - start));
        if (!c) return bad("ignore needs IDENT, ident:ID, len:N or byte:HH, joined by +");
        cfg.ignore.push_back(*c);
        if (plus == std::string_view::npos) break;
        start = plus + 1;
      }
    } else if (name == "late") {
      const std::size_t at = value.find('@');
      unsigned ms = 0;
      const std::string_view num = at == std::string_view::npos ? "" : value.substr(at + 1);
      auto [p, ec] = std::from_chars(num.data(), num.data() + num.size(), ms);
      if (at != 3 || num.empty() || ec != std::errc{} || p != num.data() + num.size() ||
          ms > 600000)
        return bad("late needs IDENT@MS: a three-character identifier, milliseconds 0-600000");
      cfg.late.push_back(FaultConfig::Late{std::string(value.substr(0, 3)), ms});
    } else if (name == "reboot") {
      std::string s(value);
      char* end = nullptr;
      const double sec = std::strtod(s.c_str(), &end);
      if (s.empty() || end != s.c_str() + s.size() || !(sec > 0 && sec <= 3600))
        return bad("reboot needs seconds, more than 0 and at most 3600");
      cfg.reboot_us = static_cast<std::uint64_t>(sec * 1e6 + 0.5);
    } else if (name == "answer-corrupt") {
      if (has_value) return bad("takes no value");
      cfg.answer_corrupt = true;
    } else {
      // the device faults (device_faults.cpp), then an unknown name
      std::string why;
      const auto p = detail::parse_device_fault(name, has_value, value, cfg.device, why);
      if (p == detail::Parsed::bad) return bad(why);
      if (p == detail::Parsed::ok) continue;
      std::string known;
      for (const std::string_view n : fault_names())
        known += (known.empty() ? "" : " ") + std::string(n);
      return bad("unknown fault (known: " + known + ")");
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
  for (const InputClass& c : cfg_.ignore)
    if (c.matches(request)) return false;
  if (!cfg_.hang_on.empty() && request.ident_view() == cfg_.hang_on) {
    hung_ = true;
    return false;
  }
  return true;
}

void FaultInjector::apply(const std::string& frame, bool stream_link, std::vector<Emission>& out) {
  if (hung() || chance(cfg_.drop)) return;
  // Draws for #TP/#tp/#tP/#Tp frames only, as it always has (the seed's
  // sequence depends on it).
  const bool plain = frame.size() >= top::prefix_size + 2 &&
                     top::header_from_string(std::string_view(frame).substr(0, 3)).has_value();
  const bool lie = plain && chance(cfg_.lying_length);
  const bool flip = plain && chance(cfg_.header_case);
  std::string f = lie || flip ? malformed(frame, lie, flip) : frame;
  // Corruption on the line, not a frame form: the last checksum digit of
  // whatever is sent (any header, the TMP form, a lying length) changes.
  if (chance(cfg_.bad_checksum) && f.size() >= 2 && is_hex_upper(f[f.size() - 1])) {
    char& c = f[f.size() - 1];
    c = c == '0' ? '1' : '0';
  }
  // checksum-case: the checksum's letters in lowercase (a parser that
  // compares the text, not the value, drops the frame).
  if (chance(cfg_.checksum_case) && f.size() >= 2)
    for (std::size_t i = f.size() - 2; i < f.size(); ++i)
      if (f[i] >= 'A' && f[i] <= 'F') f[i] = static_cast<char>(f[i] - 'A' + 'a');
  if (chance(cfg_.garbage)) f.insert(0, "\x01\xFFzz%");
  std::uint64_t delay = std::uint64_t{cfg_.delay_ms} * 1000;
  // late=: a frame of the identifier (#TP/#tp: at offset 7) leaves later.
  if (plain && f.size() >= top::prefix_size)
    for (const FaultConfig::Late& l : cfg_.late)
      if (std::string_view(frame).substr(top::prefix_size - 3, 3) == l.ident)
        delay += std::uint64_t{l.ms} * 1000;
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
