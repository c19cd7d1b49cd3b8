// Golden outputs: the real topdump binary over every capture in captures/,
// compared with captures/golden/. Regenerate (and review the diff) with
//   captures/update-golden.sh build/default
#include <gtest/gtest.h>

#include <sstream>

#include "test_support.hpp"

namespace topdump::test {
namespace {

struct Case {
  std::string name, args;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.name << ": topdump " << c.args; }

std::vector<Case> cases() {
  std::vector<Case> v;
  std::istringstream in(slurp(captures_dir() + "/golden/cases.txt"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    auto sp = line.find(' ');
    v.push_back(Case{line.substr(0, sp), line.substr(sp + 1)});
  }
  return v;
}

class Golden : public ::testing::TestWithParam<Case> {};

TEST_P(Golden, MatchesCapturesGolden) {
  const Case& c = GetParam();
  TempDir tmp;
  std::string out;
  int rc = run("cd '" + captures_dir() + "' && '" + topdump_bin() + "' " + c.args + " 2>'" +
                   tmp.file("err") + "' </dev/null",
               out);
  std::string got =
      out + "-- stderr\n" + slurp(tmp.file("err")) + "-- exit " + std::to_string(rc) + "\n";
  std::string want = slurp(captures_dir() + "/golden/" + c.name);
  ASSERT_FALSE(want.empty()) << "missing golden " << c.name << "; run captures/update-golden.sh";
  EXPECT_EQ(got, want) << "topdump " << c.args
                       << "\nregenerate with captures/update-golden.sh and review the diff";
}

TEST(GoldenCases, CoverEveryCapture) {
  // every capture file in captures/ has at least one golden case
  std::string listing;
  run("cd '" + captures_dir() + "' && ls *.pcap *.pcapng *.bin *.log *.csv sip-bench/*.pcap",
      listing);
  std::istringstream in(listing);
  std::string f;
  auto cs = cases();
  while (in >> f) {
    bool found = false;
    for (const auto& c : cs) found |= c.args.find(f) != std::string::npos;
    EXPECT_TRUE(found) << f << " has no golden case in captures/golden/cases.txt";
  }
}

INSTANTIATE_TEST_SUITE_P(Captures, Golden, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           std::string n;
                           for (char ch : i.param.name)
                             n += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return n;
                         });

}  // namespace
}  // namespace topdump::test
