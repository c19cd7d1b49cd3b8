// A profile's needs as a topconf matrix: the JSON `topconf generate`
// writes (conformance/matrix.schema.json), loaded by the one loader.
#include <string>

#include "drivers/compat.hpp"
#include "top/motion.hpp"

namespace drivers {

namespace {

using json = nlohmann::ordered_json;

// A grade as the matrix's level: must and should are its own, info is may.
topconf::Level level_of(Grade g) noexcept {
  return g == Grade::must     ? topconf::Level::must
         : g == Grade::should ? topconf::Level::should
                              : topconf::Level::may;
}

json send_of(const Need& n, std::string_view ident, std::string_view data, char control) {
  json s = {{"command", std::string(ident)},
            {"control", std::string(1, control)},
            {"data", std::string(data)}};
  if (n.send_dst) s["dst"] = std::string(1, n.send_dst);
  s["header"] = n.send_fixed ? "#TP" : "#tp";
  return s;
}

json request_of(const Need& n) {
  if (!n.raw_hex.empty()) return {{"hex", std::string(n.raw_hex)}};
  if (!n.raw.empty()) return {{"raw", std::string(n.raw)}};
  return send_of(n, n.send_ident, n.send_data, n.send_control);
}

json with_addresses(json e, const Need& n) {
  if (n.any_addresses) e["addresses"] = "any";
  return e;
}

// What the case accepts: the forms the driver reads, nothing tolerated.
json expect_of(const Need& n) {
  switch (n.check) {
    case Check::stream: {
      // min_hz..max_hz as a rate and a fraction of it.
      json st = {{"ident", std::string(n.ident)},
                 {"rate_hz", (n.min_hz + n.max_hz) / 2},
                 {"tolerance", (n.max_hz - n.min_hz) / (n.max_hz + n.min_hz)},
                 {"duration_ms", n.window_ms}};
      if (!n.pattern.empty()) st["data_pattern"] = std::string(n.pattern);
      if (n.max_gap_ms) st["max_gap_ms"] = n.max_gap_ms;
      if (n.move_axis >= 0)
        st["moves"] = {{"axis", std::string(top::to_string(static_cast<top::Axis>(n.move_axis)))},
                       {"sign", n.move_sign},
                       {"min_deg", n.move_min_deg}};
      return json::array({json{{"stream", st}}});
    }
    case Check::taken: {
      const std::string why = "taken: no ERE";
      return json::array(
          {with_addresses(json{{"echo", true}, {"note", why}}, n),
           with_addresses(json{{"reply", {{"ident", std::string(n.ident)}}}, {"note", why}}, n),
           json{{"silence_ms", 100}, {"note", why}}});
    }
    default: {
      json r = {{"ident", std::string(n.ident)}};
      if (!n.pattern.empty()) r["data_pattern"] = std::string(n.pattern);
      return json::array({with_addresses(json{{"reply", r}}, n)});
    }
  }
}

}  // namespace

std::string case_id(const Profile& p, const Need& n) {
  return "driver/" + std::string(p.name) + "/" + std::string(n.id);
}

json driver_matrix_json(const Profile& p, top::Model model) {
  json m;
  m["$schema"] = "../matrix.schema.json";
  m["format"] = "topconf-matrix-1";
  m["title"] = "What " + std::string(p.title) + " needs (generated from its driver profile)";
  m["model"] = std::string(top::to_string(model));
  m["defaults"] = {
      {"timeout_ms", 300}, {"retries", 1}, {"settle_ms", 15}, {"probe_timeout_ms", 500}};
  json cases = json::array();
  for (const Need& n : p.needs) {
    json step = {{"expect", expect_of(n)}};
    if (!n.send_ident.empty() || !n.raw.empty() || !n.raw_hex.empty()) step["send"] = request_of(n);
    if (n.check == Check::reply && n.window_ms) step["timeout_ms"] = n.window_ms;
    json steps = json::array();
    if (!n.on_ident.empty())
      steps.push_back(
          {{"send", send_of(n, n.on_ident, n.on_data, 'w')},
           {"expect",
            json::array({json{{"silence_ms", 1}, {"note", "switch-on"}},
                         json{{"echo", true}, {"addresses", "any"}, {"note", "switch-on"}}})}});
    steps.push_back(step);
    if (!n.cleanup_ident.empty())
      steps.push_back(
          {{"send", send_of(n, n.cleanup_ident, n.cleanup_data, 'w')},
           {"expect", json::array({json{{"silence_ms", 1}, {"note", "clean-up"}},
                                   json{{"echo", true}, {"addresses", "any"}, {"note", "clean-up"}},
                                   json{{"reply", {{"ident", std::string(n.cleanup_ident)}}},
                                        {"addresses", "any"},
                                        {"note", "clean-up"}}})}});
    json k = {{"id", case_id(p, n)},
              {"section", to_string(p.sources.at(static_cast<std::size_t>(n.source)))},
              {"title", std::string(n.reasoning)},
              {"level", std::string(topconf::to_string(level_of(n.grade)))},
              {"tags", json::array({"driver", std::string(p.name), std::string(n.id),
                                    std::string(to_string(n.grade))})},
              {"steps", steps}};
    // A stream that stalls once is what the driver lives through: no retry.
    if (n.check == Check::stream) k["retries"] = 0;
    cases.push_back(std::move(k));
  }
  m["cases"] = cases;
  return m;
}

topconf::LoadResult driver_matrix(const Profile& p, top::Model model) {
  return topconf::load_matrix(driver_matrix_json(p, model).dump(), "driver:" + std::string(p.name));
}

}  // namespace drivers
