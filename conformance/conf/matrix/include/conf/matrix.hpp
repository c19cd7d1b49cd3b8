// topconf's test matrix: the case model and its loader.
//
// A matrix is JSON (schema: conformance/matrix.schema.json, documented in
// conformance/README.md). load_matrix() validates it and reports every
// problem as "FILE: case ID: key: what is wrong". Pure: no I/O.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "top/device.hpp"
#include "top/top.hpp"

namespace topconf {

enum class Level : std::uint8_t { must, should, may };
std::string_view to_string(Level l) noexcept;
std::optional<Level> level_from_string(std::string_view s) noexcept;

// What a step sends: a template resolved against the transport (the client
// address U or P), with the checksum added when absent.
struct SendSpec {
  bool raw = false;  // a raw frame or hex bytes, sent as written
  std::string text;  // raw: the frame text (may hold "{client}")
  bool hex = false;  // raw bytes given as hex
  // structured command
  std::string command;  // "GAY"
  char control = 'w';
  std::string data;
  char src = 0;                       // 0: the client address of the transport
  char dst = 0;                       // 0: the command's address class
  std::optional<top::Header> header;  // default: top::choose_header
};

// A check on one decoded field of a reply.
struct FieldCheck {
  std::string name;
  std::optional<double> min, max;        // range in scaled units
  std::vector<std::string> enums;        // allowed enum names
  std::string pattern;                   // ECMAScript regex over the field text
  std::shared_ptr<const std::regex> re;  // `pattern` compiled (by load_matrix)
  std::optional<std::string> equals;     // the formatted raw text of the field
};

enum class ExpectKind : std::uint8_t { frame, echo, reply, error, silence, stream, readback };
std::string_view to_string(ExpectKind k) noexcept;

struct Expectation {
  ExpectKind kind = ExpectKind::echo;
  bool tolerated = false;      // matching only this gives non-strict
  bool any_addresses = false;  // "addresses": "any": no swap check
  std::string note;
  SendSpec frame;  // frame: the exact frame expected
  // reply
  std::string ident;  // default: the request's identifier
  char control = 0;   // 0: any
  std::vector<FieldCheck> fields;
  std::string data_pattern;                   // regex over the whole data
  std::shared_ptr<const std::regex> data_re;  // `data_pattern` compiled (by load_matrix)
  std::optional<std::string> data;            // exact data
  // silence
  std::uint32_t silence_ms = 0;
  // stream
  double rate_hz = 0;
  double tolerance = top::stream_rate_tolerance;  // fraction of rate_hz
  std::uint32_t duration_ms = 0;
  std::uint32_t max_gap_ms = 0;  // 0: any gap; the stream's `data_pattern` uses data_re
  // stream "moves": the attitude the counted pushes report on this axis
  // (top::Axis; -1: none) turns from the first to the last by at least
  // move_min_deg the `move_sign` way (+1 right or up, -1 left or down; the
  // attitude read by top/motion.hpp, its sign convention included).
  int move_axis = -1;
  int move_sign = 0;
  double move_min_deg = 0;
  // readback: the read sent after the write's reply; the reply data must
  // equal `data` when given, else the data the step wrote.
  SendSpec read;
};

struct Step {
  std::optional<SendSpec> send;     // none: only wait and watch
  std::vector<Expectation> expect;  // ordered alternatives
  std::uint32_t timeout_ms = 0;     // 0: the case's
};

struct Case {
  std::string id;
  std::string section;  // "SkyDroid 3.3.1"
  std::string title;
  Level level = Level::must;
  std::vector<top::Model> models;  // empty: every model of the matrix
  std::vector<std::string> tags;
  std::vector<Step> preconditions;  // not met: inconclusive
  std::vector<Step> steps;
  std::uint32_t timeout_ms = 0;  // 0: the matrix default
  std::int32_t retries = -1;     // -1: the matrix default
  bool applies_to(top::Model m) const noexcept;
};

struct Matrix {
  std::string file;
  std::string title;
  top::Model model = top::Model::unknown;
  top::Dialect dialect = top::Dialect::unknown;
  std::uint32_t timeout_ms = 300;  // default per-step reply timeout
  std::uint32_t retries = 1;       // default retries of a failing case
  std::uint32_t settle_ms = 15;    // watch for duplicates after a match
  std::uint32_t probe_timeout_ms = 500;
  std::optional<SendSpec> probe;  // liveness probe; any answer is life
  std::vector<Case> cases;
};

struct LoadResult {
  std::optional<Matrix> matrix;     // set when errors is empty
  std::vector<std::string> errors;  // "FILE: case ID: key: message"
};

// Parses and validates a matrix. `file` names it in errors. Never throws.
LoadResult load_matrix(std::string_view text, std::string_view file);

// Resolves a send template into bytes for a dialect and client address.
// Returns false with `error` when the template cannot make a frame.
bool resolve_send(const SendSpec& s, top::Dialect dialect, char client, std::string& bytes,
                  std::string& error);

}  // namespace topconf
