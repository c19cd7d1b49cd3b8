// The Topotek SIP "Udp&uart-Protocol" V1.1.3 command table (seeds/001_...).
// Section numbers are the document's own (chapter.number).
#include "catalog_data.hpp"

// Designated initializers leave the other members at their defaults on
// purpose; GCC before 13 warns about each omitted member under -Wextra.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace top::detail {
namespace {

// ---------------------------------------------------------------------------
// Shared pieces

// A read request: data "00".
constexpr FieldSpec kQueryFields[] = {
    {.name = "query", .kind = FieldKind::hex_u, .width = 2},
};
constexpr FormSpec kQueryForm = {.control = 'r',
                                 .role = Role::request,
                                 .min_length = 2,
                                 .max_length = 2,
                                 .fields = kQueryFields};

constexpr EnumValue kEnable[] = {
    {0x00, "disable"},
    {0x01, "enable"},
};
constexpr EnumValue kOnOffHex[] = {
    {0x00, "off"},
    {0x01, "on"},
};

// ---------------------------------------------------------------------------
// 3 M class

// 3.1.1 ZMC
constexpr EnumValue kZmc[] = {
    {0x00, "stop"},
    {0x01, "zoom_out"},
    {0x02, "zoom_in"},
};
constexpr FieldSpec kZmcFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kZmc},
};
constexpr FormSpec kZmcForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kZmcFields},
};

// 3.1.2 ZOM / 3.2.2 FOC: signed 16-bit position
constexpr FieldSpec kPositionFields[] = {
    {.name = "position", .kind = FieldKind::hex_s, .width = 4},
};
constexpr FormSpec kPositionReadForms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 4,
     .max_length = 4,
     .fields = kPositionFields},
};

// 3.2.1 FCC
constexpr EnumValue kFcc[] = {
    {0x00, "stop"},
    {0x01, "focus_plus"},
    {0x02, "focus_minus"},
    {0x10, "auto_focus"},
    {0x11, "manual_focus"},
    {0x12, "manual_focus_save"},
    {0x13, "auto_focus_save"},
};
constexpr FieldSpec kFccFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kFcc},
};
constexpr FormSpec kFccForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kFccFields},
};

// 3.3 ZFP
constexpr FieldSpec kZfpFields[] = {
    {.name = "zoom", .kind = FieldKind::hex_s, .width = 4},
    {.name = "focus",
     .kind = FieldKind::hex_s,
     .width = 4,
     .none = "NNNN",
     .note = "NNNN: zoom only, the camera focuses by itself afterwards"},
};
constexpr FormSpec kZfpForms[] = {
    {.control = 'w', .min_length = 8, .max_length = 8, .fields = kZfpFields},
};

// 3.4 ZMP (pushed after a zoom change)
constexpr FieldSpec kZmpFields[] = {
    {.name = "magnification",
     .kind = FieldKind::dec_u,
     .width = 3,
     .scale = 0.1,
     .unit = "x",
     .note = "\"123\" = 12.3x"},
    {.name = "zoom", .kind = FieldKind::hex_s, .width = 4},
};
constexpr FormSpec kZmpForms[] = {
    {.control = 'r', .role = Role::any, .min_length = 7, .max_length = 7, .fields = kZmpFields},
};

// 3.5 SWH (slave device power)
constexpr EnumValue kSwhDevice[] = {
    {'5', "rangefinder_dust_sensor_5v"},
    {'C', "fill_light_12v"},
};
constexpr EnumValue kOnOffChar[] = {
    {'0', "off"},
    {'1', "on"},
};
constexpr FieldSpec kSwhFields[] = {
    {.name = "device",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kSwhDevice,
     .note = "5 (5 V): laser rangefinder, dust detection; C (12 V): fill light"},
    {.name = "state", .kind = FieldKind::enum_char, .width = 1, .enums = kOnOffChar},
};
constexpr FormSpec kSwhForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kSwhFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kSwhFields},
};

// 3.6 IRC
constexpr EnumValue kIrc[] = {
    {0x00, "day"},
    {0x01, "night"},
    {0x0A, "toggle"},
};
constexpr FieldSpec kIrcFields[] = {
    {.name = "mode", .kind = FieldKind::enum_hex, .width = 2, .enums = kIrc},
};
constexpr FormSpec kIrcForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kIrcFields},
};

// 3.7 ATE
constexpr FieldSpec kAteFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kEnable},
};
constexpr FormSpec kAteForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kAteFields},
};

// 3.8 / 5.16 VSN
constexpr FieldSpec kVersionFields[] = {
    {.name = "version", .kind = FieldKind::text, .width = 0},
};
constexpr FormSpec kVsnForms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 1,
     .max_length = 15,
     .fields = kVersionFields,
     .note = "M class: \"M3326\" in the example; D class (5.16): 2 chars"},
};

// 3.9 MUL (optical zoom ratio, decimal)
constexpr FieldSpec kMulFields[] = {
    {.name = "ratio",
     .kind = FieldKind::dec_u,
     .width = 4,
     .scale = 0.1,
     .unit = "x",
     .note = "decimal: 0123 = 12.3x"},
};
constexpr FormSpec kMulForms[] = {
    {.control = 'w', .min_length = 4, .max_length = 4, .fields = kMulFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 4,
     .max_length = 4,
     .fields = kMulFields},
};

// 3.10 APC
constexpr EnumValue kApc[] = {
    {0x00, "stop"},
    {0x01, "aperture_minus"},
    {0x02, "aperture_plus"},
};
constexpr FieldSpec kApcFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kApc},
};
constexpr FormSpec kApcForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kApcFields},
};

// ---------------------------------------------------------------------------
// 4 G class

// 4.1 PTZ: 06/07 are lock/follow here, the reverse of SkyDroid.
constexpr EnumValue kPtz[] = {
    {0x00, "stop"},      {0x01, "up"},         {0x02, "down"},
    {0x03, "left"},      {0x04, "right"},      {0x05, "center"},
    {0x06, "lock"},      {0x07, "follow"},     {0x08, "toggle_follow_lock"},
    {0x09, "calibrate"}, {0x0A, "point_down"},
};
constexpr FieldSpec kPtzFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kPtz},
};
constexpr FormSpec kPtzForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPtzFields},
};

// 4.2 GSY/GSP/GSR/GSM/RPS/YPR (speed): 8-bit signed, deg/s per the table.
constexpr FieldSpec kSpeedFields[] = {
    {.name = "speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99,
     .note = "yaw right positive; the text says pitch down positive"},
};
constexpr FormSpec kSpeedForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kSpeedFields},
};
constexpr FieldSpec kSpeedYawPitchFields[] = {
    {.name = "yaw_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
};
constexpr FormSpec kSpeedYawPitchForms[] = {
    {.control = 'w', .min_length = 4, .max_length = 4, .fields = kSpeedYawPitchFields},
};
constexpr FieldSpec kSpeedRollPitchFields[] = {
    {.name = "roll_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
};
constexpr FormSpec kSpeedRollPitchForms[] = {
    {.control = 'w', .min_length = 4, .max_length = 4, .fields = kSpeedRollPitchFields},
};
constexpr FieldSpec kSpeedYawPitchRollFields[] = {
    {.name = "yaw_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
    {.name = "roll_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 1.0,
     .unit = "deg/s",
     .min = -99,
     .max = 99},
};
constexpr FormSpec kSpeedYawPitchRollForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kSpeedYawPitchRollFields},
};

// 4.3.1 GAY/GAP/GAR/GAM and 4.3.2 GIY/GIP/GIR/GIM (angle control)
constexpr FieldSpec kYawAngleFields[] = {
    {.name = "angle",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -150,
     .max = 150,
     .note = "right positive"},
    {.name = "speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
};
constexpr FormSpec kYawAngleForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kYawAngleFields},
};
constexpr FieldSpec kAngleFields[] = {
    {.name = "angle",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
};
constexpr FormSpec kAngleForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kAngleFields},
};
constexpr FieldSpec kAngleYawPitchFields[] = {
    {.name = "yaw",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -150,
     .max = 150},
    {.name = "yaw_speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
    {.name = "pitch",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
};
constexpr FormSpec kAngleYawPitchForms[] = {
    {.control = 'w', .min_length = 12, .max_length = 12, .fields = kAngleYawPitchFields},
};

// 4.3.3 GAC / 4.3.5 GIC (attitude read)
constexpr FieldSpec kAttitudeFields[] = {
    {.name = "yaw", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "pitch", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "roll", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
};
constexpr FormSpec kAttitudeForms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 12,
     .max_length = 12,
     .fields = kAttitudeFields,
     .note = "also the frame pushed after GAA/GIA 01"},
};

// 4.3.4 GAA / 4.3.6 GIA (attitude push on/off)
constexpr FieldSpec kPushFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kEnable},
};
constexpr FormSpec kPushForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPushFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kPushFields},
};

