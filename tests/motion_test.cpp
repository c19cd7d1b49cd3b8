// The motion table of top/motion.hpp, kept in step with the catalog.
#include "top/motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "test_util.hpp"
#include "top/top.hpp"

using namespace top;

namespace {

bool form_has_field(const CommandSpec& c, std::string_view name) {
  for (const FormSpec& f : c.forms)
    for (const FieldSpec& s : f.fields)
      if (s.name == name) return true;
  return false;
}

}  // namespace

// Every row names a command of its dialect, and every field it names is a
// field of that command's forms: a renamed field fails here, not in topsim.
TEST(Motion, EveryRowAndFieldIsInTheCatalog) {
  for (const MotionSpec& m : motions()) {
    const CommandSpec* c = find_command(m.dialect, m.ident);
    ASSERT_NE(c, nullptr) << m.ident;
    EXPECT_FALSE(m.section.empty()) << m.ident;
    if (m.kind == MotionKind::ptz) {
      EXPECT_TRUE(form_has_field(*c, "action")) << m.ident;
      continue;
    }
    EXPECT_GT(m.count, 0) << m.ident;
    for (const MotionAxis& a : m.fields()) {
      EXPECT_TRUE(form_has_field(*c, a.value)) << m.ident << " " << a.value;
      if (!a.speed.empty()) {
        EXPECT_TRUE(form_has_field(*c, a.speed)) << m.ident << " " << a.speed;
      }
      EXPECT_EQ(a.speed.empty(), m.kind != MotionKind::angle) << m.ident;
    }
  }
}

// The other way round: every gimbal command whose name says it sets an
// angle (GA?/GI? with a speed) or a speed (GS?) has a row.
TEST(Motion, EveryGimbalAngleAndSpeedCommandHasARow) {
  for (Dialect d : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(d)) {
      const std::string_view id = c.ident;
      const bool speed = id.size() == 3 && id[0] == 'G' && id[1] == 'S';
      const bool angle = id.size() == 3 && id[0] == 'G' && (id[1] == 'A' || id[1] == 'I') &&
                         form_has_field(c, "speed");
      if (speed || angle) {
        EXPECT_NE(motion_of(c.dialect, id), nullptr) << id;
      }
    }
}

TEST(Motion, AxesAndReferenceOfTheCombinedCommands) {
  const MotionSpec* gam = motion_of(Dialect::skydroid, "GAM");
  ASSERT_NE(gam, nullptr);
  ASSERT_EQ(gam->fields().size(), 2u);
  EXPECT_EQ(gam->fields()[0].axis, Axis::yaw);
  EXPECT_EQ(gam->fields()[1].axis, Axis::pitch);
  EXPECT_EQ(gam->fields()[1].speed, "pitch_speed");
  EXPECT_EQ(attitude_for(*gam), "GAC");
  const MotionSpec* gim = motion_of(Dialect::topotek, "GIM");
  ASSERT_NE(gim, nullptr);
  EXPECT_EQ(gim->reference, Reference::earth);
  EXPECT_EQ(attitude_for(*gim), "GIC");
  EXPECT_EQ(motion_of(Dialect::skydroid, "GIM"), nullptr);
  EXPECT_EQ(motion_of(Dialect::topotek, "ZMC"), nullptr);
}

// SkyDroid 3.2: pitch speed up positive. Topotek 4.2's text: down positive.
TEST(Motion, PitchRateSignPerDialect) {
  EXPECT_EQ(motion_of(Dialect::skydroid, "GSP")->fields()[0].sign, 1);
  EXPECT_EQ(motion_of(Dialect::topotek, "GSP")->fields()[0].sign, -1);
  EXPECT_EQ(motion_of(Dialect::topotek, "GSY")->fields()[0].sign, 1);
  // Angles are up positive in both documents.
  EXPECT_EQ(motion_of(Dialect::topotek, "GAP")->fields()[0].sign, 1);
}

TEST(Motion, PtzActions) {
  EXPECT_EQ(ptz_action(0x00).move, PtzMove::stop);
  EXPECT_EQ(ptz_action(0x05).move, PtzMove::centre);
  const PtzAction up = ptz_action(0x01), left = ptz_action(0x03);
  EXPECT_EQ(up.move, PtzMove::turn);
  EXPECT_EQ(up.axis, Axis::pitch);
  EXPECT_EQ(up.sign, 1);
  EXPECT_EQ(left.axis, Axis::yaw);
  EXPECT_EQ(left.sign, -1);
  // C13 trims: 0E/0F pitch, 10/11 yaw, 12/13 roll, + then -.
  EXPECT_EQ(ptz_action(0x0F).axis, Axis::pitch);
  EXPECT_EQ(ptz_action(0x0F).sign, -1);
  EXPECT_EQ(ptz_action(0x10).axis, Axis::yaw);
  EXPECT_EQ(ptz_action(0x12).axis, Axis::roll);
  EXPECT_EQ(ptz_action(0x12).sign, 1);
  EXPECT_EQ(ptz_action(0x06).move, PtzMove::none);  // follow/lock: no motion
}

