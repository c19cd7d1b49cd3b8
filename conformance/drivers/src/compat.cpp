// The verdict a vendor reads: compatible, compatible without: <features>,
// incompatible: <reasons>, from a run of a profile's matrix.
#include "drivers/compat.hpp"

#include <algorithm>
#include <iterator>

#include "top/enum_names.hpp"

namespace drivers {

namespace {

constexpr std::string_view kGrade[] = {"must", "should", "info"};
static_assert(std::size(kGrade) == static_cast<std::size_t>(Grade::info) + 1);

constexpr std::string_view kLinkKind[] = {"serial", "udp", "tcp"};
static_assert(std::size(kLinkKind) == static_cast<std::size_t>(LinkKind::tcp) + 1);

constexpr std::string_view kLevel[] = {"compatible", "compatible without", "incompatible",
                                       "unreachable"};
static_assert(std::size(kLevel) == static_cast<std::size_t>(Compatibility::Level::unreachable) + 1);

std::string joined(const std::vector<std::string>& v, std::string_view sep) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : std::string(sep)) + s;
  return out;
}

void add_once(std::vector<std::string>& v, std::string s) {
  if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(std::move(s));
}

}  // namespace

std::string_view to_string(Grade g) noexcept { return top::enum_name(kGrade, g, "info"); }
std::string_view to_string(LinkKind k) noexcept { return top::enum_name(kLinkKind, k, "udp"); }
std::string_view to_string(Compatibility::Level l) noexcept {
  return top::enum_name(kLevel, l, "unreachable");
}

std::string Compatibility::text() const {
  // the verdict's name, then what it lists: the features lost or the reasons
  const std::string name(to_string(level));
  if (level == Level::compatible) return name;
  return name + ": " + (level == Level::without ? joined(features, ", ") : joined(reasons, "; "));
}

int Compatibility::exit_code() const noexcept {
  switch (level) {
    case Level::compatible:
    case Level::without:
      return 0;
    case Level::incompatible:
      return 1;
    default:
      return 2;
  }
}

Compatibility assess(const Profile& p, const topconf::RunResult& run) {
  Compatibility c;
  c.profile = &p;
  c.model = run.model;
  if (run.unreachable) {
    c.level = Compatibility::Level::unreachable;
    c.reasons.push_back(run.unreachable_reason);
    return c;
  }
  for (const Need& n : p.needs) {
    NeedResult r;
    r.need = &n;
    const std::string id = case_id(p, n);
    const auto it = std::find_if(run.cases.begin(), run.cases.end(),
                                 [&](const topconf::CaseResult& k) { return k.spec->id == id; });
    if (it == run.cases.end()) continue;  // not selected (--case)
    r.verdict = it->verdict;
    r.reason = it->reason;
    r.served = it->verdict == topconf::Verdict::pass || it->verdict == topconf::Verdict::non_strict;
    r.outcome = std::string(n.reasoning) + "; this device: " +
                (r.served ? std::string("served") + (r.reason.empty() ? "" : " (" + r.reason + ")")
                          : r.reason + ": " + std::string(n.lost));
    if (!r.served && n.grade == Grade::must)
      add_once(c.reasons, std::string(n.feature) + ": " + std::string(n.lost));
    if (!r.served && n.grade == Grade::should) add_once(c.features, std::string(n.feature));
    c.needs.push_back(std::move(r));
  }
  c.level = !c.reasons.empty()    ? Compatibility::Level::incompatible
            : !c.features.empty() ? Compatibility::Level::without
                                  : Compatibility::Level::compatible;
  return c;
}

nlohmann::json to_json(const Compatibility& c) {
  nlohmann::json j;
  j["driver"] = c.profile ? std::string(c.profile->name) : "";
  j["title"] = c.profile ? std::string(c.profile->title) : "";
  j["model"] = std::string(top::to_string(c.model));
  j["verdict"] = std::string(to_string(c.level));
  j["text"] = c.text();
  j["exit_code"] = c.exit_code();
  j["features_lost"] = c.features;
  j["reasons"] = c.reasons;
  j["needs"] = nlohmann::json::array();
  for (const NeedResult& r : c.needs)
    j["needs"].push_back({{"id", std::string(r.need->id)},
                          {"case", case_id(*c.profile, *r.need)},
                          {"feature", std::string(r.need->feature)},
                          {"grade", std::string(to_string(r.need->grade))},
                          {"result", std::string(topconf::to_string(r.verdict))},
                          {"served", r.served},
                          {"protects", std::string(r.need->reasoning)},
                          {"outcome", r.outcome}});
  if (c.profile) j["profile"] = to_json(*c.profile);
  return j;
}

nlohmann::json to_json(const Profile& p) {
  auto src = [&](int i) { return to_string(p.sources.at(static_cast<std::size_t>(i))); };
  nlohmann::json j;
  j["name"] = std::string(p.name);
  j["title"] = std::string(p.title);
  j["models"] = nlohmann::json::array();
  for (top::Model m : p.models) j["models"].push_back(std::string(top::to_string(m)));
  j["link"] = {{"kind", std::string(to_string(p.link.kind))},
               {"note", std::string(p.link.note)},
               {"source", src(p.link.source)}};
  if (p.link.baud) j["link"]["baud"] = p.link.baud;
  if (p.link.device_port) j["link"]["device_port"] = p.link.device_port;
  if (p.link.listen_port) j["link"]["listen_port"] = p.link.listen_port;
  j["tick_ms"] = p.tick_ms;
  j["sources"] = nlohmann::json::array();
  for (std::size_t i = 0; i < p.sources.size(); ++i)
    j["sources"].push_back(src(static_cast<int>(i)));
  for (const Sent& s : p.sends) {
    nlohmann::json k = {{"ident", std::string(s.ident)},
                        {"control", std::string(1, s.control)},
                        {"data", std::string(s.data)},
                        {"header", s.fixed ? "#TP" : "#tp"},
                        {"hz", s.hz},
                        {"source", src(s.source)}};
    if (s.slot >= 0) k["round_robin_step"] = s.slot;
    if (s.until_answered) k["until_answered"] = true;
    if (!s.note.empty()) k["note"] = std::string(s.note);
    j["sends"].push_back(k);
  }
  for (const auto& [text, i] : p.parsing)
    j["parsing"].push_back({{"fact", std::string(text)}, {"source", src(i)}});
  for (std::string_view u : p.unchecked) j["unchecked"].push_back(std::string(u));
  for (const Need& n : p.needs)
    j["needs"].push_back({{"id", std::string(n.id)},
                          {"feature", std::string(n.feature)},
                          {"grade", std::string(to_string(n.grade))},
                          {"reasoning", std::string(n.reasoning)},
                          {"lost", std::string(n.lost)},
                          {"source", src(n.source)}});
  return j;
}

}  // namespace drivers
