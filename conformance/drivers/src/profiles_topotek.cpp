// The Topotek clients: ArduPilot's AP_Mount_Topotek and PixEagle's
// GimbalInterface. Facts read from their sources (each Source below); our
// own words and patterns, no code of theirs.
#include "drivers/profile.hpp"

namespace drivers {

namespace {

// The version forms AP_Mount_Topotek.cpp gimbal_version_analyse() stores:
// with a '.', digits (each read as a hex nibble) up to the third '.' (a
// non-hex character before it abandons the reply); without, the first three
// characters as digits. A non-zero digit: "0.0.00.0.0" reads as v0.0.0.
constexpr std::string_view kTopotekVersion =
    "^(?=[\\s\\S]*[1-9])(?:[0-9A-Fa-f]*\\.[0-9A-Fa-f]*\\.[0-9A-Fa-f]*\\.[\\s\\S]*"
    "|[0-9A-Fa-f.]*\\.[0-9A-Fa-f.]*|[0-9A-Fa-f]{3}[^.]*)$";
// A model name that is not the factory placeholder 000000000 (PR #27568).
constexpr std::string_view kName = "^(?!0+$)[\\s\\S]+";

}  // namespace

Profile ardupilot_topotek() {
  Profile p;
  p.name = "ardupilot-topotek";
  p.title = "ArduPilot AP_Mount_Topotek (upstream, MNT1_TYPE 12)";
  p.models = {top::Model::sip};
  p.sources = {
      {"ArduPilot/ardupilot", "libraries/AP_Mount/AP_Mount_Topotek.cpp",
       "05ad8d279741a20629cd0072d674f2318f431875"},
      {"ArduPilot/ardupilot", "libraries/AP_Mount/AP_Mount_Topotek.h",
       "3d293ff8e72953f0def4c0877ce405fd4ee79bdb"},
      {"ArduPilot/ardupilot", "pull request #27568 (model name 000000000, tracking states)",
       "PR #27568"},
      {"ArduPilot/ardupilot", "pull request #33803 (source P on a network port)", "PR #33803"},
  };
  p.link = {.kind = LinkKind::serial,
            .baud = 115200,
            .note =
                "a serial port (AP_Mount_Backend_Serial: the driver reads and writes a UART, "
                "source address U in every frame, send_variablelen_packet); the baud is the "
                "port's SERIALn_BAUD, which the vendor document gives as 115200. On a "
                "network port the source must be P (PR #33803)",
            .source = 0};
  p.tick_ms = 100;
  p.sends = {
      {"LAT", 'w', "N3520.1206", 'D', false, 10, -1, false,
       "with LON, ALT, AZI every tick, when the vehicle has a position (send_location_info)", 0},
      {"LON", 'w', "E13843.6200", 'D', false, 10, -1, false, "", 0},
      {"ALT", 'w', "000123.4", 'D', false, 10, -1, false, "", 0},
      {"AZI", 'w', "045.0", 'D', false, 10, -1, false, "", 0},
      {"VSN", 'r', "00", 'D', true, 1, 0, true, "round robin step 0, until a VSN was parsed", 0},
      {"GIA", 'w', "01", 'G', true, 1, 2, false,
       "step 2, forever: \"gimbal will continue to send attitude\" (update())", 0},
      {"SDC", 'r', "00", 'D', true, 1, 4, false, "step 4", 0},
      {"TRC", 'r', "00", 'D', true, 1, 6, false, "step 6", 0},
      {"PA2", 'r', "00", 'G', true, 1, 8, true, "step 8, until a PA2 was parsed", 0},
      {"GAY", 'w', "000063", 'G', false, 10, -1, false,
       "angle targets GAY (body frame), GIP (pitch negated), GIR, speed 99, every tick while "
       "not tracking (send_target_angles)",
       0},
      {"GIP", 'w', "000063", 'G', false, 10, -1, false, "", 0},
      {"GIR", 'w', "000063", 'G', false, 10, -1, false, "", 0},
      {"YPR", 'w', "000000", 'G', false, 10, -1, false,
       "rate targets x 1.220740379, pitch negated; PTZ 00 three times when all are zero "
       "(send_target_rates)",
       0},
      {"PTZ", 'w', "07", 'G', true, 0, -1, false, "06 lock / 07 follow when it changes", 0},
      {"UTC", 'w', "143005261126", 'D', false, 0, -1, false,
       "after an SDC reply that is not NNNN, at most 7 times (gimbal_sdcard_analyse)", 0},
      {"REC", 'w', "01", 'D', true, 0, -1, false, "on command; refused locally without a card", 0},
      {"CAP", 'w', "01", 'D', true, 0, -1, false, "on command; refused locally without a card", 0},
      {"TRC", 'w', "02", 'D', true, 0, -1, false, "02 before LOC when stopped; 01/00 to cancel", 0},
      {"LOC", 'w', "", 'D', false, 0, -1, false, "10 raw bytes: centre, size, mode", 0},
      {"LRF", 'w', "03", 'M', true, 0, -1, false, "03 continuous, 00 stop", 0},
      {"ZMC", 'w', "00", 'M', true, 0, -1, false, "stop sent twice", 0},
      {"FCC", 'w', "10", 'M', true, 0, -1, false, "", 0},
      {"PIP", 'w', "00", 'D', true, 0, -1, false, "", 0},
  };
  p.parsing = {
      {"dispatches only GIA, REC, SDC, LRF, TRC, VSN, PA2 (uart_recv_cmd_compare_list); "
       "anything else, ERE included, is ignored",
       1},
      {"header #, T or t, P or p; both addresses one of U M D E P G in either order; a hex "
       "length nibble; r or w; the checksum compared with uppercase hex only "
       "(read_incoming_packets)",
       0},
      {"no length check on GIA: data chars 0-11 are read whatever the length says "
       "(gimbal_angle_analyse); healthy while a GIA came within 1000 ms (healthy())",
       0},
      {"nothing waits for an echo: only VSN and PA2 are repeated, until answered (update())", 0},
  };
  p.unchecked = {
      "a lowercase checksum (the driver drops the frame; topconf decodes it)",
      "the serial baud (topconf opens the port at the baud of --target)",
  };
  p.needs = {
      {.id = "attitude",
       .feature = "attitude",
       .grade = Grade::must,
       .reasoning = "the driver turns attitude on with GIA 01 and takes it only from GIA frames, "
                    "yaw, pitch and roll from data chars 0-11, and is healthy only while one "
                    "came within 1000 ms",
       .lost = "attitude lost: the mount is never healthy",
       .source = 0,
       .send_ident = "GIA",
       .send_control = 'w',
       .send_data = "01",
       .check = Check::stream,
       .ident = "GIA",
       .pattern = kAngles12,
       .min_hz = 2,
       .max_hz = 100,
       .max_gap_ms = 1000,
       .window_ms = 2500},
      {.id = "version",
       .feature = "firmware version",
       .grade = Grade::should,
       .reasoning = "the driver asks VSN until a reply parses, and keeps the numbers up to the "
                    "third '.' (or three digits)",
       .lost = "firmware version unknown or a placeholder",
       .source = 0,
       .send_ident = "VSN",
       .send_dst = 'D',
       .ident = "VSN",
       .pattern = kTopotekVersion},
      {.id = "model-name",
       .feature = "model name",
       .grade = Grade::should,
       .reasoning = "the driver asks PA2 until answered and shows its data as the model name; "
                    "a unit answered 000000000 (PR #27568)",
       .lost = "model name missing or the factory placeholder",
       .source = 2,
       .send_ident = "PA2",
       .send_dst = 'G',
       .ident = "PA2",
       .pattern = kName},
      {.id = "sd-card",
       .feature = "photo and video",
       .grade = Grade::should,
       .reasoning = "the driver takes a card as present from an SDC reply whose first four "
                    "chars are not NNNN, refuses CAP and REC without one and sets the camera "
                    "clock (UTC) only after one",
       .lost = "photo and video refused (\"SD card error\"), camera clock never set",
       .source = 0,
       .send_ident = "SDC",
       .send_dst = 'D',
       .ident = "SDC",
       .pattern = "(?!NNNN)[\\s\\S]{4}[\\s\\S]*"},
      {.id = "tracking",
       .feature = "tracking",
       .grade = Grade::should,
       .reasoning = "the driver reads the TRC state from data char 1: 0 stopped, 1 waiting, 2 "
                    "tracking; 4 is a lens that does not track (PR #27568)",
       .lost = "tracking unavailable",
       .source = 1,
       .send_ident = "TRC",
       .send_dst = 'D',
       .ident = "TRC",
       .pattern = "[\\s\\S][012][\\s\\S]*"},
      {.id = "recording-state",
       .feature = "recording state",
       .grade = Grade::info,
       .reasoning = "the driver learns that it records only from a REC frame with '1' in data "
                    "char 0 or 1 (gimbal_record_analyse); it never asks",
       .lost = "the recording state is not shown",
       .source = 0,
       .send_ident = "REC",
       .send_control = 'w',
       .send_data = "01",
       .send_dst = 'D',
       .ident = "REC",
       .pattern = "(1|[\\s\\S]1)[\\s\\S]*",
       .cleanup_ident = "REC",
       .cleanup_data = "00"},
      {.id = "rangefinder",
       .feature = "rangefinder",
       .grade = Grade::info,
       .reasoning = "the driver reads an LRF frame as ERR (no range) or the digits 12345.6 at "
                    "data chars 0-4 and 6 (gimbal_dist_info_analyse); lenses without a "
                    "rangefinder have none",
       .lost = "no distance",
       .source = 0,
       .send_ident = "LRF",
       .send_control = 'w',
       .send_data = "03",
       .send_dst = 'M',
       .ident = "LRF",
       .pattern = "(ERR|[0-9]{5}[\\s\\S][0-9])[\\s\\S]*",
       .cleanup_ident = "LRF",
       .cleanup_data = "00"},
  };
  return p;
}

Profile pixeagle() {
  Profile p;
  p.name = "pixeagle";
  p.title = "PixEagle GimbalInterface (Topotek SIP over UDP)";
  p.models = {top::Model::sip};
  p.sources = {
      {"alireza787b/PixEagle", "src/classes/gimbal_interface.py",
       "3bea324fb1b5e6aab8ea21ac2bf55b2caf8e7ae8"},
  };
  p.link = {.kind = LinkKind::udp,
            .device_port = 9003,
            .listen_port = 9004,
            .note =
                "requests from an unbound socket to the camera's UDP 9003; answers read "
                "only on a second socket bound to UDP 9004, and only from the camera's IP "
                "(_init_listening_socket, _send_command, _validated_frame)",
            .source = 0};
  p.tick_ms = 100;
  p.sends = {
      {"GIC", 'r', "00", 'G', true, 10, -1, false, "every 0.1 s cycle (_query_loop)", 0},
      {"GAC", 'r', "00", 'G', true, 10.0 / 3, -1, false, "every third cycle", 0},
      {"TRC", 'r', "00", 'D', true, 2, -1, false, "every fifth cycle", 0},
  };
  p.parsing = {
      {"one frame per datagram, checksum uppercase over the whole datagram (_validated_frame)", 0},
      {"GAC, GIC, GIA only as #tpGPC + 12 hex, 24 bytes; TRC only as #TP/#tp + DP2, 14 bytes: "
       "the addresses swapped, source P",
       0},
      {"only GAC refreshes the angles, fresh for 2 s; GIC and GIA are kept as diagnostics "
       "(_ingest_parsed_data_locked)",
       0},
      {"TRC: data char 0 one of 0 1 2, the state data char 1 (_parse_tracking_response)", 0},
  };
  p.unchecked = {
      "the #tp header of GAC answers and the datagram holding one frame alone",
  };
  p.needs = {
      {.id = "body-angles",
       .feature = "gimbal angles",
       .grade = Grade::must,
       .reasoning = "PixEagle takes angles only from GAC answers, #tpGPC with 12 hex "
                    "characters, on UDP 9004; GIC and GIA never refresh them",
       .lost = "angles lost: the tracker gets no gimbal data",
       .source = 0,
       .send_ident = "GAC",
       .send_dst = 'G',
       .ident = "GAC",
       .pattern = "^[0-9A-Fa-f]{12}$",
       .any_addresses = false},
      {.id = "tracking-state",
       .feature = "tracking state",
       .grade = Grade::should,
       .reasoning = "PixEagle reads the tracking state from a TRC answer with the addresses "
                    "swapped (DP), data char 0 one of 0 1 2",
       .lost = "tracking state unknown",
       .source = 0,
       .send_ident = "TRC",
       .send_dst = 'D',
       .ident = "TRC",
       .pattern = "^[012][0-9]$",
       .any_addresses = false},
      {.id = "spatial-diagnostic",
       .feature = "spatial angle diagnostics",
       .grade = Grade::info,
       .reasoning = "PixEagle asks GIC every cycle and keeps a GIA or GIC answer as a "
                    "diagnostic only",
       .lost = "no spatial diagnostic",
       .source = 0,
       .send_ident = "GIC",
       .send_dst = 'G',
       .ident = "GIA",
       .pattern = kAngles12,
       .any_addresses = false},
  };
  return p;
}

}  // namespace drivers
