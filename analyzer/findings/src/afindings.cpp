#include "findings/afindings.hpp"

namespace topdump {

namespace {
struct Row {
  std::string_view code;
  top::Severity severity;
  std::string_view when;
};
constexpr Row kRows[] = {
#define TOPDUMP_X(e, s, sev, when) {s, top::Severity::sev, when},
#define TOPDUMP_D(e, s, sev, title, evidence, remedy) {s, top::Severity::sev, title},
    TOPDUMP_FINDINGS(TOPDUMP_X) TOP_DIAGNOSES(TOPDUMP_D)
#undef TOPDUMP_D
#undef TOPDUMP_X
};
static_assert(sizeof kRows / sizeof kRows[0] == acode_count);
}  // namespace

std::string_view to_string(ACode c) noexcept { return kRows[static_cast<std::size_t>(c)].code; }
top::Severity default_severity(ACode c) noexcept {
  return kRows[static_cast<std::size_t>(c)].severity;
}
std::string_view description(ACode c) noexcept { return kRows[static_cast<std::size_t>(c)].when; }
std::optional<ACode> acode_from_string(std::string_view s) noexcept {
  for (std::size_t i = 0; i < acode_count; ++i)
    if (kRows[i].code == s) return static_cast<ACode>(i);
  return std::nullopt;
}

}  // namespace topdump