// 4.3.6 GIA: the document's switch, and the field's attitude frame. A real
// Topotek camera (PixEagle bench) answers the GIC query with GIA frames of
// 12 hex chars, and ArduPilot's Topotek driver reads its attitude only from
// them.
constexpr FieldSpec kGiaAttitudeFields[] = {
    {.name = "yaw", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "pitch",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .note = "down positive on the wire: AP_Mount_Topotek negates it on read, ArduPilot's "
             "SIM_Topotek sends 30 deg down as 0BB8"},
    {.name = "roll", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
};
constexpr FormSpec kGiaForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPushFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kPushFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 12,
     .max_length = 12,
     .fields = kGiaAttitudeFields,
     .note = "attitude: the reply to a GIC query and the frame pushed after GIA 01, yaw, "
             "pitch, roll in 0.01 deg",
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answers #TPPG2rGIC0035 "
                 "with #tpGPCrGIA + 12 hex (PixEagle session 20260917T044930Z-queries "
                 "04:49:34.243738 -> 04:49:34.350916 #tpGPCrGIAFF25FFF8FFFE38); "
                 "AP_Mount_Topotek.cpp @ d4209711 reads its attitude from GIA after "
                 "#TPUG2wGIA013E (AP_Mount_Topotek.h @ 02246a61 dispatched GAC, @ 3d293ff8 GIA)"},
};

// 4.4 GMS (gimbal motors)
constexpr FieldSpec kGmsFields[] = {
    {.name = "motors", .kind = FieldKind::enum_hex, .width = 2, .enums = kOnOffHex},
};
constexpr FormSpec kGmsForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kGmsFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kGmsFields},
};

// 4.5.1 VER (serial number)
constexpr FieldSpec kSerialFields[] = {
    {.name = "serial_number", .kind = FieldKind::text, .width = 14},
};
constexpr FormSpec kVerForms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 14,
     .max_length = 14,
     .fields = kSerialFields},
};

// ---------------------------------------------------------------------------
// 5 D class

// 5.1 REC
constexpr EnumValue kRecAction[] = {
    {0x00, "stop"},
    {0x01, "start"},
    {0x0A, "toggle"},
};
constexpr EnumValue kRecReply[] = {
    {0x00, "stopped"},
    {0x11, "recording"},
};
constexpr EnumValue kRecState[] = {
    {0x00, "stopped"},
    {0x01, "recording"},
};
constexpr FieldSpec kRecActionFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kRecAction},
};
constexpr FieldSpec kRecReplyFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kRecReply},
    {.name = "file_index",
     .kind = FieldKind::hex_u,
     .width = 8,
     .note = "stream_0_idx.h264 (visible), stream_1_idx.h264 (thermal)"},
};
constexpr FieldSpec kRecStateFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kRecState},
};
constexpr FormSpec kRecForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kRecActionFields},
    {.control = 'w',
     .role = Role::response,
     .min_length = 10,
     .max_length = 10,
     .fields = kRecReplyFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kRecStateFields},
};

// 5.2 CAP
constexpr EnumValue kCap[] = {
    {0x01, "visible_and_thermal"},
    {0x02, "visible_only"},
    {0x03, "thermal_only"},
    {0x05, "visible_thermal_radiometric"},
};
constexpr EnumValue kCapReply[] = {
    {0x11, "captured"},
};
constexpr FieldSpec kCapFields[] = {
    {.name = "mode", .kind = FieldKind::enum_hex, .width = 2, .enums = kCap},
};
constexpr FieldSpec kCapReplyFields[] = {
    {.name = "state",
     .kind = FieldKind::enum_hex,
     .width = 2,
     .enums = kCapReply,
     .note = "11 is the only documented value"},
    {.name = "file_index",
     .kind = FieldKind::hex_u,
     .width = 8,
     .note = "snap_0_idx.jpeg, snap_1_idx.jpeg, raw_idx.raw"},
};
constexpr FormSpec kCapForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kCapFields},
    {.control = 'w',
     .role = Role::response,
     .min_length = 10,
     .max_length = 10,
     .fields = kCapReplyFields},
};

// 5.3 VID (resolution)
constexpr EnumValue kVidTarget[] = {
    {'0', "record"},
    {'1', "photo"},
    {'2', "rtsp"},
};
constexpr EnumValue kVidResolution[] = {
    {'0', "res_3840x2160"},
    {'1', "res_1920x1080"},
    {'2', "res_1280x720"},
    {'3', "res_640x480"},
};
constexpr FieldSpec kVidFields[] = {
    {.name = "target", .kind = FieldKind::enum_char, .width = 1, .enums = kVidTarget},
    {.name = "resolution", .kind = FieldKind::enum_char, .width = 1, .enums = kVidResolution},
};
constexpr FormSpec kVidForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kVidFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kVidFields},
};

// 5.4 BIT (stream 0 bit rate)
constexpr EnumValue kBitMode[] = {
    {'0', "mbps"},
    {'K', "kbps"},
};
constexpr FieldSpec kBitWriteFields[] = {
    {.name = "mode", .kind = FieldKind::enum_char, .width = 1, .enums = kBitMode},
    {.name = "rate",
     .kind = FieldKind::dec_u,
     .width = 5,
     .unit = "kbps",
     .min = 50,
     .max = 99999,
     .note = "mode K: decimal kb/s, minimum 50; mode 0: only the first digit "
             "counts, in Mbps (1-8)"},
};
constexpr FieldSpec kBitReadFields[] = {
    {.name = "rate", .kind = FieldKind::hex_u, .width = 2, .unit = "Mbps", .min = 1, .max = 8},
};
constexpr FormSpec kBitForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kBitWriteFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kBitReadFields},
};

// 5.5 SDC
constexpr EnumValue kSdcQuery[] = {
    {0x00, "free"},
    {0x01, "total"},
};
constexpr FieldSpec kSdcQueryFields[] = {
    {.name = "query", .kind = FieldKind::enum_hex, .width = 2, .enums = kSdcQuery},
};
constexpr FieldSpec kSdcFields[] = {
    {.name = "capacity",
     .kind = FieldKind::hex_u,
     .width = 5,
     .unit = "MB",
     .none = "NNNNN",
     .note = "NNNNN: no memory card"},
};
constexpr FormSpec kSdcForms[] = {
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kSdcQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 5,
     .max_length = 5,
     .fields = kSdcFields},
};

// 5.6 ROT (flip/mirror)
constexpr EnumValue kRot[] = {
    {0x00, "rotate_0"},
    {0x02, "rotate_180"},
};
constexpr FieldSpec kRotFields[] = {
    {.name = "rotation", .kind = FieldKind::enum_hex, .width = 2, .enums = kRot},
};
constexpr FormSpec kRotForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kRotFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kRotFields},
};

