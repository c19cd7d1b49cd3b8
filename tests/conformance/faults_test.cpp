// topsim's fault injection: parsing and what each fault does to a frame.
#include "sim/faults.hpp"

#include <gtest/gtest.h>

namespace {

using topsim::FaultInjector;

std::optional<topsim::FaultConfig> parse(std::string_view s) {
  std::string err;
  return topsim::parse_faults(s, err);
}

std::vector<topsim::Emission> apply_fault(std::string_view spec, const std::string& f,
                                          bool stream = false) {
  FaultInjector fi(*parse(spec), 7);
  std::vector<topsim::Emission> out;
  fi.apply(f, stream, out);
  return out;
}

const std::string kGay = "#TPGU6wGAYEF073248";

TEST(Faults, ParsesEveryNameAndRejectsBadOnes) {
  auto c = parse(
      "drop=0.1,delay=20,duplicate=0.5,bad-checksum=1,header-case=0.2,no-swap,"
      "lying-length=0.3,tmp-quirk,split,garbage=0.4,hang-on=GAY");
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->drop, 0.1);
  EXPECT_EQ(c->delay_ms, 20u);
  EXPECT_TRUE(c->no_swap && c->tmp_quirk && c->split);
  EXPECT_EQ(c->hang_on, "GAY");
  std::string err;
  EXPECT_FALSE(topsim::parse_faults("drop=2", err).has_value());
  EXPECT_NE(err.find("drop=2"), std::string::npos);
  EXPECT_FALSE(topsim::parse_faults("bogus", err).has_value());
  EXPECT_FALSE(topsim::parse_faults("delay=x", err).has_value());
  EXPECT_FALSE(topsim::parse_faults("no-swap=1", err).has_value());
  EXPECT_FALSE(topsim::parse_faults("hang-on=GA", err).has_value());
  EXPECT_EQ(topsim::fault_names().size(), 30u);  // the drive faults: drive_faults_test.cpp
}

TEST(Faults, EachFaultChangesTheFrameAsNamed) {
  EXPECT_TRUE(apply_fault("drop=1", kGay).empty());
  auto d = apply_fault("delay=25", kGay);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].delay_us, 25000u);
  EXPECT_EQ(apply_fault("duplicate=1", kGay).size(), 2u);
  auto bad = top::parse_exact(apply_fault("bad-checksum=1", kGay)[0].bytes);
  EXPECT_TRUE(bad.frame.has(top::FindingCode::bad_checksum));
  auto hc = top::parse_exact(apply_fault("header-case=1", kGay)[0].bytes);
  EXPECT_TRUE(hc.frame.has(top::FindingCode::checksum_header_case));
  auto ll = top::parse_exact(apply_fault("lying-length=1", kGay)[0].bytes);
  EXPECT_TRUE(ll.frame.has(top::FindingCode::length_mismatch)) << ll.frame.raw;
  EXPECT_EQ(ll.frame.data(), "EF0732");
  auto g = apply_fault("garbage=1", kGay);
  EXPECT_NE(g[0].bytes, kGay);
  EXPECT_EQ(g[0].bytes.substr(g[0].bytes.size() - kGay.size()), kGay);
  auto sp = apply_fault("split", kGay, true);
  ASSERT_EQ(sp.size(), 2u);
  EXPECT_EQ(sp[0].bytes + sp[1].bytes, kGay);
  EXPECT_EQ(apply_fault("split", kGay, false).size(), 1u);  // datagrams stay whole
}

