// Device behaviour tables: streams and recorded frame forms, each with its
// source. See top/device.hpp; the rules that read them are in device.cpp;
// firmware traits, field support and field notes are in device_traits.cpp.
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

}  // namespace

std::span<const StreamSpec> streams() noexcept { return kStreams; }
std::span<const DeviceForm> device_forms() noexcept { return kForms; }

}  // namespace top
