// Every fact about a device names a public source: the traits, the field's
// frame forms and streams, field support and field notes of top/device.hpp,
// the field's commands and forms of the catalog, the motion table's field
// rows and the diagnoses' evidence. A public source is a vendor document's
// section ("Topotek 5.9", "SkyDroid 2.3.1", "Topotek V1.1.3"), a pull
// request ("PR #34155"), a file at a commit ("AP_Mount_Topotek.h @
// 3d293ff8"), a PixEagle bench session ("PixEagle ...
// 20260917T044930Z-queries") or a repository path ("log114/PTZControl
// C12Service.kt"). An issue of our own tracker is never one: "issue 28" in
// a fact fails, whatever else the fact names. Our own notes
// (docs/sources/ardupilot.md) are where the facts are gathered, not a
// source: they do not count.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "top/top.hpp"

using namespace top;

namespace {

struct Fact {
  std::string where;   // which table, which row
  std::string text;    // every string of the row that could cite something
  std::string source;  // the string that must name the source; empty: no check
};

std::string str(std::string_view s) { return std::string(s); }

// An issue of our tracker: "issue 28", "Issue 29 log", "issues 28 and 29"
// (another project's is named with its project and a #: "QGroundControl
// issue #13580").
bool cites_our_issue(const std::string& text) {
  static const std::regex kIssue(R"(\bissues? +\d+)", std::regex::icase);
  return std::regex_search(text, kIssue);
}

// Whether `text` names a public source, our own documents aside.
bool names_public_source(std::string text) {
  static const std::regex kOurs(R"(\bdocs/[\w./-]+)");
  text = std::regex_replace(text, kOurs, "");
  static const std::regex kSources[] = {
      // a vendor document's section, appendix or version
      std::regex(R"(\b(Topotek|SkyDroid) (V?\d+(\.\d+)*|appendix [IVX]+)\b)"),
      // a pull request
      std::regex(R"(\bPR #\d+|github\.com/[\w.-]+/[\w.-]+/pull/\d+)"),
      // a file at a commit
      std::regex(R"([\w.-]+\.(cpp|h|hpp|c|py|kt|java|cs|md|rst|txt|json) ?@ ?[0-9a-f]{7,40}\b)"),
      // a repository path: owner/repo and a file, or a path to a file
      std::regex(R"(\b[\w.-]+/[\w.-]+[ ,(]+[\w./-]*\w\.(cpp|h|hpp|c|py|kt|java|cs|md|rst)\b)"),
      std::regex(R"(\b[\w.-]+(/[\w.-]+)+\.(cpp|h|hpp|c|py|kt|java|cs|md|rst)\b)"),
  };
  for (const std::regex& r : kSources)
    if (std::regex_search(text, r)) return true;
  // a PixEagle bench session
  static const std::regex kSession(R"(\b\d{8}T\d{6}Z-[a-z][a-z-]*)");
  return text.find("PixEagle") != std::string::npos && std::regex_search(text, kSession);
}

std::string cat_all(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (std::string_view p : parts) {
    s.append(p);
    s.push_back('\n');
  }
  return s;
}

std::vector<Fact> every_fact() {
  std::vector<Fact> out;
  for (const Trait& t : traits())
    out.push_back({"trait " + str(to_string(t.kind)) + " " + str(t.idents), str(t.evidence),
                   str(t.evidence)});
  for (const DeviceForm& f : device_forms()) {
    if (f.source != Source::field) continue;
    out.push_back({"device form " + str(f.ident), str(f.evidence), str(f.evidence)});
  }
  for (const StreamSpec& s : streams()) {
    const std::string text = cat_all({s.section, s.note, s.evidence});
    // a document's stream: its section is the source
    out.push_back({"stream " + str(s.request) + " -> " + str(s.push), text,
                   s.from_field() ? str(s.evidence) : str(s.section)});
  }
  for (const FieldSupport& f : field_support())
    out.push_back({"field support " + str(f.ident), str(f.evidence), str(f.evidence)});
  for (const FieldNote& n : field_notes())
    out.push_back({"field note " + str(n.note), cat_all({n.note, n.evidence}), str(n.evidence)});
  for (Dialect d : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(d)) {
      const std::string name = str(to_string(d)) + " " + str(c.ident);
      if (c.from_field())
        out.push_back({"field command " + name, cat_all({c.section, c.note, c.evidence}),
                       cat_all({c.section, c.evidence})});
      else
        out.push_back({"command " + name, cat_all({c.section, c.note}), str(c.section)});
      for (const FormSpec& f : c.forms) {
        std::string text = cat_all({f.note, f.evidence});
        for (const FieldSpec& x : f.fields) text += cat_all({x.note});
        out.push_back({"form of " + name + " " + std::string(1, f.control), text,
                       f.from_field() ? str(f.evidence) : str(c.section)});
      }
    }
  for (const MotionSpec& m : motions())
    out.push_back({"motion " + str(to_string(m.dialect)) + " " + str(m.ident),
                   cat_all({m.section, m.field_evidence}),
                   m.field_evidence.empty() ? str(m.section) : str(m.field_evidence)});
  for (std::size_t i = 0; i < diagnosis_count; ++i) {
    const auto d = static_cast<Diagnosis>(i);
    // A diagnosis names a field problem and its evidence, often our own
    // notes (docs/FIELD.md's traits): checked for our issues only.
    out.push_back(
        {"diagnosis " + str(to_string(d)), cat_all({title(d), evidence(d), remedy(d)}), {}});
  }
  return out;
}

}  // namespace

// The checks themselves, on strings of both kinds.
TEST(Evidence, TheCheckTellsASourceFromAnIssueOfOurs) {
  EXPECT_TRUE(cites_our_issue("a real SIP (issue 28 log)"));
  EXPECT_TRUE(cites_our_issue("per Issue 29"));
  EXPECT_TRUE(cites_our_issue("issues 28 and 29"));
  EXPECT_TRUE(cites_our_issue("a real SIP's log (ISSUE 28)"));
  EXPECT_FALSE(cites_our_issue("QGroundControl issue #13580"));
  for (const char* s :
       {"Topotek 5.9", "SkyDroid 2.3.1", "Topotek V1.1.3 section 9", "ArduPilot PR #34155",
        "AP_Mount_Topotek.h @ 3d293ff8",
        "AP_Mount_Topotek.cpp @d420971136c6db2430273e91d117ad8c9044bcee",
        "PixEagle session 20260917T044930Z-queries 04:49:34.243738",
        "log114/PTZControl C12Service.kt", "vamaskylight/custom-GCS, vgcs/skydroid/adapter.py"})
    EXPECT_TRUE(names_public_source(s)) << s;
  for (const char* s : {"a real SIP (issue 28 log)", "PixEagle bench notes on a real SIP",
                        "docs/sources/ardupilot.md 8.1", "an Android app and two Python drivers",
                        "C11/C13", "GIA/GAC", "the tool author's claim"})
    EXPECT_FALSE(names_public_source(s)) << s;
}

TEST(Evidence, NoFactCitesAnIssueOfOurs) {
  for (const Fact& f : every_fact())
    EXPECT_FALSE(cites_our_issue(f.text)) << f.where << ":\n" << f.text;
}

TEST(Evidence, EveryFactNamesAPublicSource) {
  const std::vector<Fact> facts = every_fact();
  EXPECT_GT(facts.size(), 100u);
  for (const Fact& f : facts) {
    if (f.source.empty()) continue;
    EXPECT_TRUE(names_public_source(f.source)) << f.where << ":\n" << f.source;
  }
}
