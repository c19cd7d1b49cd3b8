// The matrix loader's JSON helpers (private to conf/matrix/): the error
// context, key and value checks shared by the parsers of matrix.cpp and
// matrix_expect.cpp.
#pragma once

#include <cctype>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "conf/matrix.hpp"

namespace topconf::detail {

using json = nlohmann::json;

struct Ctx {
  std::string file;
  std::string case_id;
  std::vector<std::string>* errors;
  void err(const std::string& key, const std::string& msg) const {
    std::string s = file + ": ";
    if (!case_id.empty()) s += "case " + case_id + ": ";
    s += key + ": " + msg;
    if (errors->size() < 200) errors->push_back(std::move(s));
  }
  // Whether `o` is a JSON object; an error at `key` if not (`msg`: what it
  // must be).
  bool object(const json& o, const std::string& key,
              const std::string& msg = "must be an object") const {
    if (!o.is_object()) err(key, msg);
    return o.is_object();
  }
};

inline void only_keys(const Ctx& c, const json& o, const std::string& where,
                      std::initializer_list<std::string_view> keys) {
  for (auto it = o.begin(); it != o.end(); ++it) {
    bool ok = false;
    for (auto k : keys) ok = ok || it.key() == k;
    if (!ok) c.err(where + (where.empty() ? "" : ".") + it.key(), "unknown key");
  }
}

inline bool get_string(const Ctx& c, const json& o, const std::string& where, const char* key,
                       std::string& out, bool required) {
  auto it = o.find(key);
  if (it == o.end()) {
    if (required) c.err(where + key, "missing (a string is required)");
    return false;
  }
  if (!it->is_string()) {
    c.err(where + key, "must be a string");
    return false;
  }
  out = it->get<std::string>();
  return true;
}

inline bool get_uint(const Ctx& c, const json& o, const std::string& where, const char* key,
                     std::uint32_t& out, std::uint32_t max) {
  auto it = o.find(key);
  if (it == o.end()) return false;
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() > max) {
    c.err(where + key, "must be an integer from 0 to " + std::to_string(max));
    return false;
  }
  out = static_cast<std::uint32_t>(it->get<std::uint64_t>());
  return true;
}

// A header a step can build (not the TMP form).
inline std::optional<top::Header> header_from(std::string_view s) {
  const auto h = top::header_from_string(s);
  if (h == top::Header::tmp_quirk) return std::nullopt;
  return h;
}

inline bool is_hex(std::string_view s) {
  if (s.size() % 2) return false;
  for (char ch : s)
    if (!std::isxdigit(static_cast<unsigned char>(ch))) return false;
  return true;
}

// A send template ({"raw"}, {"hex"} or {"command"}); errors go to `c`.
std::optional<SendSpec> parse_send(const Ctx& c, const json& o, const std::string& where);
// One expectation (an alternative of a step); errors go to `c`.
std::optional<Expectation> parse_expect(const Ctx& c, const json& o, const std::string& where);

}  // namespace topconf::detail
