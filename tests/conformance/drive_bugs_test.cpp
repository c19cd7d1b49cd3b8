// The driver-like clients' bug switches (drive_client/drive_api.hpp), in
// process against topsim over a real pty or UDP socket (run_driver), each
// with the case of topconf drive that names it (docs/DRIVE.md): the clean
// client does what the case asks of a good driver, the client with the bug
// does not, on the wire or in its beliefs. (topconf drive's own proof of the
// same, through the built topkit_drive_client, is drive_proof.cmake.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "drive_client/agent.hpp"
#include "driver_harness.hpp"
#include "driver_skydroid.hpp"
#include "sim/faults.hpp"
#include "topotek_client.hpp"

namespace {

using drive::Bug;
using drive::Intent;

// A client acting on intents at its ticks, and what it sent, with the time
// since its start.
template <class Client>
class Driven : public Client {
 public:
  explicit Driven(std::vector<Intent> v, drive::Bugs b = {}) : script_(std::move(v)) {
    this->bugs = b;
    this->idle = true;
    this->guard = true;  // as topkit_drive_client runs them
  }
  struct Sent {
    std::uint64_t t_us;
    std::string frame;
  };
  std::vector<Sent> sent;
  std::uint64_t tick(std::uint64_t now_us, std::vector<std::string>& out) override {
    if (start_ == 0) start_ = now_us;
    script_.run_due(*this, now_us - start_, now_us);
    const std::size_t from = out.size();
    const std::uint64_t next = Client::tick(now_us, out);
    for (std::size_t i = from; i < out.size(); ++i) sent.push_back({now_us - start_, out[i]});
    return next;
  }
  std::uint64_t start() const { return start_; }
  // The frames sent of `ident`.
  std::vector<Sent> of(std::string_view ident) const {
    std::vector<Sent> v;
    for (const Sent& s : sent)
      if (s.frame.size() > 10 && s.frame.compare(7, 3, ident) == 0) v.push_back(s);
    return v;
  }
  // How many `ident` frames that `moves` went out when the last attitude
  // taken was over 1.2 s old.
  template <class Moves>
  int sent_on_stale(std::string_view ident, Moves moves) const {
    int n = 0;
    for (const Sent& s : of(ident)) {
      std::uint64_t last = 0;
      for (const auto& a : this->attitude)
        if (a.t_us - start_ <= s.t_us) last = a.t_us - start_;
      n += moves(s) && s.t_us - last > 1200000;
    }
    return n;
  }

