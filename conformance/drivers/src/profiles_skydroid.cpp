// The SkyDroid clients: ArduPilot's AP_Mount_SkyDroid (PR #34155), the
// C13 ground station of vamaskylight/custom-GCS and the C10Pro tool of
// DifferentialRobotics. Facts read from their sources (each Source below);
// our own words and patterns, no code of theirs.
#include "drivers/profile.hpp"

namespace drivers {

Profile ardupilot_skydroid() {
  Profile p;
  p.name = "ardupilot-skydroid";
  p.title = "ArduPilot AP_Mount_SkyDroid (PR #34155, MNT1_TYPE 15)";
  // The driver names the C11 and C13; topsim has no C11. The C12 answers
  // the same gimbal commands (the header's "IDENTICAL across models").
  p.models = {top::Model::c12, top::Model::c13};
  p.sources = {
      {"ArduPilot/ardupilot", "libraries/AP_Mount/AP_Mount_SkyDroid.cpp (PR #34155 branch)",
       "241167dc6429f4e5d7df9d06eb3d3ae88799f27d"},
      {"ArduPilot/ardupilot", "libraries/AP_Mount/AP_Mount_Backend_TPFrame.cpp (PR #34155 branch)",
       "4e7781a171249a67d61db7d95e193be079c1e90f"},
      {"ArduPilot/ardupilot", "libraries/AP_Mount/AP_Mount_SkyDroid.h (header comment)",
       "PR #34155"},
  };
  p.link = {.kind = LinkKind::udp,
            .device_port = 5000,
            .note =
                "\"control is over UDP only (no direct UART), source address is always "
                "'U'\" (header comment); the camera's TOP port UDP 5000",
            .source = 2};
  p.tick_ms = 20;  // update() at 50 Hz: GSY and GSP every call
  p.sends = {
      {"GSY", 'w', "00", 'G', true, 50, -1, false,
       "every update in rate and angle mode, yaw negated (a positive GSY turns left), 0.5 "
       "deg/s per unit (send_axis_rate)",
       0},
      {"GSP", 'w', "00", 'G', true, 50, -1, false, "every update, pitch up positive", 0},
      {"FAI", 'w', "00000000000000", 'G', false, 10, -1, false,
       "the vehicle's yaw, pitch, roll and a mode byte: 14 chars (send_attitude_to_gimbal)", 0},
      {"VER", 'r', "00", 'D', true, 1, 0, true, "round robin, until a VER was parsed", 0},
      {"TIM", 'w', "143005.00261026", 'D', false, 1, 1, false,
       "hhmmss.ccDDMMYY, the month as AP_RTC gives it, 0-11 (send_time_sync)", 0},
      {"GAA", 'w', "32", 'G', true, 1, 2, false, "50 Hz asked, re-sent every second", 0},
      {"MOD", 'r', "00", 'D', true, 1, 3, true, "until a MOD was parsed; informational", 0},
      {"SDC", 'r', "00", 'D', true, 1, 4, false, "", 0},
      {"FAE", 'w', "01", 'G', true, 1, 6, false, "accept our attitude pushes", 0},
      {"PTZ", 'w', "06", 'G', true, 0, -1, false,
       "06 follow / 07 lock on the first call and on change; 05 centre on retract/neutral", 0},
      {"CAP", 'w', "01", 'D', true, 0, -1, false, "refused locally only with a card known absent",
       0},
      {"REC", 'w', "01", 'D', true, 0, -1, false, "the state kept locally", 0},
      {"DZM", 'w', "0A", 'M', true, 0, -1, false, "0A zoom in, 0B zoom out, one step", 0},
  };
  p.parsing = {
      {"handles only GAC, REC, SDC, VER, MOD (handle_message); ERE and the rest are ignored", 0},
      {"header #, T or t, P or p; addresses of its letter set in either order; the checksum "
       "compared with uppercase hex only; a zero data length handled (read_incoming_packets)",
       1},
      {"GAC needs 12 data chars or more; healthy after a first GAC and while one came within "
       "1000 ms; angle mode sends GSY/GSP 00 when not healthy (send_target_angles)",
       0},
      {"VER must start with V, then decimal numbers between dots (gimbal_version_analyse)", 0},
      {"SDC needs 10 data chars, all 0 is no card; unanswered, CAP and REC are still allowed", 0},
  };
  p.unchecked = {
      "a lowercase checksum (the driver drops the frame; topconf decodes it)",
      "a GSY or GSP held for less than the 800 ms watched (the driver refreshes both every "
      "update, about 50 Hz)",
  };
  p.needs = {
      {.id = "attitude",
       .feature = "attitude",
       .grade = Grade::must,
       .reasoning = "the driver asks GAA at 50 Hz and takes attitude only from GAC frames of 12 "
                    "data chars or more; it is healthy only while one came within 1000 ms, and "
                    "its angle mode steers on that attitude",
       .lost = "attitude lost: the mount is never healthy and angle targets stop",
       .source = 0,
       .send_ident = "GAA",
       .send_control = 'w',
       .send_data = "32",
       .check = Check::stream,
       .ident = "GAC",
       .pattern = kAngles12,
       .min_hz = 2,
       .max_hz = 100,
       .max_gap_ms = 1000,
       .window_ms = 2500},
      {.id = "yaw-rate",
       .feature = "yaw control",
       .grade = Grade::must,
       .reasoning = "GSY is the only command the driver turns yaw with, in rate and angle mode "
                    "(GAM, GSM, GAY, GAP are never sent), and it negates it (\"a positive GSY "
                    "value moves yaw LEFT\", C11): a GSY of +20 deg/s must turn the GAC yaw left",
       .lost = "yaw cannot be moved: the device refuses or ignores GSY, or turns the other "
               "way (the angle loop never reaches its target)",
       .source = 0,
       .send_ident = "GSY",
       .send_control = 'w',
       .send_data = "28",
       .check = Check::stream,
       .ident = "GAC",
       .pattern = kAngles12,
       .min_hz = 2,
       .max_hz = 100,
       .window_ms = 800,
       .on_ident = "GAA",
       .on_data = "32",
       .move_axis = static_cast<int>(top::Axis::yaw),
       .move_sign = -1,
       .move_min_deg = 3},
      {.id = "pitch-rate",
       .feature = "pitch control",
       .grade = Grade::must,
       .reasoning = "GSP is the only command the driver tilts with, in rate and angle mode, "
                    "pitch up-positive as the document (\"sign matches the doc\", C11): a GSP of "
                    "+20 deg/s must tilt the GAC pitch up",
       .lost = "pitch cannot be moved: the device refuses or ignores GSP, or tilts the other "
               "way (the angle loop never reaches its target)",
       .source = 0,
       .send_ident = "GSP",
       .send_control = 'w',
       .send_data = "28",
       .check = Check::stream,
       .ident = "GAC",
       .pattern = kAngles12,
       .min_hz = 2,
       .max_hz = 100,
       .window_ms = 800,
       .on_ident = "GAA",
       .on_data = "32",
       .move_axis = static_cast<int>(top::Axis::pitch),
       .move_sign = 1,
       .move_min_deg = 3},
      {.id = "version",
       .feature = "firmware version",
       .grade = Grade::should,
       .reasoning = "the driver asks VER until a reply starting with V and decimal numbers "
                    "between dots parses",
       .lost = "firmware version unknown or a placeholder",
       .source = 0,
       .send_ident = "VER",
       .send_dst = 'D',
       .ident = "VER",
       .pattern = "^V(?=[\\s\\S]*[1-9])(?:[0-9A-Fa-f]*\\.[0-9A-Fa-f]*\\.[0-9A-Fa-f]*\\.[\\s\\S]*"
                  "|[0-9A-Fa-f.]*)$"},
      {.id = "model-name",
       .feature = "model name",
       .grade = Grade::should,
       .reasoning = "the driver asks MOD until answered and shows its data as the model name "
                    "(informational; real units took minutes)",
       .lost = "model name missing or a placeholder",
       .source = 0,
       .send_ident = "MOD",
       .send_dst = 'D',
       .ident = "MOD",
       .pattern = "^(?!0+$)[\\s\\S]+"},
      {.id = "sd-card",
       .feature = "SD card state",
       .grade = Grade::info,
       .reasoning = "the driver reads SDC with 10 data chars (all 0: no card); without an "
                    "answer the state stays unknown and CAP/REC are still sent",
       .lost = "card state unknown",
       .source = 0,
       .send_ident = "SDC",
       .send_dst = 'D',
       .ident = "SDC",
       .pattern = "[0-9A-Fa-f]{10}[\\s\\S]*"},
      {.id = "vehicle-attitude",
       .feature = "vehicle attitude to the gimbal",
       .grade = Grade::info,
       .reasoning = "the driver pushes FAI with 14 chars (the mode byte after the angles) at 10 "
                    "Hz and ignores any answer; what the gimbal does with it is not known",
       .lost = "the device refuses the 14-char FAI",
       .source = 0,
       .send_ident = "FAI",
       .send_control = 'w',
       .send_data = "00000000000000",
       .send_fixed = false,
       .check = Check::taken,
       .ident = "FAI"},
  };
  return p;
}

Profile skydroid_gcs() {
  Profile p;
  p.name = "skydroid-gcs";
  p.title = "vamaskylight/custom-GCS SkyDroid C12/C13 ground station (vgcs/skydroid)";
  p.models = {top::Model::c13, top::Model::c12};
  p.sources = {
      {"vamaskylight/custom-GCS", "vgcs/skydroid/adapter.py",
       "0151122d1b5663dbf4a41bd36c51bbca80259097"},
      {"vamaskylight/custom-GCS", "vgcs/skydroid/protocol.py",
       "574bcc0b9977d5d2cebacbd94a2e47eded6b6dcc"},
      {"vamaskylight/custom-GCS", "vgcs/skydroid/command_map.py",
       "209a21f0fd0fa260be01a2a01bdca23602f8688d"},
  };
  p.link = {.kind = LinkKind::udp,
            .device_port = 5000,
            .note =
                "one UDP socket to the camera's TOP port 5000 (\"PROTOCAL.doc: TOP UDP port "
                "5000\"), answers read on the same socket; the probe also tries 9003 and "
                "19856 (_C13_PROBE_PORTS)",
            .source = 0};
  p.tick_ms = 500;
  p.sends = {
      {"GAA", 'w', "05", 'G', true, 0, -1, true,
       "5 Hz asked once, until an answer came within 0.12 s (_poll_host_once)", 0},
      {"GAC", 'r', "00", 'G', true, 2, -1, false,
       "the status poll: every 0.5 s with telemetry, every 1 s without (_status_loop; "
       "status_commands GAA, GAC)",
       2},
      {"GSM", 'w', "0000", 'G', false, 0, -1, false,
       "speed in 0.1 deg/s units, clamped to 99; 12 stops 80 ms apart (_gimbal_stop_hard)", 0},
      {"GSY", 'w', "00", 'G', true, 0, -1, false, "", 1},
      {"GSP", 'w', "00", 'G', true, 0, -1, false, "", 1},
      {"GAM", 'w', "000000000000", 'G', false, 0, -1, false, "", 1},
      {"PTZ", 'w', "05", 'G', true, 0, -1, false, "", 1},
      {"DZM", 'w', "00F00A", 'D', false, 0, -1, false, "a zoom burst to 5000, 9003, 19853", 0},
  };
  p.parsing = {
      {"#tp (any case), two addresses of U M D E G (no P) in either order, a hex length, r or "
       "w; the checksum is not verified; GAC with 12 data chars or more gives yaw and pitch "
       "(parse_tp_frame)",
       1},
      {"waits 0.12 s for an answer to a status poll (_PROBE_TIMEOUT_S); motion commands wait "
       "for none (_MOTION_COMMANDS)",
       0},
  };
  p.unchecked = {"a P address in the answer (the station's parser takes U M D E G only)"};
  p.needs = {
      {.id = "attitude",
       .feature = "gimbal telemetry",
       .grade = Grade::must,
       .reasoning = "the station asks GAA 05 and reads every datagram on its socket: yaw and "
                    "pitch from any GAC frame of 12 data chars or more (pushed, or the answer "
                    "to its 2 Hz GAC poll); without one its probe finds no gimbal",
       .lost = "no gimbal found: telemetry and the laser lock are off",
       .source = 1,
       .send_ident = "GAA",
       .send_control = 'w',
       .send_data = "05",
       .check = Check::stream,
       .ident = "GAC",
       .pattern = kAngles12,
       .min_hz = 1,
       .max_hz = 100,
       .window_ms = 2000},
      {.id = "attitude-poll",
       .feature = "attitude poll",
       .grade = Grade::info,
       .reasoning = "the station polls GAC every 0.5 s and waits 0.12 s for the answer; a "
                    "pushed GAC serves it as well",
       .lost = "the poll goes unanswered: the pushes alone carry the attitude",
       .source = 0,
       .send_ident = "GAC",
       .send_dst = 'G',
       .ident = "GAC",
       .pattern = kAngles12,
       .window_ms = 120},
      {.id = "speed",
       .feature = "speed control",
       .grade = Grade::should,
       .reasoning = "the station stops and turns the gimbal with GSM (yaw and pitch speed) and "
                    "waits for no answer",
       .lost = "the device refuses GSM: the station's stops and slews do nothing",
       .source = 0,
       .send_ident = "GSM",
       .send_control = 'w',
       .send_data = "0000",
       .send_fixed = false,
       .check = Check::taken,
       .ident = "GSM"},
  };
  return p;
}

Profile c10pro_tool() {
  Profile p;
  p.name = "c10pro-tool";
  p.title = "DifferentialRobotics/C10Pro_Control (angle command line tool)";
  p.models = {top::Model::c10pro};
  p.sources = {
      {"DifferentialRobotics/C10Pro_Control", "angel_control.py",
       "57886756c90031fb7367843de8af3b45bbec8e37"},
      {"DifferentialRobotics/C10Pro_Control", "README.md",
       "57886756c90031fb7367843de8af3b45bbec8e37"},
  };
  p.link = {.kind = LinkKind::udp,
            .device_port = 5000,
            .note = "UDP to 192.168.144.108:5000; the tool never reads an answer",
            .source = 0};
  p.tick_ms = 500;
  p.sends = {
      {"GAY", 'w', "000032", 'G', true, 0, -1, false,
       "#TP with length 6: angle 0.01 deg big-endian, speed 0.1 deg/s (5 deg/s: 32)", 0},
      {"GAP", 'w', "000032", 'G', true, 0, -1, false, "", 0},
      {"PTZ", 'w', "05", 'G', true, 0, -1, false,
       "centre as #TPUG2wPTZ056FEB: a second checksum after the frame's own", 0},
  };
  p.parsing = {{"reads nothing: every command is fire and forget", 0}};
  p.unchecked = {"that the angles are reached (the tool never reads the attitude)"};
  p.needs = {
      {.id = "yaw-angle",
       .feature = "yaw angle",
       .grade = Grade::must,
       .reasoning = "the tool sets yaw with GAY under a #TP header with length 6 and reads no "
                    "answer",
       .lost = "the device refuses the tool's GAY",
       .source = 0,
       .raw = "#TPUG6wGAY000032",
       .check = Check::taken,
       .ident = "GAY"},
      {.id = "pitch-angle",
       .feature = "pitch angle",
       .grade = Grade::must,
       .reasoning = "the tool sets pitch with GAP under a #TP header with length 6",
       .lost = "the device refuses the tool's GAP",
       .source = 0,
       .raw = "#TPUG6wGAP000032",
       .check = Check::taken,
       .ident = "GAP"},
      {.id = "centre",
       .feature = "centre",
       .grade = Grade::should,
       .reasoning = "the tool centres with #TPUG2wPTZ056FEB, a frame followed by two more "
                    "checksum characters",
       .lost = "the device refuses the centre frame",
       .source = 0,
       .raw_hex = "2354505547327750545A303536464542",
       .check = Check::taken,
       .ident = "PTZ"},
  };
  return p;
}

}  // namespace drivers
