// topdump frame, run as a real process.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "output/escape.hpp"

using json = nlohmann::json;

namespace {

struct ProcResult {
  int status = -1;
  std::string out;
};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

ProcResult run_topdump(const std::vector<std::string>& args) {
  std::string cmd = std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump";
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " 2>/dev/null";
  ProcResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

bool has_finding(const json& frame, const std::string& code, int offset = -1) {
  for (const auto& f : frame["findings"])
    if (f["code"] == code && (offset < 0 || f["offset"] == offset)) return true;
  return false;
}

std::vector<json> lines(const std::string& s) {
  std::vector<json> v;
  std::istringstream in(s);
  std::string l;
  while (std::getline(in, l))
    if (!l.empty()) v.push_back(json::parse(l));
  return v;
}

}  // namespace

TEST(Escape, RoundTrip) {
  std::string err;
  auto b = topdump::unescape("a\\x23\\r\\n\\\\\\x00z", err);
  ASSERT_TRUE(b.has_value()) << err;
  EXPECT_EQ(*b, std::string("a#\r\n\\\0z", 7));
  EXPECT_EQ(topdump::escape(*b), "a#\\r\\n\\\\\\x00z");
  EXPECT_FALSE(topdump::unescape("\\xZ1", err).has_value());
  EXPECT_NE(err.find("position 0"), std::string::npos);
  EXPECT_FALSE(topdump::unescape("abc\\", err).has_value());
  EXPECT_FALSE(topdump::unescape("\\q", err).has_value());
}

TEST(TopdumpFrame, ValidFrameExitsZero) {
  ProcResult r = run_topdump({"frame", "#TPUD2wCAP013E"});
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("CAP"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checksum 3E (ok)"), std::string::npos) << r.out;
}

TEST(TopdumpFrame, JsonKeysAndResync) {
  ProcResult r = run_topdump({"frame", "--json", "#T#TPUD2wCAP013E"});
  EXPECT_EQ(r.status, 1) << r.out;  // the "#T" is a bad header: an error
  auto v = lines(r.out);
  ASSERT_EQ(v.size(), 2u) << r.out;
  EXPECT_TRUE(v[0].value("garbage", false));
  EXPECT_EQ(v[0]["findings"][0]["code"], "bad-header");
  const json& f = v[1];
  for (const char* k :
       {"header", "src", "dst", "length", "control", "ident", "data", "checksum", "checksum_ok",
        "expected_checksum", "command", "fields", "findings", "quirks"})
    EXPECT_TRUE(f.contains(k)) << k;
  EXPECT_EQ(f["ident"], "CAP");
  EXPECT_EQ(f["offset"], 2);
  EXPECT_EQ(f["checksum_ok"], true);
}

TEST(TopdumpFrame, BadChecksumExitsOneWithExpected) {
  ProcResult r = run_topdump({"frame", "--json", "#TPUD2wCAP0100"});
  EXPECT_EQ(r.status, 1);
  auto v = lines(r.out);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0]["checksum_ok"], false);
  EXPECT_EQ(v[0]["expected_checksum"], "3E");
  EXPECT_TRUE(has_finding(v[0], "bad-checksum", 12)) << r.out;
  ProcResult t = run_topdump({"frame", "#TPUD2wCAP0100"});
  EXPECT_NE(t.out.find("expected 3E"), std::string::npos) << t.out;
}

TEST(TopdumpFrame, BadUsageExitsTwo) {
  EXPECT_EQ(run_topdump({"frame"}).status, 2);
  EXPECT_EQ(run_topdump({"frame", "--dialect", "klingon", "#TPUD2wCAP013E"}).status, 2);
  EXPECT_EQ(run_topdump({"frame", "--model", "c99", "#TPUD2wCAP013E"}).status, 2);
  EXPECT_EQ(run_topdump({"frame", "\\xZZ"}).status, 2);
  EXPECT_EQ(
      run_topdump({"frame", "--model", "sip", "--dialect", "skydroid", "#TPUD2wCAP013E"}).status,
      2);
  EXPECT_EQ(run_topdump({"no-such-command"}).status, 2);
}

TEST(TopdumpFrame, NoFrameIsAnError) { EXPECT_EQ(run_topdump({"frame", "hello"}).status, 1); }

TEST(TopdumpFrame, DialectDecidesPtzNames) {
  auto sky = lines(run_topdump({"frame", "--json", "--dialect", "skydroid", "#TPUG2wPTZ0670"}).out);
  auto top = lines(run_topdump({"frame", "--json", "--dialect", "topotek", "#TPUG2wPTZ0670"}).out);
  ASSERT_EQ(sky.size(), 1u);
  ASSERT_EQ(top.size(), 1u);
  EXPECT_EQ(sky[0]["fields"]["action"]["name"], "follow");
  EXPECT_EQ(top[0]["fields"]["action"]["name"], "lock");
}

TEST(TopdumpFrame, SeveralFramesAndEscapes) {
  ProcResult r =
      run_topdump({"frame", "--json", "#TPUD2wCAP013E\\r\\n#tpUM2rZOM00A3", "#TPUD2rREC003E"});
  EXPECT_EQ(r.status, 0) << r.out;
  auto v = lines(r.out);
  ASSERT_EQ(v.size(), 3u) << r.out;
  EXPECT_EQ(v[0]["arg"], 1);
  EXPECT_EQ(v[1]["arg"], 1);
  EXPECT_EQ(v[1]["offset"], 16);
  EXPECT_EQ(v[2]["arg"], 2);
  EXPECT_TRUE(has_finding(v[0], "crlf", 14)) << r.out;
}

TEST(TopdumpFrame, LyingLength) {
  ProcResult r = run_topdump({"frame", "--json", "#tpDU3rVER0105025A"});
  EXPECT_EQ(r.status, 0);
  auto v = lines(r.out);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0]["length"], 6);
  EXPECT_EQ(v[0]["declared_length"], 3);
  EXPECT_TRUE(has_finding(v[0], "length-mismatch")) << r.out;
}
