#include "conf/fuzz_report.hpp"

#include "conf/report.hpp"
#include "junit.hpp"
#include "top/detail/text.hpp"

namespace topconf {
namespace {

using top::markup_escape;

std::string index_list(const std::vector<std::uint64_t>& v) {
  std::string s;
  for (auto i : v) s += (s.empty() ? "" : " ") + std::to_string(i);
  return s;
}

}  // namespace

nlohmann::json to_json(const FuzzCaseResult& r) {
  nlohmann::json j;
  j["index"] = r.spec.index;
  j["family"] = r.spec.family;
  j["name"] = top::ascii_text(r.spec.name);
  j["bytes"] = printable(r.spec.bytes);
  j["promise"] = std::string(to_string(r.spec.promise));
  j["level"] = std::string(to_string(r.spec.level));
  if (r.spec.mutated) {
    j["mutated"] = true;
    j["base"] = r.spec.base;
    j["repaired"] = r.spec.repaired;
  }
  j["verdict"] = r.failure ? std::string(to_string(*r.failure)) : "pass";
  if (!r.reason.empty()) j["reason"] = top::ascii_text(r.reason);
  nlohmann::json a = nlohmann::json::array();
  for (const auto& x : r.answers) a.push_back(printable(x));
  j["answers"] = a;
  j["start_us"] = r.start_us;
  j["latency_us"] = r.latency_us;
  return j;
}

nlohmann::json session_json(const FuzzResult& r) {
  return {{"session", "topconf-fuzz-1"},
          {"model", std::string(top::to_string(r.model))},
          {"seed", r.seed},
          {"target", r.target},
          {"catalog_cases", r.catalog_cases},
          {"started_at", r.started_at}};
}

nlohmann::json to_json(const FuzzFailure& f) {
  return {{"failure", std::string(to_string(f.cls))},
          {"index", f.index},
          {"name", top::ascii_text(f.spec.name)},
          {"bytes", printable(f.spec.bytes)},
          {"reason", top::ascii_text(f.reason)},
          {"before", f.before},
          {"minimised", std::string(to_string(f.how))},
          {"cases", f.cases},
          {"frame", printable(f.frame)},
          {"note", f.note},
          {"restarted", f.restarted}};
}

nlohmann::json summary_json(const FuzzResult& r) {
  nlohmann::json classes = nlohmann::json::object();
  for (FailureClass c : kFailureClasses) {
    std::size_t n = 0;
    for (const auto& f : r.failures) n += f.cls == c;
    classes[std::string(to_string(c))] = n;
  }
  return {{"summary",
           {{"cases", r.cases_run},
            {"next_index", r.next_index},
            {"seconds", r.seconds},
            {"cases_per_s", r.rate()},
            {"probes", r.probes},
            {"failures", r.failures.size()},
            {"classes", classes},
            {"unusable", r.unusable},
            {"aborted", r.aborted},
            {"exit", r.exit_code()}}}};
}

std::string failure_line(const FuzzFailure& f) {
  std::string s = "case " + std::to_string(f.index) + " (" + f.spec.family + ": " +
                  top::ascii_text(f.spec.name) + "): " + std::string(to_string(f.cls)) + ": " +
                  top::ascii_text(f.reason) + "\n  sent " + printable(f.spec.bytes);
  if (!f.before.empty()) s += "\n  cases before it: " + index_list(f.before);
  s += "\n  minimised: " + std::string(to_string(f.how));
  if (!f.cases.empty()) s += ", cases " + index_list(f.cases);
  if (!f.frame.empty()) s += ", frame " + printable(f.frame);
  if (!f.note.empty()) s += " (" + f.note + ")";
  return s;
}

void write_console(std::ostream& os, const FuzzResult& r) {
  if (r.unusable) {
    os << "target unusable: " << r.unusable_reason << "\n";
    return;
  }
  os << r.cases_run << " case(s) in " << r.seconds << " s (" << static_cast<long>(r.rate())
     << " cases/s, " << r.probes << " probes), next index " << r.next_index << ", "
     << r.failures.size() << " failure(s)\n";
  for (const auto& f : r.failures) os << failure_line(f) << "\n";
  if (r.aborted) os << "aborted: " << r.aborted_reason << "\n";
  if (!r.probe_note.empty()) os << r.probe_note << "\n";
  os << (r.exit_code() == 0 ? "PASS" : "FAIL") << ": exit status " << r.exit_code() << "\n";
}

void write_junit(std::ostream& os, const FuzzResult& r) {
  std::size_t failing = 0;
  for (FailureClass c : kFailureClasses)
    failing += std::any_of(r.failures.begin(), r.failures.end(),
                           [c](const FuzzFailure& f) { return f.cls == c; });
  detail::JunitSuite suite;
  suite.name = "topconf.fuzz." + std::string(top::to_string(r.model));
  suite.tests = std::size(kFailureClasses);
  suite.failures = failing;
  suite.errors = r.unusable ? 1 : 0;
  suite.seconds = r.seconds;
  suite.timestamp = r.started_at;
  detail::open_junit(os, suite);
  using Result = detail::JunitCase::Result;
  for (FailureClass c : kFailureClasses) {
    detail::JunitCase k{
        .classname = "topconf.fuzz", .name = std::string(to_string(c)), .seconds = 0};
    if (r.unusable) {
      k.result = Result::error;
      k.message = r.unusable_reason;
    } else {
      std::size_t n = 0;
      for (const auto& f : r.failures)
        if (f.cls == c) {
          ++n;
          k.body += failure_line(f) + "\n";
        }
      if (n) {
        k.result = Result::failure;
        k.message = std::to_string(n) + " case(s): " + std::string(describe(c));
      }
    }
    detail::write_case(os, k);
  }
  detail::close_junit(os);
}

void write_html(std::ostream& os, const FuzzResult& r) {
  write_html_head(os, "topconf fuzz " + std::string(top::to_string(r.model)) + " report");
  os << "<h1>topconf fuzz report: " << markup_escape(top::to_string(r.model)) << "</h1>\n";
  os << "<p>Target <b>" << markup_escape(r.target) << "</b>, seed " << r.seed << ", started "
     << markup_escape(r.started_at) << ", " << r.seconds << " s, " << r.cases_run << " case(s) ("
     << static_cast<long>(r.rate()) << " cases/s), " << r.probes << " probes, " << r.catalog_cases
     << " catalog cases before the mutations.</p>\n";
  if (r.unusable)
    os << "<p class=\"fail\"><b>Target unusable:</b> " << markup_escape(r.unusable_reason)
       << "</p>\n";
  if (r.aborted)
    os << "<p class=\"fail\"><b>Aborted:</b> " << markup_escape(r.aborted_reason) << "</p>\n";
  os << "<p class=\"sum\">";
  for (FailureClass c : kFailureClasses) {
    std::size_t n = 0;
    for (const auto& f : r.failures) n += f.cls == c;
    os << "<span class=\"" << (n ? "fail" : "pass") << "\">" << to_string(c) << ": " << n
       << "</span>";
  }
  os << "</p>\n<p><b>" << (r.exit_code() == 0 ? "PASS" : "FAIL") << "</b>: exit status "
     << r.exit_code() << ".</p>\n";
  os << "<table><tr><th>case</th><th>class</th><th>reason</th><th>sent</th><th>minimised</th></"
        "tr>\n";
  for (const auto& f : r.failures) {
    os << "<tr class=\"fail\"><td><code>" << f.index << "</code><br>"
       << markup_escape(f.spec.family) << ": " << markup_escape(top::ascii_text(f.spec.name))
       << "</td><td>" << to_string(f.cls) << "</td><td>" << markup_escape(top::ascii_text(f.reason))
       << "</td><td><pre>" << markup_escape(printable(f.spec.bytes)) << "</pre>";
    if (!f.before.empty())
      os << "<details><summary>cases before it</summary>" << index_list(f.before) << "</details>";
    os << "</td><td>" << to_string(f.how);
    if (!f.cases.empty()) os << ": cases " << index_list(f.cases);
    if (!f.frame.empty()) os << "<pre>" << markup_escape(printable(f.frame)) << "</pre>";
    os << markup_escape(f.note) << "</td></tr>\n";
  }
  os << "</table>\n</body></html>\n";
}

}  // namespace topconf
