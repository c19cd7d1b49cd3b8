// Data-driven vectors: every complete example frame of both documents
// (tests/vectors/skydroid.json, topotek.json) and our own cases (extra.json),
// one test name per vector.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "test_util.hpp"
#include "top/detail/text.hpp"

using namespace top;
using json = nlohmann::json;

namespace {

struct Vector {
  std::string file;
  json v;
};

// JSON strings are UTF-8; each code point <= 0xFF stands for one byte.
std::string bytes_of(const std::string& utf8) { return top::bytes_from_utf8(utf8).value(); }

std::vector<Vector> load() {
  std::vector<Vector> all;
  std::filesystem::path dir = std::filesystem::path(TOPKIT_SOURCE_DIR) / "tests" / "vectors";
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& p : files) {
    std::ifstream in(p);
    json doc = json::parse(in);
    for (const auto& v : doc.at("vectors")) all.push_back({p.filename().string(), v});
  }
  return all;
}

const std::vector<Vector>& vectors() {
  static const std::vector<Vector> v = load();
  return v;
}

struct Result {
  std::set<std::string> codes;
  bool valid = true;
  std::vector<std::string> idents;
  std::vector<Decoded> decoded;
  std::vector<Frame> frames;
  std::string describe;
};

Result run(const std::vector<StreamItem>& items, const json& v) {
  Result r;
  DecodeOptions o;
  o.dialect = dialect_from_string(v.value("dialect", "auto")).value_or(Dialect::unknown);
  o.model = model_from_string(v.value("model", "auto")).value_or(Model::unknown);
  for (const auto& it : items) {
    if (it.kind == ItemKind::garbage) {
      r.codes.insert(std::string(to_string(it.finding.code)));
      if (it.finding.severity == Severity::error) r.valid = false;
      continue;
    }
    for (const auto& f : it.frame.findings) {
      r.codes.insert(std::string(to_string(f.code)));
      if (f.severity == Severity::error) r.valid = false;
    }
    Decoded d = decode(it.frame, o);
    for (const auto& f : d.findings) {
      r.codes.insert(std::string(to_string(f.code)));
      if (f.severity == Severity::error) r.valid = false;
    }
    r.idents.emplace_back(it.frame.ident_view());
    r.decoded.push_back(std::move(d));
    r.frames.push_back(it.frame);
  }
  r.describe = toptest::describe(items);
  return r;
}

}  // namespace

class VectorTest : public ::testing::TestWithParam<std::size_t> {};

