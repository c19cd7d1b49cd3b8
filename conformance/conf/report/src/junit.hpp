// The JUnit XML envelope every topconf report writes (private to
// conf/report/): the <testsuites> and <testsuite> element around the cases.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

namespace topconf::detail {

struct JunitSuite {
  std::string name;  // "topconf.c12", "topconf.fuzz.c12"
  std::size_t tests = 0, failures = 0, errors = 0;
  std::optional<std::size_t> skipped;  // the attribute only when given
  double seconds = 0;
  std::string timestamp;  // ISO 8601
};

// Writes the XML declaration and the opening elements.
void open_junit(std::ostream& os, const JunitSuite& s);
// Closes what open_junit opened.
void close_junit(std::ostream& os);

}  // namespace topconf::detail