// The frame faults byte for byte: the length char lies with a checksum
// right for the bytes sent; the header case flips after the checksum; both
// at once; the checksum's last digit corrupted. Frames they do not apply
// to (#tP, one data char, the two-digit TMP form for a lie) pass unchanged.
TEST(Faults, FrameFaultsByteForByte) {
  const std::string tmp = "#tpDU16wTMP0100200300400500600700AB";
  const std::string ext8 = "#tPGU\x06wGAYEF073238";
  const std::string one_char = top::with_checksum("#tpMU1wZMC1");
  struct Expected {
    const char* faults;
    std::string in, out;
  };
  for (const Expected& e : {
           Expected{"lying-length=1", kGay, "#TPGU5wGAYEF073247"},
           Expected{"header-case=1", kGay, "#tpGU6wGAYEF073248"},
           Expected{"lying-length=1,header-case=1", kGay, "#tpGU5wGAYEF073247"},
           Expected{"bad-checksum=1", kGay, "#TPGU6wGAYEF073240"},
           Expected{"header-case=1", "#tpDU6wGAYEF073285", "#TPDU6wGAYEF073285"},
           Expected{"header-case=1", tmp, "#TPDU16wTMP0100200300400500600700AB"},
           Expected{"lying-length=1", tmp, tmp},
           Expected{"lying-length=1,header-case=1", ext8, ext8},
           Expected{"lying-length=1", one_char, one_char},
       }) {
    const auto out = apply_fault(e.faults, e.in);
    ASSERT_EQ(out.size(), 1u) << e.faults;
    EXPECT_EQ(out[0].bytes, e.out) << e.faults << " on " << e.in;
  }
}

TEST(Faults, HangOnSilencesEverythingAfterTheCommand) {
  FaultInjector fi(*parse("hang-on=REC"), 1);
  auto rec = top::parse_exact("#TPUD2wREC0155");
  auto ver = top::parse_exact("#TPUD2rVER0051");
  EXPECT_TRUE(fi.on_request(ver.frame));
  EXPECT_FALSE(fi.on_request(rec.frame));
  EXPECT_FALSE(fi.on_request(ver.frame));
  std::vector<topsim::Emission> out;
  fi.apply(kGay, false, out);
  EXPECT_TRUE(out.empty());
}

// ignore=: a device without those commands (ArduPilot's simulators answer
// neither VER nor AWB): no answer to them, the rest as before, no hang.
TEST(Faults, IgnoreDropsTheRequestsOfItsClassesOnly) {
  auto c = parse("ignore=VER+ident:AWB,ignore=len:20");
  ASSERT_TRUE(c.has_value());
  ASSERT_EQ(c->ignore.size(), 3u);
  EXPECT_EQ(c->ignore[0].to_string(), "ident:VER");
  EXPECT_EQ(c->ignore[1].to_string(), "ident:AWB");
  EXPECT_EQ(c->ignore[2].to_string(), "len:20");
  EXPECT_TRUE(c->any());
  std::string err;
  for (const char* bad : {"ignore", "ignore=", "ignore=VE", "ignore=VER+", "ignore=VER+len:x"}) {
    EXPECT_FALSE(topsim::parse_faults(bad, err).has_value()) << bad;
    EXPECT_NE(err.find("ignore needs"), std::string::npos) << bad << ": " << err;
  }
  FaultInjector fi(*parse("ignore=VER+AWB"), 1);
  auto ver = top::parse_exact("#TPUD2rVER0051");
  auto awb = top::parse_exact(top::with_checksum("#TPUD2rAWB00"));
  auto rec = top::parse_exact("#TPUD2wREC0155");
  for (int i = 0; i < 2; ++i) {
    EXPECT_FALSE(fi.on_request(ver.frame));
    EXPECT_FALSE(fi.on_request(awb.frame));
    EXPECT_TRUE(fi.on_request(rec.frame));  // the device did not hang
  }
  EXPECT_FALSE(fi.hung());
  std::vector<topsim::Emission> out;
  fi.apply(kGay, false, out);
  EXPECT_EQ(out.size(), 1u);
}

TEST(Faults, SeededProbabilitiesRepeat) {
  auto run = [](std::uint64_t seed) {
    FaultInjector fi(*parse("drop=0.5"), seed);
    std::string pattern;
    for (int i = 0; i < 64; ++i) {
      std::vector<topsim::Emission> out;
      fi.apply(kGay, false, out);
      pattern += out.empty() ? '0' : '1';
    }
    return pattern;
  };
  EXPECT_EQ(run(3), run(3));
  EXPECT_NE(run(3), run(4));
  const std::string p = run(3);
  const auto ones = std::count(p.begin(), p.end(), '1');
  EXPECT_GT(ones, 16);
  EXPECT_LT(ones, 48);
}

}  // namespace

