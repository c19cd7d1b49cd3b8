// Device behaviour tables: streams, recorded frame forms, firmware traits
// and field support, each with its source. See top/device.hpp; the rules
// that read them are in device.cpp.
#include <cstdint>
#include <span>

#include "catalog_data.hpp"
#include "top/device.hpp"

#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace top {
namespace {

using detail::c10;
using detail::c10pro;
using detail::c12;
using detail::c13;
using detail::c20;
using detail::sip;

constexpr StreamSpec kStreams[] = {
    {.dialect = Dialect::skydroid,
     .request = "GAA",
     .push = "GAC",
     .rate_in_data = true,
     .section = "SkyDroid 3.3.2",
     .note = "GAA 01-64 (hex) pushes GAC at 1-100 Hz; 00 stops it",
     .periodic = true},
    {.dialect = Dialect::skydroid,
     .request = "FAE",
     .push = "FAI",
     .sender = Sender::client,
     .section = "SkyDroid 3.3.6",
     .note = "FAE 01 lets the flight controller send its attitude as FAI writes; "
             "the document gives FAI no reply",
     .periodic = true},
    {.dialect = Dialect::topotek,
     .request = "GAA",
     .push = "GAC",
     .section = "Topotek 3.4",
     .note = "GAA 01 switches the gimbal attitude push on, 00 off; the rate is "
             "the device's",
     .periodic = true},
    {.dialect = Dialect::topotek,
     .request = "GIA",
     .push = "GIC",
     .section = "Topotek 3.6",
     .note = "GIA 01 switches the gyroscope attitude push on, 00 off; the rate "
             "is the device's",
     .periodic = true},
    // The field: pushes the documents do not give. After the document's
    // entry of the same request, so that stream_enabled_by() without a
    // profile keeps the document's.
    // A real Topotek camera's event pushes (PixEagle bench @3bea324,
    // alireza787b/PixEagle docs/reporting/agent-ops/codex-modernization/
    // evidence/2026-09-17-gimbal-control-bench/<session>/events.jsonl): none
    // runs at a rate of its own asking (periodic false).
    {.dialect = Dialect::topotek,
     .request = "FED",
     .push = "ODR",
     .section = "field: PixEagle sessions 20260917T071854Z-ai-observe, "
                "20260917T072135Z-ai-select",
     .note = "FED 10 turns the detector's output on: ODR frames come at irregular times "
             "(0.07 to 2.5 s apart, bursts at 15 Hz), or none at all (PixEagle: absence does "
             "not tell no detection from other conditions); FED 20 turns it off. The camera "
             "answers neither",
     .off = 0x20,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D): after "
                 "#TPPD2wFED1034 at 07:18:56.503172, 8 ODR from 07:18:56.928933 to "
                 "07:19:02.395536, none after #TPPD2wFED2035 at 07:19:03.716098 (session "
                 "20260917T071854Z-ai-observe); 19 ODR from 07:21:37.929076, 0.65 s after "
                 "FED 10 (20260917T072135Z-ai-select); none in 8 s after the same FED 10 in "
                 "20260917T072022Z-ai-observe"},
    {.dialect = Dialect::topotek,
     .request = "ZMC",
     .push = "ODZ",
     .section = "field: PixEagle session 20260917T050955Z-zoom",
     .note = "while the lens zooms (ZMC 02 in, 01 out) ODZ frames come every 30 ms; none after "
             "the stop (ZMC 00). Only that one session shows them: what turns them on is not "
             "known beyond it",
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D): "
                 "#TPPM2wZMC0259 at 05:09:57.270748, 5 ODZ from 05:09:57.284912 to "
                 "05:09:57.405052, the stop #TPPM2wZMC0057 at 05:09:57.421025, none after; "
                 "the same after #TPPM2wZMC0158 at 05:09:58.653264 (session "
                 "20260917T050955Z-zoom)"},
    {.dialect = Dialect::topotek,
     .request = "GIA",
     .push = "GIA",
     .section = "field: ArduPilot AP_Mount_Topotek.h @ 3d293ff8 (GIA dispatch); PixEagle "
                "20260917T044930Z-queries (GIC answered with GIA)",
     .note = "GIA 01 pushes 12-char GIA attitude frames (yaw, pitch down positive, roll in "
             "0.01 deg); ArduPilot's driver re-sends the enable once a second and is healthy "
             "only while GIA frames arrive",
     .periodic = true,
     .evidence =
         "AP_Mount_Topotek.cpp @ d4209711 sends #TPUG2wGIA013E once a second and parses only "
         "GIA for attitude (AP_Mount_Topotek.h @ 02246a61 dispatched GAC, @ 3d293ff8 GIA; the "
         "driver was tested on real hardware, PR #27053); ArduPilot's SIM_Topotek pushes "
         "#TPUGCrGIA at 10 Hz; a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answers "
         "the GIC query with a 12-char GIA (PixEagle session 20260917T044930Z-queries "
         "04:49:34.243738 #TPPG2rGIC0035 -> 04:49:34.350916 #tpGPCrGIAFF25FFF8FFFE38). No "
         "public capture shows the push after GIA 01 itself: it rests on the driver"},
    {.dialect = Dialect::topotek,
     .request = "LOC",
     .push = "OFT",
     .section = "field: PixEagle sessions 20260917T051606Z-point, 20260917T072332Z-box",
     .note = "a tracking start (LOC) pushes OFT tracking boxes at about video rate while the "
             "unit tracks; after a cancel one OFT with an all-zero box and status 1",
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D): after LOC at "
                 "05:16:08.703292, 33 OFT from 05:16:08.832750 to 05:16:09.898290, 33 ms apart "
                 "(about 30 Hz; PixEagle session 20260917T051606Z-point); after the cancel "
                 "#TPPD2wTRC014E at 07:23:41.799582 one OFT with an all-zero box and status '1' "
                 "at 07:23:41.846893 (PixEagle session 20260917T072332Z-box)"},
};

