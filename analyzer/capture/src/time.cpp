// Capture times: ISO 8601 and epoch seconds in, ISO 8601 out.
#include "capture/time.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>

#include "capture/sink.hpp"

namespace topdump {

std::int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::optional<std::int64_t> parse_time(std::string_view s) {
  if (s.empty()) return std::nullopt;
  auto digits = [&](std::size_t at, std::size_t n, int& out) {
    if (at + n > s.size()) return false;
    out = 0;
    for (std::size_t i = at; i < at + n; ++i) {
      if (s[i] < '0' || s[i] > '9') return false;
      out = out * 10 + (s[i] - '0');
    }
    return true;
  };
  if (s.size() >= 19 && s[4] == '-' && s[7] == '-' && (s[10] == 'T' || s[10] == ' ')) {
    int Y, M, D, h, m, sec;
    if (!digits(0, 4, Y) || !digits(5, 2, M) || !digits(8, 2, D) || !digits(11, 2, h) ||
        s[13] != ':' || !digits(14, 2, m) || s[16] != ':' || !digits(17, 2, sec))
      return std::nullopt;
    std::tm tm{};
    tm.tm_year = Y - 1900;
    tm.tm_mon = M - 1;
    tm.tm_mday = D;
    tm.tm_hour = h;
    tm.tm_min = m;
    tm.tm_sec = sec;
    std::int64_t us = static_cast<std::int64_t>(timegm(&tm)) * 1000000;
    std::size_t i = 19;
    if (i < s.size() && (s[i] == '.' || s[i] == ',')) {
      ++i;
      std::int64_t frac = 0, scale = 100000;
      while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
        if (scale > 0) frac += (s[i] - '0') * scale;
        scale /= 10;
        ++i;
      }
      us += frac;
    }
    if (i < s.size() && s[i] == 'Z') {
      ++i;
    } else if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
      int oh, om;
      bool neg = s[i] == '-';
      if (!digits(i + 1, 2, oh)) return std::nullopt;
      std::size_t j = i + 3;
      if (j < s.size() && s[j] == ':') ++j;
      if (!digits(j, 2, om)) return std::nullopt;
      std::int64_t off = (oh * 3600 + om * 60) * std::int64_t{1000000};
      us += neg ? off : -off;
      i = j + 2;
    }
    if (i != s.size()) return std::nullopt;
    return us;
  }
  // epoch seconds
  std::int64_t whole = 0, frac = 0, scale = 100000;
  std::size_t i = 0;
  bool any = false;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9')
    whole = whole * 10 + (s[i++] - '0'), any = true;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') {
      if (scale > 0) frac += (s[i] - '0') * scale;
      scale /= 10;
      ++i;
      any = true;
    }
  }
  if (!any || i != s.size()) return std::nullopt;
  return whole * 1000000 + frac;
}

std::string format_time(std::int64_t us) {
  if (us == kNoTime) return "-";
  // the civil date by chrono's calendar (no gmtime_r and printf per line:
  // the text output prints one per frame)
  using namespace std::chrono;
  const sys_time<microseconds> tp{microseconds(us)};
  const auto day = floor<days>(tp);
  const year_month_day ymd{day};
  const hh_mm_ss<microseconds> hms{tp - day};
  const int y = static_cast<int>(ymd.year());
  if (y < 0 || y > 9999) {  // printf's form for years the fast path does not write
    char b[64];
    std::snprintf(b, sizeof b, "%04d-%02u-%02uT%02lld:%02lld:%02lld.%06lldZ", y,
                  static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()),
                  static_cast<long long>(hms.hours().count()),
                  static_cast<long long>(hms.minutes().count()),
                  static_cast<long long>(hms.seconds().count()),
                  static_cast<long long>(hms.subseconds().count()));
    return b;
  }
  char b[27];  // 2024-05-01T12:00:00.123456Z
  auto put = [&](int at, long long v, int digits) {
    for (int i = digits - 1; i >= 0; --i, v /= 10) b[at + i] = static_cast<char>('0' + v % 10);
  };
  put(0, y, 4);
  b[4] = '-';
  put(5, static_cast<unsigned>(ymd.month()), 2);
  b[7] = '-';
  put(8, static_cast<unsigned>(ymd.day()), 2);
  b[10] = 'T';
  put(11, hms.hours().count(), 2);
  b[13] = ':';
  put(14, hms.minutes().count(), 2);
  b[16] = ':';
  put(17, hms.seconds().count(), 2);
  b[19] = '.';
  put(20, hms.subseconds().count(), 6);
  b[26] = 'Z';
  return std::string(b, sizeof b);
}

}  // namespace topdump
