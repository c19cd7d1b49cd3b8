// The device rules of top/device.hpp that topsim, topconf, the fuzzers and
// topdump all ask: which link answers which source, which findings make a
// device reject a request, the ERE reply, the timing limits.
#include "top/device.hpp"

#include <gtest/gtest.h>

#include <string>

#include "top/top.hpp"

using namespace top;

namespace {

Decoded decode_text(const std::string& text, Model model) {
  const ParseResult r = parse_exact(with_checksum(text));
  EXPECT_EQ(r.status, ParseStatus::frame) << text;
  DecodeOptions o;
  o.dialect = dialect_of(model);
  o.model = model;
  return decode(r.frame, o);
}

}  // namespace

TEST(DeviceRules, ClientAddressIsTheLinksOnTopotekAndUOnSkydroid) {
  EXPECT_EQ(client_address(Dialect::topotek, Link::network), 'P');
  EXPECT_EQ(client_address(Dialect::topotek, Link::uart), 'U');
  EXPECT_EQ(client_address(Dialect::skydroid, Link::network), 'U');
  EXPECT_EQ(client_address(Dialect::skydroid, Link::uart), 'U');
}

// Topotek 2: the source byte names the interface; the trait is a document
// rule, so it holds under both profiles.
TEST(DeviceRules, TopotekAnswersOnlyTheLinkTheSourceNames) {
  for (Profile p : {Profile::field, Profile::document}) {
    EXPECT_TRUE(answers_source(Model::sip, p, Link::network, 'P'));
    EXPECT_FALSE(answers_source(Model::sip, p, Link::network, 'U'));
    EXPECT_TRUE(answers_source(Model::sip, p, Link::uart, 'U'));
    EXPECT_FALSE(answers_source(Model::sip, p, Link::uart, 'P'));
  }
  ASSERT_NE(find_trait(TraitKind::link_by_source, Model::sip, Profile::document), nullptr);
  // A capture's device of unknown model: the dialect's rule.
  EXPECT_FALSE(answers_source(Dialect::topotek, Profile::field, Link::network, 'U'));
  EXPECT_TRUE(answers_source(Dialect::topotek, Profile::field, Link::uart, 'U'));
  EXPECT_TRUE(answers_source(Dialect::skydroid, Profile::field, Link::network, 'P'));
}

TEST(DeviceRules, SkydroidAnswersEverySource) {
  for (Model m : {Model::c10, Model::c12, Model::c13, Model::c20})
    for (Link l : {Link::network, Link::uart})
      for (char src : {'U', 'P'}) EXPECT_TRUE(answers_source(m, Profile::field, l, src));
}

TEST(DeviceRules, RejectionOfACleanCommandIsNone) {
  EXPECT_EQ(rejection(decode_text("#TPUG2wGAA0A", Model::c12), Model::c12), Rejection::none);
  EXPECT_EQ(rejection(Decoded{}, Model::c12), Rejection::none);
}

TEST(DeviceRules, UnknownIdentifierIsUnsupported) {
  const Decoded d = decode_text("#TPUG2wQQQ01", Model::c12);
  EXPECT_EQ(rejection(d, Model::c12), Rejection::unsupported);
}

TEST(DeviceRules, WrongLengthOrRangeIsInvalid) {
  EXPECT_EQ(rejection(decode_text("#TPUG4wGAA0A0B", Model::c12), Model::c12), Rejection::invalid);
  EXPECT_EQ(rejection(decode_text("#tpUG6wGAY7FFF10", Model::c12), Model::c12), Rejection::invalid);
}

// C13 PTZ 0E: the document lists PTZ for other models, field evidence says
// the C13 takes it. The decoder makes that a warning; the field profile
// takes it, the document profile (no field evidence) refuses it.
TEST(DeviceRules, FieldEvidenceLiftsUnsupportedOnModel) {
  const Decoded d = decode_text("#TPUG2wPTZ0E", Model::c13);
  ASSERT_FALSE(d.findings.empty());
  EXPECT_EQ(rejection(d, Model::c13, true), Rejection::none);
  EXPECT_EQ(rejection(d, Model::c13, false), Rejection::unsupported);
  // The evidence names the values it saw working: PTZ 06 (follow) is not
  // one of them, so the C13 refuses it whatever the decoder's severity.
  EXPECT_EQ(rejection(decode_text("#TPUG2wPTZ06", Model::c13), Model::c13, true),
            Rejection::unsupported);
}

TEST(DeviceRules, UnsupportedWinsOverInvalid) {
  Decoded d;
  d.findings = {make_finding(FindingCode::data_length, 0, ""),
                make_finding(FindingCode::unknown_ident, 0, "")};
  EXPECT_EQ(rejection(d, Model::c12), Rejection::unsupported);
  d.findings.pop_back();
  EXPECT_EQ(rejection(d, Model::c12), Rejection::invalid);
  EXPECT_TRUE(rejects(FindingCode::bad_field));
  EXPECT_FALSE(rejects(FindingCode::bad_checksum));
  EXPECT_FALSE(rejects(FindingCode::lowercase_hex));
}

// SkyDroid 2.3.2's example: a rejected request to the lens is answered
// #TPMU2wERE!!30, addresses swapped; Topotek documents no such reply.
TEST(DeviceRules, ErrorReplyIsTheDocumentsExample) {
  const ParseResult r = parse_exact(with_checksum("#TPUM2wZZZ01"));
  ASSERT_EQ(r.status, ParseStatus::frame);
  const std::string ere = build_frame(error_reply(r.frame));
  EXPECT_EQ(ere, "#TPMU2wERE!!30");
  const ParseResult back = parse_exact(ere);
  ASSERT_EQ(back.status, ParseStatus::frame);
  EXPECT_TRUE(is_error_reply(back.frame));
  EXPECT_FALSE(is_error_reply(r.frame));
  EXPECT_TRUE(answers_error_reply(Dialect::skydroid));
  EXPECT_FALSE(answers_error_reply(Dialect::topotek));
}

TEST(DeviceRules, SpeedHoldIsTheTraitsValueElseTheDefault) {
  const Trait* t = find_trait(TraitKind::speed_refresh, Model::c12, Profile::field);
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(speed_hold_ms(Model::c12, Profile::field), t->value);
  // The trait is field evidence: the document profile has none.
  EXPECT_EQ(find_trait(TraitKind::speed_refresh, Model::c12, Profile::document), nullptr);
  EXPECT_EQ(speed_hold_ms(Model::c12, Profile::document), default_speed_hold_ms);
  EXPECT_EQ(find_trait(TraitKind::speed_refresh, Model::sip, Profile::field), nullptr);
  EXPECT_EQ(speed_hold_ms(Model::sip, Profile::field), default_speed_hold_ms);
}

TEST(DeviceRules, NamesOfTheRuleEnums) {
  EXPECT_EQ(to_string(Link::network), "network");
  EXPECT_EQ(to_string(Link::uart), "uart");
  EXPECT_EQ(to_string(Rejection::invalid), "invalid");
}