// 5.7 IPV/GTW/RST (network)
constexpr FieldSpec kAddressFields[] = {
    {.name = "address", .kind = FieldKind::text, .width = 0},
};
constexpr FormSpec kAddressForms[] = {
    {.control = 'w', .min_length = 7, .max_length = 15, .fields = kAddressFields},
};
constexpr EnumValue kRst[] = {
    {0x01, "reset"},
};
constexpr FieldSpec kRstFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kRst},
};
constexpr FormSpec kRstForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kRstFields},
};

// 5.8.1 LON / 5.8.2 LAT (input, NMEA) and 5.8.7 (target solution output)
constexpr EnumValue kEastWest[] = {
    {'E', "east"},
    {'W', "west"},
};
constexpr EnumValue kNorthSouth[] = {
    {'N', "north"},
    {'S', "south"},
};
constexpr FieldSpec kLonInFields[] = {
    {.name = "longitude",
     .kind = FieldKind::nmea,
     .width = 11,
     .unit = "deg",
     .note = "E/W + dddmm.mmmm as in $GPGGA"},
};
constexpr FieldSpec kLonOutFields[] = {
    {.name = "hemisphere", .kind = FieldKind::enum_char, .width = 1, .enums = kEastWest},
    {.name = "longitude",
     .kind = FieldKind::number,
     .width = 10,
     .unit = "deg",
     .min = 0,
     .max = 180,
     .note = "ddd.ddddd per the text; bytes 1-10 per the byte count"},
};
constexpr FormSpec kLonForms[] = {
    {.control = 'w',
     .role = Role::request,
     .min_length = 11,
     .max_length = 11,
     .fields = kLonInFields},
    {.control = 'w',
     .role = Role::response,
     .min_length = 11,
     .max_length = 11,
     .fields = kLonOutFields,
     .note = "5.8.7: target longitude solved from attitude and range"},
};
constexpr FieldSpec kLatInFields[] = {
    {.name = "latitude",
     .kind = FieldKind::nmea,
     .width = 10,
     .unit = "deg",
     .note = "N/S + ddmm.mmmm as in $GPGGA"},
};
constexpr FieldSpec kLatOutFields[] = {
    {.name = "hemisphere", .kind = FieldKind::enum_char, .width = 1, .enums = kNorthSouth},
    {.name = "latitude",
     .kind = FieldKind::number,
     .width = 9,
     .unit = "deg",
     .min = 0,
     .max = 90,
     .note = "dd.ddddd per the text; bytes 1-9 per the byte count"},
};
constexpr FormSpec kLatForms[] = {
    {.control = 'w',
     .role = Role::request,
     .min_length = 10,
     .max_length = 10,
     .fields = kLatInFields},
    {.control = 'w',
     .role = Role::response,
     .min_length = 10,
     .max_length = 10,
     .fields = kLatOutFields,
     .note = "5.8.7: target latitude solved from attitude and range"},
};

// 5.8.3 ALT
constexpr FieldSpec kAltFields[] = {
    {.name = "altitude",
     .kind = FieldKind::number,
     .width = 0,
     .unit = "m",
     .min = -9999.9,
     .max = 9999.9,
     .note = "as in $GPGGA"},
};
constexpr FormSpec kAltForms[] = {
    {.control = 'w', .min_length = 1, .max_length = 15, .fields = kAltFields},
};

// 5.8.4 AZI
constexpr FieldSpec kAziFields[] = {
    {.name = "course",
     .kind = FieldKind::number,
     .width = 5,
     .unit = "deg",
     .min = 0,
     .max = 359.9,
     .note = "000.0-359.9 from true north, leading zeros sent ($GPRMC)"},
};
constexpr FormSpec kAziForms[] = {
    {.control = 'w', .min_length = 5, .max_length = 5, .fields = kAziFields},
};

// 5.8.5 GPS (packed C struct, read little-endian)
constexpr FieldSpec kGpsFields[] = {
    {.name = "uav_heading",
     .kind = FieldKind::le_i16,
     .width = 2,
     .scale = 0.01,
     .unit = "deg",
     .note = "unit not given; 0.01 deg assumed as for the UAV yaw; left "
             "negative offset to the gimbal's centre"},
    {.name = "longitude",
     .kind = FieldKind::le_i32,
     .width = 4,
     .scale = 1e-7,
     .unit = "deg",
     .min = -180,
     .max = 180},
    {.name = "latitude",
     .kind = FieldKind::le_i32,
     .width = 4,
     .scale = 1e-7,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "altitude",
     .kind = FieldKind::le_i32,
     .width = 4,
     .scale = 1e-3,
     .unit = "m",
     .min = -500,
     .max = 10000},
};
constexpr FormSpec kGpsForms[] = {
    {.control = 'w', .min_length = 14, .max_length = 14, .fields = kGpsFields},
};

// 5.8.6 UAV (packed C struct, read little-endian)
constexpr FieldSpec kUavFields[] = {
    {.name = "yaw",
     .kind = FieldKind::le_i16,
     .width = 2,
     .scale = 0.01,
     .unit = "deg",
     .min = 0,
     .max = 360,
     .note = "int16_t cannot hold 327.68-360.00 deg"},
    {.name = "pitch",
     .kind = FieldKind::le_i16,
     .width = 2,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90,
     .note = "down positive"},
    {.name = "roll",
     .kind = FieldKind::le_i16,
     .width = 2,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90,
     .note = "right positive"},
    {.name = "speed",
     .kind = FieldKind::le_u16,
     .width = 2,
     .scale = 0.01,
     .unit = "m/s",
     .min = 0,
     .max = 200},
    {.name = "flight_path",
     .kind = FieldKind::le_u16,
     .width = 2,
     .scale = 0.01,
     .unit = "deg",
     .min = 0,
     .max = 360},
};
constexpr FormSpec kUavForms[] = {
    {.control = 'w', .min_length = 10, .max_length = 10, .fields = kUavFields},
};

// 5.9 LRF: control (to M, long-range versions) and result (from D)
constexpr EnumValue kLrfControl[] = {
    {0x00, "stop"},
    {0x01, "on"},
    {0x02, "single"},
    {0x03, "continuous"},
};
constexpr FieldSpec kLrfControlFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kLrfControl},
};
constexpr FieldSpec kLrfResultFields[] = {
    {.name = "distance",
     .kind = FieldKind::number,
     .width = 0,
     .unit = "m",
     .min = 0,
     .max = 99999.9,
     .none = "ERR",
     .note = "X1X2X3X4X5.X6, 0.1 m; ERR: measurement failed"},
};
constexpr FormSpec kLrfForms[] = {
    {.control = 'w',
     .min_length = 2,
     .max_length = 2,
     .fields = kLrfControlFields,
     .note = "control, sent to M on long-range versions"},
    {.control = 'w',
     .role = Role::response,
     .min_length = 3,
     .max_length = 7,
     .fields = kLrfResultFields,
     .note = "result, sent by D after each successful measurement: X1X2X3X4X5.X6 metres "
             "(00123.4), ERR when it failed; AP_Mount_Topotek.cpp @ d4209711 "
             "gimbal_dist_info_analyse() reads \"12345.6\" and ERR"},
};

// 5.10 TIM (Beijing time) and UTC, decimal
constexpr FieldSpec kTimFields[] = {
    {.name = "year", .kind = FieldKind::dec_u, .width = 4},
    {.name = "month", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 12},
    {.name = "day", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 31},
    {.name = "hour", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 23},
    {.name = "minute", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 59},
    {.name = "second", .kind = FieldKind::dec_u, .width = 2, .unit = "s", .min = 0, .max = 59},
};
constexpr FormSpec kTimForms[] = {
    {.control = 'w', .min_length = 14, .max_length = 14, .fields = kTimFields},
};
constexpr FieldSpec kUtcFields[] = {
    {.name = "hour", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 23},
    {.name = "minute", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 59},
    {.name = "second", .kind = FieldKind::dec_u, .width = 2, .unit = "s", .min = 0, .max = 59},
    {.name = "day", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 31},
    {.name = "month", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 12},
    {.name = "year", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 99},
};
constexpr FormSpec kUtcForms[] = {
    {.control = 'w', .min_length = 12, .max_length = 12, .fields = kUtcFields},
};

