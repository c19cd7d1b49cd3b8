// topconf's matrix loader: validation messages and the default matrices.
#include "conf/matrix.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <set>

#include "conf/generate.hpp"
#include "test_matrix_util.hpp"
#include "top/motion.hpp"

namespace {

using topconf::load_matrix;

const char* kMinimal = R"({
  "format": "topconf-matrix-1", "model": "c12",
  "cases": [{"id": "a", "section": "SkyDroid 3.3.1", "level": "must",
             "steps": [{"send": {"command": "GAY", "data": "EF0732"}, "expect": [{"echo": true}]}]}]})";

std::vector<std::string> errors_of(const std::string& text) {
  return load_matrix(text, "m.json").errors;
}

std::string replace(std::string s, std::string_view from, std::string_view to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

// fuzz/regressions/matrix/number-overflow-throws (found by fuzz_matrix): a
// matrix with the number 3e7043, too large for a double. nlohmann reports it
// as out_of_range 406, not parse_error, and load_matrix (which never throws)
// let it escape. Must: an error naming the file and the byte offset.
TEST(FuzzRegression, MatrixNumberOverflowIsAnErrorNotAThrow) {
  std::ifstream in(
      std::string(TOPKIT_SOURCE_DIR) + "/fuzz/regressions/matrix/number-overflow-throws",
      std::ios::binary);
  ASSERT_TRUE(in);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  topconf::LoadResult r;
  ASSERT_NO_THROW(r = load_matrix(text, "overflow.json"));
  EXPECT_FALSE(r.matrix);
  ASSERT_EQ(r.errors.size(), 1u);
  const std::size_t at = text.find("3e7043");
  ASSERT_NE(at, std::string::npos);
  // the offset is where the lexer stands after the number: its last byte
  EXPECT_NE(
      r.errors[0].find("overflow.json: (json): not valid JSON at byte " + std::to_string(at + 6)),
      std::string::npos)
      << r.errors[0];
  EXPECT_NE(r.errors[0].find("number overflow"), std::string::npos) << r.errors[0];

  // Small: the same in a minimal matrix, and a syntax error keeps its offset.
  auto e = errors_of(R"({"format": 1e999})");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_NE(e[0].find("number overflow parsing '1e999'"), std::string::npos) << e[0];
  e = errors_of(R"({"format": })");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_NE(e[0].find("m.json: (json): not valid JSON at byte 12: "), std::string::npos) << e[0];
}

TEST(Matrix, LoadsAMinimalMatrix) {
  auto r = load_matrix(kMinimal, "m.json");
  ASSERT_TRUE(r.matrix) << (r.errors.empty() ? "" : r.errors[0]);
  ASSERT_EQ(r.matrix->cases.size(), 1u);
  const auto& c = r.matrix->cases[0];
  EXPECT_EQ(c.steps.at(0).expect.at(0).kind, topconf::ExpectKind::echo);
  std::string bytes, err;
  ASSERT_TRUE(topconf::resolve_send(*c.steps[0].send, top::Dialect::skydroid, 'U', bytes, err));
  EXPECT_EQ(bytes, "#TPUG6wGAYEF073248");  // #TP for G class, checksum added
}

TEST(Matrix, ErrorsNameFileCaseAndKey) {
  auto e = errors_of(replace(kMinimal, R"("level": "must")", R"("level": "shall")"));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0], "m.json: case a: level: must be must, should or may");
  e = errors_of(replace(kMinimal, R"({"echo": true})", R"({"silence_ms": -3})"));
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e[0].rfind("m.json: case a: steps[0].expect[0].silence_ms:", 0), 0u) << e[0];
  e = errors_of(replace(kMinimal, R"("data": "EF0732")", R"("data": "EF0732", "colour": 1)"));
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e[0], "m.json: case a: steps[0].send.colour: unknown key");
  e = errors_of(replace(kMinimal, R"("model": "c12")", R"("model": "c99")"));
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e[0], "m.json: model: must be one of " + top::model_list());
  e = errors_of(replace(kMinimal, R"({"echo": true})", R"({"echo": true, "silence_ms": 5})"));
  ASSERT_FALSE(e.empty());
  EXPECT_NE(e[0].find("needs exactly one of"), std::string::npos);
  e = errors_of(
      replace(kMinimal, R"({"echo": true})", R"({"reply": {"fields": {"x": {"pattern": "("}}}})"));
  ASSERT_FALSE(e.empty());
  EXPECT_NE(e[0].find("steps[0].expect[0].reply.fields.x.pattern: not a valid regular expression"),
            std::string::npos)
      << e[0];
  e = errors_of("{\"format\": ");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].rfind("m.json: (json): not valid JSON at byte", 0), 0u);
  // Duplicate ids.
  std::string two = kMinimal;
  auto at = two.find("[{\"id\"");
  auto end = two.rfind("]}");
  const std::string one = two.substr(at + 1, end - at - 1);
  two.insert(end, "," + one);
  e = errors_of(two);
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e[0], "m.json: case a: id: duplicate case id");
}