constexpr DeviceForm kForms[] = {
    // SkyDroid 3.3.2.2, receive example: "#TPUGCrGACY0Y1Y2Y3P0P1P2P3R0R1R2R3CC".
    {.dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c20,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::push,
     .header = Header::fixed,
     .order = Order::request_order,
     .source = Source::document_example,
     .evidence = "SkyDroid 3.3.2.2 example #TPUGCrGACY0Y1Y2Y3P0P1P2P3R0R1R2R3CC: "
                 "uppercase #TP, U first"},
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::push,
     .header = Header::variable,
     .order = Order::request_order,
     .source = Source::field,
     .evidence = "real C12s push #tpUGCrGAC<12 hex><cs>: a C12 Android app (log114/PTZControl "
                 "app/src/main/java/com/yiku/ptzcontrol/MainActivity.kt) reads the attitude "
                 "only from data holding #tpUGCrGAC, as do Python C12 clients (one checks the "
                 "checksum)"},
    // SkyDroid 4.22, reply example: "#TPUD4rSLR0005BC".
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::request_order,
     .source = Source::document_example,
     .evidence = "SkyDroid 4.22 reply example #TPUD4rSLR0005BC: #TP with length 4, U first"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a public C13 SDK (sadikbarun/skydroid_c13_miniSDK skydroid.py @ d5a1ae12) "
                 "takes a range only from a datagram holding #TPDU and SLR: #TP with length 4, "
                 "addresses swapped"},
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "VER",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real C12 answered VER with #tpDU3rVER0105025A (its length char lies): "
                 "CinarSamet/skydroid-c12-toolkit src/skydroid_c12/protocol.py @ 82a4a6b8, "
                 "\"confirmed on a real C12 unit\""},
    // Topotek 3.5: "receive: #tpGU C r GIC Y0Y1Y2Y3P0P1P2P3R0R1R2R3 CC".
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GIC",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::document_example,
     .evidence = "Topotek 3.5 example #tpGU C r GIC Y0Y1Y2Y3P0P1P2P3R0R1R2R3 CC"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a Topotek device answered #TPPG2rGAC002D with #tpGPCrGACFF36ED5A0048DE "
                 "(alireza787b/gimbal_control protocol_validator.py @ d2456511, \"from the "
                 "logs\"); a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered "
                 "04:49:33.442799 #TPPG2rGAC002D with 04:49:33.551667 #tpGPCrGACFFCC063202F3D6 "
                 "(PixEagle session 20260917T044930Z-queries)"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GIA",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered the GIC query "
                 "04:49:34.243738 #TPPG2rGIC0035 with 04:49:34.350916 #tpGPCrGIAFF25FFF8FFFE38 "
                 "(again at 04:49:36.754050, 04:49:39.157290; PixEagle session "
                 "20260917T044930Z-queries)",
     .answers = "GIC"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GMS",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered "
                 "18:52:14.971018 #tpPG2rGMS0089 with 18:52:15.082037 #tpGP2rGMS018A: #tp kept "
                 "on a 2-data-char reply (again 18:52:18.282093, 18:52:21.485252; PixEagle "
                 "session 20260917T185212Z-identity)"},
    // Lengths that count bytes. The SLR reply's source names no model: no
    // model bit, so only a capture of unknown model matches it.
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "IMG",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a C12 Android app (log114/PTZControl C12Service.kt) waits for #TPDU1rIMG and "
                 "takes the 2 chars after IMG as the palette: length 1 for 2 data chars; a "
                 "Python C12 console reads the palette only from a reply that starts #TPDU "
                 "and holds IMG",
     .length_in_bytes = true},
    {.dialect = Dialect::skydroid,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real device answered the range read with #TPDU2rSLR0018BE, data 0018 = 24 dm "
                 "under length 2 (a Qt ground station's note: lgs::SkydroidSdkClient, "
                 "video/skydroid_sdk_client.cpp, repository not known; it names no model)",
     .length_in_bytes = true},
};

