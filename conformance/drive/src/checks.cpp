#include "checks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "top/motion.hpp"

namespace topconf::drive::detail {

std::string secs(double t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f s", t);
  return b;
}

std::vector<double> attitude_times(const Record& r) {
  std::vector<double> v;
  for (const WireFrame& w : r.wire)
    if (!w.from_driver && w.attitude) v.push_back(w.t);
  return v;
}

std::optional<Gap> longest_gap(const Record& r, double from) {
  const std::vector<double> t = attitude_times(r);
  std::optional<Gap> best;
  double prev = -1;
  for (double x : t) {
    if (x < from) {
      prev = x;
      continue;
    }
    if (prev >= 0 && (!best || x - prev > best->length())) best = Gap{prev, x};
    prev = x;
  }
  if (prev >= 0 && (!best || r.duration_s - prev > best->length())) best = Gap{prev, r.duration_s};
  return best;
}

bool moving(const WireFrame& w) {
  if (!w.rate) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if (w.axis[i] && std::abs(w.value[i]) > 1e-9) return true;
  return false;
}

int moving_frames(const Record& r, double from, double to) {
  int n = 0;
  for (const WireFrame& w : r.wire)
    if (w.from_driver && w.t > from && w.t <= to && moving(w)) ++n;
  return n;
}

bool stopping(const WireFrame& w) { return w.rate && !moving(w); }

std::optional<double> intent_at(const Record& r, std::string_view what) {
  for (const Intent& i : r.intents)
    if (i.what() == what) return i.t;
  return std::nullopt;
}

namespace {

// The health a belief line states: its `healthy`, else healthy when it
// carries an attitude and nothing was said before.
std::optional<bool> stated(const nlohmann::json& j, std::optional<bool> before) {
  if (auto h = j.find("healthy"); h != j.end() && h->is_boolean()) return h->get<bool>();
  if (j.contains("attitude") && !before) return true;
  return before;
}

bool attitude_of(const nlohmann::json& j, double out[3]) {
  auto a = j.find("attitude");
  if (a == j.end() || !a->is_object()) return false;
  const char* keys[3] = {"yaw", "pitch", "roll"};
  for (int i = 0; i < 3; ++i) {
    auto v = a->find(keys[i]);
    out[i] = v != a->end() && v->is_number() ? v->get<double>() : 0.0;
  }
  return true;
}

}  // namespace

std::optional<bool> healthy_at(const Record& r, double t) {
  std::optional<bool> h;
  for (const Belief& b : r.beliefs) {
    if (b.t > t) break;
    h = stated(b.line, h);
  }
  return h;
}

bool unhealthy_in(const Record& r, double from, double to) {
  std::optional<bool> h;
  for (const Belief& b : r.beliefs) {
    h = stated(b.line, h);
    if (b.t > from && b.t <= to && h && !*h) return true;
  }
  return false;
}

bool healthy_in(const Record& r, double from, double to) {
  std::optional<bool> h;
  for (const Belief& b : r.beliefs) {
    h = stated(b.line, h);
    if (b.t > from && b.t <= to && h && *h && b.line.contains("attitude")) return true;
  }
  return false;
}

const Truth* truth_at(const Record& r, double t) {
  const Truth* best = nullptr;
  for (const Truth& x : r.truth)
    if (!best || std::abs(x.t - t) < std::abs(best->t - t)) best = &x;
  return best;
}

BeliefCheck beliefs_follow_truth(const Record& r, double from) {
  BeliefCheck out;
  out.check.name = "belief within 2 deg of the truth";
  std::optional<bool> h;
  int judged = 0, unhealthy = 0;
  for (const Belief& b : r.beliefs) {
    h = stated(b.line, h);
    double a[3];
    if (b.t < from || !attitude_of(b.line, a)) {
      if (b.t >= from && h && !*h) ++unhealthy;
      continue;
    }
    if (h && !*h) {
      ++unhealthy;
      continue;
    }
    // The truth the driver could have seen: up to 0.6 s before (its stream
    // and its own cadence), the closest, between the 50 ms samples too
    // (a fast axis moves degrees between two).
    double best = 1e9;
    Truth at{};
    bool found = false;
    for (std::size_t k = 0; k + 1 < r.truth.size(); ++k) {
      const Truth &x0 = r.truth[k], &x1 = r.truth[k + 1];
      if (x1.t < b.t - 0.6 || x0.t > b.t + 0.1) continue;
      for (int step = 0; step <= 10; ++step) {
        const double f = step / 10.0;
        Truth x = x0;
        x.t = x0.t + f * (x1.t - x0.t);
        for (int i = 0; i < 3; ++i)
          x.angle[i] = x0.angle[i] + f * (i == 0 ? top::short_way(x1.angle[i] - x0.angle[i])
                                                 : x1.angle[i] - x0.angle[i]);
        double e = 0;
        for (int i = 0; i < 3; ++i)
          e = std::max(e, std::abs(i == 0 ? top::short_way(a[i] - x.angle[i]) : a[i] - x.angle[i]));
        if (e < best) best = e, at = x, found = true;
      }
    }
    if (!found) continue;
    ++judged;
    if (best > 2.0) {
      char d[200];
      std::snprintf(d, sizeof d,
                    "at %.2f s the driver believed yaw %.1f pitch %.1f roll %.1f, healthy; the "
                    "device was at yaw %.1f pitch %.1f roll %.1f (%.1f deg off)",
                    b.t, a[0], a[1], a[2], at.angle[0], at.angle[1], at.angle[2], best);
      out.grade = Grade::fail;
      out.check.detail = d;
      return out;
    }
  }
  if (judged == 0 && unhealthy == 0) {
    out.grade = Grade::unimplemented;
    out.check.detail = "no attitude or health belief after " + secs(from);
    return out;
  }
  out.check.ok = true;
  out.check.detail = std::to_string(judged) + " attitude beliefs within 2 deg, " +
                     std::to_string(unhealthy) + " unhealthy";
  return out;
}

std::optional<std::string> last_belief(const Record& r, const char* key) {
  std::optional<std::string> v;
  for (const Belief& b : r.beliefs) {
    auto it = b.line.find(key);
    if (it == b.line.end()) continue;
    v = it->is_string() ? it->get<std::string>() : it->is_null() ? "unknown" : it->dump();
  }
  return v;
}

namespace {

std::vector<long> numbers_of(std::string_view s) {
  std::vector<long> v;
  std::size_t i = 0;
  while (i < s.size() && !std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  while (i < s.size()) {
    long n = 0;
    std::size_t j = i;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j])) && j - i < 9)
      n = n * 10 + (s[j++] - '0');
    if (j == i) break;
    v.push_back(n);
    if (j >= s.size() || s[j] != '.') break;
    i = j + 1;
  }
  return v;
}

}  // namespace