// A stream's "moves": the axis, the way and the least turn of the attitude.
TEST(Matrix, StreamMovesIsLoadedAndChecked) {
  const std::string stream =
      R"({"stream": {"ident": "GAC", "rate_hz": 10, "duration_ms": 800, "moves": MOVES}})";
  const auto with = [&](std::string_view moves) {
    return replace(kMinimal, R"({"echo": true})", replace(stream, "MOVES", moves));
  };
  auto r = load_matrix(with(R"({"axis": "pitch", "sign": -1, "min_deg": 3})"), "m.json");
  ASSERT_TRUE(r.matrix) << (r.errors.empty() ? "" : r.errors[0]);
  const auto& e = r.matrix->cases[0].steps[0].expect[0];
  EXPECT_EQ(e.move_axis, static_cast<int>(top::Axis::pitch));
  EXPECT_EQ(e.move_sign, -1);
  EXPECT_DOUBLE_EQ(e.move_min_deg, 3);
  auto err = errors_of(with(R"({"axis": "tilt", "sign": 1, "min_deg": 3})"));
  ASSERT_FALSE(err.empty());
  EXPECT_EQ(err[0],
            "m.json: case a: steps[0].expect[0].stream.moves.axis: must be \"yaw\", "
            "\"pitch\" or \"roll\"");
  err = errors_of(with(R"({"axis": "yaw", "sign": 2, "min_deg": 3})"));
  ASSERT_FALSE(err.empty());
  EXPECT_EQ(err[0], "m.json: case a: steps[0].expect[0].stream.moves.sign: must be 1 or -1");
  err = errors_of(with(R"({"axis": "yaw", "sign": 1, "min_deg": 0})"));
  ASSERT_FALSE(err.empty());
  EXPECT_NE(err[0].find("stream.moves.min_deg: must be a number above 0"), std::string::npos);
}

TEST(Matrix, ChecksumIsAddedOnlyWhenAbsent) {
  topconf::SendSpec s;
  s.raw = true;
  s.text = "#TPUG2wGAA0A";
  std::string b, err;
  topconf::resolve_send(s, top::Dialect::skydroid, 'U', b, err);
  EXPECT_EQ(b, "#TPUG2wGAA0A46");
  s.text = "#TPUG2wGAA0A00";  // a deliberately wrong checksum is kept
  topconf::resolve_send(s, top::Dialect::skydroid, 'U', b, err);
  EXPECT_EQ(b, "#TPUG2wGAA0A00");
  s.text = "#TP{client}G2rGIC00";
  topconf::resolve_send(s, top::Dialect::topotek, 'P', b, err);
  EXPECT_EQ(b.substr(0, 12), "#TPPG2rGIC00");
}

class DefaultMatrix : public ::testing::TestWithParam<top::Model> {};

TEST_P(DefaultMatrix, LoadsAndCoversEveryCommandOfTheModel) {
  const top::Model m = GetParam();
  topconf::Matrix mx = default_matrix(m);
  EXPECT_EQ(mx.model, m);
  std::set<std::string> sent;
  std::set<std::string> kinds;
  for (const auto& c : mx.cases) {
    for (const auto& t : c.tags) kinds.insert(t);
    for (const auto& s : c.steps)
      if (s.send && !s.send->raw) sent.insert(s.send->command);
  }
  for (const auto& cmd : top::commands(top::dialect_of(m))) {
    // The field's commands (neither document lists them) are not the
    // default matrices' business.
    if (!cmd.supports(m) || cmd.ident == "ERE" || cmd.from_field()) continue;
    EXPECT_TRUE(sent.count(std::string(cmd.ident)))
        << cmd.ident << " has no case in " << mx.file
        << " (regenerate: conformance/matrices/regenerate.sh)";
  }
  for (const char* k :
       {"positive", "negative", "state", "bad-checksum", "unknown-ident", "wrong-length"})
    EXPECT_TRUE(kinds.count(k)) << k;
  if (m != top::Model::c13) {
    EXPECT_TRUE(kinds.count("stream"));
  }
}

TEST_P(DefaultMatrix, GeneratorRoundTripsThroughTheLoader) {
  const std::string text = topconf::generate_matrix(GetParam()).dump();
  auto r = load_matrix(text, "generated");
  EXPECT_TRUE(r.matrix) << (r.errors.empty() ? "" : r.errors[0]);
}

INSTANTIATE_TEST_SUITE_P(Models, DefaultMatrix, ::testing::ValuesIn(top::all_models()),
                         [](const auto& i) { return std::string(top::to_string(i.param)); });

TEST(Matrix, SchemaFileIsValidJson) {
  const std::string s =
      read_text(std::string(TOPKIT_SOURCE_DIR) + "/conformance/matrix.schema.json");
  auto j = nlohmann::json::parse(s);
  EXPECT_EQ(j.at("properties").at("format").at("const"), "topconf-matrix-1");
}

// The schema's model list is the library's (regenerate.sh writes it from
// `topconf models`).
TEST(Matrix, SchemaListsTheLibrarysModels) {
  const auto j = nlohmann::json::parse(
      read_text(std::string(TOPKIT_SOURCE_DIR) + "/conformance/matrix.schema.json"));
  std::vector<std::string> models;
  for (top::Model m : top::all_models()) models.emplace_back(top::to_string(m));
  EXPECT_EQ(j.at("$defs").at("model").at("enum").get<std::vector<std::string>>(), models);
}

}  // namespace
