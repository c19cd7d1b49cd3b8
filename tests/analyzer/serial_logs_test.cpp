// Serial log formats: socat text and hex dumps, Saleae CSV, line logs and
// raw binary, and how their bad lines are reported.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "pcapio/writer.hpp"
#include "test_support.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

using pcapio::write_file;

// The log has exactly one log_syntax note, and it says `what`.
void expect_one_log_syntax_note(const Recorder& r, std::string_view what) {
  ASSERT_EQ(r.count_note(ACode::log_syntax), 1u);
  for (const auto& n : r.notes)
    if (n.note.code == ACode::log_syntax) {
      EXPECT_NE(n.note.message.find(what), std::string::npos) << n.note.message;
    }
}

// A byte as a Saleae export's data column writes it: 0x23.
// A request from channel `from` to `to` and its reply: the two frames of a
// two-channel log.
void expect_request_and_reply(const Recorder& r, std::string_view from, std::string_view to) {
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].from, from);
  EXPECT_EQ(r.frames[0].to, to);
  EXPECT_EQ(r.frames[1].from, to);
  EXPECT_EQ(r.frames[1].reply_to, 1u);
}

// `csv` read as a Saleae Logic export.
Recorder read_saleae(const std::string& csv) {
  TempDir tmp;
  write_file(tmp.file("s.csv"), csv);
  return read(tmp.file("s.csv"), {}, Format::saleae);
}

std::string saleae_byte(char c) {
  return std::string("0x") + "0123456789ABCDEF"[(c >> 4) & 15] + "0123456789ABCDEF"[c & 15];
}

TEST(SerialLogs, FormatDetection) {
  EXPECT_EQ(detect_format(std::string("\xd4\xc3\xb2\xa1", 4)), Format::pcap);
  EXPECT_EQ(detect_format(std::string("\x0a\x0d\x0d\x0a", 4)), Format::pcapng);
  EXPECT_EQ(detect_format("> 2024/05/01 12:00:00.000000000  length=3 from=0 to=2\nabc"),
            Format::socat);
  EXPECT_EQ(detect_format("name,type,start_time,duration,data\n"), Format::saleae);
  EXPECT_EQ(detect_format("2024-05-01T12:00:00Z TX #TPUG2wPTZ056F\n"), Format::lines);
  EXPECT_EQ(detect_format("# comment\n2024-05-01T12:00:00Z RX #TP\n"), Format::lines);
  EXPECT_EQ(detect_format("#TPUG2wPTZ056F"), Format::raw);
}

TEST(SerialLogs, SocatTextWithGluedHeaderAndCr) {
  TempDir tmp;
  std::string f1 = top::with_checksum("#TPUG2wPTZ05"), f2 = top::with_checksum("#TPGU2wPTZ05");
  std::string log = "> 2024/05/01 12:00:00.000100000  length=" + std::to_string(f1.size() + 2) +
                    " from=0 to=15\n" + f1 + "\\r\n" +
                    "< 2024/05/01 12:00:00.005100000  length=" + std::to_string(f2.size()) +
                    " from=0 to=13\n" + f2 +  // no newline: socat glues the next header
                    "> 2024/05/01 12:00:00.010000000  length=3 from=16 to=18\n..#";
  write_file(tmp.file("s.log"), log);
  Recorder r = read(tmp.file("s.log"));
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].ts, T + 100);
  EXPECT_EQ(r.frames[0].from, "left");
  EXPECT_TRUE(has_code(r.frames[0], "crlf"));
  EXPECT_EQ(r.frames[1].reply_to, 1u);
  EXPECT_EQ(r.frames[1].latency, 5000);
  EXPECT_FALSE(r.has_note(ACode::log_syntax));
}

TEST(SerialLogs, SocatHexDump) {
  TempDir tmp;
  std::string log =
      "> 2024/05/01 12:00:00.000000000  length=14 from=0 to=13\n"
      " 23 54 50 55 47 32 77 50 54 5a 30 35 36 46        #TPUG2wPTZ056F\n"
      "--\n";
  write_file(tmp.file("s.log"), log);
  Recorder r = read(tmp.file("s.log"));
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].raw, "#TPUG2wPTZ056F");
}

