// The checks of sections 3 to 9 of topconf drive (docs/DRIVE.md): identity,
// tracking, errors, transport, line, replies, clock.
#include <cmath>
#include <cstdio>

#include "checks.hpp"
#include "top/decode.hpp"
#include "top/diagnoses.hpp"
#include "top/frame.hpp"

namespace topconf::drive::detail {
namespace {

// The stream kept on and the rate intent served (3.x, 5.1).
void served(Judge& j, const Record& r) {
  const std::vector<double> t = attitude_times(r);
  if (!t.empty() && t.back() >= r.duration_s - 1.0)
    j.pass("stream kept", "attitude reports until " + secs(t.back()));
  else
    j.fail("stream kept", t.empty() ? "the device never reported an attitude (the stream never "
                                      "switched on)"
                                    : "the last attitude report came at " + secs(t.back()));
  const auto go = intent_at(r, "rate"), stop = intent_at(r, "stop");
  if (!go) return;
  const int n = moving_frames(r, *go, stop.value_or(r.duration_s) + 0.3);
  if (n > 0)
    j.pass("motion served", std::to_string(n) + " rate commands for the rate intent");
  else
    j.fail("motion served", "no rate command after the rate intent at " + secs(*go));
}

// The version or model the driver reports against the device's (`device`
// empty: the device never answered, unknown is right).
void identity(Judge& j, const Record& r, const char* key, std::string_view device, bool version) {
  if (r.beliefs.empty()) return;
  const auto v = last_belief(r, key);
  const std::string name = std::string(key) + " belief";
  const std::string dev(device);
  const bool placeholder = !dev.empty() && dev.find_first_not_of('0') == std::string::npos;
  const bool unknown = !v || *v == "unknown" || v->empty();
  if (unknown && (dev.empty() || placeholder))
    j.pass(name, dev.empty() ? "reported unknown: the device never answered"
                             : "reported unknown for the placeholder '" + dev + "'");
  else if (unknown)
    j.add(Grade::non_strict, name, true, "reported unknown (the device answered '" + dev + "')");
  else if (dev.empty())
    j.fail(name, "'" + *v + "', but the device never answered");
  else if (!version && *v == dev && placeholder)
    j.add(Grade::non_strict, name, true, "the placeholder '" + *v + "' reported as the model");
  else if (same_identity(*v, device, version))
    j.pass(name, "'" + *v + "', the device answered '" + dev + "'");
  else
    j.fail(name, "'" + *v + "', but the device answered '" + dev + "'");
}

// The attitude beliefs keep coming (no gap over 1 s) from `from` on.
void not_blocked(Judge& j, const Record& r, double from) {
  double prev = -1, worst = 0, at = 0;
  for (const Belief& b : r.beliefs) {
    if (!b.line.contains("attitude") || b.t < from) continue;
    if (prev >= 0 && b.t - prev > worst) worst = b.t - prev, at = prev;
    prev = b.t;
  }
  if (prev < 0) {
    j.add(Grade::unimplemented, "beliefs keep coming", false, "no attitude belief");
    return;
  }
  if (r.duration_s - prev - 0.3 > worst) worst = r.duration_s - 0.3 - prev, at = prev;
  if (worst > 1.0)
    j.fail("beliefs keep coming", "no attitude belief for " + secs(worst) + " from " + secs(at));
  else
    j.pass("beliefs keep coming", "never more than " + secs(worst) + " apart");
}

void tight_loop(Judge& j, const Record& r, std::string_view ident) {
  const int n = most_per_second(r, ident);
  const std::string name = "no tight retry of " + std::string(ident);
  if (n > 5)
    j.fail(name, std::to_string(n) + " in one second");
  else
    j.pass(name, "at most " + std::to_string(n) + " in any second");
}

// The month of the driver's clock writes.
void clock(Judge& j, const Record& r, top::Model model) {
  top::DecodeOptions o;
  o.dialect = top::dialect_of(model);
  o.model = model;
  o.role = top::Role::request;
  int seen = 0;
  for (const WireFrame& w : r.wire) {
    if (!w.from_driver || w.control != 'w') continue;
    const top::ParseResult p = top::parse_exact(w.raw);
    if (p.status != top::ParseStatus::frame || !top::carries_date(w.ident)) continue;
    const top::Decoded d = top::decode(p.frame, o);
    const auto dt = d.form ? top::date_time_of(*d.form, w.data) : std::nullopt;
    if (!dt) continue;
    ++seen;
    if (dt->month != 12)
      j.fail("month 1-based", w.ident + " sent month " + std::to_string(dt->month) +
                                  " for 2026-12-06 (" + w.raw + ")");
    else
      j.pass("month 1-based", w.ident + " sent month 12 for 2026-12-06");
  }
  if (!seen) j.add(Grade::unimplemented, "month 1-based", false, "no clock write on the wire");
}

}  // namespace

void grade_other(Judge& j, const CaseSpec& c, top::Model model, topsim::TransportKind link,
                 const Record& r) {
  const std::string id(c.id);
  const Idents ids = idents_of(model);
  if (id[0] == '3') {
    served(j, r);
    if (id == "3.1" || id == "3.4") identity(j, r, "model", r.model, false);
    if (id == "3.2" || id == "3.3") identity(j, r, "version", r.version, true);
    if (id == "3.4") not_blocked(j, r, 0.5);
  } else if (id == "4.1") {
    const auto t = last_belief(r, "tracking");
    bool tracking = false;
    for (const Belief& b : r.beliefs)
      tracking = tracking || b.line.value("tracking", nlohmann::json()) == "tracking";
    if (tracking)
      j.fail("never tracking", "the driver believed it tracks a target the device refused");
    else if (!t)
      j.add(Grade::unimplemented, "never tracking", false, "no tracking belief");
    else
      j.pass("never tracking", "last tracking belief '" + *t + "'");
  } else if (id == "5.1") {
    if (most_per_second(r, "CAP") == 0)
      j.add(Grade::unimplemented, "photo", false, "no photo command on the wire");
    tight_loop(j, r, "CAP");
    served(j, r);
  } else if (id == "6.4") {
    int u = 0, n = 0;
    for (const WireFrame& w : r.wire)
      if (w.from_driver) ++n, u += w.src == 'U';
    (void)link;
    if (n == 0)
      j.add(Grade::unimplemented, "network address", false, "the driver sent nothing");
    else if (u)
      j.fail("network address", std::to_string(u) + " of " + std::to_string(n) +
                                    " requests name the UART source U on a network link");
    else
      j.pass("network address", std::to_string(n) + " requests, none with the UART source U");
  } else if (id[0] == '6' || id[0] == '7') {
    j.beliefs(r, 0.5);
    if (id == "6.3") tight_loop(j, r, "CAP");
  } else if (id == "8.1" || id == "8.2") {
    not_blocked(j, r, 0.5);
    identity(j, r, "version", id == "8.2" ? std::string() : r.version, true);
    if (id == "8.2") tight_loop(j, r, ids.version);
  } else if (id == "8.3") {
    double last = -1;
    bool any = false;
    for (const Belief& b : r.beliefs)
      if (auto v = b.line.find("range_m"); v != b.line.end() && v->is_number())
        last = v->get<double>(), any = true;
    char t[120];
    std::snprintf(t, sizeof t, "the driver's range %.2f m, the device's %.2f m", last, r.range_m);
    if (!any)
      j.add(Grade::unimplemented, "range", false, "no range belief");
    else if (std::abs(last - r.range_m) <= 0.1)
      j.pass("range", t);
    else
      j.fail("range", t);
  } else if (id == "9.1") {
    clock(j, r, model);
  }
}

}  // namespace topconf::drive::detail