// 5.11 PIP, one char each for x0/x1
constexpr EnumValue kPip[] = {
    {'0', "main_only"},
    {'1', "main_and_secondary"},
    {'2', "secondary_and_main"},
    {'3', "secondary_only"},
    {'A', "next"},
    {'B', "previous"},
};
constexpr FieldSpec kPipFields[] = {
    {.name = "x0",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kPip,
     .note = "used with two visible-light lenses"},
    {.name = "x1", .kind = FieldKind::enum_char, .width = 1, .enums = kPip},
};
constexpr FormSpec kPipForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPipFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kPipFields},
};

// 5.12 TMP (temperature measurement); every digit read as hex.
constexpr FieldSpec kTmpHighCenterFields[] = {
    {.name = "x_high", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 320},
    {.name = "y_high", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 256},
    {.name = "t_high", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "degC"},
    {.name = "t_center", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "degC"},
};
constexpr FieldSpec kTmpHighLowFields[] = {
    {.name = "x_high", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 320},
    {.name = "y_high", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 256},
    {.name = "t_high", .kind = FieldKind::hex_s, .width = 4, .scale = 0.1, .unit = "degC"},
    {.name = "x_low", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 320},
    {.name = "y_low", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 256},
    {.name = "t_low", .kind = FieldKind::hex_s, .width = 4, .scale = 0.1, .unit = "degC"},
    {.name = "t_center", .kind = FieldKind::hex_s, .width = 4, .scale = 0.1, .unit = "degC"},
};
constexpr FieldSpec kTmpAreaRequestFields[] = {
    {.name = "x", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 640},
    {.name = "y", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 512},
    {.name = "width", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 64},
    {.name = "height", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 64},
};
constexpr FieldSpec kTmpAreaResponseFields[] = {
    {.name = "x", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 640},
    {.name = "y", .kind = FieldKind::hex_u, .width = 3, .unit = "px", .min = 0, .max = 512},
    {.name = "width", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 64},
    {.name = "height", .kind = FieldKind::hex_u, .width = 2, .unit = "px", .min = 0, .max = 64},
    {.name = "t_avg", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "degC"},
};
constexpr FormSpec kTmpForms[] = {
    {.control = 'w',
     .role = Role::any,
     .min_length = 13,
     .max_length = 13,
     .fields = kTmpHighCenterFields,
     .note = "12.1 #tpDPDwTMP: hottest point and centre, 0.01 degC"},
    {.control = 'w',
     .role = Role::any,
     .min_length = 22,
     .max_length = 22,
     .fields = kTmpHighLowFields,
     .note = "12.2 #PDP16TMP (malformed header): hottest, coldest, centre, "
             "0.1 degC"},
    {.control = 'r',
     .role = Role::request,
     .min_length = 10,
     .max_length = 10,
     .fields = kTmpAreaRequestFields,
     .note = "12.3 point (width and height 0) or area; some models"},
    {.control = 'r',
     .role = Role::response,
     .min_length = 14,
     .max_length = 14,
     .fields = kTmpAreaResponseFields,
     .note = "12.3 average temperature of the point or area, 0.01 degC"},
};

// 5.12.4 TMR (temperature range)
constexpr EnumValue kTmr[] = {
    {0x00, "low_range"},
    {0x01, "high_range"},
};
constexpr FieldSpec kTmrFields[] = {
    {.name = "range",
     .kind = FieldKind::enum_hex,
     .width = 2,
     .enums = kTmr,
     .note = "00: -20 to 150 degC (power-on default); 01: -20 to 550 degC"},
};
constexpr FormSpec kTmrForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTmrFields},
};

// 5.13 IMG (thermal palette)
constexpr EnumValue kImg[] = {
    {0x00, "white_hot"}, {0x01, "lava"},      {0x02, "iron_red"}, {0x03, "hot_iron"},
    {0x04, "medical"},   {0x05, "arctic"},    {0x06, "rainbow1"}, {0x07, "rainbow2"},
    {0x08, "red_tint"},  {0x09, "black_hot"}, {0x0A, "next"},     {0x0B, "previous"},
};
constexpr FieldSpec kImgFields[] = {
    {.name = "palette", .kind = FieldKind::enum_hex, .width = 2, .enums = kImg},
};
constexpr FormSpec kImgForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kImgFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kImgFields},
};

// 5.14 DZM (digital zoom)
constexpr EnumValue kDzmLens[] = {
    {'0', "visible"},
    {'1', "thermal"},
};
constexpr EnumValue kDzmCodes[] = {
    {0x0A, "zoom_in_step"}, {0x0B, "zoom_out_step"}, {0x0C, "zoom_in"},
    {0x0D, "zoom_out"},     {0x0E, "zoom_stop"},
};
constexpr FieldSpec kDzmWriteFields[] = {
    {.name = "lens", .kind = FieldKind::enum_char, .width = 1, .enums = kDzmLens},
    {.name = "zoom",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "x",
     .min = 0,
     .max = 12.8,
     .enums = kDzmCodes,
     .note = "00-80: go to ratio (0.1); 0A/0B step 0.5; 0C/0D until 0E"},
};
constexpr FieldSpec kDzmReadFields[] = {
    {.name = "thermal", .kind = FieldKind::hex_u, .width = 2, .scale = 0.1, .unit = "x"},
    {.name = "visible", .kind = FieldKind::hex_u, .width = 2, .scale = 0.1, .unit = "x"},
};
constexpr FormSpec kDzmForms[] = {
    {.control = 'w', .min_length = 3, .max_length = 3, .fields = kDzmWriteFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 4,
     .max_length = 4,
     .fields = kDzmReadFields},
};

// 5.15 DFG (electronic defog)
constexpr EnumValue kDfgMode[] = {
    {'0', "off"},
    {'1', "auto"},
    {'2', "manual"},
};
constexpr FieldSpec kDfgFields[] = {
    {.name = "mode",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kDfgMode,
     .note = "0 has no description in the table"},
    {.name = "strength", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
};
constexpr FormSpec kDfgForms[] = {
    {.control = 'w', .min_length = 3, .max_length = 3, .fields = kDfgFields},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 3,
     .max_length = 3,
     .fields = kDfgFields},
};

// 5.17 ENT (encoding)
constexpr EnumValue kEntStream[] = {
    {'0', "stream0"},
    {'1', "stream1"},
    {'2', "main_camera_record"},
    {'3', "second_camera_record"},
};
constexpr EnumValue kEntCodec[] = {
    {'0', "h264"},
    {'1', "h265"},
};
constexpr FieldSpec kEntFields[] = {
    {.name = "stream", .kind = FieldKind::enum_char, .width = 1, .enums = kEntStream},
    {.name = "codec", .kind = FieldKind::enum_char, .width = 1, .enums = kEntCodec},
};
constexpr FormSpec kEntForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kEntFields},
};

// ---------------------------------------------------------------------------
// The field: identifiers neither document lists, each with its source
// (docs/sources/ardupilot.md).

// PA2 (model name)
constexpr FieldSpec kModelNameFields[] = {
    {.name = "model",
     .kind = FieldKind::text,
     .width = 0,
     .note = "000000000 on units whose name was not set at production (PR #27568)"},
};
constexpr FormSpec kPa2Forms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 1,
     .max_length = 15,
     .fields = kModelNameFields,
     .evidence = "AP_Mount_Topotek takes the reply's data as the model name (PR #27568); "
                 "ArduPilot's SIM_Topotek answers #TPUG6rPA2SIM_TPBA"},
};