// A chunk header whose length is not a number is noted and read as an empty
// chunk; the chunks after it are read as usual. ("length=-5" was read by
// strtoul as 2^64 - 5, and the rest of the log became that chunk's data.)
TEST(SerialLogs, SocatLengthNotANumber) {
  TempDir tmp;
  std::string f = top::with_checksum("#TPUG2wPTZ05");
  std::string log =
      "> 2024/05/01 12:00:00.000000000  length=-5 from=0 to=13\n" + std::string("--\n") +
      "> 2024/05/01 12:00:00.001000000  length=" + std::to_string(f.size()) + " from=0 to=13\n" +
      f + "\n--\n" + "> 2024/05/01 12:00:00.002000000  length=x from=0 to=13\n" +
      "< 2024/05/01 12:00:00.003000000  length=" + std::to_string(f.size()) + " from=0 to=13\n" +
      f + "\n";
  write_file(tmp.file("s.log"), log);
  Recorder r = read(tmp.file("s.log"));
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].ts, T + 1000);
  EXPECT_EQ(r.frames[0].raw, f);
  EXPECT_EQ(r.frames[1].ts, T + 3000);
  EXPECT_EQ(r.frames[1].from, "right");
  EXPECT_EQ(r.count_note(ACode::log_syntax), 2u);
}

TEST(SerialLogs, SaleaeCsvTwoChannels) {
  TempDir tmp;
  std::string csv = "name,type,start_time,duration,data,error\n";
  auto add = [&](const char* ch, double t, const std::string& bytes) {
    for (std::size_t i = 0; i < bytes.size(); ++i)  // to_string: six decimals
      csv += std::string(ch) + ",data," + std::to_string(t + static_cast<double>(i) * 1e-4) +
             ",8.68e-05," + saleae_byte(bytes[i]) + ",\n";
  };
  add("TX", 1.0, top::with_checksum("#TPUG2wPTZ05"));
  add("RX", 1.01, top::with_checksum("#TPGU2wPTZ05"));
  csv += "RX,data,2.0,8.68e-05,0xZZ,\n";
  write_file(tmp.file("s.csv"), csv);
  Recorder r = read(tmp.file("s.csv"));
  expect_request_and_reply(r, "TX", "RX");
  EXPECT_TRUE(r.has_note(ACode::log_syntax));
}

// CSV quoting as Logic 2 writes it (RFC 4180): a quoted field may hold commas
// and doubled quotes, a quote may open mid-field, and a quote left open runs
// to the end of the line. The reader splits a row a run of plain bytes at a
// time; each case lands in the column it belongs to.
TEST(SerialLogs, SaleaeCsvQuotedColumns) {
  std::string csv = "name,type,start_time,duration,data,error\n";
  auto add = [&](const std::string& name, const std::string& bytes, const std::string& tail) {
    for (char c : bytes)
      csv += name + ",\"da\"ta,1.0,8.68e-05," + saleae_byte(c) + "," + tail + "\n";
  };
  add("\"T,X\"", top::with_checksum("#TPUG2wPTZ05"), "");
  add("\"R\"\"X\"", top::with_checksum("#TPGU2wPTZ05"), "");
  add("\"T,X\"", "#", "\"framing, \"\"stop\"\" bit");  // open quote: the rest of the line
  const Recorder r = read_saleae(csv);
  expect_request_and_reply(r, "T,X", "R\"X");
  expect_one_log_syntax_note(r, "line 30: the analyzer flagged this byte: framing, \"stop\" bit");
}

// The row splitter finds each next comma and quote once and looks again
// only after passing it: commas inside several quoted columns of one row,
// a quote right after a comma, "" at a column's end and empty columns all
// split as before.
TEST(SerialLogs, SaleaeCsvSeveralQuotedColumnsInARow) {
  std::string csv = "type,name,start_time,duration,data,error\n";
  auto add = [&](const std::string& name, const std::string& bytes) {
    for (char c : bytes) csv += "\"data\"," + name + ",1.0,," + saleae_byte(c) + ",\n";
  };
  add("\"a,b\"", top::with_checksum("#TPUG2wPTZ05"));
  add("\"c,,d\"\"\"", top::with_checksum("#TPGU2wPTZ05"));
  csv += "\"data\",\"a,b\",2.0,,0x23,\"e,\"\"f\"\"\"\n";
  const Recorder r = read_saleae(csv);
  expect_request_and_reply(r, "a,b", "c,,d\"");
  expect_one_log_syntax_note(r, "line 30: the analyzer flagged this byte: e,\"f\"");
}

// A row is split only up to the last column the header names (the rest of
// the line is never looked at): columns past it, an unterminated quote among
// them or hundreds of commas, change nothing.
TEST(SerialLogs, SaleaeCsvColumnsPastTheHeadersAreNotRead) {
  std::string csv = "name,type,start_time,duration,data,error\n";
  const std::string req = top::with_checksum("#TPUG2wPTZ05");
  const std::string tails[] = {"", ",extra", ",\"open, quote", "," + std::string(500, ',')};
  for (std::size_t i = 0; i < req.size(); ++i)  // to_string: six decimals
    csv += "TX,data," + std::to_string(1.0 + static_cast<double>(i) * 1e-4) + ",8.68e-05," +
           saleae_byte(req[i]) + "," + tails[i % 4] + "\n";
  const Recorder r = read_saleae(csv);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].raw, req);
  EXPECT_EQ(r.frames[0].from, "TX");
  EXPECT_EQ(r.count_note(ACode::log_syntax), 0u);
}

