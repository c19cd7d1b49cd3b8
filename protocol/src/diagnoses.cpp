// The diagnoses table (top/diagnoses.hpp) and the device rules its
// detectors ask: placeholder identities, refused tracking, dates carried by
// frames.
#include "top/diagnoses.hpp"

#include "top/catalog.hpp"

namespace top {

namespace {
struct Row {
  std::string_view code;
  Severity severity;
  std::string_view title, evidence, remedy;
};
constexpr Row kRows[] = {
#define TOP_X(e, s, sev, t, ev, rem) {s, Severity::sev, t, ev, rem},
    TOP_DIAGNOSES(TOP_X)
#undef TOP_X
};
static_assert(std::size(kRows) == diagnosis_count);

const Row& row(Diagnosis d) noexcept { return kRows[static_cast<std::size_t>(d)]; }

char lower(char c) noexcept { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}
}  // namespace

std::string_view to_string(Diagnosis d) noexcept { return row(d).code; }
Severity severity(Diagnosis d) noexcept { return row(d).severity; }
std::string_view title(Diagnosis d) noexcept { return row(d).title; }
std::string_view evidence(Diagnosis d) noexcept { return row(d).evidence; }
std::string_view remedy(Diagnosis d) noexcept { return row(d).remedy; }
std::optional<Diagnosis> diagnosis_from_string(std::string_view s) noexcept {
  for (std::size_t i = 0; i < diagnosis_count; ++i)
    if (kRows[i].code == s) return static_cast<Diagnosis>(i);
  return std::nullopt;
}

bool is_placeholder_identity(std::string_view v) noexcept {
  while (!v.empty() && (v.back() == ' ' || v.back() == '\0')) v.remove_suffix(1);
  while (!v.empty() && v.front() == ' ') v.remove_prefix(1);
  if (v.empty()) return true;
  // all zeros, perhaps with separators (000000000, 0.0.0, V0.0.0)
  std::string_view z = v;
  if (z.front() == 'V' || z.front() == 'v') z.remove_prefix(1);
  bool zeros = !z.empty(), digit = false;
  for (char c : z) {
    if (c == '0')
      digit = true;
    else if (c != '.' && c != '-')
      zeros = false;
  }
  if (zeros && digit) return true;
  return v == "123" || v == "1.2.3" || iequals(v, "unknown");
}

std::optional<DateTime> date_time_of(const FormSpec& form, std::string_view data) noexcept {
  DateTime t;
  bool year = false, month = false, day = false;
  std::size_t at = 0;
  for (const FieldSpec& f : form.fields) {
    const std::size_t w = f.width ? f.width : data.size() - std::min(at, data.size());
    if (at + w > data.size()) return std::nullopt;
    const std::string_view s = data.substr(at, w);
    at += w;
    int* slot = f.name == "year"     ? &t.year
                : f.name == "month"  ? &t.month
                : f.name == "day"    ? &t.day
                : f.name == "hour"   ? &t.hour
                : f.name == "minute" ? &t.minute
                : f.name == "second" ? &t.second
                                     : nullptr;
    if (!slot) continue;
    int v = 0;
    std::size_t digits = 0;
    for (char c : s) {
      if (c == '.') break;  // ss.ss: the whole seconds
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
      ++digits;
    }
    if (digits == 0) return std::nullopt;
    if (slot == &t.year) {
      year = true;
      // two digits (SkyDroid TIM, Topotek UTC): 69-99 are 1969-1999 and
      // 00-68 are 2000-2068, as POSIX strptime's %y reads them, so a
      // camera that never set its clock (70 01 01) reads 1970, not 2070
      if (digits <= 2) v += v >= 69 ? 1900 : 2000;
    }
    month |= slot == &t.month;
    day |= slot == &t.day;
    *slot = v;
  }
  if (!year || !month || !day) return std::nullopt;
  return t;
}

std::int64_t epoch_seconds(const DateTime& t) noexcept {
  // days from civil (H. Hinnant's algorithm), months normalised first
  std::int64_t y = t.year, m = t.month;
  y += (m - 1 >= 0 ? (m - 1) / 12 : (m - 12) / 12);
  m = ((m - 1) % 12 + 12) % 12 + 1;
  y -= m <= 2;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + t.day - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  const std::int64_t days = era * 146097 + doe - 719468;
  return days * 86400 + std::int64_t{t.hour} * 3600 + std::int64_t{t.minute} * 60 + t.second;
}

}  // namespace top