constexpr Trait kTraits[] = {
    // Signs, per identifier: what the attitude (GAC) reports against the
    // command. Where the sources conflict the default serves the autopilot
    // (ArduPilot's SkyDroid driver closes its loop on GAC with GSY/GSP).
    {.kind = TraitKind::yaw_inverted,
     .dialect = Dialect::skydroid,
     .models = c12,
     .source = Source::field,
     .evidence = "for: AP_Mount_SkyDroid negates GSY (\"a positive GSY value moves yaw LEFT\", "
                 "real C11, PR #34155; SkyDroid told its author the commands are the same across "
                 "models) and a station used on a real C13 (custom-GCS) agrees: on the wire +GSY "
                 "makes GAC yaw decrease; two public C12 clients negate yaw before GAY/GAM, one "
                 "noting the attitude reports the opposite sign of the GAM input. Against: a C12 "
                 "Android app (log114/PTZControl) turns left with GSY E2, the document's sign "
                 "(topsim --yaw-sign normal). The default serves the autopilot",
     .idents = "GSY GAY GAM"},
    {.kind = TraitKind::pitch_inverted,
     .dialect = Dialect::skydroid,
     .models = c12,
     .source = Source::field,
     .evidence = "for: only a C12 visual-servoing README's tuning example, which sets inv_y "
                 "(image to pitch: weak; no public C12 client that negates pitch before GAM was "
                 "found). Against: a C12 Android app (log114/PTZControl "
                 "app/src/main/java/com/yiku/ptzcontrol/service/C12Service.kt @ adfe4ccb) sends "
                 "GAP DCD8 (-90.00) for down and GSP +30 for up, the document's signs; a C12 "
                 "toolkit (CinarSamet/skydroid-c12-toolkit src/skydroid_c12/protocol.py @ "
                 "82a4a6b8) found GAP up positive on a real C12; AP_Mount_SkyDroid (C11, PR "
                 "#34155) and a C13 "
                 "station (custom-GCS) keep GSP and GAC pitch up positive, and SkyDroid told the "
                 "driver's author the commands are the same; AP_Mount_SkyDroid.cpp @ c5aa8452 "
                 "closes its angle loop on GAC pitch with GSP, so with it the driver's pitch "
                 "would run away to the limit (inference). Unconfirmed: not applied by "
                 "default (topsim --pitch-sign inverted inverts every pitch command)",
     .idents = "GAM",
     .contested = true},
    {.kind = TraitKind::yaw_inverted,
     .dialect = Dialect::skydroid,
     .models = c13,
     .source = Source::field,
     .evidence = "on the wire +GSY makes GAC yaw decrease, the reverse of SkyDroid 3.2.1: "
                 "AP_Mount_SkyDroid negates GSY (\"a positive GSY value moves yaw LEFT\", real "
                 "C11, PR #34155; SkyDroid says C11/C13 commands are the same) and a station "
                 "used on a real C13 (custom-GCS, _LRF_C13_INVERT_GSY) agrees; which of GSY or "
                 "GAC yaw differs from the document physically is not established. Against: "
                 "none found for the C13",
     .idents = "GSY"},
    {.kind = TraitKind::answers_to_source,
     .dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c13 | c20,
     .source = Source::field,
     .evidence = "C12 clients send from a bound UDP port and read the replies and GAC pushes on "
                 "that socket (CinarSamet/skydroid-c12-toolkit src/skydroid_c12/protocol.py @ "
                 "82a4a6b8, on a real C12 at port 5000; log114/PTZControl "
                 "app/src/main/java/com/yiku/ptzcontrol/service/C12Service.kt @ adfe4ccb): the "
                 "device answers the datagram's source"},
    {.kind = TraitKind::link_by_source,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::document_rule,
     .evidence = "Topotek 2: the source byte names the interface (P network, U UART); a "
                 "UDP request with source U gets no answer (public Topotek clients agree)"},
    {.kind = TraitKind::speed_refresh,
     .dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c20,
     .value = 1000,
     .source = Source::field,
     .evidence = "\"the firmware auto-stops the motor a few tens of milliseconds after the last "
                 "command if it isn't refreshed at roughly 20Hz\" (a real C12: CinarSamet/"
                 "skydroid-c12-toolkit src/skydroid_c12/protocol.py @ 82a4a6b8); "
                 "AP_Mount_SkyDroid.cpp @ c5aa8452 (PR #34155) re-sends GSY/GSP on every update"},
    {.kind = TraitKind::keeps_request_header,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answers #tpPG2rGMS0089 "
                 "with #tpGP2rGMS018A (#tp kept on 2 data chars; PixEagle session "
                 "20260917T185212Z-identity 18:52:14.971018 -> 18:52:15.082037) and "
                 "#TPPD2rTRC0048 with #TPDP2rTRC0048 (PixEagle session 20260917T044930Z-queries "
                 "04:49:32.641749 -> 04:49:32.643626)"},
    {.kind = TraitKind::double_checksum,
     .dialect = Dialect::skydroid,
     .models = c10pro,
     .source = Source::field,
     .evidence = "a C10 Pro tool (DifferentialRobotics/C10Pro_Control README.md, "
                 "angel_control.py @ 57886756) sends "
                 "#TPUG2wPTZ056FEB, #TPUG2wPTZ016BE3, #TPUG2wPTZ026CE5: a valid frame, then a "
                 "checksum over it and its checksum; that the camera takes them is the tool "
                 "author's claim",
     .idents = "PTZ"},
    // A real Topotek camera on UDP: PixEagle's bench evidence
    // (alireza787b/PixEagle @ 3bea324, docs/reporting/agent-ops/
    // codex-modernization/evidence/2026-09-17-gimbal-control-bench/<session>/
    // events.jsonl; captures/sip-bench/ holds them as pcaps).
    {.kind = TraitKind::ephemeral_reply_port,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) answered "
                 "requests to UDP 9003 from port 38909 (sessions 20260917T044930Z-queries and "
                 "045021Z-routing), "
                 "57707 (045346Z to 045454Z), 35496 (050911Z to 051227Z), 59598 (051516Z to "
                 "052716Z), 50076 (071735Z to 072435Z) and 48413 (185212Z-identity), never from "
                 "9003: its reply port changes between sessions"},
    {.kind = TraitKind::fan_out,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) sent each "
                 "reply to the asking port, to UDP 9004 and to the client port that asked "
                 "before it: in 20260917T045021Z-routing the TRC read from port 48611 at "
                 "04:50:26.437400 reached 8080, 9004, 48611 and 9004 within 0.11 ms; in "
                 "20260917T044930Z-queries the reads from 9004 reached 8080 too"},
    {.kind = TraitKind::duplicate_to_client_port,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) sent two "
                 "copies of each reply to UDP 9004 in 20260917T045021Z-routing and from "
                 "050955Z-zoom on (051804Z-queries 05:18:06.710040 and .710110); one in "
                 "044930Z-queries and 045346Z-stops to 045454Z-tilt"},
    {.kind = TraitKind::silent_writes,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) echoed none "
                 "of the 361 writes of its 28 UDP sessions of 2026-09-17 (PTZ, ZMC, GSY, GSP, TRC, "
                 "LOC, FED), and they took effect: after #TPPD2wTRC024F (20260917T045408Z-"
                 "tracking-ready 04:54:10.483447) the next TRC read answered 01; after "
                 "#TPUG2wGSY0564 (045437Z-pan 04:54:39.435460) GAC yaw went from -2.72 to -2.37 "
                 "deg. Topotek V1.1.3 defines w as set/control and gives plain writes no reply"},
};

