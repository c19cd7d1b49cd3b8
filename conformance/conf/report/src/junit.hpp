// The JUnit XML every topconf report writes (private to conf/report/): the
// <testsuites> and <testsuite> envelope, and each <testcase> in it.
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

// One <testcase>. Texts are raw: write_case escapes them.
struct JunitCase {
  enum class Result { pass, failure, error, skipped };
  std::string classname, name;
  std::optional<double> seconds;  // the time attribute only when given
  Result result = Result::pass;
  std::string message;             // the result element's message
  std::string type;                // its type attribute, when not empty
  std::string body;                // its text, when not empty
  std::optional<std::string> out;  // <system-out>, when given
};
void write_case(std::ostream& os, const JunitCase& c);

}  // namespace topconf::detail
