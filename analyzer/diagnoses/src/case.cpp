#include "diagnoses/case.hpp"

#include <cstdio>

namespace topdump::diag {

namespace {
// civil from days (H. Hinnant's algorithm)
void civil(std::int64_t days, int& y, int& m, int& d) noexcept {
  days += 719468;
  const std::int64_t era = (days >= 0 ? days : days - 146096) / 146097;
  const std::int64_t doe = days - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  y = static_cast<int>(yoe + era * 400 + (m <= 2));
}
std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)));
}
}  // namespace

std::string date_text(std::int64_t s) {
  const std::int64_t days = floor_div(s, 86400), sec = s - days * 86400;
  int y = 0, m = 0, d = 0;
  civil(days, y, m, d);
  char b[48];
  std::snprintf(b, sizeof b, "%04d-%02d-%02d %02d:%02d:%02d", y, m, d, static_cast<int>(sec / 3600),
                static_cast<int>(sec / 60 % 60), static_cast<int>(sec % 60));
  return b;
}

std::string time_text(std::int64_t us) {
  if (us == kNoTime) return "an unknown time";
  const std::int64_t s = floor_div(us, 1'000'000);
  char b[8];
  std::snprintf(b, sizeof b, ".%03d", static_cast<int>((us - s * 1'000'000) / 1000));
  return date_text(s) + b;
}

std::string seconds_text(std::int64_t us) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", static_cast<double>(us) / 1e6);
  return b;
}

}  // namespace topdump::diag
