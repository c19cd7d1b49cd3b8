#include "junit.hpp"

#include "top/detail/text.hpp"

namespace topconf::detail {

void open_junit(std::ostream& os, const JunitSuite& s) {
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  os << "<testsuites>\n<testsuite name=\"" << top::markup_escape(s.name) << "\" tests=\"" << s.tests
     << "\" failures=\"" << s.failures << "\" errors=\"" << s.errors << "\"";
  if (s.skipped) os << " skipped=\"" << *s.skipped << "\"";
  os << " time=\"" << s.seconds << "\" timestamp=\"" << top::markup_escape(s.timestamp) << "\">\n";
}

void close_junit(std::ostream& os) { os << "</testsuite>\n</testsuites>\n"; }

void write_case(std::ostream& os, const JunitCase& c) {
  using top::markup_escape;
  os << "  <testcase classname=\"" << markup_escape(c.classname) << "\" name=\""
     << markup_escape(c.name) << "\"";
  if (c.seconds) os << " time=\"" << *c.seconds << "\"";
  os << ">";
  if (c.result != JunitCase::Result::pass) {
    const char* tag = c.result == JunitCase::Result::failure ? "failure"
                      : c.result == JunitCase::Result::error ? "error"
                                                             : "skipped";
    os << "<" << tag << " message=\"" << markup_escape(c.message) << "\"";
    if (!c.type.empty()) os << " type=\"" << markup_escape(c.type) << "\"";
    if (c.body.empty())
      os << "/>";
    else
      os << ">" << markup_escape(c.body) << "</" << tag << ">";
  }
  if (c.out) os << "<system-out>" << markup_escape(*c.out) << "</system-out>";
  os << "</testcase>\n";
}

}  // namespace topconf::detail
