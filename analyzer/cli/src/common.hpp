// What read, stats, live and serial share (cli's own header): the common
// options, the analyzer settings they make, the output sink, progress,
// signals and the exit status.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "capture/sources.hpp"
#include "commands.hpp"
#include "output/output.hpp"
#include "session/analyzer.hpp"

namespace topdump {

// Set by SIGINT and SIGTERM once install_signals() ran: live inputs end.
extern std::atomic<bool> g_stop;
void install_signals();

struct Common {
  std::string dialect = "auto";
  std::string model = "auto";
  std::string format = "auto";
  std::vector<std::uint16_t> ports;
  std::vector<std::string> idents;
  std::vector<std::string> addrs;
  std::string severity;
  std::string from, to;
  std::vector<std::string> findings, mute;
  std::uint64_t count = 0;
  double timeout_ms = 2000;
  bool json = false;
  bool verbose = false;
  std::string csv;
  bool no_progress = false;
};

// The reorder window of read (--help, docs/topdump-json.md): one second of
// capture time covers TCP reassembly and serial CR/LF holds; a wider one
// costs read --json a fifth of its speed (the held output leaves the
// cache), so an unanswered finding found at the timeout (2 s after its
// request) is beyond its reach.
constexpr std::int64_t kReorderWindowUs = 1'000'000;

// What a subcommand with the common options is (read, stats, live, serial):
// its name and help line, what it prints, where it reads, whether it takes
// --port, and its --help footer's own notes and examples.
struct CommandSpec {
  // events: --json (JSON Lines), -V and --csv, and output_help() in the
  // footer; stats: --json, one JSON object.
  enum class Outputs { events, stats };
  // files: --format and --no-progress; live: the note that Ctrl-C ends.
  enum class Input { files, live };
  const char* name;
  const char* help;
  Outputs outputs;
  Input input;
  bool ports;
  const char* notes;     // the footer's text before "Examples:"
  const char* examples;  // the footer's example lines
};

struct Setup {
  AnalyzerOptions aopts;
  Filter filter;
  SourceOptions sopts;
  Format format = Format::automatic;
};

// Turns the options into analyzer settings; false, after the message, on
// bad usage.
bool setup(const Common& o, Setup& s);

// The subcommands with the common options, and their specs (one table,
// common.cpp).
enum class CommandId { read, stats, live, serial };
const CommandSpec& spec_of(CommandId id);

// The positional input of read and serial: one, or two taps of one UART
// (one per direction) read as one conversation.
void add_taps(CLI::App& sub, const char* name, std::vector<std::string>& inputs,
              const std::string& help);

// Adds the common options of `spec` to `sub` and sets its footer.
void declare_common(CLI::App& sub, Common& o, const CommandSpec& spec);

// A subcommand with the common options (read, stats, live, serial), as a
// topkit::cli::OwnSubcommand: `Own` holds only what is the command's own,
// its options (added by declare(CLI::App&) after the common ones) and
// run(const Common&).
template <class Own>
struct WithCommon {
  explicit WithCommon(const CommandSpec& s) : spec(s) {}
  void declare(CLI::App& sub) {
    declare_common(sub, c, spec);
    own.declare(sub);
  }
  int run() { return own.run(c); }
  const CommandSpec& spec;
  Common c;
  Own own;
};

template <class Own>
std::unique_ptr<topkit::cli::Subcommand> make_command(CLI::App& app, CommandId id) {
  const CommandSpec& spec = spec_of(id);
  return topkit::cli::make_subcommand<WithCommon<Own>>(app, spec.name, spec.help, spec);
}

// A source finding on stderr, naming the file once: "topdump: FILE: !! ...",
// the message without its own "FILE: ".
void source_note_to_stderr(const std::string& file, const NoteEvent& e);
// True when stdout and stderr are the same file or terminal (a copy on
// stderr would print each line twice).
bool stderr_is_stdout();

// Source findings also go to stderr, naming the file, unless stderr is
// where stdout goes.
class Tee : public Sink {
 public:
  Tee(Sink& inner, std::string file)
      : inner_(inner), file_(std::move(file)), copy_(!stderr_is_stdout()) {}
  void frame(const FrameEvent& e) override { inner_.frame(e); }
  void garbage(const GarbageEvent& e) override { inner_.garbage(e); }
  void note(const NoteEvent& e) override {
    if (!e.conv && copy_) source_note_to_stderr(file_, e);
    inner_.note(e);
  }
  Sink& inner_;
  std::string file_;
  bool copy_;
};

// The sink of --csv, --json or text; null, after the message, on a bad
// column.
std::unique_ptr<Sink> make_sink(const Common& o, Out& out);

void progress_bar(std::uint64_t done, std::uint64_t total);
// The progress bar goes to stderr when it is a terminal and stdout is not
// one: on the same terminal it would mix with the output lines.
bool show_progress(const Common& c);

// 1 when an error finding was seen, else 0.
int status_of(const Analyzer& a);

// The statistics live and serial print at their end.
void print_final_stats(const Common& c, const Analyzer& a);

// Reads a live input (an interface, serial ports) named `name` with
// `capture` until it ends or SIGINT / SIGTERM, its events printed as they
// are decoded, then the statistics: live and serial. `capture` returns
// false with `err` set when the input fails.
using Capture = std::function<bool(Analyzer& a, SourceOptions& sopts, const std::atomic<bool>& stop,
                                   std::string& err)>;
int run_live_input(const Common& c, const std::string& name, const Capture& capture);

inline constexpr const char* kFormats = "auto, pcap, pcapng, raw, socat, saleae or lines";
inline const std::vector<std::string> kFormatNames{"auto",  "pcap",   "pcapng", "raw",
                                                   "socat", "saleae", "lines"};

// How read, live and serial print: the text line format, the order, and the
// CSV columns (one list, from the column table).
std::string output_help();

}  // namespace topdump