// SkyDroid 3.1 lists PTZ for C10, C10Pro, C12 and C20, and 0E-13 as trim.
constexpr std::int64_t kC13Ptz[] = {0x02, 0x05, 0x0E, 0x0F, 0x10, 0x11, 0x12, 0x13};
// ArduPilot's SkyDroid driver sends these PTZ codes to C11 and C13 alike.
constexpr std::int64_t kC13PtzDriver[] = {0x05, 0x06, 0x07};
constexpr FieldSupport kFieldSupport[] = {
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "PTZ",
     .values = kC13Ptz,
     .evidence = "a public C13 SDK (sadikbarun/skydroid_c13_miniSDK skydroid.py @ d5a1ae12) "
                 "lists PTZ 02 (down), 05 (center) and 0E/0F pitch +/-, 10/11 yaw +/-, 12/13 "
                 "roll +/- for the C13"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "PTZ",
     .values = kC13PtzDriver,
     .evidence = "AP_Mount_SkyDroid (PR #34155, https://github.com/ArduPilot/ardupilot/pull/"
                 "34155) sends PTZ 06 follow, 07 lock and 05 centre to C11 and C13 alike; its "
                 "author: SkyDroid confirmed the C11/C13 commands are the same"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GAA",
     .evidence = "AP_Mount_SkyDroid (PR #34155) turns the C13's attitude on with "
                 "#TPUG2wGAA323A (SkyDroid confirmed the C11/C13 commands are the same); a "
                 "station used on a real C13 (custom-GCS) sends GAA 1-100 Hz"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GAC",
     .evidence = "a station used on a real C13 (custom-GCS) reads GAC attitude "
                 "(#TPUG2rGAC00); AP_Mount_SkyDroid (PR #34155) reads the C13's GAC pushes"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GSY",
     .evidence = "AP_Mount_SkyDroid (PR #34155) drives C11 and C13 yaw with GSY (SkyDroid "
                 "confirmed the C11/C13 commands are the same); a station used on a real C13 "
                 "(custom-GCS) sends GSY"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GSP",
     .evidence = "AP_Mount_SkyDroid (PR #34155) drives C11 and C13 pitch with GSP (SkyDroid "
                 "confirmed the C11/C13 commands are the same); a station used on a real C13 "
                 "(custom-GCS) sends GSP, sign as documented"},
    // What the SkyDroid driver sends the C13 as the C11 beyond the gimbal
    // commands: the document's support lines leave the C13 out.
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "VER",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its version read (answered by ArduPilot's SIM_SkyDroid for its C13) as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "SDC",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its SD card read (answered by ArduPilot's SIM_SkyDroid for its C13) as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "TIM",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its time write as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "FAE",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its attitude input enable as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "FAI",
     .evidence =
         "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
         "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
         "its own attitude as the C11, in 14 chars with a mode byte (the catalog's field form "
         "of FAI; SkyDroid 3.3.6.2 gives 12)"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "REC",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its recording as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "CAP",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its photo as the C11"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "DZM",
     .evidence = "AP_Mount_SkyDroid (PR #34155, written against real C11/C13 units; "
                 "SkyDroid confirmed the C11/C13 commands are the same) sends the C13 "
                 "its digital zoom as the C11"},
};