TEST_P(VectorTest, Verdict) {
  const Vector& vec = vectors()[GetParam()];
  const json& v = vec.v;
  const std::string bytes = bytes_of(v.at("bytes").get<std::string>());
  SCOPED_TRACE(vec.file + ": " + v.value("section", "") + " " + v.value("note", ""));

  Result whole = run(toptest::decode_all(bytes), v);
  std::set<std::string> expected;
  for (const auto& c : v.at("findings")) expected.insert(c.get<std::string>());
  EXPECT_EQ(whole.codes, expected) << whole.describe;
  EXPECT_EQ(whole.valid, v.at("valid").get<bool>()) << whole.describe;
  if (v.contains("ident")) {
    ASSERT_EQ(whole.idents.size(), 1u) << whole.describe;
    EXPECT_EQ(whole.idents[0], v.at("ident").get<std::string>());
  }
  if (v.contains("fields") && !whole.decoded.empty()) {
    const Decoded& d = whole.decoded[0];
    for (const auto& [name, want] : v.at("fields").items()) {
      const FieldValue* fv = nullptr;
      for (const auto& f : d.fields)
        if (field_key(f) == name) fv = &f;  // a record's field: "x[1]"
      ASSERT_NE(fv, nullptr) << "no field " << name;
      if (want.is_number()) {
        EXPECT_NEAR(fv->value, want.get<double>(), 1e-6) << name;
      } else {
        std::string w = want.get<std::string>();
        EXPECT_TRUE(fv->enum_name == w || fv->text == w)
            << name << ": want " << w << ", got " << format_value(*fv);
      }
    }
  }
  // The same verdict from an exact-size buffer and split at every byte.
  if (whole.frames.size() == 1 && whole.valid) {
    toptest::ExactBuffer buf(bytes);
    Result exact = run(toptest::decode_all(buf.view()), v);
    EXPECT_EQ(exact.describe, whole.describe);
    for (std::size_t cut = 1; cut < bytes.size(); ++cut) {
      top::StreamDecoder d;
      toptest::ExactBuffer a(std::string_view(bytes).substr(0, cut));
      toptest::ExactBuffer b(std::string_view(bytes).substr(cut));
      d.feed(a.view());
      d.feed(b.view());
      d.finish();
      std::vector<StreamItem> items;
      StreamItem it;
      while (d.next(it)) items.push_back(std::move(it));
      ASSERT_EQ(toptest::describe(items), whole.describe) << "split at " << cut;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Docs, VectorTest, ::testing::Range<std::size_t>(0, vectors().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& i) {
                           return vectors()[i.param].v.at("name").get<std::string>();
                         });

TEST(Vectors, NamesAreUniqueAndFilesPresent) {
  std::set<std::string> names;
  std::set<std::string> files;
  for (const auto& v : vectors()) {
    EXPECT_TRUE(names.insert(v.v.at("name").get<std::string>()).second) << v.v.at("name");
    files.insert(v.file);
  }
  EXPECT_TRUE(files.count("skydroid.json"));
  EXPECT_TRUE(files.count("topotek.json"));
  EXPECT_TRUE(files.count("extra.json"));
  EXPECT_GT(vectors().size(), 150u);
}

namespace {

// Everything a parse says about a frame, as text.
std::string describe_parse(const ParseResult& r) {
  std::string s = std::to_string(static_cast<int>(r.status)) + " " + std::to_string(r.consumed);
  if (r.status != ParseStatus::frame)
    return s + " " + std::string(to_string(r.error.code)) + "@" + std::to_string(r.error.offset) +
           " " + r.error.message;
  const Frame& f = r.frame;
  s += " " + f.raw + " h" + std::to_string(static_cast<int>(f.header)) + " " + f.src + f.dst +
       std::to_string(f.control) + std::string(f.ident_view()) + " L" +
       std::to_string(f.declared_length) + "/" + std::to_string(f.data_length) + "@" +
       std::to_string(f.data_offset) + " c" + std::to_string(f.checksum) + "/" +
       std::to_string(f.expected_checksum) + (f.checksum_present ? "p" : "") +
       (f.checksum_ok ? "k" : "") + " t" + std::to_string(f.terminator);
  for (const auto& x : f.findings)
    s += " [" + std::string(to_string(x.code)) + "@" + std::to_string(x.offset) + " " + x.message +
         "]";
  return s;
}

std::string describe_decoded(const Decoded& d) {
  std::string s = std::to_string(static_cast<int>(d.dialect)) + " " +
                  std::to_string(static_cast<int>(d.role)) + " " +
                  (d.command ? std::string(d.command->ident) : "-") + " " +
                  (d.form ? std::to_string(d.form->min_length) : "-") + " " + d.summary();
  for (const auto& x : d.findings)
    s += " [" + std::string(to_string(x.code)) + "@" + std::to_string(x.offset) + " " + x.message +
         "]";
  return s;
}

}  // namespace

// parse_frame and decode into a reused result (the analyzer's loop) give
// what the fresh ones give, whatever the previous frame left behind: every
// vector, and each vector cut short, in order and in reverse.
TEST(Vectors, ReusedParseAndDecodeEqualFresh) {
  ParseResult reused;
  Decoded reused_d;
  std::vector<std::string> inputs;
  for (const auto& v : vectors()) {
    const std::string b = bytes_of(v.v.at("bytes").get<std::string>());
    inputs.push_back(b);
    if (b.size() > 4) inputs.push_back(b.substr(0, b.size() - 3));
  }
  std::vector<std::string> order = inputs;
  order.insert(order.end(), inputs.rbegin(), inputs.rend());
  std::size_t frames = 0;
  for (const std::string& b : order) {
    for (bool at_end : {true, false}) {
      const ParseResult fresh = parse_frame(b, at_end);
      parse_frame(b, at_end, ParseOptions{}, reused);
      ASSERT_EQ(describe_parse(reused), describe_parse(fresh)) << b;
      if (fresh.status != ParseStatus::frame) continue;
      ++frames;
      for (Dialect dl : {Dialect::unknown, Dialect::skydroid, Dialect::topotek}) {
        const DecodeOptions o{dl, Model::unknown, Role::any};
        decode(reused.frame, o, reused_d);
        ASSERT_EQ(describe_decoded(reused_d), describe_decoded(decode(fresh.frame, o))) << b;
      }
    }
  }
  EXPECT_GT(frames, 300u);
}

namespace {

// The verdict of a decode: what a caller that only counts needs.
std::string describe_verdict(const Decoded& d) {
  std::string s = std::to_string(static_cast<int>(d.dialect)) + " " +
                  std::to_string(static_cast<int>(d.role)) + " " +
                  (d.command ? std::string(d.command->ident) : "-") + " " +
                  (d.form ? std::to_string(d.form - d.command->forms.data()) : "-");
  for (const auto& x : d.findings)
    s += " [" + std::string(to_string(x.code)) + "/" +
         std::to_string(static_cast<int>(x.severity)) + "@" + std::to_string(x.offset) + " " +
         std::string(x.quirk) + "]";
  return s;
}

}  // namespace

// Decoding without detail (topdump stats) gives the verdict decoding with
// detail gives, findings and their severities and offsets included, with no
// field values and no messages: every vector and each cut short, under
// every dialect, role and a model of each dialect, into one reused result.
TEST(Vectors, DecodeWithoutDetailKeepsTheVerdict) {
  Decoded lean;
  std::size_t frames = 0, with_findings = 0;
  for (const auto& v : vectors()) {
    const std::string b = bytes_of(v.v.at("bytes").get<std::string>());
    for (const std::string& in : {b, b.size() > 4 ? b.substr(0, b.size() - 3) : b}) {
      const ParseResult r = parse_frame(in, true);
      if (r.status != ParseStatus::frame) continue;
      ++frames;
      for (Dialect dl : {Dialect::unknown, Dialect::skydroid, Dialect::topotek})
        for (Role role : {Role::any, Role::request, Role::response})
          for (Model m : {Model::unknown, Model::c12, Model::sip}) {
            DecodeOptions o{dl, m, role};
            const Decoded full = decode(r.frame, o);
            o.detail = false;
            decode(r.frame, o, lean);
            ASSERT_EQ(describe_verdict(lean), describe_verdict(full)) << in;
            EXPECT_TRUE(lean.fields.empty()) << in;
            for (const auto& x : lean.findings) EXPECT_TRUE(x.message.empty()) << in;
            with_findings += !full.findings.empty();
          }
    }
  }
  EXPECT_GT(frames, 150u);
  EXPECT_GT(with_findings, 1000u);
}
