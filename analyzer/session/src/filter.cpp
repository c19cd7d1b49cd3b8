// The command line's selection of frames, garbage and findings.
#include <algorithm>
#include <charconv>
#include <cmath>

#include "session/analyzer.hpp"

namespace topdump {

namespace {
std::string_view host_of(std::string_view ep) {
  if (!ep.empty() && ep.front() == '[') {
    auto e = ep.find(']');
    return e == std::string_view::npos ? ep : ep.substr(1, e - 1);
  }
  auto c = ep.rfind(':');
  return c == std::string_view::npos ? ep : ep.substr(0, c);
}
// "10.0.0.1", "10.0.0.1:5000", "fd00::10", "[fd00::10]", "[fd00::10]:5000"
bool endpoint_matches(std::string_view want, std::string_view ep) {
  if (want == ep || want == host_of(ep)) return true;
  return want.size() > 2 && want.front() == '[' && want.back() == ']' &&
         want.substr(1, want.size() - 2) == host_of(ep);
}
char upper(char c) noexcept { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; }
bool same_ident_nocase(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}
bool endpoints_match(const std::vector<std::string>& addrs, const std::string* from,
                     const std::string* to) {
  for (const std::string& a : addrs)
    if (a.size() > 1 && ((from && endpoint_matches(a, *from)) || (to && endpoint_matches(a, *to))))
      return true;
  return false;
}
bool letters_match(const std::vector<std::string>& addrs, char src, char dst) {
  for (const std::string& a : addrs)
    if (a.size() == 1 && (src == a[0] || dst == a[0])) return true;
  return false;
}
}  // namespace

std::optional<std::int64_t> parse_duration(std::string_view s) {
  double v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end == s.data() || !std::isfinite(v) || v < 0) return std::nullopt;
  const std::string_view unit(end, static_cast<std::size_t>(s.data() + s.size() - end));
  double scale = 0;
  if (unit.empty() || unit == "s") scale = 1e6;
  if (unit == "ms") scale = 1e3;
  if (unit == "us") scale = 1;
  if (scale == 0 || v * scale > 9e18) return std::nullopt;
  return static_cast<std::int64_t>(std::llround(v * scale));
}

bool Filter::selects_time(std::int64_t ts) const {
  if (ts == kNoTime) return from == kNoTime && to == kNoTime;
  if (from != kNoTime && ts < from) return false;
  if (to != kNoTime && ts > to) return false;
  return true;
}

bool Filter::selects_ident(std::string_view ident) const {
  if (idents.empty()) return true;
  for (const std::string& i : idents)
    if (same_ident_nocase(i, ident)) return true;
  return false;
}

bool Filter::active() const {
  return !idents.empty() || !addrs.empty() || severity_set || from != kNoTime || to != kNoTime ||
         from_rel != kNoTime || to_rel != kNoTime || !findings.empty() || !afindings.empty() ||
         !mute.empty() || !amute.empty() || max_frames != 0;
}

void Filter::start_at(std::int64_t first) {
  if (first == kNoTime) return;
  if (from_rel != kNoTime) from = first + from_rel;
  if (to_rel != kNoTime) to = first + to_rel;
  from_rel = to_rel = kNoTime;
}

bool Filter::add_code(std::string_view name, bool muted) {
  if (auto c = top::finding_code_from_string(name)) {
    (muted ? mute : findings).push_back(*c);
    return true;
  }
  if (auto c = acode_from_string(name)) {
    (muted ? amute : afindings).push_back(*c);
    return true;
  }
  return false;
}

bool Filter::selects(const FrameEvent& e) const {
  const top::Frame& f = *e.entry->frame;
  if (!selects_ident(f.ident_view())) return false;
  if (!addrs.empty() && !letters_match(addrs, f.src, f.dst) &&
      !endpoints_match(addrs, e.from, e.to))
    return false;
  if (severity_set && e.worst() < min_severity) return false;
  if (!findings.empty() || !afindings.empty()) {
    bool any = false;
    for (const top::Finding& x : f.findings)
      any |= std::find(findings.begin(), findings.end(), x.code) != findings.end();
    for (const top::Finding& x : e.entry->decoded.findings)
      any |= std::find(findings.begin(), findings.end(), x.code) != findings.end();
    for (const Note& n : e.notes)
      any |= std::find(afindings.begin(), afindings.end(), n.code) != afindings.end();
    if (!any) return false;
  }
  return selects_time(e.ts);
}

bool Filter::selects(const NoteEvent& e) const {
  const Note& n = e.note;
  if (mutes(n.code)) return false;
  if (severity_set && n.severity < min_severity) return false;
  if ((!findings.empty() || !afindings.empty()) &&
      std::find(afindings.begin(), afindings.end(), n.code) == afindings.end())
    return false;
  if (!e.conv) return true;  // about the capture file
  if (!idents.empty() && (n.ident[0] == 0 || !selects_ident(std::string_view(n.ident, 3))))
    return false;
  if (!addrs.empty() && !letters_match(addrs, n.src, n.dst) &&
      !endpoints_match(addrs, e.from, e.to))
    return false;
  return e.ts == kNoTime || selects_time(e.ts);
}

bool Filter::selects(const GarbageEvent& e) const {
  const top::Finding& x = e.item->finding;
  if (mutes(x.code)) return false;
  if (!idents.empty()) return false;  // garbage has no identifier
  if (!addrs.empty() && !endpoints_match(addrs, e.from, e.to)) return false;
  if (severity_set && x.severity < min_severity) return false;
  if ((!findings.empty() || !afindings.empty()) &&
      std::find(findings.begin(), findings.end(), x.code) == findings.end())
    return false;
  return selects_time(e.ts);
}

}  // namespace topdump