// TRC (tracking): writes, and the state in data char 1
constexpr EnumValue kTrcAction[] = {
    {0x00, "exit"},
    {0x01, "cancel_to_waiting"},
    {0x02, "prepare"},
};
constexpr FieldSpec kTrcActionFields[] = {
    {.name = "action",
     .kind = FieldKind::enum_hex,
     .width = 2,
     .enums = kTrcAction,
     .note = "AP_Mount_Topotek sends 02 before a LOC when stopped, 01 to cancel while "
             "tracking, else 00 (PR #27568); PixEagle's bench: 02 prepare, 01 cancel the "
             "target, 00 exit"},
};
constexpr EnumValue kTrcState[] = {
    {'0', "stopped"},          {'1', "waiting"},          {'2', "tracking"},
    {'3', "temporarily_lost"}, {'4', "lens_unsupported"},
};
constexpr FieldSpec kTrcStateFields[] = {
    {.name = "x0", .kind = FieldKind::dec_u, .width = 1, .note = "0 in every reply seen"},
    {.name = "state",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kTrcState,
     .note = "0 stopped, 1 waiting, 2 tracking (AP_Mount_Topotek, PR #27568); 3 temporarily "
             "lost (PixEagle bench on a SIP, the vendor's tracking PDF section 3; ArduPilot "
             "ignores it); 4 this lens does not track (PR #31768)"},
};
constexpr FormSpec kTrcForms[] = {
    {.control = 'w',
     .min_length = 2,
     .max_length = 2,
     .fields = kTrcActionFields,
     .evidence = "AP_Mount_Topotek sends #TPUD2wTRC0254, #TPUD2wTRC0153 and #TPUD2wTRC0052 "
                 "(PR #27568); PixEagle sent #TPPD2wTRC024F, #TPPD2wTRC014E, #TPPD2wTRC004D to a "
                 "real Topotek camera (PixEagle session 20260917T051606Z-point 05:16:07.901740, "
                 "05:16:09.904481, 05:16:10.705791)"},
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTrcStateFields,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered 04:49:32.641749 "
                 "#TPPD2rTRC0048 with 04:49:32.643626 #TPDP2rTRC0048, 1.9 ms (PixEagle session "
                 "20260917T044930Z-queries); AP_Mount_Topotek.cpp @ d4209711 "
                 "gimbal_track_analyse() reads the state from data char 1 (PR #27568, "
                 "PR #31768)"},
};

// TRA (tracker fault query)
constexpr FieldSpec kTraFields[] = {
    {.name = "fault",
     .kind = FieldKind::text,
     .width = 2,
     .note = "11 in every reply of a Topotek camera whose tracker was ready (PixEagle session "
             "20260917T071854Z-ai-observe); the vendor's PDF says a reply means an abnormal "
             "tracker"},
};
constexpr FormSpec kTraForms[] = {
    kQueryForm,
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTraFields,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered "
                 "07:18:56.503256 #TPPD2rTRA0046 with 07:18:56.511155 #TPDP2rTRA1148 (PixEagle "
                 "session 20260917T071854Z-ai-observe)"},
};

// LOC (tracking point or rectangle), 10 binary bytes, big-endian
constexpr EnumValue kLocMode[] = {
    {0x0001, "rectangle"},
    {0x0009, "point"},
};
constexpr FieldSpec kLocFields[] = {
    {.name = "x",
     .kind = FieldKind::be_i16,
     .width = 2,
     .min = -1000,
     .max = 1000,
     .note = "centre, -1000 left to +1000 right of the image"},
    {.name = "y",
     .kind = FieldKind::be_i16,
     .width = 2,
     .min = -1000,
     .max = 1000,
     .note = "centre, -1000 top to +1000 bottom"},
    {.name = "width",
     .kind = FieldKind::be_u16,
     .width = 2,
     .min = 0,
     .max = 2000,
     .note = "0-2000 of the image width"},
    {.name = "height",
     .kind = FieldKind::be_u16,
     .width = 2,
     .min = 0,
     .max = 2000,
     .note = "0-2000 of the image height"},
    {.name = "mode",
     .kind = FieldKind::be_u16,
     .width = 2,
     .enums = kLocMode,
     .note = "00 then 09 point (fuzzy click) or 01 rectangle (AP_Mount_Topotek, PixEagle); "
             "the vendor PDF's example has 00 08, and 00 00 also works (PixEagle)"},
};
constexpr FormSpec kLocForms[] = {
    // either role: the device echoes the write (top::write_reply)
    {.control = 'w',
     .min_length = 10,
     .max_length = 10,
     .fields = kLocFields,
     .evidence = "AP_Mount_Topotek sends #tpUDAwLOC + 10 bytes (PR #27568); PixEagle sent "
                 "#tpPDAwLOC 00 00 00 00 00 3E 00 6F 00 09 E7 to a real Topotek camera, which "
                 "then tracked (PixEagle session 20260917T051606Z-point 05:16:08.703292)"},
};

// OFT (tracking box push), 9 binary bytes, little-endian
constexpr EnumValue kOftStatus[] = {
    {'1', "stopped"},
    {'2', "tracking"},
    {'3', "temporarily_lost"},
};
constexpr FieldSpec kOftFields[] = {
    {.name = "x", .kind = FieldKind::le_u16, .width = 2, .unit = "px", .note = "top left, of 1920"},
    {.name = "y", .kind = FieldKind::le_u16, .width = 2, .unit = "px", .note = "top left, of 1080"},
    {.name = "width", .kind = FieldKind::le_u16, .width = 2, .unit = "px"},
    {.name = "height", .kind = FieldKind::le_u16, .width = 2, .unit = "px"},
    {.name = "status",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kOftStatus,
     .note = "2 while tracking; 1 with an all-zero box after a cancel; 3 while the target "
             "is lost, the box frozen (PixEagle session 20260917T051606Z-point "
             "05:16:08.998653, with TRC state 03 in 20260918T060352Z-point 06:03:55.511523; "
             "the name is TRC's state 3, the vendor's tracking PDF section 3)"},
};
constexpr FormSpec kOftForms[] = {
    {.control = 'w',
     .role = Role::response,
     .min_length = 9,
     .max_length = 9,
     .fields = kOftFields,
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) pushes #tpDP9wOFT + 9 "
                 "bytes while it tracks: 33 from 05:16:08.832750 to 05:16:09.898290, 33 ms apart "
                 "(PixEagle session 20260917T051606Z-point)"},
};

// A real Topotek camera's detection and zoom frames that neither document
// lists: PixEagle's bench (alireza787b/PixEagle @ 3bea324, docs/reporting/
// agent-ops/codex-modernization/evidence/2026-09-17-gimbal-control-bench/
// <session>/events.jsonl; captures/sip-bench/ makes pcaps of them). Times are
// each frame's first delivery, UTC. PixEagle's reading of them: its
// checkpoints/2026-09-17-phase-5-gimbal-control-bench.md ("phase 5
// checkpoint") and evidence/.../vendor-protocol-findings.md, which quotes the
// vendor's tracking PDF (not public).

// FED (detection output switch): 10 on, 20 off
constexpr EnumValue kFedOutput[] = {
    {0x10, "on"},
    {0x20, "off"},
};
constexpr FieldSpec kFedFields[] = {
    {.name = "output",
     .kind = FieldKind::enum_hex,
     .width = 2,
     .enums = kFedOutput,
     .note = "10 detection output on, 20 off (off by default: the vendor's tracking PDF section "
             "9 as PixEagle quotes it); no other value is known"},
};
constexpr FormSpec kFedForms[] = {
    {.control = 'w',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kFedFields,
     .evidence = "PixEagle sent #TPPD2wFED1034 to a real Topotek camera (PixEagle bench @3bea324, "
                 "VSN 1.6.26.R.D) at 07:18:56.503172 and #TPPD2wFED2035 at 07:19:03.716098 "
                 "(session 20260917T071854Z-ai-observe); the camera answered neither"},
};

