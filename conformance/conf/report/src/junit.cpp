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

}  // namespace topconf::detail