constexpr ModelSet kC13 = model_bit(Model::c13);
constexpr FieldNote kFieldNotes[] = {
    {.dialect = Dialect::skydroid,
     .models = kC13,
     .ident = "GAC",
     .note = "GAC pitch often reads 0.0 while the gimbal tilts; yaw is reliable",
     .evidence = "a station used on a real C13 (vamaskylight/custom-GCS, vgcs/skydroid/adapter.py "
                 "@ 0151122d, _gac_pitch_trusted: \"C13 GAC pitch often reads 0.0 even while the "
                 "gimbal tilts (yaw is reliable)\"; it distrusts a 0.0 pitch when its aim moved "
                 "pitch by 2.5 deg or more). A station's note, confirmed nowhere else: topsim's "
                 "C13 reports "
                 "the pitch it moves to; a C13 pitch that stays 0.0 in topdump report's motion "
                 "plot while yaw moves may be this"},
    {.dialect = Dialect::skydroid,
     .models = kC13,
     .note = "some C13 builds also listen on UDP 9003 and 19853 (zoom and lens/system commands)",
     .evidence = "a station used on a real C13 (vamaskylight/custom-GCS, vgcs/skydroid/adapter.py "
                 "@ 0151122d: \"lens/system also on 9003 on some C13 builds\", "
                 "_ZOOM_EXTRA_PORTS = (9003, 19853); the same file's probe list has 19856 where "
                 "the zoom list has 19853). Not a port rule: UDP 9003 is the Topotek device port "
                 "(Topotek V1.1.3), which tells topdump and the dissector the Topotek dialect, and "
                 "one station's constants, at odds within the file, are not enough to serve "
                 "19853"},
};

}  // namespace

std::span<const StreamSpec> streams() noexcept { return kStreams; }
std::span<const DeviceForm> device_forms() noexcept { return kForms; }
std::span<const Trait> traits() noexcept { return kTraits; }
std::span<const FieldSupport> field_support() noexcept { return kFieldSupport; }
std::span<const FieldNote> field_notes() noexcept { return kFieldNotes; }

}  // namespace top