// ODR (detections), #tP: a count byte, then that many records of six
// little-endian 16-bit fields
constexpr FieldSpec kOdrFields[] = {
    {.name = "count",
     .kind = FieldKind::u8,
     .width = 1,
     .note = "the records that follow; 1 in every ODR recorded (the one-byte length holds 21 at "
             "most, where the vendor's PDF declares an array of 255)"},
};
constexpr FieldSpec kOdrRecord[] = {
    {.name = "x", .kind = FieldKind::le_i16, .width = 2, .unit = "px", .note = "top left, of 1920"},
    {.name = "y", .kind = FieldKind::le_i16, .width = 2, .unit = "px", .note = "top left, of 1080"},
    {.name = "width", .kind = FieldKind::le_i16, .width = 2, .unit = "px"},
    {.name = "height", .kind = FieldKind::le_i16, .width = 2, .unit = "px"},
    {.name = "label",
     .kind = FieldKind::le_i16,
     .width = 2,
     .note = "label id: 127 in every record recorded; the label table is not public"},
    {.name = "confidence",
     .kind = FieldKind::le_i16,
     .width = 2,
     .scale = 0.0001,
     .note = "a fraction, sent times 10000 (the vendor's tracking PDF section 8 as PixEagle "
             "quotes it); 0 in every record recorded"},
};
constexpr FormSpec kOdrForms[] = {
    {.control = 'w',
     .role = Role::response,
     .min_length = 1,
     .max_length = 255,
     .fields = kOdrFields,
     .record = kOdrRecord,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) pushed #tPDP "
                 "0D wODR 01 15 06 05 00 65 01 02 04 7F 00 00 00 F0 (1557, 5, 357, 1026, 127, 0) "
                 "at 07:18:56.928933, 0.43 s after #TPPD2wFED1034 (session "
                 "20260917T071854Z-ai-observe); 19 in 20260917T072135Z-ai-select, each of one "
                 "record"},
};

// ODZ (pushed while the lens zooms): ten bytes of unknown meaning
constexpr FieldSpec kOdzFields[] = {
    {.name = "data",
     .kind = FieldKind::raw,
     .width = 10,
     .note = "meaning unknown (PixEagle's phase 5 checkpoint: \"Their meaning is unknown\"): ten "
             "zero bytes in every ODZ recorded, while the zoom went 1.0x to 1.5x and back"},
};
constexpr FormSpec kOdzForms[] = {
    {.control = 'w',
     .role = Role::response,
     .min_length = 10,
     .max_length = 10,
     .fields = kOdzFields,
     .evidence = "a real Topotek camera (PixEagle bench @3bea324, VSN 1.6.26.R.D) pushed "
                 "#tpDPAwODZ + ten 0x00 bytes + 40 from 05:09:57.284912, 14 ms after the zoom in "
                 "#TPPM2wZMC0259, every 30 ms until the stop #TPPM2wZMC0057 at 05:09:57.421025 "
                 "(session 20260917T050955Z-zoom)"},
};

// Appendix II only (the checksum example): no layout.
constexpr FieldSpec kRawFields[] = {
    {.name = "data", .kind = FieldKind::raw, .width = 0},
};
constexpr FormSpec kAppendixForms[] = {
    {.control = 'r', .role = Role::any, .min_length = 0, .max_length = 255, .fields = kRawFields},
    {.control = 'w', .role = Role::any, .min_length = 0, .max_length = 255, .fields = kRawFields},
};

// ---------------------------------------------------------------------------

