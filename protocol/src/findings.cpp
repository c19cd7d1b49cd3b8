#include "top/findings.hpp"

#include <array>

#include "swap_members.hpp"

namespace top {

namespace {

struct Row {
  std::string_view code;
  Severity severity;
  std::string_view quirk;
  std::string_view when;
};

constexpr std::array<Row, finding_code_count> kRows = {{
#define TOP_X(e, s, sev, quirk, when) {s, Severity::sev, quirk, when},
    TOP_FINDINGS(TOP_X)
#undef TOP_X
}};

}  // namespace

constexpr std::string_view kSeverity[] = {"info", "warning", "error"};
static_assert(std::size(kSeverity) == static_cast<std::size_t>(Severity::error) + 1);

std::string_view to_string(Severity s) noexcept {
  const auto i = static_cast<std::size_t>(s);
  return i < std::size(kSeverity) ? kSeverity[i] : "?";
}

std::string_view to_string(FindingCode c) noexcept {
  auto i = static_cast<std::size_t>(c);
  return i < kRows.size() ? kRows[i].code : "?";
}

Severity default_severity(FindingCode c) noexcept {
  auto i = static_cast<std::size_t>(c);
  return i < kRows.size() ? kRows[i].severity : Severity::error;
}

std::string_view description(FindingCode c) noexcept {
  auto i = static_cast<std::size_t>(c);
  return i < kRows.size() ? kRows[i].when : "";
}

std::string_view quirk_id(FindingCode c) noexcept {
  auto i = static_cast<std::size_t>(c);
  return i < kRows.size() ? kRows[i].quirk : "";
}

std::optional<FindingCode> finding_code_from_string(std::string_view s) noexcept {
  for (std::size_t i = 0; i < kRows.size(); ++i)
    if (kRows[i].code == s) return static_cast<FindingCode>(i);
  return std::nullopt;
}

void swap(Finding& a, Finding& b) noexcept {
  detail::swap_members(a, b, &Finding::code, &Finding::severity, &Finding::offset,
                       &Finding::message, &Finding::quirk);
}

Finding make_finding(FindingCode code, std::uint32_t offset, std::string message,
                     std::string_view quirk) {
  return Finding{code, default_severity(code), offset, std::move(message), quirk};
}

}  // namespace top