// fuzz/regressions/capture_saleae/duplicate-name-column-out-of-range (found by
// fuzz_capture_saleae): the header names "name", "type" and "start_time"
// twice, the second "name" past the end of every data row. The reader took the
// last column of each name and indexed the row with it unchecked: a read past
// the row's end, then std::length_error. Must: say the header repeats a
// column, read the first one, report short rows as log-syntax, and go on.
TEST(FuzzRegression, SaleaeCsvWithADuplicatedColumnReadsTheFirst) {
  const std::string path = std::string(TOPKIT_SOURCE_DIR) +
                           "/fuzz/regressions/capture_saleae/duplicate-name-column-out-of-range";
  Recorder r = read(path, {}, Format::saleae);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_EQ(r.notes[0].note.code, ACode::log_syntax);
  EXPECT_NE(r.notes[0].note.message.find("line 1: the header names column \"name\" twice"),
            std::string::npos)
      << r.notes[0].note.message;

  // The same header shape, well-formed rows: the first columns are read.
  TempDir tmp;
  std::string csv = "name,type,start_time,duration,data,error,name\n";
  for (char c : top::with_checksum("#TPUG2wPTZ05"))
    csv += "TX,data,1.0,8.68e-05," + saleae_byte(c) + ",\n";
  csv += "TX,data,1.0\n";  // short: too few columns, not a crash
  write_file(tmp.file("d.csv"), csv);
  Recorder d = read(tmp.file("d.csv"), {}, Format::saleae);
  ASSERT_EQ(d.frames.size(), 1u);
  EXPECT_EQ(d.frames[0].from, "TX");
  EXPECT_EQ(d.count_note(ACode::log_syntax), 2u);  // the header, the short row
}

// The same input through `topdump read --json`: a short row's message quotes
// its data column, which holds a byte 0xAB. nlohmann refused to dump the
// non-UTF-8 message and threw: topdump aborted (exit 134). Must: exit 1 (the
// log has errors) with every line valid JSON, the byte written as \xAB.
TEST(FuzzRegression, SaleaeCsvNonUtf8BytesInMessagesAreEscapedInJson) {
  std::string out;
  const int rc =
      run("'" + topdump_bin() + "' read --json --format saleae '" + std::string(TOPKIT_SOURCE_DIR) +
              "/fuzz/regressions/capture_saleae/duplicate-name-column-out-of-range' "
              "2>/dev/null",
          out);
  EXPECT_EQ(rc, 1);
  std::istringstream in(out);
  std::string line;
  std::size_t lines = 0;
  bool escaped = false;
  while (std::getline(in, line)) {
    ++lines;
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
    escaped |= line.find("\\\\xAB") != std::string::npos;
  }
  EXPECT_GT(lines, 3u);
  EXPECT_TRUE(escaped) << out;
}

// A start_time too large for a microsecond count (1e300 s) is no time, not
// an undefined conversion (the asan preset adds -fsanitize=float-cast-overflow,
// which GCC leaves out of "undefined", to catch it).
TEST(SerialLogs, SaleaeCsvHugeTimeIsNoTime) {
  std::string csv = "name,type,start_time,duration,data,error\n";
  for (char c : top::with_checksum("#TPUG2wPTZ05"))
    csv += "TX,data,1e300,8.68e-05," + saleae_byte(c) + ",\n";
  const Recorder r = read_saleae(csv);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].ts, kNoTime);
}

TEST(SerialLogs, LineLogWithEscapesAndBadLines) {
  TempDir tmp;
  std::string log = "2024-05-01T12:00:00.5Z TX " + top::with_checksum("#TPUG2wPTZ05") + "\\r\\n\n" +
                    "not a line\n" + "2024-05-01T12:00:00.52+00:00 RX " +
                    top::with_checksum("#TPGU2wPTZ05") + "\n";
  write_file(tmp.file("l.log"), log);
  Recorder r = read(tmp.file("l.log"));
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].ts, T + 500000);
  EXPECT_EQ(r.frames[1].latency, 20000);
  EXPECT_EQ(r.count_note(ACode::log_syntax), 1u);
  EXPECT_EQ(r.notes[0].pos.record, 2u);
}

TEST(SerialLogs, RawBinaryGpsWithHashBytes) {
  TempDir tmp;
  std::string gps = top::with_checksum(
      "#tpPDEwGPS" + std::string("\x23\x23\x40\x23\x5e\x45\x11\xe4\x23\x0d\xe8\x03\x00\x00", 14));
  write_file(tmp.file("r.bin"), gps + gps);
  Recorder r = read(tmp.file("r.bin"));
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[1].pos.offset, gps.size());
  EXPECT_TRUE(r.garbage_codes.empty());
}

}  // namespace
}  // namespace topdump::test
