// Device behaviour tables: firmware traits, field support and field notes,
// each with its source. See top/device.hpp; the rules that read them are in
// device.cpp; streams and frame forms are in device_tables.cpp.
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

constexpr FieldNote kFieldNotes[] = {
    {.dialect = Dialect::skydroid,
     .models = c13,
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
     .models = c13,
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

std::span<const Trait> traits() noexcept { return kTraits; }
std::span<const FieldSupport> field_support() noexcept { return kFieldSupport; }
std::span<const FieldNote> field_notes() noexcept { return kFieldNotes; }

}  // namespace top