constexpr CommandSpec kTable[] = {
    // 3 M class
    {.ident = "ZMC",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "zoom control",
     .section = "Topotek 3.1.1",
     .models = sip,
     .forms = kZmcForms,
     .note = "zoom in/out run until the stop command"},
    {.ident = "ZOM",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "zoom position",
     .section = "Topotek 3.1.2",
     .models = sip,
     .forms = kPositionReadForms,
     .note = "signed 16-bit position, FFB4 = -76"},
    {.ident = "FCC",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "focus control",
     .section = "Topotek 3.2.1",
     .models = sip,
     .forms = kFccForms,
     .note = "focus +/- run until the stop command; the network examples "
             "are labelled uart"},
    {.ident = "FOC",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "focus position",
     .section = "Topotek 3.2.2",
     .models = sip,
     .forms = kPositionReadForms,
     .note = "signed 16-bit position, FFB4 = -76"},
    {.ident = "ZFP",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "set zoom and focus position",
     .section = "Topotek 3.3",
     .models = sip,
     .forms = kZfpForms,
     .note = "focus NNNN sets the zoom only and lets the camera focus"},
    {.ident = "ZMP",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "zoom ratio and position",
     .section = "Topotek 3.4",
     .models = sip,
     .forms = kZmpForms,
     .note = "sent by itself after each zoom change ('r' control, no "
             "request); ratio in decimal digits, 0.1x; its example reuses a "
             "ZOM frame"},
    {.ident = "SWH",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "slave device power",
     .section = "Topotek 3.5",
     .models = sip,
     .forms = kSwhForms,
     .note = "not supported yet per the document; X0 5 = 5 V rail "
             "(rangefinder, dust sensor), C = 12 V rail (fill light); X1 "
             "0 off, 1 on"},
    {.ident = "IRC",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "day/night switch",
     .section = "Topotek 3.6",
     .models = sip,
     .forms = kIrcForms},
    {.ident = "ATE",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "ATE mode",
     .section = "Topotek 3.7",
     .models = sip,
     .forms = kAteForms,
     .note = "the document does not say what ATE mode does"},
    {.ident = "VSN",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "version",
     .section = "Topotek 3.8",
     .models = sip,
     .forms = kVsnForms,
     .note = "also sent to D (5.16, reply 2 chars); the M example reply "
             "#tpPM5rVSNM33265D is data \"M3326\" with checksum 5D and keeps "
             "the request's addresses"},
    {.ident = "MUL",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "optical zoom ratio",
     .section = "Topotek 3.9",
     .models = sip,
     .forms = kMulForms,
     .note = "some models; four decimal digits in 0.1x (0123 = 12.3x)"},
    {.ident = "APC",
     .dialect = Dialect::topotek,
     .address = 'M',
     .title = "aperture control",
     .section = "Topotek 3.10",
     .models = sip,
     .forms = kApcForms,
     .note = "some models; values known only from the examples"},
    // 4 G class
    {.ident = "PTZ",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal control",
     .section = "Topotek 4.1",
     .models = sip,
     .forms = kPtzForms},
    {.ident = "GSY",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedForms,
     .note = "the table says deg/s, the text 0.1 deg/s; we follow the table"},
    {.ident = "GSP",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal pitch speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedForms,
     .note = "the table says deg/s, the text 0.1 deg/s; we follow the table; "
             "the text makes pitch down positive (angles: up positive)"},
    {.ident = "GSR",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal roll speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedForms,
     .note = "the table says deg/s, the text 0.1 deg/s; we follow the table"},
    {.ident = "GSM",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw and pitch speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedYawPitchForms,
     .note = "#tp header in the table; the table says deg/s, the text "
             "0.1 deg/s; we follow the table"},
    {.ident = "RPS",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal roll and pitch speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedRollPitchForms,
     .note = "the table says deg/s, the text 0.1 deg/s; we follow the table"},
    {.ident = "YPR",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw, pitch and roll speed",
     .section = "Topotek 4.2",
     .models = sip,
     .forms = kSpeedYawPitchRollForms,
     .note = "the table says deg/s, the text 0.1 deg/s; we follow the table"},
    {.ident = "GAY",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw angle (magnetic encoder)",
     .section = "Topotek 4.3.1",
     .models = sip,
     .forms = kYawAngleForms,
     .note = "angle relative to the aircraft; the example #tpUG6wGAY "
             "checksum 88 is correct"},
    {.ident = "GAP",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal pitch angle (magnetic encoder)",
     .section = "Topotek 4.3.1",
     .models = sip,
     .forms = kAngleForms,
     .note = "angle relative to the aircraft; up positive"},
    {.ident = "GAR",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal roll angle (magnetic encoder)",
     .section = "Topotek 4.3.1",
     .models = sip,
     .forms = kAngleForms,
     .note = "angle relative to the aircraft"},
    {.ident = "GAM",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw and pitch angle (magnetic encoder)",
     .section = "Topotek 4.3.1",
     .models = sip,
     .forms = kAngleYawPitchForms,
     .note = "the appendix calls GAM a joint speed control (erratum)"},
    {.ident = "GIY",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw angle (gyroscope)",
     .section = "Topotek 4.3.2",
     .models = sip,
     .forms = kYawAngleForms,
     .note = "angle in the earth frame, whatever the aircraft attitude"},
    {.ident = "GIP",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal pitch angle (gyroscope)",
     .section = "Topotek 4.3.2",
     .models = sip,
     .forms = kAngleForms,
     .note = "angle in the earth frame; up positive"},
    {.ident = "GIR",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal roll angle (gyroscope)",
     .section = "Topotek 4.3.2",
     .models = sip,
     .forms = kAngleForms,
     .note = "angle in the earth frame"},
    {.ident = "GIM",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal yaw and pitch angle (gyroscope)",
     .section = "Topotek 4.3.2",
     .models = sip,
     .forms = kAngleYawPitchForms,
     .note = "angle in the earth frame"},
    {.ident = "GAC",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal attitude (magnetic encoder)",
     .section = "Topotek 4.3.3",
     .models = sip,
     .forms = kAttitudeForms,
     .note = "reply #tpGU C r GAC: yaw, pitch, roll in 0.01 deg; also pushed "
             "after GAA 01"},
    {.ident = "GAA",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "attitude push (magnetic encoder)",
     .section = "Topotek 4.3.4",
     .models = sip,
     .forms = kPushForms,
     .note = "01 enable, 00 disable (no rate, unlike SkyDroid)"},
    {.ident = "GIC",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal attitude (gyroscope)",
     .section = "Topotek 4.3.5",
     .models = sip,
     .forms = kAttitudeForms,
     .note = "reply #tpGU C r GIC: yaw, pitch, roll in 0.01 deg; also pushed "
             "after GIA 01"},
    {.ident = "GIA",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "attitude push (gyroscope)",
     .section = "Topotek 4.3.6",
     .models = sip,
     .forms = kGiaForms,
     .note = "01 enable, 00 disable; the field: real units answer the GIC query with a "
             "12-char GIA attitude frame, and push it after GIA 01"},
    {.ident = "GMS",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "gimbal motor switch",
     .section = "Topotek 4.4",
     .models = sip,
     .forms = kGmsForms,
     .note = "the read says only \"data: see setting\"; request 00 and a "
             "reply in the set layout assumed"},
    {.ident = "VER",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "serial number",
     .section = "Topotek 4.5.1",
     .models = sip,
     .forms = kVerForms,
     .note = "some models; reply X0-X13, 14 chars"},
    // 5 D class
    {.ident = "REC",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "recording",
     .section = "Topotek 5.1",
     .models = sip,
     .forms = kRecForms,
     .note = "the write is answered #tpDUAwREC11xxxxxxxx (started) or "
             "REC00xxxxxxxx (stopped) with the hex file index"},
    {.ident = "CAP",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "take photo",
     .section = "Topotek 5.2",
     .models = sip,
     .forms = kCapForms,
     .note = "answered #tpDUAwCAP11xxxxxxxx with the hex file index"},
    {.ident = "VID",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "resolution",
     .section = "Topotek 5.3",
     .models = sip,
     .forms = kVidForms,
     .note = "x1 selects record/photo/RTSP, x2 the resolution; the read "
             "sends 00 and does not say which setting it returns"},
    {.ident = "BIT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "RTSP stream 0 bit rate",
     .section = "Topotek 5.4",
     .models = sip,
     .forms = kBitForms,
     .note = "write 0X.... sets X Mbps (1-8, only X2 counts); write "
             "Knnnnn sets nnnnn kb/s decimal (minimum K00050); the read "
             "reply is in Mbps"},
    {.ident = "SDC",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "memory card capacity",
     .section = "Topotek 5.5",
     .models = sip,
     .forms = kSdcForms,
     .note = "request 00 free, 01 total; reply 5 hex digits in MB, NNNNN = "
             "no card"},
    {.ident = "ROT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "flip/mirror",
     .section = "Topotek 5.6",
     .models = sip,
     .forms = kRotForms,
     .note = "only 00 (0 deg) and 02 (180 deg) are listed; the subsections "
             "are numbered 3.1/3.2"},
    {.ident = "IPV",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "camera IP address",
     .section = "Topotek 5.7",
     .models = sip,
     .forms = kAddressForms,
     .note = "only the set command is documented"},
    {.ident = "GTW",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "camera gateway",
     .section = "Topotek 5.7",
     .models = sip,
     .forms = kAddressForms,
     .note = "only the set command is documented"},
    {.ident = "RST",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "reset network settings",
     .section = "Topotek 5.7",
     .models = sip,
     .forms = kRstForms,
     .note = "01 resets to ip 192.168.144.108, gateway 192.168.144.10"},
    {.ident = "LON",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "longitude",
     .section = "Topotek 5.8.1",
     .models = sip,
     .forms = kLonForms,
     .note = "input E/W dddmm.mmmm; 5.8.7 output (rangefinder models) is "
             "E/W + degrees, 11 bytes though \"ddd.ddddd\" has 9 chars"},
    {.ident = "LAT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "latitude",
     .section = "Topotek 5.8.2",
     .models = sip,
     .forms = kLatForms,
     .note = "input N/S ddmm.mmmm; 5.8.7 output (rangefinder models) is "
             "N/S + degrees, 10 bytes though \"dd.ddddd\" has 8 chars"},
    {.ident = "ALT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "altitude",
     .section = "Topotek 5.8.3",
     .models = sip,
     .forms = kAltForms,
     .note = "-9999.9 to 9999.9 m as in $GPGGA"},
    {.ident = "AZI",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "ground course",
     .section = "Topotek 5.8.4",
     .models = sip,
     .forms = kAziForms,
     .note = "000.0-359.9 deg from true north as in $GPRMC"},
    {.ident = "GPS",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "GPS position and heading",
     .section = "Topotek 5.8.5",
     .models = sip,
     .forms = kGpsForms,
     .note = "packed C struct sTPGpsInfo, 14 binary bytes under #tp length "
             "E, read little-endian (the document does not say); uavHeading "
             "has no unit: 0.01 deg assumed"},
    {.ident = "UAV",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "UAV attitude",
     .section = "Topotek 5.8.6",
     .models = sip,
     .forms = kUavForms,
     .note = "packed C struct sTPUavInfo, 10 binary bytes, read "
             "little-endian; yaw is int16_t with range [0,36000], which "
             "overflows past 32767"},
    {.ident = "LRF",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "laser rangefinder",
     .section = "Topotek 5.9",
     .models = sip,
     .forms = kLrfForms,
     .note = "the result comes from D after each successful measurement "
             "(00123.4 m; ERR = failed); on long-range versions the control "
             "(00 stop, 01 on, 02 single, 03 continuous) goes to M "
             "(#TPUM2wLRF02)"},
    {.ident = "TIM",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "Beijing time",
     .section = "Topotek 5.10",
     .models = sip,
     .forms = kTimForms,
     .note = "YYYYMMDDHHMMSS, decimal, zero padded; the sample code uses "
             "printf for sprintf"},
    {.ident = "UTC",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "UTC time",
     .section = "Topotek 5.10",
     .models = sip,
     .forms = kUtcForms,
     .note = "HHMMSSDDMMYY, decimal, zero padded"},
    {.ident = "PIP",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "picture in picture",
     .section = "Topotek 5.11",
     .models = sip,
     .forms = kPipForms,
     .note = "m main camera, s secondary; x0 and x1 both used with two "
             "visible-light lenses; B is described only as \"-\" (previous "
             "by analogy with IMG 0B)"},
    {.ident = "TMP",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "temperature measurement",
     .section = "Topotek 5.12",
     .models = sip,
     .forms = kTmpForms,
     .note = "the document does not say hex or decimal: read as hex like "
             "the rest of the protocol (2 chars cannot hold 256 in decimal "
             "either); 12.2 #PDP16TMP has a malformed header, its length "
             "0x16 = 22 needs two digits (known quirk); 12.3 on some models"},
    {.ident = "TMR",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "temperature range",
     .section = "Topotek 5.12.4",
     .models = sip,
     .forms = kTmrForms,
     .note = "some models; the first range at power-on"},
    {.ident = "IMG",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "thermal palette",
     .section = "Topotek 5.13",
     .models = sip,
     .forms = kImgForms,
     .note = "palettes differ per thermal core: the list is indicative; the "
             "codes differ from SkyDroid (0A is next here, medical there)"},
    {.ident = "DZM",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "digital zoom",
     .section = "Topotek 5.14",
     .models = sip,
     .forms = kDzmForms,
     .note = "some models; the command codes 0A-0E overlap the direct "
             "ratios 00-80 (1.0x-1.4x); read reply: thermal then visible "
             "increment in 0.1x"},
    {.ident = "DFG",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "electronic defog",
     .section = "Topotek 5.15",
     .models = sip,
     .forms = kDfgForms,
     .note = "some models; X0 1 auto, 2 manual (0 has no description, read "
             "as off), X1X2 strength 0-255 hex"},
    {.ident = "ENT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "encoding",
     .section = "Topotek 5.17",
     .models = sip,
     .forms = kEntForms,
     .note = "only the set command is documented"},
    // Appendix II only
    {.ident = "AWB",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "white balance",
     .section = "Topotek appendix II",
     .models = sip,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only): appears only in the "
             "checksum example #TPUD2wAWB0144"},
    // The field
    {.ident = "FED",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "detection output",
     .section = "field: PixEagle session 20260917T071854Z-ai-observe; vendor tracking PDF "
                "section 9",
     .models = sip,
     .forms = kFedForms,
     .note = "10 turns the detector's output on (ODR frames follow), 20 off; no answer",
     .evidence = "PixEagle bench @3bea324 on a real Topotek camera: FED10 at 07:18:56.503172, "
                 "ODR from 07:18:56.928933 to 07:19:02.395536, none after FED20 at "
                 "07:19:03.716098 (session 20260917T071854Z-ai-observe)"},
    {.ident = "ODR",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "detections",
     .section = "field: PixEagle session 20260917T071854Z-ai-observe; vendor tracking PDF "
                "section 8",
     .models = sip,
     .forms = kOdrForms,
     .note = "#tP (raw length byte): a count, then per detection x, y, width, height in pixels "
             "(little-endian 16-bit, top left of 1920x1080), a label id and the confidence "
             "times 10000; pushed while detection output is on, irregularly",
     .evidence = "PixEagle bench @3bea324 on a real Topotek camera (sessions "
                 "20260917T071854Z-ai-observe, 20260917T072135Z-ai-select); the layout is the "
                 "vendor's tracking PDF section 8 as PixEagle's vendor-protocol-findings.md "
                 "quotes it"},
    {.ident = "ODZ",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "zoom push (meaning unknown)",
     .section = "field: PixEagle session 20260917T050955Z-zoom",
     .models = sip,
     .forms = kOdzForms,
     .note = "pushed every 30 ms while the lens zooms; ten bytes, all zero when recorded, "
             "whose meaning no source gives",
     .evidence = "PixEagle bench @3bea324 on a real Topotek camera (session "
                 "20260917T050955Z-zoom: 5 ODZ after each of ZMC 02 and 01, none after ZMC 00 "
                 "or in any other session); PixEagle's phase 5 checkpoint: \"Their meaning is "
                 "unknown\""},
    {.ident = "PA2",
     .dialect = Dialect::topotek,
     .address = 'G',
     .title = "model name",
     .section = "field: ArduPilot AP_Mount_Topotek (PR #27568)",
     .models = sip,
     .forms = kPa2Forms,
     .note = "read until answered by ArduPilot's driver, #TPUG2rPA2002A; the reply's data "
             "is the model name",
     .evidence = "AP_Mount_Topotek.cpp sends and parses PA2 (PR #27568, "
                 "https://github.com/ArduPilot/ardupilot/pull/27568)"},
    {.ident = "TRC",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "tracking",
     .section = "field: ArduPilot AP_Mount_Topotek (PR #27568)",
     .models = sip,
     .forms = kTrcForms,
     .note = "write 00 exit, 01 cancel to waiting, 02 prepare; the read's data char 1 is the "
             "state: 0 stopped, 1 waiting, 2 tracking, 3 temporarily lost, 4 this lens does "
             "not track; the state is not an acknowledgement (PixEagle: it changes ~0.4 s "
             "after a LOC)",
     .evidence = "AP_Mount_Topotek.cpp (PR #27568 https://github.com/ArduPilot/ardupilot/pull/"
                 "27568, state 4: PR #31768 https://github.com/ArduPilot/ardupilot/pull/31768); "
                 "states 00 -> 01 (+1.673 s) -> 02 (+2.676 s) -> 03 (+5.285 s) -> 01 -> 00 on a "
                 "real Topotek camera (PixEagle session 20260918T185503Z-qt-point, manifest "
                 "tracking_transitions) and the vendor's tracking PDF (state 3)"},
    {.ident = "TRA",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "tracker fault",
     .section = "field: PixEagle session 20260917T071854Z-ai-observe; vendor tracking PDF "
                "section 4",
     .models = sip,
     .forms = kTraForms,
     .note = "answered 11 on a healthy tracker: not a health acknowledgement",
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D) answered "
                 "07:18:56.503256 #TPPD2rTRA0046 with 07:18:56.511155 #TPDP2rTRA1148 (PixEagle "
                 "session 20260917T071854Z-ai-observe; the vendor's serial example "
                 "#TPUD2rTRA004B -> "
                 "#TPDU2rTRA114D)"},
    {.ident = "LOC",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "tracking point or rectangle",
     .section = "field: ArduPilot AP_Mount_Topotek (PR #27568)",
     .models = sip,
     .forms = kLocForms,
     .note = "10 binary bytes: centre x, centre y, width, height as big-endian 16-bit on a "
             "+/-1000 grid, then 00 and 09 point or 01 rectangle; tracking starts (TRC state "
             "2) and OFT frames follow",
     .evidence = "AP_Mount_Topotek.cpp set_tracking() (PR #27568 https://github.com/ArduPilot/"
                 "ardupilot/pull/27568); PixEagle session 20260917T051606Z-point on a real "
                 "Topotek camera"},
    {.ident = "OFT",
     .dialect = Dialect::topotek,
     .address = 'D',
     .title = "tracking box",
     .section = "field: PixEagle session 20260917T051606Z-point",
     .models = sip,
     .forms = kOftForms,
     .note = "pushed at about 30 Hz while tracking: 9 binary bytes, x, y, width, height as "
             "little-endian 16-bit pixels (LOC is big-endian), status '2' tracking, '3' lost or "
             "'1' stopped; never attitude",
     .evidence = "a real Topotek camera (PixEagle bench, VSN 1.6.26.R.D): 33 OFT from "
                 "05:16:08.832750 to 05:16:09.898290, 33 ms apart, after LOC at 05:16:08.703292 "
                 "(PixEagle session 20260917T051606Z-point); the vendor's tracking PDF "
                 "section 7"},
};

}  // namespace

std::span<const CommandSpec> topotek_table() noexcept { return kTable; }

}  // namespace top::detail