namespace {

top::Frame frame_of(const std::string& text) { return top::parse_exact(text).frame; }

TEST(FirmwareFaults, InputClassesParseAndMatch) {
  auto id = topsim::parse_input_class("ident:GAY");
  auto bare = topsim::parse_input_class("GAY");
  auto len = topsim::parse_input_class("len:6");
  auto byte = topsim::parse_input_class("byte:FF");
  ASSERT_TRUE(id && bare && len && byte);
  EXPECT_EQ(id->to_string(), "ident:GAY");
  EXPECT_EQ(bare->to_string(), "ident:GAY");
  EXPECT_EQ(len->to_string(), "len:6");
  EXPECT_EQ(byte->to_string(), "byte:FF");
  const top::Frame gay = frame_of(top::with_checksum("#TPUG6wGAYEF0732"));
  EXPECT_TRUE(id->matches(gay));
  EXPECT_TRUE(len->matches(gay));
  EXPECT_FALSE(byte->matches(gay));
  EXPECT_FALSE(len->matches(frame_of(top::with_checksum("#TPUD2rAWB00"))));
  for (const char* bad : {"", "len:", "len:x", "byte:FFF", "byte:GG", "ident:GA", "size:3", "GA"})
    EXPECT_FALSE(topsim::parse_input_class(bad).has_value()) << bad;
  std::string err;
  EXPECT_FALSE(topsim::parse_faults("crash-on=len:x", err).has_value());
  EXPECT_NE(err.find("crash-on=len:x"), std::string::npos);
  EXPECT_FALSE(topsim::parse_faults("answer-corrupt=1", err).has_value());
  auto c =
      topsim::parse_faults("crash-on=byte:23,hang-on=len:4,hang-s=2,slow-on=VER,slow-ms=50", err);
  ASSERT_TRUE(c.has_value()) << err;
  EXPECT_TRUE(c->any());
  EXPECT_EQ(c->hang_s, 2u);
  EXPECT_EQ(c->slow_ms, 50u);
  EXPECT_EQ(c->hang_on, "");
}

TEST(FirmwareFaults, CrashUntilRestartHangForSecondsSlowAndAnswerCorrupt) {
  std::string err;
  top::Frame gay = frame_of(top::with_checksum("#TPUG6wGAYEF0732"));
  top::Frame awb = frame_of(top::with_checksum("#TPUD2rAWB00"));
  {
    FaultInjector fi(*topsim::parse_faults("crash-on=ident:GAY", err), 1);
    EXPECT_TRUE(fi.admit(awb, 0));
    EXPECT_FALSE(fi.admit(gay, 10));
    EXPECT_TRUE(fi.crashed());
    EXPECT_FALSE(fi.admit(awb, 10000000));  // still down, however long
    fi.restart();
    EXPECT_TRUE(fi.admit(awb, 10000001));
  }
  {
    FaultInjector fi(*topsim::parse_faults("hang-on=ident:GAY,hang-s=2", err), 1);
    EXPECT_FALSE(fi.admit(gay, 1000000));
    EXPECT_FALSE(fi.admit(awb, 2999999));
    EXPECT_TRUE(fi.admit(awb, 3000000));  // two seconds later it answers again
  }
  {
    FaultInjector fi(*topsim::parse_faults("slow-on=ident:GAY,slow-ms=40", err), 1);
    std::vector<topsim::Emission> out;
    EXPECT_TRUE(fi.admit(gay, 0));
    fi.apply("#TPGU6wGAYEF073248", false, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].delay_us, 40000u);
  }
  {
    top::Frame bad = frame_of("#TPUD2rAWB0000");
    ASSERT_FALSE(bad.ok());
    FaultInjector strict(topsim::FaultConfig{}, 1);
    top::Frame copy = bad;
    EXPECT_TRUE(strict.admit(copy, 0));
    EXPECT_FALSE(copy.ok());  // the device model drops it
    FaultInjector lax(*topsim::parse_faults("answer-corrupt", err), 1);
    EXPECT_TRUE(lax.admit(bad, 0));
    EXPECT_TRUE(bad.ok());  // repaired: the device answers it
  }
}

}  // namespace