bool same_identity(std::string_view belief, std::string_view device, bool version) {
  if (belief == device) return true;
  if (!version) return false;
  std::string_view d = device;
  if (!d.empty() && (d.front() == 'V' || d.front() == 'v')) d.remove_prefix(1);
  if (belief == d) return true;
  std::vector<long> want = numbers_of(d), got = numbers_of(belief);
  if (want.empty() || got.empty()) return false;
  // "123": three digits without a dot, read as 1.2.3 (AP_Mount_Topotek's form).
  if (d.find('.') == std::string_view::npos && d.size() > 1) {
    std::vector<long> split;
    for (char c : d)
      if (std::isdigit(static_cast<unsigned char>(c))) split.push_back(c - '0');
    return got == want || got == split;
  }
  while (got.size() > want.size() && got.back() == 0) got.pop_back();
  return got == want;
}

namespace {
int rank(Grade g) {
  switch (g) {
    case Grade::pass:
      return 0;
    case Grade::non_strict:
    case Grade::informational:
      return 1;
    case Grade::unimplemented:
      return 2;
    case Grade::fail:
      return 3;
    case Grade::error:
      return 4;
  }
  return 4;
}
}  // namespace

void Judge::add(Grade g, std::string name, bool ok, std::string detail) {
  if (rank(g) > rank(v.grade) ||
      (g != Grade::pass && rank(g) == rank(v.grade) && v.reason.empty())) {
    v.grade = g;
    v.reason = name + ": " + detail;
  }
  v.checks.push_back(Check{std::move(name), ok, std::move(detail)});
}

void Judge::beliefs(const Record& r, double from) {
  const BeliefCheck b = beliefs_follow_truth(r, from);
  add(b.grade, b.check.name, b.check.ok, b.check.detail);
}

int most_per_second(const Record& r, std::string_view ident) {
  std::vector<double> t;
  for (const WireFrame& w : r.wire)
    if (w.from_driver && w.ident == ident) t.push_back(w.t);
  int most = 0;
  for (std::size_t i = 0, j = 0; j < t.size(); ++j) {
    while (t[j] - t[i] >= 1.0) ++i;
    most = std::max(most, static_cast<int>(j - i + 1));
  }
  return most;
}

}  // namespace topconf::drive::detail