// The field's Topotek signs and units (ArduPilot's AP_Mount_Topotek, PR
// #29002): GIP and the GIA attitude down positive, YPR and the angle speed
// in the driver's deg/s x 1.2207; the document's stay for its profile.
TEST(Motion, TopotekFieldSignsAndUnits) {
  const MotionSpec* gip = motion_of(Dialect::topotek, "GIP");
  ASSERT_NE(gip, nullptr);
  EXPECT_EQ(gip->fields()[0].sign_in(false), 1);
  EXPECT_EQ(gip->fields()[0].sign_in(true), -1);
  EXPECT_FALSE(gip->field_evidence.empty());
  const MotionSpec* gia = motion_of(Dialect::topotek, "GIA");
  ASSERT_NE(gia, nullptr);
  EXPECT_EQ(gia->kind, MotionKind::attitude);
  EXPECT_EQ(gia->fields()[1].axis, Axis::pitch);
  EXPECT_EQ(gia->fields()[1].sign_in(true), -1);
  const MotionSpec* ypr = motion_of(Dialect::topotek, "YPR");
  ASSERT_NE(ypr, nullptr);
  // 12 counts: 12 deg/s in the document, 12 / 1.2207 in the field.
  EXPECT_DOUBLE_EQ(motion_speed(*ypr, 12, 12, false), 12);
  EXPECT_NEAR(motion_speed(*ypr, 12, 12, true), 12 / 1.220740379, 1e-9);
  // The angle speed byte 99 (0.1 deg/s in the document).
  EXPECT_DOUBLE_EQ(motion_speed(*gip, 9.9, 99, false), 9.9);
  EXPECT_NEAR(motion_speed(*gip, 9.9, 99, true), 99 / 1.220740379, 1e-9);
  // Every row with a field sign or unit names its evidence; SkyDroid has none.
  for (const MotionSpec& m : motions()) {
    bool field = m.field_unit != 0;
    for (const MotionAxis& a : m.fields()) field = field || a.field_sign != 0;
    if (field) {
      EXPECT_FALSE(m.field_evidence.empty()) << m.ident;
    }
    if (m.dialect == Dialect::skydroid) {
      EXPECT_FALSE(field) << m.ident;
    }
  }
}

// decode() gives the command's motion row with the command, from the shape
// cache too (the session reads it for every frame): the row motion_of
// gives, and none for a command that does not move the gimbal.
TEST(Motion, DecodeGivesTheCommandsRow) {
  detail::DecodeCache cache;
  for (const bool detail : {true, false})
    for (const char* ident : {"GAC", "GAY", "PTZ", "VER"}) {
      BuildSpec b;
      b.header = Header::fixed;
      b.src = 'U';
      b.dst = 'G';
      b.control = 'w';
      b.ident = ident;
      b.data = "00";
      const ParseResult r = parse_frame(build_frame(b), true);
      ASSERT_EQ(r.status, ParseStatus::frame) << ident;
      DecodeOptions o{Dialect::skydroid, Model::unknown, Role::request};
      o.detail = detail;
      for (int twice = 0; twice < 2; ++twice) {  // the second from the cache
        const Decoded d = detail ? decode(r.frame, o) : toptest::decode_cached(r.frame, o, cache);
        ASSERT_NE(d.command, nullptr) << ident;
        EXPECT_EQ(d.motion, motion_of(Dialect::skydroid, ident)) << ident << " " << detail;
        EXPECT_EQ(d.motion == nullptr, std::string_view(ident) == "VER") << ident;
      }
    }
}

// short_way is std::remainder(d, 360.0), bit for bit: on the ties (odd
// multiples of 180, which go to the even multiple), next to them, and on
// a spread of magnitudes up to a million turns.
TEST(Motion, ShortWayIsTheRemainderBy360) {
  std::vector<double> xs = {
      0.0,     -0.0,  180.0,  -180.0, 540.0,  -540.0, 900.0, 359.99,
      -359.99, 360.0, -360.0, 720.0,  -720.0, 1e-300, 0.01,  179.99999999999997};
  for (int k = -2000; k <= 2000; ++k) {
    const double tie = 180.0 + 360.0 * k;
    xs.insert(xs.end(), {tie, std::nextafter(tie, 1e300), std::nextafter(tie, -1e300)});
  }
  std::mt19937_64 rng(7);
  for (const double scale : {1.0, 360.0, 1e4, 1e6, 3.6e8}) {
    std::uniform_real_distribution<double> u(-scale, scale);
    for (int i = 0; i < 20000; ++i) xs.push_back(u(rng));
  }
  for (const double x : xs) {
    const double want = std::remainder(x, 360.0), got = short_way(x);
    ASSERT_EQ(std::memcmp(&want, &got, sizeof want), 0) << std::hexfloat << x << " " << got;
  }
}