 private:
  drive::Script script_;
  std::uint64_t start_ = 0;
};

Intent at(double t_s, Intent::Do what, double yaw = 0, double pitch = 0) {
  Intent i;
  i.at_us = static_cast<std::uint64_t>(t_s * 1e6);
  i.what = what;
  i.yaw = yaw, i.pitch = pitch;
  return i;
}

topsim::FaultConfig faults(const std::string& spec) {
  std::string why;
  const auto f = topsim::parse_faults(spec, why);
  EXPECT_TRUE(f.has_value()) << spec << ": " << why;
  return f.value_or(topsim::FaultConfig{});
}

constexpr auto kPty = topsim::TransportKind::pty;

// Each bug's test runs twice, clean and with the bug, as two tests.
class DriveBugsBoth : public ::testing::TestWithParam<bool> {};
constexpr auto kUdp = topsim::TransportKind::udp;

// pitch-rate-sign (case 2.1): a positive pitch rate intent raises the pitch;
// with the bug it lowers it, until the runaway guard gives the axis up.
TEST_P(DriveBugsBoth, PitchRateSign) {
  for (const top::Model m : {top::Model::sip, top::Model::c12}) {
    const std::vector<Intent> v = {at(0.4, Intent::Do::rate, 0, 10), at(1.4, Intent::Do::stop)};
    const bool bug = GetParam();
    SCOPED_TRACE(std::string(top::to_string(m)) + (bug ? " with the bug" : " clean"));
    drive::Bugs b;
    if (bug) b.set(Bug::pitch_rate_sign);
    double last = 0;
    if (m == top::Model::sip) {
      Driven<TopotekClient> c(v, b);
      run_driver(c, m, kPty, 1800, "");
      ASSERT_FALSE(c.attitude.empty());
      last = c.attitude.back().pitch;
      EXPECT_EQ(!c.error.empty(), bug) << c.error;
    } else {
      Driven<SkyDroidDriver> c(v, b);
      run_driver(c, m, kUdp, 1800, "");
      ASSERT_FALSE(c.attitude.empty());
      last = c.attitude.back().pitch;
      EXPECT_EQ(!c.error.empty(), bug) << c.error;
    }
    if (bug) {
      EXPECT_LT(last, -2.0);
      EXPECT_GT(last, -6.0);  // the guard stopped it near 3 deg
    } else {
      EXPECT_GT(last, 6.0);
    }
  }
}

// uart-address-on-network (6.4): over UDP a Topotek camera answers only a
// request whose source is P; U gets no answer (PR #33803).
TEST(DriveBugs, UartAddressOnNetwork) {
  for (const bool bug : {false, true}) {
    SCOPED_TRACE(bug ? "with the bug" : "clean");
    drive::Bugs b;
    if (bug) b.set(Bug::uart_address_on_network);
    Driven<TopotekClient> c({at(0.1, Intent::Do::identity)}, b);
    run_driver(c, top::Model::sip, kUdp, 1200, "");
    ASSERT_FALSE(c.sent.empty());
    for (const auto& s : c.sent) {
      ASSERT_EQ(s.frame[3], bug ? 'U' : 'P') << s.frame;
    }
    EXPECT_EQ(c.attitude.empty(), bug);
    EXPECT_EQ(c.version_parsed, !bug);
  }
  // On a serial line both say U.
  drive::Bugs b;
  Driven<TopotekClient> c({}, b.set(Bug::uart_address_on_network));
  run_driver(c, top::Model::sip, kPty, 600, "");
  EXPECT_FALSE(c.attitude.empty());
}

// strict-version (3.2): "123" is 1.2.3 to a good driver, 123.0.0 to the
// strict parser; a short "1" is 1, or 1.0.0 (3.3). The parser on the
// version forms, then the clients on topsim's answer (VSN, VER "V...").
TEST(DriveBugs, StrictVersion) {
  struct Want {
    std::string reply, clean, strict;
  };
  for (const Want& w : {Want{"123", "1.2.3", "123.0.0"}, Want{"1", "1", "1.0.0"},
                        Want{"1.6.26.R.D", "1.6.26", "1.6.26"}, Want{"1.0.78", "1.0.78", "1.0.78"},
                        Want{"1.2.3", "1.2.3", "1.2.3"}, Want{"R.D", "", ""}}) {
    EXPECT_EQ(drive::parse_version(w.reply, false).text(), w.clean) << w.reply;
    EXPECT_EQ(drive::parse_version(w.reply, true).text(), w.strict) << w.reply;
  }
  for (const bool bug : {false, true}) {
    SCOPED_TRACE(bug ? "strict" : "clean");
    drive::Bugs b;
    if (bug) b.set(Bug::strict_version);
    const std::vector<Intent> v = {at(0.1, Intent::Do::identity)};
    topsim::DeviceOptions o;
    o.version = "123";
    Driven<TopotekClient> t(v, b);
    run_driver(t, top::Model::sip, kPty, 1200, "", o);  // VSN at the round robin's step 0, 0.9 s
    EXPECT_EQ(t.beliefs(0).version.value_or("none"), bug ? "123.0.0" : "1.2.3");
    o.version = "V123";
    Driven<SkyDroidDriver> k(v, b);
    run_driver(k, top::Model::c12, kUdp, 1200, "", o);
    EXPECT_EQ(k.beliefs(0).version.value_or("none"), bug ? "123.0.0" : "1.2.3");
  }
}

// echo-as-attitude (6.5): a device that echoes writes echoes GIA 01; the
// clean client ignores the 2-char GIA, the buggy one reads an attitude from
// its checksum and the leftovers of the last GIA (yaw 2.56-5.11 deg off).
TEST(DriveBugs, EchoAsAttitude) {
  topsim::DeviceOptions o;
  o.write_echo = true;
  for (const bool bug : {false, true}) {
    SCOPED_TRACE(bug ? "with the bug" : "clean");
    drive::Bugs b;
    if (bug) b.set(Bug::echo_as_attitude);
    Driven<TopotekClient> c({}, b);
    run_driver(c, top::Model::sip, kPty, 2300, "", o);
    EXPECT_GE(c.short_gia, 2);  // the echoes came
    double worst = 0;
    for (const auto& a : c.attitude) worst = std::max(worst, std::fabs(a.yaw));
    if (bug) {
      EXPECT_GT(worst, 2.5);
    } else {
      EXPECT_LT(worst, 0.1);
    }
  }
}

// range-fixed-offsets (8.3): a range reply of another length than the
// document's 00012.5 is read right by its length, and wrong at fixed offsets.
TEST(DriveBugs, RangeFixedOffsets) {
  for (const std::string data : {"12.5", "00012.5", "812.25"}) {
    const std::string raw = top::build_frame({.header = top::Header::variable,
                                              .src = 'M',
                                              .dst = 'P',
                                              .control = 'w',
                                              .ident = "LRF",
                                              .data = data});
    const top::ParseResult p = top::parse_exact(raw);
    ASSERT_EQ(p.status, top::ParseStatus::frame) << raw;
    TopotekClient clean, buggy;
    buggy.bugs.set(Bug::range_fixed_offsets);
    clean.on_frame(p.frame, 1), buggy.on_frame(p.frame, 1);
    EXPECT_NEAR(clean.distance_m, std::stod(data), 1e-9) << raw;
    if (data.size() == 7) {
      EXPECT_NEAR(buggy.distance_m, 12.5, 1e-9) << raw;
    } else {
      EXPECT_GT(std::fabs(buggy.distance_m - std::stod(data)), 1) << raw << " " << buggy.distance_m;
    }
  }
  // And from topsim: the document's form, both right; the short form
  // (range-form=short), right by its length only.
  topsim::DeviceOptions o;
  o.range_m = 812.3;
  for (const bool shorter : {false, true}) {
    for (const bool bug : {false, true}) {
      SCOPED_TRACE(std::string(shorter ? "short" : "document") + (bug ? ", bug" : ", clean"));
      drive::Bugs b;
      if (bug) b.set(Bug::range_fixed_offsets);
      Driven<TopotekClient> c({at(0.2, Intent::Do::range)}, b);
      run_driver(c, top::Model::sip, kPty, 600, "", o, faults(shorter ? "range-form=short" : ""));
      ASSERT_TRUE(c.beliefs(0).range_m.has_value());
      EXPECT_EQ(std::fabs(*c.beliefs(0).range_m - 812.3) < 1e-9, !(bug && shorter))
          << *c.beliefs(0).range_m;
    }
  }
}

// month-zero-based (9.1): the clock intent of December 6 sets month 12, or
// 11 with the bug (UTC HHMMSSDDMMYY on the SIP, TIM hhmmss.ccDDMMYY on SkyDroid).
TEST(DriveBugs, MonthZeroBased) {
  Intent clock = at(0.2, Intent::Do::clock);
  clock.utc = "2026-12-06T12:00:00Z";
  for (const bool bug : {false, true}) {
    drive::Bugs b;
    if (bug) b.set(Bug::month_zero_based);
    Driven<TopotekClient> t({clock}, b);
    run_driver(t, top::Model::sip, kPty, 500, "");
    // The first clock write at or after the intent (the SIP's own UTC after
    // an SD card reply, and SkyDroid's TIM every second, go out too).
    const auto after = [](const auto& v) {
      const auto i =
          std::find_if(v.begin(), v.end(), [](const auto& s) { return s.t_us >= 200000; });
      return i == v.end() ? std::string() : i->frame;
    };
    EXPECT_EQ(after(t.of("UTC")).substr(10, 12), bug ? "120000061126" : "120000061226");
    Driven<SkyDroidDriver> s({clock}, b);
    run_driver(s, top::Model::c12, kUdp, 500, "");
    EXPECT_EQ(after(s.of("TIM")).substr(10, 15), bug ? "120000.00061126" : "120000.00061226");
  }
}

// no-stop-after-last-rate (2.4): after the stop intent a zero rate goes
// out within 0.5 s (PTZ 00 on the SIP, GSY/GSP 00 on SkyDroid); none with
// the bug.
TEST_P(DriveBugsBoth, NoStopAfterLastRate) {
  const std::vector<Intent> v = {at(0.3, Intent::Do::rate, 10, 0), at(1.0, Intent::Do::stop)};
  const bool bug = GetParam();
  SCOPED_TRACE(bug ? "with the bug" : "clean");
  drive::Bugs b;
  if (bug) b.set(Bug::no_stop_after_last_rate);
  Driven<TopotekClient> t(v, b);
  run_driver(t, top::Model::sip, kPty, 1700, "");
  EXPECT_FALSE(t.of("YPR").empty());
  int stops = 0;
  for (const auto& s : t.of("PTZ"))
    stops += s.frame.substr(10, 2) == "00" && s.t_us >= 1000000 && s.t_us <= 1500000;
  EXPECT_EQ(stops > 0, !bug);
  Driven<SkyDroidDriver> k(v, b);
  run_driver(k, top::Model::c12, kUdp, 1700, "");
  int zeros = 0, moving = 0;
  for (const auto& s : k.of("GSY")) {
    if (s.frame.substr(10, 2) == "00" && s.t_us >= 1000000 && s.t_us <= 1500000) ++zeros;
    if (s.frame.substr(10, 2) != "00") ++moving;
  }
  EXPECT_GT(moving, 10);
  EXPECT_EQ(zeros > 0, !bug);
  EXPECT_LE(zeros, 3);  // a stop is said three times, not at every update
}

// no-reenable-after-reboot (1.4): the device power-cycles at 1 s with its
// streams off (reboot=1); the stream switch goes out every second, so the
// attitude comes back; with the bug it went out only until the first
// attitude, and after the reboot none comes.
TEST_P(DriveBugsBoth, NoReenableAfterReboot) {
  const bool bug = GetParam();
  SCOPED_TRACE(bug ? "with the bug" : "clean");
  drive::Bugs b;
  if (bug) b.set(Bug::no_reenable_after_reboot);
  const auto after_reboot = [](const auto& c) {
    return std::count_if(c.attitude.begin(), c.attitude.end(),
                         [&](const auto& a) { return a.t_us - c.start() > 2300000; });
  };
  Driven<TopotekClient> t({}, b);
  run_driver(t, top::Model::sip, kPty, 3400, "", {}, faults("reboot=1"));
  EXPECT_EQ(t.of("GIA").size(), bug ? 1u : 4u);  // at 0.1, 1.1, 2.1, 3.1 s
  EXPECT_EQ(after_reboot(t) > 0, !bug);
  Driven<SkyDroidDriver> k({}, b);
  run_driver(k, top::Model::c12, kUdp, 3400, "", {}, faults("reboot=1"));
  EXPECT_EQ(k.of("GAA").size(), bug ? 1u : 4u);
  EXPECT_EQ(after_reboot(k) > 0, !bug);
}

// rates-on-stale-attitude (2.5): the stream stalls from 1 s for 1.5 s under
// a held yaw rate; no rate command while the last attitude is over 1.2 s
// old, but with the bug. And while no attitude ever came (1.1), neither.
TEST_P(DriveBugsBoth, RatesOnStaleAttitude) {
  const std::vector<Intent> v = {at(0.4, Intent::Do::rate, 10, 0)};
  const bool bug = GetParam();
  SCOPED_TRACE(bug ? "with the bug" : "clean");
  drive::Bugs b;
  if (bug) b.set(Bug::rates_on_stale_attitude);
  Driven<TopotekClient> t(v, b);
  run_driver(t, top::Model::sip, kPty, 3000, "", {}, faults("stall=GIA@1+1.5"));
  const int stale = t.sent_on_stale("YPR", [](const auto&) { return true; });
  EXPECT_EQ(stale > 0, bug) << stale;
  EXPECT_FALSE(t.of("YPR").empty());  // and before the stall, rates went out
  Driven<SkyDroidDriver> k(v, b);
  run_driver(k, top::Model::c12, kUdp, 3000, "", {}, faults("stall=GAC@1+1.5"));
  const int moving_stale =
      k.sent_on_stale("GSY", [](const auto& s) { return s.frame.substr(10, 2) != "00"; });
  EXPECT_EQ(moving_stale > 0, bug) << moving_stale;
  // Never a rate with no attitude at all (1.1), bug or not.
  Driven<TopotekClient> n(v, b);
  run_driver(n, top::Model::sip, kPty, 1200, "", {}, faults("no-stream=GIA"));
  EXPECT_TRUE(n.attitude.empty());
  EXPECT_TRUE(n.of("YPR").empty());
}

// The runaway guard (2.2): on a device whose pitch answers the other way,
// SkyDroid's angle loop (GSP) is given up after 3 deg the wrong way, with an
// error, instead of running to the limit; the belief follows the device.
TEST(DriveBugs, RunawayGuardOnAnInvertedPitch) {
  Driven<SkyDroidDriver> k({at(0.3, Intent::Do::angle, 0, -30)});
  run_driver(k, top::Model::c12, kUdp, 2500, "", {}, faults("invert=pitch"));
  ASSERT_FALSE(k.attitude.empty());
  double highest = -90;
  for (const auto& a : k.attitude) highest = std::max(highest, a.pitch);
  EXPECT_GT(highest, 2.0);   // it did turn the wrong way
  EXPECT_LT(highest, 10.0);  // and was stopped, far from the limit
  EXPECT_NE(k.error.find("pitch turns against"), std::string::npos) << k.error;
  // Without the fault, the loop reaches the target and the guard stays quiet.
  Driven<SkyDroidDriver> ok({at(0.3, Intent::Do::angle, 0, -30)});
  run_driver(ok, top::Model::c12, kUdp, 2500, "");
  ASSERT_FALSE(ok.attitude.empty());
  EXPECT_NEAR(ok.attitude.back().pitch, -30, 5);
  EXPECT_TRUE(ok.error.empty()) << ok.error;
}

INSTANTIATE_TEST_SUITE_P(Switch, DriveBugsBoth, ::testing::Bool(),
                         [](const auto& i) { return i.param ? "bug" : "clean"; });

}  // namespace
